//! `tribosim calibrate`: read a table and a scene (the paper's preset when none is given),
//! fit, and write the fit as JSON.

use std::io::Write;
use std::path::{Path, PathBuf};

use thiserror::Error;

use super::{
    ArchardOptions, CalibrationError, ChangeCycle, HardnessOptions, RegimeOptions, Table,
    TafelOptions, fit_archard, fit_archard_regimes, fit_hardness, fit_ocp, fit_tafel,
};
use crate::scene::{DALMAU2018_316L, Scene, SceneErrors, presets};
use crate::simulation::parse_scene_str;

/// Which fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FitKind {
    /// H = A + B ln n from `cycles` (or `time_s`) and `hardness_mpa`.
    Hardness,
    /// a_c, b_c from `potential_v` and `current_density_a_cm2` (or `_a_m2`).
    Tafel,
    /// The depassivated area and `anodic_area_factor` from `time_s` and `potential_v`.
    Ocp,
    /// Archard's k from `time_s` (or `cycles`), `volume_mm3` and optional `spread_mm3`.
    Archard,
}

/// The settings of the fits the command line exposes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CommandOptions {
    /// Hardness: leave the scene's bulk value out of the fit.
    pub without_bulk: bool,
    /// Tafel: E_corr, V, instead of the potential of the smallest current.
    pub corrosion_potential_v: Option<f64>,
    /// Archard: also fit a change of regime at this cycle (or the best one), against one k.
    pub regime_change: Option<ChangeCycle>,
}

/// Why the command failed.
#[derive(Debug, Error)]
pub enum CommandError {
    /// A file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The output could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file, or `-` for standard output.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The scene file is invalid.
    #[error("invalid scene {}: {errors}", path.display())]
    Scene {
        /// The file.
        path: PathBuf,
        /// Every problem in it.
        errors: SceneErrors,
    },
    /// The table could not be fitted.
    #[error("{}: {source}", path.display())]
    Fit {
        /// The table.
        path: PathBuf,
        /// Why.
        source: CalibrationError,
    },
    /// An option given to a fit it does not apply to.
    #[error("{option} applies to `calibrate {applies_to}` only")]
    NotForThisFit {
        /// The option.
        option: &'static str,
        /// The fit it applies to.
        applies_to: &'static str,
    },
    /// The fit could not be serialised.
    #[error("serialising the fit: {0}")]
    Json(#[from] serde_json::Error),
}

/// Fits `table` (CSV or JSON) with `scene` (the paper's preset if `None`) and writes the
/// fit as JSON to `output`, or standard output.
pub fn calibrate_files(
    kind: FitKind,
    table: &Path,
    scene: Option<&Path>,
    output: Option<&Path>,
    options: CommandOptions,
) -> Result<(), CommandError> {
    if options.regime_change.is_some() && kind != FitKind::Archard {
        return Err(CommandError::NotForThisFit {
            option: "--regime-change",
            applies_to: "archard",
        });
    }
    let text = read(table)?;
    let fit_error = |source: CalibrationError| CommandError::Fit {
        path: table.to_owned(),
        source,
    };
    let parsed = Table::parse(&text).map_err(|e| fit_error(e.into()))?;
    let scene = match scene {
        Some(path) => parse_scene_str(&read(path)?).map_err(|errors| CommandError::Scene {
            path: path.to_owned(),
            errors,
        })?,
        None => paper_scene(),
    };
    let json = match kind {
        FitKind::Hardness => {
            let options = HardnessOptions {
                include_bulk: !options.without_bulk,
            };
            serde_json::to_string_pretty(
                &fit_hardness(&parsed, &scene, options).map_err(fit_error)?,
            )
        }
        FitKind::Tafel => {
            let options = TafelOptions {
                corrosion_potential_v: options.corrosion_potential_v,
                upper_v: None,
            };
            serde_json::to_string_pretty(&fit_tafel(&parsed, &scene, options).map_err(fit_error)?)
        }
        FitKind::Ocp => serde_json::to_string_pretty(&fit_ocp(&parsed, &scene).map_err(fit_error)?),
        FitKind::Archard => match options.regime_change {
            None => serde_json::to_string_pretty(
                &fit_archard(&parsed, &scene, ArchardOptions::default()).map_err(fit_error)?,
            ),
            Some(change) => {
                let options = RegimeOptions {
                    change,
                    archard: ArchardOptions::default(),
                };
                serde_json::to_string_pretty(
                    &fit_archard_regimes(&parsed, &scene, options).map_err(fit_error)?,
                )
            }
        },
    }?;
    match output {
        Some(path) => std::fs::write(path, json + "\n").map_err(|source| CommandError::Write {
            path: path.to_owned(),
            source,
        }),
        None => writeln!(std::io::stdout(), "{json}").map_err(|source| CommandError::Write {
            path: PathBuf::from("-"),
            source,
        }),
    }
}

fn read(path: &Path) -> Result<String, CommandError> {
    std::fs::read_to_string(path).map_err(|source| CommandError::Read {
        path: path.to_owned(),
        source,
    })
}

/// The paper's scene, the default a table is fitted with.
fn paper_scene() -> Scene {
    presets()
        .into_iter()
        .find(|p| p.name == DALMAU2018_316L)
        .map(|p| p.scene)
        .unwrap_or_default()
}
