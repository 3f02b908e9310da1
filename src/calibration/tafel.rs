//! The cathodic Tafel coefficients a_c, b_c (paper Section 4.1, Table 2) from a
//! polarization curve: `potential_v` and `current_density_a_cm2` (or `_a_m2`; either sign).
//!
//! The Tafel line is eq. 18's, E = E_corr + a_c - b_c log10 |i| with i in A/cm^2, as the
//! corrosion module has it. The applied potential is the controlled variable and the current
//! the measured one, so the fit regresses log10 |i| on E - E_corr and converts: b_c = -1/slope,
//! a_c = -intercept/slope, their errors by first-order propagation of the covariance.
//!
//! E_corr is given (`--e-corr`), or where the measured current changes sign (the scan's own
//! zero-current potential), or the lab's scene's; never guessed from a curve that does not
//! show it: the top of a cathodic-only scan lies below E_corr by however far the scan
//! stopped short of it.
//!
//! The domain, chosen from the data unless its ends are given (`--tafel-overpotential-max`,
//! `--tafel-overpotential-min`; `options.tafel_overpotential_max_v`, `_min_v`, as E - E_corr):
//! from the scan's most cathodic point up, the longest stretch on which a parabola in E does
//! not bend log10 |i| by more than 3 standard errors of its curvature (the scatter floored at
//! the current's resolution, [`checks::RESOLUTION_DECADES`]), then cut back to twice its
//! distance below E_corr ([`BEND_MARGIN`]), or kept whole, with a warning, where twice as
//! far leaves too little of the scan to measure a line on. Near E_corr the anodic current bends the curve away from
//! the line, which the test sees where the bend is near the noise. A domain narrower than
//! [`MIN_DOMAIN_SPAN_V`] or of fewer than [`MIN_TAFEL_POINTS`] points is refused: it cannot
//! show a Tafel line.
//!
//! Before the fit, a current column whose rows jump by decades between neighbours is refused
//! (mixed units); after it, the residuals' outliers are flagged and the fitted E_corr, b_c and
//! i_corr judged by the scene's plausibility rules (a current 1000 times 316L's names
//! mA/cm^2 typed as A/cm^2).

use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

use super::line::Line;
use super::{CalibrationError, Estimate, Table, require_increasing};
use checks::RESOLUTION_DECADES;

mod checks;
use crate::scene::{Corrosion, Scene, TAFEL_OVERPOTENTIAL_RANGE_V};

/// The domain's least cathodic end, as the service and the command line name it.
const MAX_OPTION: (&str, &str) = ("tafel_overpotential_max_v", "--tafel-overpotential-max");
/// The domain's most cathodic end, as the service and the command line name it.
const MIN_OPTION: (&str, &str) = ("tafel_overpotential_min_v", "--tafel-overpotential-min");

/// A/cm^2 per A/m^2.
const A_CM2_PER_A_M2: f64 = 1e-4;

/// Fewest points a Tafel domain may have: a parabola's three coefficients and two degrees
/// of freedom for the scatter its curvature test needs.
const MIN_DOMAIN_POINTS: usize = 5;

/// Narrowest domain a Tafel line is fitted on, V. A Tafel line is the exponential limit of
/// the Butler-Volmer kinetics, reached a few RT / F (25.7 mV at 25 C) from E_corr; over less
/// than 2 RT / F the straight line cannot be told from the curvature of the mixed region.
pub const MIN_DOMAIN_SPAN_V: f64 = 0.05;

/// Fewest points a fitted domain may have. The standard errors are scaled by the residual
/// scatter, estimated on n - 2 degrees of freedom, whose relative standard deviation is
/// about 1 / sqrt(2 (n - 2)): 25% at 10 points, 50% at 4. Below 10 points the reported
/// errors would themselves be uncertain by more than a quarter.
pub const MIN_TAFEL_POINTS: usize = 10;

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

/// Settings of the Tafel fit.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TafelOptions {
    /// E_corr, V; absent: where the current changes sign, else the scene's when
    /// `scene_corrosion_potential`.
    pub corrosion_potential_v: Option<f64>,
    /// Whether the scene's E_corr is the lab's own and may stand for a curve that does not
    /// show one (false for the default preset, whose E_corr is the paper's).
    pub scene_corrosion_potential: bool,
    /// The domain's least cathodic end as E - E_corr, V; absent: chosen from the data.
    pub overpotential_max_v: Option<f64>,
    /// The domain's most cathodic end as E - E_corr, V; absent: the scan's end.
    pub overpotential_min_v: Option<f64>,
}

