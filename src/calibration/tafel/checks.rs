//! What makes a Tafel fit silently wrong, found in the curve: a column whose rows mix units
//! (mA/cm^2 rows among A/cm^2 ones jump by three decades between neighbours), outliers, and
//! fitted values no real 316L cell gives (the rules of [`crate::corrosion::plausible`]).

use super::{CalibrationError, MIN_DOMAIN_SPAN_V, TafelResidual};
use crate::corrosion::plausible::{self, Finding};

/// The resolution of a measured log10 |i|, decades: potentiostats read currents to about
/// 0.2% of the reading (8.7e-4 decades), so scatter or bends below 1e-3 decades are not
/// measurable. It floors the scatter of the curvature test and of the outlier test, which a
/// noise-free curve would otherwise set at round-off.
pub(super) const RESOLUTION_DECADES: f64 = 1e-3;

/// The steepest log10 |i| against E a Tafel line has, decades per V: 1 / b_c at the
/// smallest slope any reaction gives (2.303 RT / (4F) = 0.0148 V/decade).
const STEEPEST_DECADES_PER_V: f64 = 1.0 / plausible::SMALLEST_TAFEL_SLOPE_V_PER_DECADE;

/// A jump between neighbouring rows of at least this many decades, steeper than any Tafel
/// line, is a change of units: mA and A differ by 3 decades, A/m^2 and A/cm^2 by 4. Two is
/// far above any noise a potentiostat shows (0.02 decades on the paper's curve).
const MIXED_JUMP_DECADES: f64 = 2.0;

/// A residual this many robust standard deviations (1.4826 times the median absolute
/// deviation, the normal's sigma) from the median is an outlier: Iglewicz and Hoaglin's
/// modified z-score bound, 3.5 (How to Detect and Handle Outliers, ASQC, 1993).
const OUTLIER_Z: f64 = 3.5;

/// Refuses a cathodic branch (`points`: E - E_corr increasing, log10 |i|, table row from 1)
/// whose neighbouring rows jump by more than [`MIXED_JUMP_DECADES`] more steeply than any
/// Tafel line: rows in other units. The first [`MIN_DOMAIN_SPAN_V`] below E_corr are left
/// out, where the net current passes through 0 and its logarithm dives.
pub(super) fn mixed_units(points: &[(f64, f64, usize)]) -> Result<(), CalibrationError> {
    let away: Vec<&(f64, f64, usize)> =
        points.iter().filter(|p| p.0 < -MIN_DOMAIN_SPAN_V).collect();
    let jump = away.windows(2).find(|pair| {
        let (a, b) = (pair[0], pair[1]);
        let decades = (b.1 - a.1).abs();
        decades >= MIXED_JUMP_DECADES && decades > STEEPEST_DECADES_PER_V * (b.0 - a.0)
    });
    match jump {
        Some(pair) => Err(CalibrationError::MixedUnits {
            rows: (pair[0].2.min(pair[1].2), pair[0].2.max(pair[1].2)),
            decades: (pair[1].1 - pair[0].1).abs(),
            millivolts: (pair[1].0 - pair[0].0) * 1e3,
        }),
        None => Ok(()),
    }
}

/// The residuals more than [`OUTLIER_Z`] robust standard deviations from their median (the
/// deviation floored at [`RESOLUTION_DECADES`]).
pub(super) fn outliers(residuals: &[TafelResidual]) -> Vec<TafelResidual> {
    let values: Vec<f64> = residuals.iter().map(|r| r.residual_decades).collect();
    let centre = median(&values);
    let deviations: Vec<f64> = values.iter().map(|v| (v - centre).abs()).collect();
    let sigma = (1.4826 * median(&deviations)).max(RESOLUTION_DECADES);
    residuals
        .iter()
        .filter(|r| (r.residual_decades - centre).abs() > OUTLIER_Z * sigma)
        .copied()
        .collect()
}

/// The median of `values` (not empty).
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    }
}

/// E_corr judged as a scene's is: a warning for the fit, or the refusal of a value no cell
/// gives.
pub(super) fn potential(e_corr_v: f64) -> Result<Vec<String>, CalibrationError> {
    judged([("E_corr", plausible::corrosion_potential(e_corr_v))])
}

/// The fitted b_c and line current at E_corr judged as a scene's are.
pub(super) fn line(
    b_c_v_per_decade: f64,
    i_corr_a_cm2: f64,
) -> Result<Vec<String>, CalibrationError> {
    judged([
        (
            "tafel_b_c_v_per_decade",
            plausible::tafel_slope(b_c_v_per_decade),
        ),
        (
            "corrosion_current_density_a_cm2",
            plausible::corrosion_current("i_corr, 10^(a_c / b_c)", i_corr_a_cm2),
        ),
    ])
}

/// The refusal among `findings`, else their warnings' words.
fn judged<const N: usize>(
    findings: [(&'static str, Option<Finding>); N],
) -> Result<Vec<String>, CalibrationError> {
    let found: Vec<(&'static str, Finding)> = findings
        .into_iter()
        .filter_map(|(what, finding)| finding.map(|f| (what, f)))
        .collect();
    if let Some((what, finding)) = found.iter().find(|(_, f)| f.refuse) {
        return Err(CalibrationError::Implausible {
            what,
            message: finding.message.clone(),
        });
    }
    Ok(found
        .into_iter()
        .map(|(what, f)| format!("{what}: {}", f.message))
        .collect())
}
