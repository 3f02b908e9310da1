//! The depassivation model's parameter from a measured open-circuit potential (paper Section
//! 5.1, Figs. 6 and 14): `time_s`, `potential_v`, with the rubbing's start and stop when the
//! table is the whole trace ([`OcpOptions`]).
//!
//! Eq. 18 is inverted at each potential during the rubbing for the depassivated area A_a(t),
//! set against the real contact F / H(t) and the model's wear track. The parameter of the
//! scene's `corrosion.anodic_area` is then fitted by least squares on the potentials during
//! the rubbing: the repassivation time tau for `depassivated_wake` and `hertz_band`,
//! `anodic_area_factor` for the others. Rows before the rubbing are compared with E_corr,
//! rows after it with the model's recovery; neither is fitted (the model's recovery takes a
//! few tau, a measured one is slower: `docs/corrosion.md`).

mod model;
mod phases;

use serde::Serialize;

use super::minimise::{golden_section, standard_error};
use super::{CalibrationError, Estimate, Table};
use crate::corrosion::{AreaInputs, CorrosionModel, recovering_area_m2};
use crate::scene::{AnodicArea, Corrosion, GalvanicCell, Scene};
use crate::simulation::OcpPhase;

use model::model_areas;
pub use phases::OcpOptions;
pub(super) use phases::trace;

/// The factor's search bracket starts here (a thousandth of the chosen area).
const LOWEST_FACTOR: f64 = 1e-3;

/// The repassivation time's search bracket starts here, s: a thousandth of the paper's
/// "milliseconds" (Section 5.1), far below any measurable wake.
const SHORTEST_TAU_S: f64 = 1e-6;

/// The search stops when the parameter is known to this relative precision, far below any
/// measurement's.
const PARAMETER_TOLERANCE: f64 = 1e-7;

/// Which parameter the fit adjusts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum OcpParameter {
    /// `corrosion.repassivation_time_s`.
    RepassivationTimeS,
    /// `corrosion.anodic_area_factor`.
    AnodicAreaFactor,
}

/// One measured potential, its areas and the model's potential.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OcpPoint {
    /// Time on the table's clock, s.
    pub time_s: f64,
    /// Which part of the test the row belongs to.
    pub phase: OcpPhase,
    /// Measured potential, V.
    pub potential_v: f64,
    /// During the rubbing: the depassivated area by eq. 18 inverted, mm^2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub anodic_area_mm2: Option<f64>,
    /// During the rubbing: the real contact area F / H(t), mm^2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub real_contact_area_mm2: Option<f64>,
    /// During the rubbing: the model's wear track (worn width times track length), mm^2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wear_track_area_mm2: Option<f64>,
    /// The model's potential at the fitted parameter, V.
    pub model_potential_v: f64,
    /// Measured minus model potential, V.
    pub residual_v: f64,
    /// Whether the row takes part in the fit (the rows during the rubbing).
    pub fitted: bool,
}

/// The fitted parameter, the areas and the residuals.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OcpFit {
    /// Which model area the parameter belongs to (the scene's `corrosion.anodic_area`).
    pub anodic_area: AnodicArea,
    /// Which parameter was fitted.
    pub parameter: OcpParameter,
    /// The fitted `repassivation_time_s`, s; absent when the factor was fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repassivation_time_s: Option<Estimate>,
    /// Q_p = i_a tau, mC/cm^2, with the same relative standard error; absent when the
    /// factor was fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repassivation_charge_mc_cm2: Option<Estimate>,
    /// The fitted `anodic_area_factor`; absent when tau was fitted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub anodic_area_factor: Option<Estimate>,
    /// Geometric mean over the rubbing rows of A_a / (F / H) (the paper: about 50).
    pub anodic_to_real_contact: f64,
    /// Geometric mean over the rubbing rows of A_a / wear-track area.
    pub anodic_to_wear_track: f64,
    /// Each row.
    pub points: Vec<OcpPoint>,
    /// Root-mean-square potential residual over the rubbing rows, V.
    pub rms_residual_v: f64,
    /// Cells per side of the run that gave the model's areas (the scene's own numerics).
    pub grid_cells: usize,
    /// What the fit assumed that the table may contradict.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// The scene with the parameter filled in and, for a whole trace, its rubbing time and
    /// open-circuit times.
    pub scene: Scene,
}

/// The spot models and the balanced cell are predictions: nothing in them is fitted.
fn refuse_predictions(corrosion: &Corrosion) -> Result<(), CalibrationError> {
    let refused = match (corrosion.anodic_area, corrosion.galvanic_cell) {
        (AnodicArea::AsperitySpots, _) => Some(("anodic_area", "asperity_spots")),
        (AnodicArea::ContactSpots, _) => Some(("anodic_area", "contact_spots")),
        (_, GalvanicCell::Balanced) => Some(("galvanic_cell", "balanced")),
        _ => None,
    };
    refused.map_or(Ok(()), |(field, value)| {
        Err(CalibrationError::NotFittable { field, value })
    })
}