/// Where E_corr came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CorrosionPotentialSource {
    /// Given (`--e-corr`, `options.e_corr_v`).
    Option,
    /// Where the measured current changes sign.
    SignChange,
    /// The scene's `corrosion.corrosion_potential_v`.
    Scene,
}

/// The stretch of the curve the line was fitted on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TafelDomain {
    /// Most cathodic potential, V.
    pub lower_v: f64,
    /// Potential nearest E_corr, V.
    pub upper_v: f64,
    /// `lower_v` as E - E_corr, V.
    pub overpotential_min_v: f64,
    /// `upper_v` as E - E_corr, V.
    pub overpotential_max_v: f64,
    /// Whether the bounds were given (the options) rather than chosen from the data.
    pub given: bool,
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
    /// Whether E_corr was given (the option or the scene) rather than taken from the table.
    pub corrosion_potential_given: bool,
    /// Where E_corr came from.
    pub corrosion_potential_source: CorrosionPotentialSource,
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
    /// The domain's points whose residual lies more than 3.5 robust standard deviations
    /// from the median (each also in `residuals`; the fit keeps them).
    pub outliers: Vec<TafelResidual>,
    /// What the fit assumed: where E_corr came from, how the domain was cut.
    pub warnings: Vec<String>,
    /// The scene with `corrosion` E_corr, a_c, b_c and the domain filled in.
    pub scene: Scene,
}

/// Fits a_c and b_c to a cathodic polarization curve.
pub fn fit_tafel(
    table: &Table,
    scene: &Scene,
    options: TafelOptions,
) -> Result<TafelFit, CalibrationError> {
    check_bounds(options)?;
    let (potential, current) = curve(table)?;
    let (e_corr, source, mut warnings) = corrosion_potential(&potential, &current, scene, options)?;
    warnings.extend(checks::potential(e_corr)?);
    let branch = cathodic_branch(&potential, &current, e_corr)?;
    checks::mixed_units(&branch)?;
    let etas: Vec<f64> = branch.iter().map(|p| p.0).collect();
    let logs: Vec<f64> = branch.iter().map(|p| p.1).collect();
    let (start, end) = domain(&etas, &logs, e_corr, options, &mut warnings)?;
    let (etas, logs) = (&etas[start..end], &logs[start..end]);
    require_measurable(etas, e_corr)?;
    let line = Line::fit(etas, logs);
    if line.slope >= 0.0 {
        return Err(CalibrationError::NoTafelDomain(
            "|i| does not grow as the potential falls".to_owned(),
        ));
    }
    let fit = finish(scene, e_corr, &line, etas, logs);
    warnings.extend(checks::line(
        fit.tafel_b_c_v_per_decade.value,
        fit.corrosion_current_density_a_cm2,
    )?);
    let outliers = checks::outliers(&fit.residuals);
    if let Some(worst) = outliers.iter().max_by(|a, b| {
        a.residual_decades
            .abs()
            .total_cmp(&b.residual_decades.abs())
    }) {
        warnings.push(format!(
            "{} of the domain's {} points lie more than 3.5 robust standard deviations off the \
             line (`outliers`), the worst at {:.4} V by {:+.3} decades; the fit keeps them: \
             check those rows, or narrow the domain",
            outliers.len(),
            etas.len(),
            worst.potential_v,
            worst.residual_decades
        ));
    }
    let given = options.overpotential_max_v.is_some() || options.overpotential_min_v.is_some();
    Ok(TafelFit {
        corrosion_potential_given: source != CorrosionPotentialSource::SignChange,
        corrosion_potential_source: source,
        warnings,
        outliers,
        domain: TafelDomain {
            given,
            ..fit.domain
        },
        ..fit
    })
}

/// The cathodic branch below `e_corr`, most cathodic first: E - E_corr, log10 |i| and the
/// table's row (from 1).
fn cathodic_branch(
    potential: &[f64],
    current: &[f64],
    e_corr: f64,
) -> Result<Vec<(f64, f64, usize)>, CalibrationError> {
    let mut branch: Vec<(f64, f64, usize)> = potential
        .iter()
        .zip(current)
        .enumerate()
        .filter(|&(_, (&e, &i))| e < e_corr && i != 0.0)
        .map(|(row, (&e, &i))| (e - e_corr, i.abs().log10(), row + 1))
        .collect();
    branch.sort_by(|a, b| a.0.total_cmp(&b.0));
    let etas: Vec<f64> = branch.iter().map(|p| p.0).collect();
    require_increasing("potential_v", &etas)?;
    if branch.len() < MIN_DOMAIN_POINTS {
        return Err(CalibrationError::NoTafelDomain(format!(
            "{} points below E_corr = {e_corr} V, a domain needs {MIN_DOMAIN_POINTS}",
            branch.len()
        )));
    }
    Ok(branch)
}

