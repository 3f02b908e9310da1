//! One entry point for every fit: which fit ([`FitKind`]), its settings, the cheap check of
//! a table before any run ([`check`]) and the fit itself ([`calibrate`]), as the command line
//! and the service call them.

use serde::{Deserialize, Serialize};

use super::{
    ArchardFit, ArchardOptions, CalibrationError, ChangeCycle, HardnessFit, HardnessOptions,
    OcpFit, OcpOptions, RegimeFit, RegimeOptions, Table, TafelFit, TafelOptions, archard,
    fit_archard, fit_archard_regimes, fit_hardness, fit_ocp, fit_tafel, ocp, regime,
};
use crate::scene::{Scene, dalmau2018_316l};

/// Which fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FitKind {
    /// H = A + B ln n from `cycles` (or `time_s`) and `hardness_mpa`.
    Hardness,
    /// a_c, b_c from `potential_v` and `current_density_a_cm2` (or `_a_m2`).
    Tafel,
    /// The depassivation model's parameter from `time_s` and `potential_v`.
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
            upper_v: None,
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
    Ok(match kind {
        FitKind::Hardness => Fit::Hardness(fit_hardness(table, scene, options.hardness())?),
        FitKind::Tafel => Fit::Tafel(fit_tafel(table, scene, options.tafel())?),
        FitKind::Ocp => Fit::Ocp(fit_ocp(table, scene, options.ocp())?),
        FitKind::Archard => match options.regime_change {
            None => Fit::Archard(fit_archard(table, scene, ArchardOptions::default())?),
            Some(change) => {
                let options = RegimeOptions {
                    change,
                    archard: ArchardOptions::default(),
                };
                Fit::Regimes(Box::new(fit_archard_regimes(table, scene, options)?))
            }
        },
    })
}

/// Refuses what [`calibrate`] would refuse about the table and the scene (column and row
/// named) without any simulated run: the immediate fits are made and dropped, the others
/// checked up to their runs. A fit that passes may still fail later (not converging).
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
    }
}

/// The paper's scene, which a table is fitted with unless a scene is given.
pub fn default_scene() -> Scene {
    dalmau2018_316l()
}
