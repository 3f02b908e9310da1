//! `tribosim run` and the scene reading `run` and `contact` share: the plan's warnings and
//! estimate before the run, the result where [`super::output`] decides, the summary last.

use std::io::IsTerminal;
use std::path::Path;
use std::sync::atomic::AtomicBool;

use indicatif::{ProgressBar, ProgressStyle};

use tribosim::scene::SurfaceSpec;
use tribosim::simulation::{
    CycleRecord, Plan, RunOptions, first_contact_with, parse_scene_str, run_with,
};
use tribosim::surface::{HeightMap, HeightUnit, read_file as read_surface};

use super::error::CliError;
use super::output::{Destination, FileName, destination, today, write_json};

/// The scene at `path` (`-`: standard input), checked into a plan.
pub fn read_scene(path: &Path) -> Result<Plan, CliError> {
    let text = if path == Path::new("-") {
        std::io::read_to_string(std::io::stdin()).map_err(CliError::Stdin)?
    } else {
        std::fs::read_to_string(path).map_err(|e| unreadable(path, e))?
    };
    parse_scene_str(&text).map_err(|errors| CliError::Scene {
        path: path.to_owned(),
        errors,
    })
}

/// Why `path` could not be read; for an argument that is a scene's text rather than a
/// file's name, how to give the text.
fn unreadable(path: &Path, source: std::io::Error) -> CliError {
    let given = path.to_string_lossy();
    if given.trim_start().starts_with('{') {
        CliError::SceneAsArgument(given.into_owned())
    } else {
        CliError::File {
            action: "read",
            path: path.to_owned(),
            source,
        }
    }
}

/// A measured surface given on the command line.
pub struct SurfaceFile<'a> {
    /// The map's file.
    pub path: &'a Path,
    /// A text matrix's pixel size, um.
    pub pixel_um: Option<f64>,
    /// Whether to subtract the map's tilt.
    pub remove_tilt: bool,
    /// A text map's height unit; `None` for heights in m.
    pub height_unit: Option<HeightUnit>,
}

/// The map of `file`, and `plan`'s scene with `disc.surface` naming it, checked again.
fn with_surface(plan: Plan, file: &SurfaceFile) -> Result<(Plan, HeightMap), CliError> {
    let surface_error = |source| CliError::Surface {
        path: file.path.to_owned(),
        source,
    };
    let (mut map, format) =
        read_surface(file.path, file.pixel_um.map(|um| um * 1e-6)).map_err(surface_error)?;
    if let Some(unit) = file.height_unit {
        unit.apply(&mut map, format).map_err(surface_error)?;
    }
    let id = file.path.file_name().map_or_else(
        || file.path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut scene = plan.into_scene();
    scene.disc.surface = Some(SurfaceSpec::measured(&id, file.remove_tilt));
    Ok((Plan::new(scene)?, map))
}

/// The scene at `path` checked into a plan, on the measured map of `surface` if given.
fn read_scene_on(
    path: &Path,
    surface: Option<&SurfaceFile>,
) -> Result<(Plan, Option<HeightMap>), CliError> {
    let plan = read_scene(path)?;
    match surface {
        Some(file) => with_surface(plan, file).map(|(plan, map)| (plan, Some(map))),
        None => Ok((plan, None)),
    }
}

/// `tribosim contact`: the first cycle's contact of the scene at `path`, on the measured
/// map of `surface` if given, as JSON on standard output.
pub fn contact_scene(path: &Path, surface: Option<&SurfaceFile>) -> Result<(), CliError> {
    let (plan, map) = read_scene_on(path, surface)?;
    let options = RunOptions {
        surface: map.as_ref(),
        ..RunOptions::default()
    };
    let contact = first_contact_with(&plan, &options)?;
    write_json(&contact, &Destination::Stdout)
}

/// Runs the scene at `path`: its warnings (with the estimate of a long run) on standard
/// error before the first cycle, a progress bar, the result JSON where
/// [`super::output::destination`] decides, then the summary.
pub fn run_scene(
    path: &Path,
    output: Option<&Path>,
    surface: Option<&SurfaceFile>,
) -> Result<(), CliError> {
    let (plan, map) = read_scene_on(path, surface)?;
    for warning in plan.warnings() {
        eprintln!("warning: {warning}");
    }
    // indicatif draws nothing when standard error is not a terminal, so logs stay clean.
    let bar = ProgressBar::new(plan.scene().test.cycles);
    bar.set_style(ProgressStyle::with_template(
        "{elapsed_precise} [{bar:40}] cycle {pos}/{len}, {per_sec}, {eta} left {msg}",
    )?);
    let mut on_cycle = |record: &CycleRecord| {
        bar.set_position(record.cycle);
        bar.set_message(format!("V = {:.3e} mm3", record.wear_volume_mm3));
    };
    let options = RunOptions {
        surface: map.as_ref(),
        ..RunOptions::default()
    };
    let result = run_with(&plan, &options, &mut on_cycle, &AtomicBool::new(false));
    bar.finish_and_clear();
    let result = result?;
    let name = FileName {
        kind: "result",
        label: &result.scene.name,
        date: today(),
    };
    let terminal = std::io::stdout().is_terminal();
    write_json(
        &result,
        &destination(output, terminal, Path::new("."), &name),
    )?;
    // The plan's warnings were printed before the run; the run adds its own.
    for warning in result.field_warnings.iter().skip(plan.warnings().len()) {
        eprintln!("warning: {warning}");
    }
    eprintln!("{}", result.summary);
    Ok(())
}
