//! The cathodic Tafel coefficients a_c, b_c (paper Section 4.1, Table 2) from a
//! polarization curve: `potential_v` and `current_density_a_cm2` (or `_a_m2`; either sign).
//!
//! The Tafel line is eq. 18's, E = E_corr + a_c - b_c log10 |i| with i in A/cm^2, as the
//! corrosion module has it. The applied potential is the controlled variable and the current
//! the measured one, so the fit regresses log10 |i| on E - E_corr and converts: b_c = -1/slope,
//! a_c = -intercept/slope, their errors by first-order propagation of the covariance.
//!
//! The domain: from the most cathodic point up, the longest stretch on which a parabola in
//! E does not bend log10 |i| by more than 3 standard errors of its curvature, then cut back
//! to twice its distance below E_corr ([`BEND_MARGIN`]). Near E_corr the anodic current
//! bends the curve away from the line, which the test sees where the bend is near the noise.

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

use super::line::Line;
use super::{CalibrationError, Estimate, Table, require_increasing};
use crate::scene::{Corrosion, Scene};

/// A/cm^2 per A/m^2.
const A_CM2_PER_A_M2: f64 = 1e-4;

/// Fewest points a Tafel domain may have: a parabola's three coefficients and two degrees
/// of freedom for the scatter its curvature test needs.
const MIN_DOMAIN_POINTS: usize = 5;

/// Curvature, in its standard errors, above which a stretch is not straight (3: a straight
/// stretch fails with probability 0.27% under normal noise).
const CURVATURE_LIMIT: f64 = 3.0;

/// A domain the test cut short ends `BEND_MARGIN` times as far below E_corr as the test
/// allows. The bend the test cannot see is still there: the anodic current falls
/// exponentially with the distance from E_corr, so its bend of log10 |i|, about one decade
/// at E_corr and at the noise level (some 0.02 decades) where the test stops, is that level
/// squared (4e-4 decades) twice as far. On the Table 2 curve with 0.02 decades of noise over
/// 30 seeds, a_c and b_c are off by +2.7 and -2.9 standard errors on average when the domain
/// ends where the test stops, by +0.8 and -0.9 with a margin of 1.5, and by +0.22 and -0.24
/// (largest 2.1) with 2 (`tafel::tests`).
const BEND_MARGIN: f64 = 2.0;

/// Relative round-off of the parabola's residuals (sums of up to thousands of terms near
/// 1e-16 each, with margin), below which residual scatter is not noise.
const ROUND_OFF: f64 = 1e-12;

/// Settings of the Tafel fit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TafelOptions {
    /// E_corr, V; absent: the potential of the smallest |i| in the table.
    pub corrosion_potential_v: Option<f64>,
    /// The domain's upper end, V; absent: found by the curvature test.
    pub upper_v: Option<f64>,
}

/// The stretch of the curve the line was fitted on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TafelDomain {
    /// Most cathodic potential, V.
    pub lower_v: f64,
    /// Potential nearest E_corr, V.
    pub upper_v: f64,
    /// Points in it.
    pub points: usize,
}

/// One point of the domain against the line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TafelResidual {
    /// Applied potential, V.
    pub potential_v: f64,
    /// Measured log10 |i| (A/cm^2).
    pub log10_current_density_a_cm2: f64,
    /// Measured minus fitted log10 |i|, decades.
    pub residual_decades: f64,
}

/// The fitted Tafel line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TafelFit {
    /// E_corr used, V.
    pub corrosion_potential_v: f64,
    /// Whether E_corr was given rather than taken from the table.
    pub corrosion_potential_given: bool,
    /// a_c, V (for i in A/cm^2).
    pub tafel_a_c_v: Estimate,
    /// b_c, V per decade.
    pub tafel_b_c_v_per_decade: Estimate,
    /// The line's current at E_corr, 10^(a_c / b_c), A/cm^2 (Table 2's i_corr).
    pub corrosion_current_density_a_cm2: f64,
    /// The domain used.
    pub domain: TafelDomain,
    /// Each domain point's residual.
    pub residuals: Vec<TafelResidual>,
    /// Root-mean-square residual, decades.
    pub rms_residual_decades: f64,
    /// The scene with `corrosion` E_corr, a_c and b_c filled in.
    pub scene: Scene,
}

