//! What the model offers the anodic area at each measured time, from one run of the scene:
//! the real contact F / H(t) of the hardness law (exact at any time), and the solved
//! contact's area and mean chord and the wear track, interpolated between solved cycles. In
//! the model the corrosion does not feed back on the wear, so one run serves every value of
//! the fitted parameter.

use std::sync::atomic::AtomicBool;

use super::super::{CalibrationError, interpolate};
use crate::corrosion::{AreaInputs, real_contact_area_m2};
use crate::scene::{AnodicArea, Scene};
use crate::simulation::{Plan, RunOptions, Setup, run_setup};

/// The model's areas at each measured time, and the run that gave them.
pub(in crate::calibration) struct ModelAreas {
    /// What each time offers the anodic area models.
    pub(in crate::calibration) inputs: Vec<AreaInputs>,
    /// Cells per side of the run's first grid.
    pub(in crate::calibration) grid_cells: usize,
}

/// Runs `scene` to the last of `rubbing_times_s` (its own numerics: the fit's parameter is
/// then the one its default run would need) and reads the areas at each time.
pub(in crate::calibration) fn model_areas(
    scene: &Scene,
    rubbing_times_s: &[f64],
) -> Result<ModelAreas, CalibrationError> {
    let cycles: Vec<f64> = rubbing_times_s
        .iter()
        .map(|&t| scene.cycles_at(t))
        .collect();
    let mut run_scene = scene.clone();
    run_scene.test.cycles = cycles.iter().fold(1.0_f64, |m, &n| m.max(n)).ceil() as u64;
    // The wear track's area is read from the records; the fit's own area is rebuilt from
    // the inputs for every trial value.
    if let Some(c) = run_scene.corrosion.as_mut() {
        c.anodic_area = AnodicArea::WearTrack;
        c.anodic_area_factor = 1.0;
    }
    let plan = Plan::new(run_scene)?;
    let band_width_m = 2.0 * plan.hertz().contact_radius_m();
    let setup = Setup::new(&plan, &RunOptions::default())?;
    let result = run_setup(&setup, &mut |_| {}, &AtomicBool::new(false))?;
    let solved: Vec<f64> = result.cycles.iter().map(|r| r.cycle as f64).collect();
    let column = |f: &dyn Fn(&crate::simulation::CycleRecord) -> f64| -> Vec<f64> {
        result.cycles.iter().map(f).collect()
    };
    let track = column(&|r| r.anodic_area_mm2.unwrap_or(0.0) * 1e-6);
    let contact = column(&|r| r.contact_area_mm2 * 1e-6);
    let chord = column(&|r| r.contact_chord_um.unwrap_or(f64::NAN) * 1e-6);
    let law = scene.hardness_law()?;
    let inputs = cycles
        .iter()
        .map(|&n| {
            let chord_m = interpolate(&solved, &chord, n);
            AreaInputs {
                real_contact_m2: real_contact_area_m2(scene.load_n(), law.hardness_pa(n)),
                contact_area_m2: interpolate(&solved, &contact, n),
                mean_chord_m: chord_m.is_finite().then_some(chord_m),
                wear_track_m2: interpolate(&solved, &track, n),
                band_width_m,
                sliding_speed_m_s: scene.sliding_speed_m_s(),
                // The fit refuses the spot models (`refuse_predictions`).
                spot_area_m2: 0.0,
            }
        })
        .collect();
    Ok(ModelAreas {
        inputs,
        grid_cells: setup.grid.nx,
    })
}
