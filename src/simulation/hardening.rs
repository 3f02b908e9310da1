//! What the run reports about the hardness law (paper Fig. 9): the fitted A and B, the points
//! they were fitted to with each one's residual, and a warning for a point far off the law.

use crate::hardness::HardnessLaw;
use crate::scene::{Disc, FieldWarning};

use super::{Model, ModelChoice};

/// A measured hardness further than this fraction from the fitted law is worth a warning.
/// Table 3's largest spread is 90 MPa on 2551 MPa (3.5%), and the paper's own fit leaves at
/// most 2% (50 MPa at n = 10); 5% is beyond what measurement scatter explains.
pub const FAR_OFF_FRACTION: f64 = 0.05;

/// The `work_hardening` model choice for `disc` and its fitted `law`, and a warning per point
/// more than [`FAR_OFF_FRACTION`] off the law.
pub(super) fn work_hardening_report(
    disc: &Disc,
    law: &HardnessLaw,
) -> (ModelChoice, Vec<FieldWarning>) {
    let HardnessLaw::Logarithmic { a_pa, b_pa } = *law else {
        let choice = ModelChoice {
            name: Model::WorkHardening,
            active: false,
            reason: format!("no table: H = {} MPa throughout", disc.hardness_mpa),
        };
        return (choice, Vec::new());
    };
    let points = disc.hardness_fit_points().unwrap_or_default();
    let mut warnings = Vec::new();
    let residuals: Vec<String> = points
        .iter()
        .map(|&(n, h_pa)| {
            let fitted = law.hardness_pa(n);
            let residual = h_pa - fitted;
            if (residual / fitted).abs() > FAR_OFF_FRACTION {
                warnings.push(FieldWarning::new(
                    "disc.hardness_table",
                    format!(
                        "the point at n = {n} ({:.0} MPa) lies {:+.0} MPa ({:+.1}%) off the \
                         fitted law H = {:.1} + {:.2} ln n MPa",
                        h_pa / 1e6,
                        residual / 1e6,
                        100.0 * residual / fitted,
                        a_pa / 1e6,
                        b_pa / 1e6
                    ),
                ));
            }
            format!("n = {n}: {:+.1}", residual / 1e6)
        })
        .collect();
    let bulk = if disc.hardness_fit_includes_bulk {
        "the table and the bulk value at n = 1"
    } else {
        "the table alone (bulk value left out)"
    };
    let softening = if law.is_decreasing() {
        " (decreasing: softening)"
    } else {
        ""
    };
    let choice = ModelChoice {
        name: Model::WorkHardening,
        active: true,
        reason: format!(
            "H = {:.1} + {:.2} ln n MPa{softening}, least squares through {bulk}; residuals \
             (measured - fitted, MPa): {}",
            a_pa / 1e6,
            b_pa / 1e6,
            residuals.join(", ")
        ),
    };
    (choice, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_table_fits_within_the_spread_and_an_outlier_is_named() {
        let disc = Disc::default();
        let law = disc.hardness_law().expect("the paper table fits");
        let (choice, warnings) = work_hardening_report(&disc, &law);
        assert!(choice.active);
        // The fit of Table 3 with the bulk value: H(10) = 2600.9 MPa against 2551 measured.
        assert!(choice.reason.contains("n = 10: -49.9"), "{}", choice.reason);
        assert!(warnings.is_empty(), "{warnings:?}");

        let mut outlier = Disc::default();
        if let Some(table) = outlier.hardness_table.as_mut() {
            table[2].1 = 3400.0;
        }
        let law = outlier.hardness_law().expect("still fits");
        let (_, warnings) = work_hardening_report(&outlier, &law);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].message.contains("n = 300"), "{}", warnings[0]);
    }

    #[test]
    fn leaving_the_bulk_value_out_changes_the_fit() {
        let with = Disc::default();
        let without = Disc {
            hardness_fit_includes_bulk: false,
            ..Disc::default()
        };
        let a = |disc: &Disc| match disc.hardness_law().expect("fits") {
            HardnessLaw::Logarithmic { a_pa, .. } => a_pa,
            HardnessLaw::Constant { .. } => panic!("a table gives a logarithmic law"),
        };
        // The bulk point (2473 MPa at n = 1) sits 18 MPa above the table-only line's
        // intercept, so the two fits differ by more than rounding.
        assert!((a(&with) - a(&without)).abs() > 1e6);
        let (choice, _) = work_hardening_report(&without, &without.hardness_law().expect("fits"));
        assert!(choice.reason.contains("bulk value left out"));
        assert!(!choice.reason.contains("n = 1:"));
    }
}
