//! `tribosim calibrate`: read a table and a scene (the paper's preset when none is given),
//! fit, and write the fit as JSON.

use std::io::Write;
use std::path::{Path, PathBuf};

use thiserror::Error;

use super::{CalibrationError, CommandOptions, FitKind, Table, calibrate, default_scene};
use crate::scene::{Scene, SceneErrors};
use crate::simulation::parse_scene_str;

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
/// fit as JSON to `output`, or standard output; gives the fit's JSON, for a summary (which
/// shows the fit's warnings).
pub fn calibrate_files(
    kind: FitKind,
    table: &Path,
    scene: Option<&Path>,
    output: Option<&Path>,
    options: CommandOptions,
) -> Result<serde_json::Value, CommandError> {
    refuse_misplaced(kind, &options)?;
    let text = read(table)?;
    let fit_error = |source: CalibrationError| CommandError::Fit {
        path: table.to_owned(),
        source,
    };
    let parsed = Table::parse(&text).map_err(|e| fit_error(e.into()))?;
    // A lab's export read under other names is said, so the user sees what was fitted.
    for (header, name) in parsed.renamed() {
        eprintln!(
            "note: {}: read the column `{header}` as `{name}`",
            table.display()
        );
    }
    let scene = scene_of(scene)?;
    let fit = serde_json::to_value(calibrate(kind, &parsed, &scene, options).map_err(fit_error)?)?;
    write_fit(&serde_json::to_string_pretty(&fit)?, output)?;
    Ok(fit)
}

/// Refuses an option given to a fit it does not apply to, naming the fit it is for.
fn refuse_misplaced(kind: FitKind, options: &CommandOptions) -> Result<(), CommandError> {
    let misplaced = [
        (
            "--regime-change",
            "archard",
            options.regime_change.is_some(),
            FitKind::Archard,
        ),
        (
            "--e-corr",
            "tafel",
            options.corrosion_potential_v.is_some(),
            FitKind::Tafel,
        ),
        (
            "--tafel-overpotential-max",
            "tafel",
            options.tafel_overpotential_max_v.is_some(),
            FitKind::Tafel,
        ),
        (
            "--tafel-overpotential-min",
            "tafel",
            options.tafel_overpotential_min_v.is_some(),
            FitKind::Tafel,
        ),
        (
            "--rubbing-start",
            "ocp",
            options.rubbing_start_s.is_some(),
            FitKind::Ocp,
        ),
        (
            "--rubbing-stop",
            "ocp",
            options.rubbing_stop_s.is_some(),
            FitKind::Ocp,
        ),
    ];
    if let Some(&(option, applies_to, ..)) = misplaced
        .iter()
        .find(|&&(_, _, given, fit)| given && fit != kind)
    {
        return Err(CommandError::NotForThisFit { option, applies_to });
    }
    Ok(())
}

/// The scene a fit fills in: the file's at `path`, or the paper's preset.
fn scene_of(path: Option<&Path>) -> Result<Scene, CommandError> {
    let Some(path) = path else {
        return Ok(default_scene());
    };
    let parsed = parse_scene_str(&read(path)?).map_err(|errors| CommandError::Scene {
        path: path.to_owned(),
        errors,
    })?;
    Ok(parsed.into_scene())
}

/// The fit's JSON to `output`, or to standard output.
fn write_fit(json: &str, output: Option<&Path>) -> Result<(), CommandError> {
    match output {
        Some(path) => {
            std::fs::write(path, format!("{json}\n")).map_err(|source| CommandError::Write {
                path: path.to_owned(),
                source,
            })
        }
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
