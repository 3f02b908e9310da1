//! The work-hardening law H = A + B ln n (paper Section 4.5, Fig. 9) from a hardness table
//! (`cycles` or `time_s`, and `hardness_mpa`), with or without the bulk value at n = 1. The
//! coefficients come from [`HardnessLaw::fit`], the one home of that fit; this adds their
//! standard errors and the residuals.

use serde::Serialize;

use super::line::covariance;
use super::{
    CalibrationError, Estimate, Table, cycles_of, require_at_least, require_increasing,
    require_points,
};
use crate::hardness::HardnessLaw;
use crate::scene::Scene;

/// How the hardness law is fitted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HardnessOptions {
    /// Whether the scene's bulk hardness (`disc.hardness_mpa`) is a point at n = 1, as the
    /// paper and the scene's own law take it.
    pub include_bulk: bool,
}

impl Default for HardnessOptions {
    fn default() -> Self {
        Self { include_bulk: true }
    }
}

/// One measured hardness against the law.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HardnessResidual {
    /// Cycle count (n = 1 for the bulk value).
    pub cycles: f64,
    /// Measured hardness, MPa.
    pub hardness_mpa: f64,
    /// The law at this cycle count, MPa.
    pub fitted_mpa: f64,
    /// Measured minus fitted, MPa.
    pub residual_mpa: f64,
}

/// The fitted hardness law.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HardnessFit {
    /// A = H(1), MPa.
    pub a_mpa: Estimate,
    /// B, MPa per unit of ln n.
    pub b_mpa: Estimate,
    /// Whether the bulk value took part, as the first residual.
    pub bulk_included: bool,
    /// Each point's residual.
    pub residuals: Vec<HardnessResidual>,
    /// Root-mean-square residual, MPa.
    pub rms_residual_mpa: f64,
    /// The scene with the table as `disc.hardness_table` (without the bulk value,
    /// `disc.hardness_mpa` becomes the fitted A: a point on the fitted line leaves a
    /// least-squares fit unchanged, so the scene's law is this fit).
    pub scene: Scene,
}