/// Fits a_c and b_c to a cathodic polarization curve.
pub fn fit_tafel(
    table: &Table,
    scene: &Scene,
    options: TafelOptions,
) -> Result<TafelFit, CalibrationError> {
    let (potential, current) = curve(table)?;
    let e_corr = options.corrosion_potential_v.unwrap_or_else(|| {
        let smallest = (0..current.len())
            .min_by(|&a, &b| current[a].abs().total_cmp(&current[b].abs()))
            .unwrap_or(0);
        potential[smallest]
    });
    // The cathodic branch, most cathodic first.
    let mut branch: Vec<(f64, f64)> = potential
        .iter()
        .zip(&current)
        .filter(|&(&e, &i)| e < e_corr && i != 0.0)
        .map(|(&e, &i)| (e - e_corr, i.abs().log10()))
        .collect();
    branch.sort_by(|a, b| a.0.total_cmp(&b.0));
    let etas: Vec<f64> = branch.iter().map(|p| p.0).collect();
    require_increasing("potential_v", &etas)?;
    let logs: Vec<f64> = branch.iter().map(|p| p.1).collect();
    if branch.len() < MIN_DOMAIN_POINTS {
        return Err(CalibrationError::NoTafelDomain(format!(
            "{} points below E_corr = {e_corr} V, a domain needs {MIN_DOMAIN_POINTS}",
            branch.len()
        )));
    }
    let end = match options.upper_v {
        Some(upper) => etas.partition_point(|&eta| eta <= upper - e_corr),
        None => {
            let straight = straight_end(&etas, &logs).ok_or_else(|| {
                CalibrationError::NoTafelDomain(format!(
                    "log10 |i| bends by more than {CURVATURE_LIMIT} standard errors of its curvature on every stretch of {MIN_DOMAIN_POINTS} or more points from the most cathodic one"
                ))
            })?;
            if straight == etas.len() {
                straight
            } else {
                let top = BEND_MARGIN * etas[straight - 1];
                etas.partition_point(|&eta| eta <= top)
            }
        }
    };
    if end < MIN_DOMAIN_POINTS {
        return Err(CalibrationError::NoTafelDomain(format!(
            "{end} points below the given upper end, a domain needs {MIN_DOMAIN_POINTS}"
        )));
    }
    let line = Line::fit(&etas[..end], &logs[..end]);
    if line.slope >= 0.0 {
        return Err(CalibrationError::NoTafelDomain(
            "|i| does not grow as the potential falls".to_owned(),
        ));
    }
    Ok(finish(
        scene,
        e_corr,
        options,
        &line,
        &etas[..end],
        &logs[..end],
    ))
}

/// Potentials and current densities (A/cm^2) of the table.
fn curve(table: &Table) -> Result<(Vec<f64>, Vec<f64>), CalibrationError> {
    let potential = table.column("potential_v")?.to_vec();
    let current = match (
        table.optional("current_density_a_cm2"),
        table.optional("current_density_a_m2"),
    ) {
        (Some(a_cm2), _) => a_cm2.to_vec(),
        (None, Some(a_m2)) => a_m2.iter().map(|i| i * A_CM2_PER_A_M2).collect(),
        (None, None) => {
            return Err(table
                .missing("`current_density_a_cm2` or `current_density_a_m2`".to_owned())
                .into());
        }
    };
    Ok((potential, current))
}

