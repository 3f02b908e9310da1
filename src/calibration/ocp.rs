//! The depassivated area from the potential measured during rubbing (paper Section 5.1,
//! Fig. 14): eq. 18 inverted for A_a(t), set against the real contact area F / H(t) of the
//! hardness law and the model's wear-track area, and `corrosion.anodic_area_factor` fitted so
//! that the model's potential follows the measurement.
//!
//! In the model the corrosion does not feed back on the wear, so one run gives the areas for
//! every factor, and the factor is a 1-D least squares on the potentials of that run.

use std::sync::atomic::AtomicBool;

use serde::Serialize;

use super::minimise::{golden_section, standard_error};
use super::{
    CalibrationError, Estimate, Table, calibration_scene, interpolate, require_at_least,
    require_increasing, require_points,
};
use crate::corrosion::{CorrosionModel, real_contact_area_m2};
use crate::scene::{AnodicArea, Corrosion, Scene};
use crate::simulation::{Plan, run};

/// The factor's search bracket starts here (a thousandth of the chosen area).
const LOWEST_FACTOR: f64 = 1e-3;

/// The search stops when the factor is known to this relative precision, far below any
/// measurement's.
const FACTOR_TOLERANCE: f64 = 1e-7;

/// One measured potential and the areas at its time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OcpPoint {
    /// Rubbing time, s.
    pub time_s: f64,
    /// Measured potential, V.
    pub potential_v: f64,
    /// Depassivated area by eq. 18 inverted, mm^2.
    pub anodic_area_mm2: f64,
    /// Real contact area F / H(t), mm^2.
    pub real_contact_area_mm2: f64,
    /// The model's wear-track area (worn width times track length), mm^2.
    pub wear_track_area_mm2: f64,
    /// The model's potential at the fitted factor, V.
    pub model_potential_v: f64,
    /// Measured minus model potential, V.
    pub residual_v: f64,
}

/// The depassivated area and the fitted factor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OcpFit {
    /// Which model area the factor multiplies (the scene's `corrosion.anodic_area`).
    pub anodic_area: AnodicArea,
    /// The fitted `anodic_area_factor`.
    pub anodic_area_factor: Estimate,
    /// Geometric mean over the points of A_a / (F / H) (the paper: about 50).
    pub anodic_to_real_contact: f64,
    /// Geometric mean over the points of A_a / wear-track area.
    pub anodic_to_wear_track: f64,
    /// Each point.
    pub points: Vec<OcpPoint>,
    /// Root-mean-square potential residual, V.
    pub rms_residual_v: f64,
    /// Cells per side of the run that gave the model's areas.
    pub grid_cells: usize,
    /// The scene with `corrosion.anodic_area_factor` filled in.
    pub scene: Scene,
}

