//! One entry point for every fit: which fit ([`FitKind`]), its settings, the cheap check of
//! a table before any run ([`check`]) and the fit itself ([`calibrate`]), as the command line
//! and the service call them.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use serde::{Deserialize, Serialize};

use super::{
    ArchardFit, ArchardOptions, CalibrationError, ChangeCycle, HardnessFit, HardnessOptions,
    OcpFit, OcpOptions, RegimeFit, RegimeOptions, Table, TafelFit, TafelOptions, archard,
    calibration_scene, cycles_of, fit_archard_regimes_until, fit_archard_until, fit_hardness,
    fit_ocp, fit_tafel, ocp, regime,
};
use crate::scene::{Scene, dalmau2018_316l};
use crate::simulation::Plan;

/// Which fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FitKind {
    /// H = A + B ln n from `cycles` (or `time_s`) and `hardness_mpa`.
    Hardness,
    /// a_c, b_c from `potential_v` and `current_density_a_cm2` (or `_a_m2`).
    Tafel,
    /// The depassivation model's parameter from `time_s` and `potential_v`: the OCP, which
    /// a job's measurements call `ocp` too (`potential` is accepted for it in both).
    #[value(alias = "potential")]
    #[serde(alias = "potential")]
    Ocp,
    /// Archard's k from `time_s` (or `cycles`), `volume_mm3` and optional `spread_mm3`.
    Archard,
}

/// The settings of the fits the command line and the service expose.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CommandOptions {
    /// Hardness: leave the scene's bulk value out of the fit.
    pub without_bulk: bool,
    /// Tafel: E_corr, V.
    pub corrosion_potential_v: Option<f64>,
    /// Tafel: the domain's least cathodic end, E - E_corr, V; absent: from the data.
    pub tafel_overpotential_max_v: Option<f64>,
    /// Tafel: the domain's most cathodic end, E - E_corr, V; absent: the scan's end.
    pub tafel_overpotential_min_v: Option<f64>,
    /// Tafel: whether the scene is the lab's own (given by the caller, not the default
    /// preset), so that its E_corr may stand for a curve that does not show one.
    pub scene_given: bool,
    /// OCP: when the rubbing started and stopped on the table's clock, s.
    pub rubbing_start_s: Option<f64>,
    /// OCP: when the rubbing stopped, s.
    pub rubbing_stop_s: Option<f64>,
    /// Archard: also fit a change of regime at this cycle (or the best one), against one k.
    pub regime_change: Option<ChangeCycle>,
}

impl CommandOptions {
    fn hardness(self) -> HardnessOptions {
        HardnessOptions {
            include_bulk: !self.without_bulk,
        }
    }

    fn tafel(self) -> TafelOptions {
        TafelOptions {
            corrosion_potential_v: self.corrosion_potential_v,
            scene_corrosion_potential: self.scene_given,
            overpotential_max_v: self.tafel_overpotential_max_v,
            overpotential_min_v: self.tafel_overpotential_min_v,
        }
    }

    fn ocp(self) -> OcpOptions {
        OcpOptions {
            rubbing_start_s: self.rubbing_start_s,
            rubbing_stop_s: self.rubbing_stop_s,
        }
    }
}

/// A fit of any kind; its JSON is the fit's own (`tribosim calibrate -o`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Fit {
    /// The hardness law.
    Hardness(HardnessFit),
    /// The Tafel line.
    Tafel(TafelFit),
    /// The depassivated area.
    Ocp(OcpFit),
    /// Archard's k.
    Archard(ArchardFit),
    /// Archard's k with a change of regime, beside one k.
    Regimes(Box<RegimeFit>),
}

/// Fits `table` with `scene`. The Archard fit runs whole simulations (seconds to minutes),
/// the OCP fit one; the others are immediate.
pub fn calibrate(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
    options: CommandOptions,
) -> Result<Fit, CalibrationError> {
    calibrate_until(kind, table, scene, options, &Arc::default())
}

/// [`calibrate`], stopped once `cancel` is set: an Archard fit's run under way ends within a
/// cycle and the fit fails with the run's `Cancelled`. The OCP fit's single run and the
/// immediate fits are not interrupted.
pub fn calibrate_until(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
    options: CommandOptions,
    cancel: &Arc<AtomicBool>,
) -> Result<Fit, CalibrationError> {
    Ok(match kind {
        FitKind::Hardness => Fit::Hardness(fit_hardness(table, scene, options.hardness())?),
        FitKind::Tafel => Fit::Tafel(fit_tafel(table, scene, options.tafel())?),
        FitKind::Ocp => Fit::Ocp(fit_ocp(table, scene, options.ocp())?),
        FitKind::Archard => match options.regime_change {
            None => Fit::Archard(fit_archard_until(
                table,
                scene,
                ArchardOptions::default(),
                cancel,
            )?),
            Some(change) => {
                let options = RegimeOptions {
                    change,
                    archard: ArchardOptions::default(),
                };
                let fit = fit_archard_regimes_until(table, scene, options, cancel)?;
                Fit::Regimes(Box::new(fit))
            }
        },
    })
}