/// The line's values, their errors by propagation, the residuals and the scene.
fn finish(
    scene: &Scene,
    e_corr: f64,
    options: TafelOptions,
    line: &Line,
    etas: &[f64],
    logs: &[f64],
) -> TafelFit {
    let (alpha, beta, cov) = (line.intercept, line.slope, line.covariance);
    let b_c = -1.0 / beta;
    let a_c = -alpha / beta;
    // Gradients of b_c = -1/beta and a_c = -alpha/beta with respect to (alpha, beta).
    let var_b = cov.slope / beta.powi(4);
    let var_a = cov.intercept / beta.powi(2) + alpha * alpha * cov.slope / beta.powi(4)
        - 2.0 * alpha * cov.cross / beta.powi(3);
    let residuals: Vec<TafelResidual> = etas
        .iter()
        .zip(logs)
        .map(|(&eta, &y)| TafelResidual {
            potential_v: eta + e_corr,
            log10_current_density_a_cm2: y,
            residual_decades: y - line.at(eta),
        })
        .collect();
    let rss: f64 = residuals.iter().map(|r| r.residual_decades.powi(2)).sum();
    let mut fitted = scene.clone();
    let corrosion = fitted.corrosion.get_or_insert_with(Corrosion::default);
    corrosion.corrosion_potential_v = e_corr;
    corrosion.tafel_a_c_v = a_c;
    corrosion.tafel_b_c_v_per_decade = b_c;
    TafelFit {
        corrosion_potential_v: e_corr,
        corrosion_potential_given: options.corrosion_potential_v.is_some(),
        tafel_a_c_v: Estimate {
            value: a_c,
            standard_error: var_a.sqrt(),
        },
        tafel_b_c_v_per_decade: Estimate {
            value: b_c,
            standard_error: var_b.sqrt(),
        },
        corrosion_current_density_a_cm2: 10f64.powf(alpha),
        domain: TafelDomain {
            lower_v: etas[0] + e_corr,
            upper_v: etas[etas.len() - 1] + e_corr,
            points: etas.len(),
        },
        rms_residual_decades: (rss / etas.len() as f64).sqrt(),
        residuals,
        scene: fitted,
    }
}

/// The number of points, from the most cathodic, of the longest straight stretch.
fn straight_end(etas: &[f64], logs: &[f64]) -> Option<usize> {
    (MIN_DOMAIN_POINTS..=etas.len())
        .rev()
        .find(|&end| curvature_t(&etas[..end], &logs[..end]) < CURVATURE_LIMIT)
}

/// |c2| / se(c2) of the parabola y = c0 + c1 u + c2 u^2 fitted by least squares, with u the
/// abscissa centred and scaled to [-1, 1] so that the normal equations stay well conditioned.
fn curvature_t(xs: &[f64], ys: &[f64]) -> f64 {
    let (lo, hi) = (xs[0], xs[xs.len() - 1]);
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    let mut normal = Matrix3::zeros();
    let mut rhs = Vector3::zeros();
    for (&x, &y) in xs.iter().zip(ys) {
        let u = (x - mid) / half;
        let row = Vector3::new(1.0, u, u * u);
        normal += row * row.transpose();
        rhs += row * y;
    }
    let Some(inverse) = normal.try_inverse() else {
        return f64::INFINITY;
    };
    let c = inverse * rhs;
    let rss: f64 = xs
        .iter()
        .zip(ys)
        .map(|(&x, &y)| {
            let u = (x - mid) / half;
            (y - c[0] - c[1] * u - c[2] * u * u).powi(2)
        })
        .sum();
    // Noise-free data leave only round-off in the residuals; floor the scatter there so
    // that a straight line's round-off curvature does not count as bending.
    let floor = ROUND_OFF * ys.iter().fold(0.0_f64, |m, y| m.max(y.abs()));
    let scatter = (rss / (xs.len() as f64 - 3.0)).max(floor * floor);
    let se = (scatter * inverse[(2, 2)]).sqrt();
    c[2].abs() / se
}

#[cfg(test)]
mod tests;
