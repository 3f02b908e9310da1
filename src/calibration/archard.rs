//! Archard's k from measured wear volumes (paper Table 3): `cycles` or `time_s`,
//! `volume_mm3`, optional `spread_mm3`.
//!
//! The model's volume is the yield groove of the first cycles plus Archard wear, so it is not
//! proportional to k and eq. 14 alone does not fit it. A measured volume is a total (ASTM
//! G119: the profilometer sees the mechanical loss and the corrosion together): when the
//! scene has corrosion, the runs' totals (wear plus WAC) are compared with it, so that k is
//! the mechanical part's ([`VolumeCompared`]). The fit minimises the squared
//! residuals of whole simulated runs over ln k by golden section on a bracket around eq. 14's
//! k from the last point; each run goes to the last measured cycle on the calibration grid.
//! Each run starts cold: the simulation's warm start lives inside one run.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use serde::Serialize;

use super::minimise::{Trial, golden_section, standard_error};
use super::{
    CalibrationError, Estimate, Table, calibration_scene, cycles_of, interpolate, require_at_least,
    require_increasing, require_points,
};
use crate::scene::{ArchardRegimeChange, Scene};
use crate::simulation::{Plan, run};
use crate::wear::{VolumeBasis, archard_k_from_measurement};

/// Settings of the Archard fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArchardOptions {
    /// The search brackets k within this factor either side of eq. 14's k.
    pub span: f64,
    /// Relative precision of k at which the search stops. The default 1e-3 is ten times the
    /// cycle stepping's own error on the volume (1e-4, `STEP_CHANGE_BOUND`'s measurement).
    pub tolerance: f64,
}

impl Default for ArchardOptions {
    fn default() -> Self {
        Self {
            span: 10.0,
            tolerance: 1e-3,
        }
    }
}

/// Which of the model's volumes the measured ones are compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VolumeCompared {
    /// The total, wear plus wear-accelerated corrosion: the scene has corrosion, and k is
    /// fitted on the mechanical part of the measured totals.
    Total,
    /// The wear alone: the scene has no corrosion, so the measured volume is taken as
    /// mechanical.
    Mechanical,
}

/// One measured volume against the fitted run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct VolumeResidual {
    /// Cycle count.
    pub cycles: f64,
    /// Measured volume, mm^3.
    pub volume_mm3: f64,
    /// Its stated spread, mm^3, if the table has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spread_mm3: Option<f64>,
    /// The fitted run's volume at this cycle (its total with corrosion), mm^3.
    pub model_volume_mm3: f64,
    /// The fitted run's wear-accelerated corrosion volume at this cycle, mm^3; absent
    /// without corrosion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_wac_volume_mm3: Option<f64>,
    /// Measured minus model, mm^3.
    pub residual_mm3: f64,
    /// The run at eq. 14's k, mm^3.
    pub eq14_model_volume_mm3: f64,
}

/// The fitted Archard coefficient.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArchardFit {
    /// k fitted over whole runs.
    pub archard_k: Estimate,
    /// k by eq. 14 from the last point alone, V H / (F s) with H from the scene's law.
    pub eq14_archard_k: f64,
    /// Whether residuals were weighted by 1 / spread (only when every spread is positive).
    pub weighted: bool,
    /// Which model volume the measured ones are compared with.
    pub volume_compared: VolumeCompared,
    /// Each point.
    pub residuals: Vec<VolumeResidual>,
    /// Residual sum of squares of the fitted run (weighted when `weighted`), mm^6 unweighted.
    pub rss: f64,
    /// Root-mean-square residual of the fitted run, mm^3.
    pub rms_residual_mm3: f64,
    /// Root-mean-square residual of the run at eq. 14's k, mm^3.
    pub eq14_rms_residual_mm3: f64,
    /// Every k the search tried, with its (weighted) residual sum of squares.
    pub tried: Vec<Trial>,
    /// Cells per side of the runs.
    pub grid_cells: usize,
    /// Simulated runs made.
    pub runs: usize,
    /// Wall time of the calibration, s.
    pub wall_s: f64,
    /// The scene with `wear.archard_k` filled in.
    pub scene: Scene,
}

/// The measurements, and the runs they are compared with.
pub(super) struct Problem {
    /// The measured cycles, increasing.
    pub(super) cycles: Vec<f64>,
    /// The measured volumes, mm^3.
    pub(super) volumes: Vec<f64>,
    /// The stated spreads, mm^3.
    pub(super) spreads: Option<Vec<f64>>,
    /// Each residual's weight.
    pub(super) weights: Vec<f64>,
    /// Whether the weights are 1 / spread.
    pub(super) weighted: bool,
    /// The scene of the runs: to the last measured cycle, on the calibration grid.
    pub(super) scene: Scene,
    /// Cells per side of the runs.
    pub(super) grid_cells: usize,
    /// Runs made so far.
    pub(super) runs: usize,
    /// Set by the caller to stop the fit: its run under way ends within a cycle.
    pub(super) cancel: Arc<AtomicBool>,
}