/// The size of each simulated run a fit makes: the cells per side of its grid and the
/// cycles it goes to (the table's last point). A caller bounds a fit's memory by the cells
/// and its CPU time by cells squared times cycles, before the fit runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunSize {
    /// Cells per side.
    pub cells: usize,
    /// Cycles each run goes to.
    pub cycles: u64,
}

impl RunSize {
    /// Cells times cycles: the work of a run that solves every cycle, an upper bound on one
    /// whose stepping skips some.
    pub fn cell_cycles(self) -> u64 {
        let cells = self.cells as u64;
        cells.saturating_mul(cells).saturating_mul(self.cycles)
    }
}

/// The size of the runs a fit of `kind` makes (`None` for the fits that make none), from the
/// table's last point and the scene's grid.
pub fn run_size(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
) -> Result<Option<RunSize>, CalibrationError> {
    Ok(run_scene(kind, table, scene)?.map(|(run, cells)| RunSize {
        cells,
        cycles: run.test.cycles,
    }))
}

/// The scene of a fit's simulated runs and its cells per side, `None` for a fit without.
fn run_scene(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
) -> Result<Option<(Scene, usize)>, CalibrationError> {
    if matches!(kind, FitKind::Hardness | FitKind::Tafel) {
        return Ok(None);
    }
    let (cycles, _) = cycles_of(table, scene)?;
    let last = cycles.iter().copied().fold(0.0, f64::max);
    Ok(Some(calibration_scene(scene, last)))
}

/// Refuses what [`calibrate`] would refuse about the table and the scene (column and row
/// named) without any simulated run: the immediate fits are made and dropped, the others
/// checked up to their runs, and their runs' scene (to the table's last point) checked as
/// the simulation checks a scene, so a last point past the cycle limit is refused here. A
/// fit that passes may still fail later (not converging).
pub fn check(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
    options: CommandOptions,
) -> Result<(), CalibrationError> {
    match kind {
        FitKind::Hardness | FitKind::Tafel => calibrate(kind, table, scene, options).map(drop),
        FitKind::Ocp => ocp::trace(table, scene, options.ocp()).map(drop),
        FitKind::Archard => match options.regime_change {
            None => archard::check(table, scene),
            Some(change) => regime::check(table, scene, change),
        },
    }?;
    if let Some((run, _)) = run_scene(kind, table, scene)? {
        let cycles = run.test.cycles;
        Plan::new(run).map_err(|source| CalibrationError::RunRefused { cycles, source })?;
    }
    Ok(())
}

/// The paper's scene, which a table is fitted with unless a scene is given.
pub fn default_scene() -> Scene {
    dalmau2018_316l()
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::ValueEnum;

    #[test]
    fn the_ocp_fit_is_also_called_potential_as_a_measurement_once_was() {
        assert_eq!(FitKind::from_str("potential", false), Ok(FitKind::Ocp));
        let kind: FitKind = serde_json::from_str("\"potential\"").expect("an alias");
        assert_eq!(kind, FitKind::Ocp);
        assert_eq!(serde_json::to_string(&kind).expect("serialises"), "\"ocp\"");
    }

    #[test]
    fn a_last_point_past_the_cycle_limit_is_refused_before_any_run() {
        let scene = default_scene();
        let options = CommandOptions::default();
        let past = Table::parse("cycles,volume_mm3\n10,0.001\n2000000,0.01\n").expect("a table");
        let err = check(FitKind::Archard, &past, &scene, options).expect_err("past the limit");
        assert!(
            matches!(
                err,
                CalibrationError::RunRefused {
                    cycles: 2_000_000,
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("test.cycles"), "{err}");
        let within = Table::parse("cycles,volume_mm3\n10,0.001\n3600,0.01\n").expect("a table");
        check(FitKind::Archard, &within, &scene, options).expect("within the limit");
        let size = run_size(FitKind::Archard, &within, &scene).expect("a size");
        assert_eq!(
            size,
            Some(RunSize {
                cells: 32,
                cycles: 3600
            })
        );
        assert_eq!(size.map(RunSize::cell_cycles), Some(32 * 32 * 3600));
        let hardness = Table::parse("cycles,hardness_mpa\n10,2551\n60,2727\n").expect("a table");
        assert_eq!(
            run_size(FitKind::Hardness, &hardness, &scene).ok(),
            Some(None)
        );
    }
}