/// Fits H = A + B ln n to `table` (`cycles` or `time_s`, `hardness_mpa`).
pub fn fit_hardness(
    table: &Table,
    scene: &Scene,
    options: HardnessOptions,
) -> Result<HardnessFit, CalibrationError> {
    let (cycles, cycle_column) = cycles_of(table, scene)?;
    let hardness = table.column("hardness_mpa")?;
    require_increasing(cycle_column, &cycles)?;
    require_at_least(
        cycle_column,
        &cycles,
        if cycle_column == "cycles" { 1.0 } else { 0.0 },
    )?;
    require_at_least("hardness_mpa", hardness, f64::MIN_POSITIVE)?;
    let bulk = options
        .include_bulk
        .then_some((1.0, scene.disc.hardness_mpa));
    let points: Vec<(f64, f64)> = bulk
        .into_iter()
        .chain(
            cycles
                .iter()
                .map(|&n| n.max(1.0))
                .zip(hardness.iter().copied()),
        )
        .collect();
    // Two coefficients and at least one degree of freedom for the scatter.
    let ns: Vec<f64> = points.iter().map(|p| p.0).collect();
    require_points("hardness_mpa", &ns, 3)?;
    let points_pa: Vec<(f64, f64)> = points.iter().map(|&(n, h)| (n, h * 1e6)).collect();
    let law = HardnessLaw::fit_points(&points_pa)?;
    let residuals: Vec<HardnessResidual> = points
        .iter()
        .map(|&(n, h)| {
            let fitted = law.hardness_pa(n) / 1e6;
            HardnessResidual {
                cycles: n,
                hardness_mpa: h,
                fitted_mpa: fitted,
                residual_mpa: h - fitted,
            }
        })
        .collect();
    let rss: f64 = residuals.iter().map(|r| r.residual_mpa.powi(2)).sum();
    let logs: Vec<f64> = ns.iter().map(|n| n.ln()).collect();
    let cov = covariance(&logs, rss);
    let (a_pa, b_pa) = match law {
        HardnessLaw::Logarithmic { a_pa, b_pa } => (a_pa, b_pa),
        HardnessLaw::Constant { hardness_pa } => (hardness_pa, 0.0),
    };
    let mut fitted = scene.clone();
    fitted.disc.hardness_table = Some(
        cycles
            .iter()
            .copied()
            .zip(hardness.iter().copied())
            .collect(),
    );
    if !options.include_bulk {
        fitted.disc.hardness_mpa = a_pa / 1e6;
    }
    Ok(HardnessFit {
        a_mpa: Estimate {
            value: a_pa / 1e6,
            standard_error: cov.intercept.sqrt(),
        },
        b_mpa: Estimate {
            value: b_pa / 1e6,
            standard_error: cov.slope.sqrt(),
        },
        bulk_included: options.include_bulk,
        rms_residual_mpa: (rss / points.len() as f64).sqrt(),
        residuals,
        scene: fitted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table3() -> Table {
        Table::parse("cycles,hardness_mpa\n10,2551\n60,2727\n300,2854\n1800,2933\n3600,2953\n")
            .expect("valid table")
    }

    fn relative_error(got: f64, want: f64) -> f64 {
        ((got - want) / want).abs()
    }

    #[test]
    fn table_3_with_the_bulk_value_gives_the_scene_law() {
        let scene = Scene::default();
        let fit = fit_hardness(&table3(), &scene, HardnessOptions::default()).expect("fits");
        // The same numbers as the hardness module's own test of this table (closed-form
        // normal equations in Python): A = 2454.986623221253, B = 63.38253953265306 MPa.
        assert!(relative_error(fit.a_mpa.value, 2454.986623221253) < 1e-9);
        assert!(relative_error(fit.b_mpa.value, 63.38253953265306) < 1e-9);
        // Standard errors from the same Python evaluation of s^2 (X^T X)^-1 (RSS = 4829.43
        // MPa^2 over 4 degrees of freedom): 26.977756781 and 4.955312493 MPa.
        assert!(relative_error(fit.a_mpa.standard_error, 26.977756781) < 1e-9);
        assert!(relative_error(fit.b_mpa.standard_error, 4.955312493) < 1e-9);
        let law = fit.scene.hardness_law().expect("scene law");
        assert!(relative_error(law.hardness_pa(300.0) / 1e6, fit.residuals[3].fitted_mpa) < 1e-12);
    }

    #[test]
    fn without_the_bulk_value_the_scene_reproduces_the_fit() {
        let scene = Scene::default();
        let options = HardnessOptions {
            include_bulk: false,
        };
        let fit = fit_hardness(&table3(), &scene, options).expect("fits");
        assert_eq!(fit.residuals.len(), 5);
        let law = fit.scene.hardness_law().expect("scene law");
        // Adding (1, A) lies on the fitted line, so the scene's bulk-anchored fit is this
        // one: equal to the SVD's round-off (a few ulps times the condition number ~10).
        for r in &fit.residuals {
            let scene_mpa = law.hardness_pa(r.cycles) / 1e6;
            assert!(
                relative_error(scene_mpa, r.fitted_mpa) < 1e-12,
                "n = {}",
                r.cycles
            );
        }
    }

    #[test]
    fn noise_free_law_comes_back_with_vanishing_errors() {
        let (a, b) = (2400.0, 75.0);
        let cycles = [3.0, 17.0, 250.0, 4000.0];
        let hardness: Vec<f64> = cycles.iter().map(|n: &f64| a + b * n.ln()).collect();
        let table = Table::from_columns(&[("cycles", &cycles), ("hardness_mpa", &hardness)])
            .expect("equal-length finite columns");
        let scene = Scene {
            disc: crate::scene::Disc {
                hardness_mpa: a,
                ..Default::default()
            },
            ..Scene::default()
        };
        let fit = fit_hardness(&table, &scene, HardnessOptions::default()).expect("fits");
        // Exact data: the SVD's round-off only (see the hardness module's exact-law test).
        assert!(relative_error(fit.a_mpa.value, a) < 1e-9);
        assert!(relative_error(fit.b_mpa.value, b) < 1e-9);
        assert!(fit.b_mpa.standard_error < 1e-9 * b);
    }

    #[test]
    fn bad_tables_are_refused_naming_the_column() {
        let scene = Scene::default();
        let options = HardnessOptions::default();
        let unordered = Table::parse("cycles,hardness_mpa\n60,2727\n10,2551\n").expect("valid");
        let err = fit_hardness(&unordered, &scene, options).expect_err("not increasing");
        assert!(err.to_string().contains("`cycles`"), "{err}");
        let short = Table::parse("cycles,hardness_mpa\n60,2727\n").expect("valid");
        let err = fit_hardness(&short, &scene, options).expect_err("too few");
        assert!(matches!(err, CalibrationError::TooFewPoints { .. }));
        let negative = Table::parse("cycles,hardness_mpa\n10,2551\n60,-1\n").expect("valid");
        let err = fit_hardness(&negative, &scene, options).expect_err("negative");
        assert!(err.to_string().contains("`hardness_mpa`"), "{err}");
        let unnamed = Table::parse("n,h\n10,2551\n").expect("valid");
        let err = fit_hardness(&unnamed, &scene, options).expect_err("no column");
        assert!(err.to_string().contains("`cycles` or `time_s`"), "{err}");
    }
}