/// Fits the parameter of the scene's anodic area to a measured potential table.
pub fn fit_ocp(
    table: &Table,
    scene: &Scene,
    options: OcpOptions,
) -> Result<OcpFit, CalibrationError> {
    let trace = trace(table, scene, options)?;
    let corrosion = trace.corrosion;
    refuse_predictions(corrosion)?;
    let cell = corrosion.model();
    let rubbing = trace.rubbing();
    let times: Vec<f64> = rubbing.iter().map(|&i| trace.rubbing_time_s(i)).collect();
    let measured: Vec<f64> = rubbing.iter().map(|&i| trace.potentials[i]).collect();
    let areas = model_areas(scene, &times)?;
    let parameter = if corrosion.depassivates() {
        OcpParameter::RepassivationTimeS
    } else {
        OcpParameter::AnodicAreaFactor
    };
    let with = |value: f64| with_parameter(corrosion, parameter, value);
    let residuals = |value: f64| potential_residuals(&cell, &with(value), &measured, &areas.inputs);
    let bracket = match parameter {
        OcpParameter::RepassivationTimeS => (SHORTEST_TAU_S, 0.999 * scene.cycle_period_s()),
        OcpParameter::AnodicAreaFactor => {
            let largest = areas
                .inputs
                .iter()
                .map(|inputs| with(1.0).anodic_area_m2(inputs))
                .fold(0.0_f64, f64::max);
            // Keep the anode below half the electrode so that a cathode remains (eq. 18).
            (LOWEST_FACTOR, 0.5 * cell.exposed_area_m2 / largest)
        }
    };
    let name = match parameter {
        OcpParameter::RepassivationTimeS => "repassivation_time_s",
        OcpParameter::AnodicAreaFactor => "anodic_area_factor",
    };
    let (value, _) = golden_section(name, bracket, PARAMETER_TOLERANCE, &mut |p| {
        Ok(residuals(p).iter().map(|r| r * r).sum())
    })?;
    let best = residuals(value);
    let se = standard_error(value, &best, 1e-3, &mut |p| Ok(residuals(p)))?;
    let estimate = Estimate {
        value,
        standard_error: se,
    };
    let fitted = with(value);
    let points = points(&trace, &cell, &fitted, &areas.inputs);
    let anodic: Vec<f64> = measured.iter().map(|&e| cell.anodic_area_m2(e)).collect();
    let real: Vec<f64> = areas.inputs.iter().map(|a| a.real_contact_m2).collect();
    let track: Vec<f64> = areas.inputs.iter().map(|a| a.wear_track_m2).collect();
    let rms = (best.iter().map(|r| r * r).sum::<f64>() / best.len() as f64).sqrt();
    let q_p = |tau: Estimate| Estimate {
        value: tau.value * corrosion.anodic_current_density_a_cm2 * 1e3,
        standard_error: tau.standard_error * corrosion.anodic_current_density_a_cm2 * 1e3,
    };
    let tau = (parameter == OcpParameter::RepassivationTimeS).then_some(estimate);
    Ok(OcpFit {
        anodic_area: corrosion.anodic_area,
        parameter,
        repassivation_time_s: tau,
        repassivation_charge_mc_cm2: tau.map(q_p),
        anodic_area_factor: (parameter == OcpParameter::AnodicAreaFactor).then_some(estimate),
        anodic_to_real_contact: geometric_mean_ratio(&anodic, &real),
        anodic_to_wear_track: geometric_mean_ratio(&anodic, &track),
        warnings: warnings(&trace, &points, rms),
        rms_residual_v: rms,
        points,
        grid_cells: areas.grid_cells,
        scene: fitted_scene(scene, fitted, &trace, options),
    })
}

/// `corrosion` with `parameter` set to `value`.
fn with_parameter(corrosion: &Corrosion, parameter: OcpParameter, value: f64) -> Corrosion {
    let mut changed = corrosion.clone();
    match parameter {
        OcpParameter::RepassivationTimeS => changed.repassivation_time_s = value,
        OcpParameter::AnodicAreaFactor => changed.anodic_area_factor = value,
    }
    changed
}

/// Measured minus model potential (eq. 18 at the area `corrosion` gives each time's
/// `inputs`), V.
fn potential_residuals(
    cell: &CorrosionModel,
    corrosion: &Corrosion,
    measured: &[f64],
    inputs: &[AreaInputs],
) -> Vec<f64> {
    measured
        .iter()
        .zip(inputs)
        .map(|(&e, inputs)| {
            // The brackets keep the anode below half the electrode, so eq. 18 is defined;
            // E_corr stands in should it ever not be.
            let model = cell
                .potential_v(corrosion.anodic_area_m2(inputs))
                .unwrap_or(cell.corrosion_potential_v);
            e - model
        })
        .collect()
}