impl Problem {
    /// A problem whose volumes are made by the model rather than measured: runs of `scene`
    /// (on `grid_cells` cells) at `cycles`, unweighted; the volumes to fit start at 0.
    #[cfg(test)]
    pub(super) fn maker(cycles: &[f64], scene: Scene, grid_cells: usize) -> Self {
        Self {
            cycles: cycles.to_vec(),
            volumes: vec![0.0; cycles.len()],
            spreads: None,
            weights: vec![1.0; cycles.len()],
            weighted: false,
            scene,
            grid_cells,
            runs: 0,
            cancel: Arc::default(),
        }
    }

    /// The model's volumes at the measured cycles for `k`, mm^3.
    fn volumes_at(&mut self, k: f64) -> Result<Vec<f64>, CalibrationError> {
        self.volumes_with(k, None)
    }

    /// The model's volumes at the measured cycles for `k` after `change` (throughout without
    /// one): the totals with corrosion, else the wear, mm^3.
    pub(super) fn volumes_with(
        &mut self,
        k: f64,
        change: Option<ArchardRegimeChange>,
    ) -> Result<Vec<f64>, CalibrationError> {
        Ok(self.run_with(k, change)?.0)
    }

    /// Which model volume is compared with the measured ones.
    pub(super) fn compared(&self) -> VolumeCompared {
        if self.scene.corrosion.is_some() {
            VolumeCompared::Total
        } else {
            VolumeCompared::Mechanical
        }
    }

    /// [`Self::volumes_with`] and the WAC volumes at the measured cycles (`None` without
    /// corrosion), mm^3.
    pub(super) fn run_with(
        &mut self,
        k: f64,
        change: Option<ArchardRegimeChange>,
    ) -> Result<(Vec<f64>, Option<Vec<f64>>), CalibrationError> {
        let scene = fitted_scene(&self.scene, k, change);
        let result = run(&Plan::new(scene)?, &mut |_| {}, &self.cancel)?;
        self.runs += 1;
        let solved: Vec<f64> = result.cycles.iter().map(|r| r.cycle as f64).collect();
        let at = |values: &[f64]| -> Vec<f64> {
            self.cycles
                .iter()
                .map(|&n| interpolate(&solved, values, n))
                .collect()
        };
        let totals: Vec<f64> = result
            .cycles
            .iter()
            .map(|r| r.total_volume_mm3.unwrap_or(r.wear_volume_mm3))
            .collect();
        let wac: Option<Vec<f64>> = result.cycles.iter().map(|r| r.wac_volume_mm3).collect();
        Ok((at(&totals), wac.as_deref().map(at)))
    }

    /// Weighted residuals, measured minus model.
    fn residuals_at(&mut self, k: f64) -> Result<Vec<f64>, CalibrationError> {
        let model = self.volumes_at(k)?;
        Ok(self.weighted_residuals(&model))
    }

    /// Weighted residuals of the model's volumes `model`, measured minus model.
    pub(super) fn weighted_residuals(&self, model: &[f64]) -> Vec<f64> {
        self.volumes
            .iter()
            .zip(model)
            .zip(&self.weights)
            .map(|((v, m), w)| (v - m) * w)
            .collect()
    }

    /// Root-mean-square of the unweighted residuals of `model`, mm^3.
    pub(super) fn rms(&self, model: &[f64]) -> f64 {
        let sum: f64 = self
            .volumes
            .iter()
            .zip(model)
            .map(|(v, m)| (v - m).powi(2))
            .sum();
        (sum / model.len() as f64).sqrt()
    }
}

/// Fits Archard's k to a wear-volume table over whole simulated runs of `scene`.
pub fn fit_archard(
    table: &Table,
    scene: &Scene,
    options: ArchardOptions,
) -> Result<ArchardFit, CalibrationError> {
    fit_archard_until(table, scene, options, &Arc::default())
}