/// Refuses a domain bound outside the scene's range of Tafel overpotentials, or bounds in
/// the wrong order.
fn check_bounds(options: TafelOptions) -> Result<(), CalibrationError> {
    let (low, high) = TAFEL_OVERPOTENTIAL_RANGE_V;
    let bounds = [
        (MAX_OPTION, options.overpotential_max_v),
        (MIN_OPTION, options.overpotential_min_v),
    ];
    for ((option, flag), value) in bounds {
        let Some(value) = value else { continue };
        if !(low..high).contains(&value) {
            let slip = if value.abs() > high - low {
                format!("was it in mV? {value} mV = {} V", value * 1e-3)
            } else {
                "a value at or above 0 lies above E_corr: was it E rather than E - E_corr, or \
                 its sign left out?"
                    .to_owned()
            };
            return Err(CalibrationError::DomainOption {
                option,
                flag,
                value,
                why: format!(
                    "an overpotential E - E_corr of the cathodic branch, from {low} V to below \
                     {high} V: {slip}"
                ),
            });
        }
    }
    if let (Some(max), Some(min)) = (options.overpotential_max_v, options.overpotential_min_v) {
        if max <= min {
            return Err(CalibrationError::DomainOption {
                option: MAX_OPTION.0,
                flag: MAX_OPTION.1,
                value: max,
                why: format!("must lie above {} = {min} V (nearer E_corr)", MIN_OPTION.0),
            });
        }
    }
    Ok(())
}

/// The domain's first and last-plus-one index into `etas` (E - E_corr, increasing): the
/// options' bounds, else from the scan's end up to where [`chosen_end`] stops.
fn domain(
    etas: &[f64],
    logs: &[f64],
    e_corr: f64,
    options: TafelOptions,
    warnings: &mut Vec<String>,
) -> Result<(usize, usize), CalibrationError> {
    let start = options
        .overpotential_min_v
        .map_or(0, |min| etas.partition_point(|&eta| eta < min));
    let (etas, logs) = (&etas[start..], &logs[start..]);
    let end = match options.overpotential_max_v {
        Some(max) => etas.partition_point(|&eta| eta <= max),
        None if etas.len() < MIN_DOMAIN_POINTS => etas.len(),
        None => chosen_end(etas, logs, e_corr, warnings)?,
    };
    Ok((start, start + end))
}

/// Where the data's straight stretch from the most cathodic point ends, cut back by
/// [`BEND_MARGIN`]; where the margin's end lies past the scan's end, or leaves too few
/// points or too little span to measure a line on, the stretch's own end, with a warning:
/// the margin once put the domain's end past the scan's and refused a clean curve.
fn chosen_end(
    etas: &[f64],
    logs: &[f64],
    e_corr: f64,
    warnings: &mut Vec<String>,
) -> Result<usize, CalibrationError> {
    let straight = straight_end(etas, logs).ok_or_else(|| {
        CalibrationError::NoTafelDomain(format!(
            "log10 |i| bends by more than {CURVATURE_LIMIT} standard errors of its curvature on every stretch of {MIN_DOMAIN_POINTS} or more points from the most cathodic one"
        ))
    })?;
    if straight == etas.len() {
        return Ok(straight);
    }
    let stop = etas[straight - 1];
    let margin = BEND_MARGIN * stop;
    let end = etas.partition_point(|&eta| eta <= margin);
    let bent = format!(
        "the curve bends away from a line above {:.4} V",
        stop + e_corr
    );
    if end >= MIN_TAFEL_POINTS && margin - etas[0] >= MIN_DOMAIN_SPAN_V {
        warnings.push(format!(
            "{bent}; the domain ends at {:.4} V, twice as far below E_corr, where the anodic \
             current's bend is below the noise",
            margin + e_corr
        ));
        return Ok(end);
    }
    warnings.push(format!(
        "{bent}; twice as far below E_corr, {:.4} V, leaves too little of the scan (it ends \
         at {:.4} V), so the domain ends where the curve bends, where the anodic current's bend \
         is up to the noise and may bias a_c and b_c by a few standard errors; `{}` sets the \
         end",
        margin + e_corr,
        etas[0] + e_corr,
        MAX_OPTION.1
    ));
    Ok(straight)
}