/// Every row against the model at the fitted `corrosion`: E_corr before the rubbing, eq. 18
/// during it, the recovery from the last rubbing row's area after it.
fn points(
    trace: &phases::Trace,
    cell: &CorrosionModel,
    corrosion: &Corrosion,
    inputs: &[AreaInputs],
) -> Vec<OcpPoint> {
    let e_corr = cell.corrosion_potential_v;
    let rubbing = trace.rubbing();
    let at_stop = inputs.last().map_or(0.0, |a| corrosion.anodic_area_m2(a));
    let potential = |area: f64| cell.potential_v(area).unwrap_or(e_corr);
    let mut during = rubbing.iter().zip(inputs);
    (0..trace.times.len())
        .map(|i| {
            let measured = trace.potentials[i];
            let phase = trace.phases[i];
            let (model, areas) = match phase {
                OcpPhase::Before => (e_corr, None),
                OcpPhase::Rubbing => {
                    let (_, inputs) = during.next().expect("one input per rubbing row");
                    (potential(corrosion.anodic_area_m2(inputs)), Some(inputs))
                }
                OcpPhase::After => {
                    // The model's rubbing ends at the last rubbing row's area: the table's
                    // stop may fall within a cycle of it.
                    let since = (trace.times[i] - trace.stop_s).max(0.0);
                    let area = recovering_area_m2(at_stop, since, corrosion.repassivation_time_s);
                    (potential(area), None)
                }
            };
            OcpPoint {
                time_s: trace.times[i],
                phase,
                potential_v: measured,
                anodic_area_mm2: areas.map(|_| cell.anodic_area_m2(measured) * 1e6),
                real_contact_area_mm2: areas.map(|a| a.real_contact_m2 * 1e6),
                wear_track_area_mm2: areas.map(|a| a.wear_track_m2 * 1e6),
                model_potential_v: model,
                residual_v: measured - model,
                fitted: phase == OcpPhase::Rubbing,
            }
        })
        .collect()
}

/// What the rows outside the rubbing say against the model's assumptions.
fn warnings(trace: &phases::Trace, points: &[OcpPoint], rms_rubbing_v: f64) -> Vec<String> {
    let mut warnings = Vec::new();
    let rms = |phase: OcpPhase| {
        let residuals: Vec<f64> = points
            .iter()
            .filter(|p| p.phase == phase)
            .map(|p| p.residual_v)
            .collect();
        let n = residuals.len();
        (n > 0).then(|| (residuals.iter().map(|r| r * r).sum::<f64>() / n as f64).sqrt())
    };
    if let Some(before) = rms(OcpPhase::Before).filter(|&r| r > rms_rubbing_v) {
        warnings.push(format!(
            "before the rubbing the potential lies {before:.4} V (rms) from the scene's E_corr \
             ({} V), more than the rubbing rows from the fit ({rms_rubbing_v:.4} V): eq. 18 \
             counts from that E_corr; set `corrosion.corrosion_potential_v` to the measured \
             one",
            trace.corrosion.corrosion_potential_v
        ));
    }
    if let Some(after) = rms(OcpPhase::After) {
        warnings.push(format!(
            "the rows after the stop are not fitted (rms {after:.4} V from the model): the \
             model repassivates the bare area as exp(-t / tau), back at E_corr within a few \
             tau, while a measured recovery also has the slow tail of the film thickening \
             over the whole track, which the model leaves out"
        ));
    }
    warnings
}

/// `scene` with the fitted cell and, for a whole trace, the rubbing's cycles and the
/// open-circuit times around it.
fn fitted_scene(
    scene: &Scene,
    corrosion: Corrosion,
    trace: &phases::Trace,
    options: OcpOptions,
) -> Scene {
    let mut fitted = scene.clone();
    fitted.corrosion = Some(corrosion);
    if let Some(start) = options.rubbing_start_s {
        let last = trace.times[trace.times.len() - 1];
        fitted.test.ocp_before_s = start;
        fitted.test.ocp_after_s = (last - trace.stop_s).max(0.0);
        let cycles = scene.cycles_at(trace.stop_s - start).round().max(1.0);
        fitted.test.cycles = cycles as u64;
    }
    fitted
}

/// exp(mean ln(a / b)) over the pairs with both areas positive.
fn geometric_mean_ratio(a: &[f64], b: &[f64]) -> f64 {
    let logs: Vec<f64> = a
        .iter()
        .zip(b)
        .filter(|&(&x, &y)| x > 0.0 && y > 0.0)
        .map(|(x, y)| (x / y).ln())
        .collect();
    (logs.iter().sum::<f64>() / logs.len() as f64).exp()
}

#[cfg(test)]
mod tests;