/// [`fit_archard`], stopped (failing with the run's `Cancelled`) once `cancel` is set.
pub fn fit_archard_until(
    table: &Table,
    scene: &Scene,
    options: ArchardOptions,
    cancel: &Arc<AtomicBool>,
) -> Result<ArchardFit, CalibrationError> {
    let started = Instant::now();
    let mut problem = problem(table, scene)?;
    problem.cancel = Arc::clone(cancel);
    let eq14 = eq14_k(&problem, scene)?;
    let bracket = (eq14 / options.span, eq14 * options.span);
    let (k, tried) = golden_section("archard_k", bracket, options.tolerance, &mut |k| {
        Ok(problem.residuals_at(k)?.iter().map(|r| r * r).sum())
    })?;
    let best = problem.residuals_at(k)?;
    // A step of 1% in k: far above the stepping's 1e-4 noise on the volume, and small
    // enough that the volume is linear in k across it.
    let se = standard_error(k, &best, 0.01, &mut |q| problem.residuals_at(q))?;
    let (fitted, wac) = problem.run_with(k, None)?;
    let at_eq14 = problem.volumes_at(eq14)?;
    let residuals: Vec<VolumeResidual> = (0..problem.cycles.len())
        .map(|j| VolumeResidual {
            cycles: problem.cycles[j],
            volume_mm3: problem.volumes[j],
            spread_mm3: problem.spreads.as_ref().map(|s| s[j]),
            model_volume_mm3: fitted[j],
            model_wac_volume_mm3: wac.as_ref().map(|w| w[j]),
            residual_mm3: problem.volumes[j] - fitted[j],
            eq14_model_volume_mm3: at_eq14[j],
        })
        .collect();
    let filled = fitted_scene(scene, k, None);
    Ok(ArchardFit {
        archard_k: Estimate {
            value: k,
            standard_error: se,
        },
        eq14_archard_k: eq14,
        weighted: problem.weighted,
        volume_compared: problem.compared(),
        rss: best.iter().map(|r| r * r).sum(),
        rms_residual_mm3: problem.rms(&fitted),
        eq14_rms_residual_mm3: problem.rms(&at_eq14),
        residuals,
        tried,
        grid_cells: problem.grid_cells,
        runs: problem.runs,
        wall_s: started.elapsed().as_secs_f64(),
        scene: filled,
    })
}

/// Refuses a table the Archard fit cannot use, naming the column and row, without running
/// anything: the cheap part of [`fit_archard`].
pub(super) fn check(table: &Table, scene: &Scene) -> Result<(), CalibrationError> {
    eq14_k(&problem(table, scene)?, scene).map(drop)
}

/// Eq. 14's k from the last point, with H from the scene's law; refused when not positive.
fn eq14_k(problem: &Problem, scene: &Scene) -> Result<f64, CalibrationError> {
    let last = problem.cycles.len() - 1;
    let (n_last, v_last) = (problem.cycles[last], problem.volumes[last]);
    let law = scene.hardness_law()?;
    let eq14 = archard_k_from_measurement(
        v_last * 1e-9,
        law.hardness_pa(n_last),
        scene.load_n(),
        n_last * scene.track_length_m(),
    );
    if eq14 <= 0.0 {
        return Err(CalibrationError::BelowMinimum {
            column: "volume_mm3",
            row: last + 1,
            value: v_last,
            minimum: f64::MIN_POSITIVE,
        });
    }
    Ok(eq14)
}

/// The checked measurements and the scene the runs use.
pub(super) fn problem(table: &Table, scene: &Scene) -> Result<Problem, CalibrationError> {
    let (cycles, cycle_column) = cycles_of(table, scene)?;
    let volumes = table.column("volume_mm3")?.to_vec();
    // One parameter and at least one degree of freedom for the scatter.
    require_points(cycle_column, &cycles, 2)?;
    require_at_least(cycle_column, &cycles, f64::MIN_POSITIVE)?;
    require_increasing(cycle_column, &cycles)?;
    require_at_least("volume_mm3", &volumes, 0.0)?;
    let spreads = table.optional("spread_mm3").map(<[f64]>::to_vec);
    if let Some(spreads) = &spreads {
        require_at_least("spread_mm3", spreads, 0.0)?;
    }
    // Inverse-spread weights need every spread positive; Table 3 states 0.0 at 300 s, so
    // such a table is fitted unweighted.
    let weighted = spreads.as_ref().is_some_and(|s| s.iter().all(|&x| x > 0.0));
    let weights = match &spreads {
        Some(s) if weighted => s.iter().map(|x| 1.0 / x).collect(),
        _ => vec![1.0; cycles.len()],
    };
    let (run_scene, grid_cells) = calibration_scene(scene, cycles[cycles.len() - 1]);
    Ok(Problem {
        cycles,
        volumes,
        spreads,
        weights,
        weighted,
        scene: run_scene,
        grid_cells,
        runs: 0,
        cancel: Arc::default(),
    })
}

#[cfg(test)]
mod tests;

/// `scene` with the fitted `k` and `change` in place of its own wear coefficients. The fit
/// matches the measured totals with the run's total: the groove plus its corrosion when the
/// scene has a cell, so k is then the mechanical loss's (`wear.archard_k_basis`
/// `mechanical`), and the groove alone without one, the total loss's.
pub(super) fn fitted_scene(scene: &Scene, k: f64, change: Option<ArchardRegimeChange>) -> Scene {
    let mut fitted = scene.clone();
    fitted.wear.archard_k = Some(k);
    fitted.wear.archard_calibration = None;
    fitted.wear.archard_regime_change = change;
    fitted.wear.archard_k_basis = if scene.corrosion.is_some() {
        VolumeBasis::Mechanical
    } else {
        VolumeBasis::TotalLoss
    };
    fitted
}