/// E_corr and where it came from (with the words that say so): the option, where the
/// current changes sign, or the lab's scene; refused otherwise.
fn corrosion_potential(
    potential: &[f64],
    current: &[f64],
    scene: &Scene,
    options: TafelOptions,
) -> Result<(f64, CorrosionPotentialSource, Vec<String>), CalibrationError> {
    if let Some(given) = options.corrosion_potential_v {
        return Ok((given, CorrosionPotentialSource::Option, Vec::new()));
    }
    let crossings = sign_changes(potential, current);
    if !crossings.is_empty() {
        let mut sorted = crossings;
        sorted.sort_by(f64::total_cmp);
        let median = sorted[sorted.len() / 2];
        let mut words = format!("E_corr = {median:.4} V, where the measured current changes sign");
        if sorted.len() > 1 {
            words.push_str(&format!(
                " (the median of {} sign changes between {:.4} and {:.4} V: the current is \
                 at the noise there)",
                sorted.len(),
                sorted[0],
                sorted[sorted.len() - 1]
            ));
        }
        return Ok((median, CorrosionPotentialSource::SignChange, vec![words]));
    }
    match scene.corrosion.as_ref() {
        Some(corrosion) if options.scene_corrosion_potential => {
            let e_corr = corrosion.corrosion_potential_v;
            Ok((
                e_corr,
                CorrosionPotentialSource::Scene,
                vec![format!(
                    "E_corr = {e_corr} V from the scene: the curve's current never changes \
                     sign, so it does not show E_corr itself"
                )],
            ))
        }
        _ => Err(CalibrationError::CorrosionPotentialUnknown),
    }
}

/// The potentials at which the current changes sign, interpolated linearly between the two
/// points either side (a zero current is a crossing where it lies).
fn sign_changes(potential: &[f64], current: &[f64]) -> Vec<f64> {
    let mut points: Vec<(f64, f64)> = potential
        .iter()
        .copied()
        .zip(current.iter().copied())
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut crossings: Vec<f64> = points.iter().filter(|p| p.1 == 0.0).map(|p| p.0).collect();
    for pair in points.windows(2) {
        let ((e0, i0), (e1, i1)) = (pair[0], pair[1]);
        if i0 * i1 < 0.0 {
            crossings.push(e0 - i0 * (e1 - e0) / (i1 - i0));
        }
    }
    crossings
}

/// Refuses a domain (`etas`, E - E_corr, increasing) too narrow to show a Tafel line.
fn require_measurable(etas: &[f64], e_corr: f64) -> Result<(), CalibrationError> {
    let span = etas
        .last()
        .zip(etas.first())
        .map_or(0.0, |(top, bottom)| top - bottom);
    if etas.len() < MIN_TAFEL_POINTS {
        return Err(CalibrationError::NarrowTafelDomain(format!(
            "{} points, a measurable Tafel line needs at least {MIN_TAFEL_POINTS} (the \
             standard errors rest on the scatter of n - 2 residuals)",
            etas.len()
        )));
    }
    if span < MIN_DOMAIN_SPAN_V {
        return Err(CalibrationError::NarrowTafelDomain(format!(
            "{:.1} mV ({:.4} to {:.4} V), a Tafel line needs at least {:.0} mV (2 RT / F: \
             over less, a line cannot be told from the curvature of the mixed region near \
             E_corr)",
            span * 1e3,
            etas[0] + e_corr,
            etas[etas.len() - 1] + e_corr,
            MIN_DOMAIN_SPAN_V * 1e3
        )));
    }
    Ok(())
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
                .missing(&["current_density_a_cm2", "current_density_a_m2"])
                .into());
        }
    };
    Ok((potential, current))
}

/// The line's values, their errors by propagation, the residuals and the scene (E_corr's
/// source and the warnings are the caller's).
fn finish(scene: &Scene, e_corr: f64, line: &Line, etas: &[f64], logs: &[f64]) -> TafelFit {
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
    corrosion.tafel_overpotential_min_v = etas[0];
    corrosion.tafel_overpotential_max_v = etas[etas.len() - 1];
    TafelFit {
        corrosion_potential_v: e_corr,
        corrosion_potential_given: true,
        corrosion_potential_source: CorrosionPotentialSource::Option,
        warnings: Vec::new(),
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
            overpotential_min_v: etas[0],
            overpotential_max_v: etas[etas.len() - 1],
            given: false,
            points: etas.len(),
        },
        rms_residual_decades: (rss / etas.len() as f64).sqrt(),
        outliers: Vec::new(),
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
    // Noise-free data leave only round-off in the residuals, against which any bend is
    // significant; floor the scatter at the current's resolution, below which no measured
    // curve shows a bend.
    let scatter = (rss / (xs.len() as f64 - 3.0)).max(RESOLUTION_DECADES.powi(2));
    let se = (scatter * inverse[(2, 2)]).sqrt();
    c[2].abs() / se
}

#[cfg(test)]
mod tests;