/// Inverts eq. 18 over a potential-during-rubbing table (`time_s`, `potential_v`) and fits
/// the scene's anodic area factor to it.
pub fn fit_ocp(table: &Table, scene: &Scene) -> Result<OcpFit, CalibrationError> {
    let (times, potentials, corrosion) = checked(table, scene)?;
    let cell = corrosion.model();
    let cycles: Vec<f64> = times.iter().map(|&t| scene.cycles_at(t)).collect();
    let (run_scene, grid_cells) = calibration_scene(scene, cycles[cycles.len() - 1]);
    let law = scene.hardness_law()?;
    let real: Vec<f64> = cycles
        .iter()
        .map(|&n| real_contact_area_m2(scene.load_n(), law.hardness_pa(n)))
        .collect();
    let track = model_areas(&run_scene, AnodicArea::WearTrack, &cycles)?;
    // F / H is the model's real contact area at any cycle, solved or not: taken exactly
    // rather than interpolated between solved cycles.
    let chosen = match corrosion.anodic_area {
        AnodicArea::WearTrack => track.clone(),
        AnodicArea::RealContact => real.clone(),
        AnodicArea::BemContact => model_areas(&run_scene, AnodicArea::BemContact, &cycles)?,
    };
    let anodic: Vec<f64> = potentials.iter().map(|&e| cell.anodic_area_m2(e)).collect();
    let largest = chosen.iter().fold(0.0_f64, |m, &a| m.max(a));
    // Keep the anode below half the electrode so that a cathode remains (eq. 18).
    let highest = 0.5 * cell.exposed_area_m2 / largest;
    let residuals = |factor: f64| potential_residuals(&cell, potentials, &chosen, factor);
    let (factor, _) = golden_section(
        "anodic_area_factor",
        (LOWEST_FACTOR, highest),
        FACTOR_TOLERANCE,
        &mut |f| Ok(residuals(f).iter().map(|r| r * r).sum()),
    )?;
    let best = residuals(factor);
    let se = standard_error(factor, &best, 1e-3, &mut |f| Ok(residuals(f)))?;
    let points: Vec<OcpPoint> = (0..times.len())
        .map(|j| OcpPoint {
            time_s: times[j],
            potential_v: potentials[j],
            anodic_area_mm2: anodic[j] * 1e6,
            real_contact_area_mm2: real[j] * 1e6,
            wear_track_area_mm2: track[j] * 1e6,
            model_potential_v: potentials[j] - best[j],
            residual_v: best[j],
        })
        .collect();
    let mut fitted = scene.clone();
    if let Some(c) = fitted.corrosion.as_mut() {
        c.anodic_area_factor = factor;
    }
    Ok(OcpFit {
        anodic_area: corrosion.anodic_area,
        anodic_area_factor: Estimate {
            value: factor,
            standard_error: se,
        },
        anodic_to_real_contact: geometric_mean_ratio(&anodic, &real),
        anodic_to_wear_track: geometric_mean_ratio(&anodic, &track),
        rms_residual_v: (best.iter().map(|r| r * r).sum::<f64>() / best.len() as f64).sqrt(),
        points,
        grid_cells,
        scene: fitted,
    })
}

/// The table's times and potentials and the scene's cell, refused (column and row named)
/// unless the fit can use them: the cheap part of [`fit_ocp`], before its run.
pub(super) fn checked<'a>(
    table: &'a Table,
    scene: &'a Scene,
) -> Result<(&'a [f64], &'a [f64], &'a Corrosion), CalibrationError> {
    let times = table.column("time_s")?;
    let potentials = table.column("potential_v")?;
    require_points("time_s", times, 3)?;
    require_at_least("time_s", times, 0.0)?;
    require_increasing("time_s", times)?;
    let corrosion = scene
        .corrosion
        .as_ref()
        .ok_or(CalibrationError::MissingSection("corrosion"))?;
    let e_corr = corrosion.model().corrosion_potential_v;
    if let Some(row) = potentials.iter().position(|&e| e >= e_corr) {
        return Err(CalibrationError::AboveCorrosionPotential {
            row: row + 1,
            value: potentials[row],
            corrosion_potential_v: e_corr,
        });
    }
    scene.hardness_law()?;
    Ok((times, potentials, corrosion))
}

/// The model's anodic area of kind `kind` (factor 1) at each cycle count, m^2.
fn model_areas(
    scene: &Scene,
    kind: AnodicArea,
    cycles: &[f64],
) -> Result<Vec<f64>, CalibrationError> {
    let mut scene = scene.clone();
    if let Some(c) = scene.corrosion.as_mut() {
        c.anodic_area = kind;
        c.anodic_area_factor = 1.0;
    }
    let result = run(&Plan::new(scene)?, &mut |_| {}, &AtomicBool::new(false))?;
    let solved: Vec<f64> = result.cycles.iter().map(|r| r.cycle as f64).collect();
    let areas: Vec<f64> = result
        .cycles
        .iter()
        .map(|r| r.anodic_area_mm2.unwrap_or(0.0) * 1e-6)
        .collect();
    Ok(cycles
        .iter()
        .map(|&n| interpolate(&solved, &areas, n))
        .collect())
}

/// Measured minus model potential (eq. 18 at `factor` times the model's area), V.
fn potential_residuals(
    cell: &CorrosionModel,
    measured: &[f64],
    areas: &[f64],
    factor: f64,
) -> Vec<f64> {
    measured
        .iter()
        .zip(areas)
        .map(|(&e, &a)| {
            // The bracket keeps the anode below half the electrode, so eq. 18 is defined;
            // E_corr stands in should it ever not be.
            let model = cell
                .potential_v(factor * a)
                .unwrap_or(cell.corrosion_potential_v);
            e - model
        })
        .collect()
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
