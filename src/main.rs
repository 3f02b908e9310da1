//! The `tribosim` command line: serve the HTTP API and page (the default), run a scene,
//! inspect its first contact, list presets, fit parameters to measurements, run a study,
//! or print the speed-against-error tables.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use tribosim::bench::{self, BenchTarget};
use tribosim::calibration::{ChangeCycle, CommandOptions, FitKind, calibrate_files};
use tribosim::scene::{SurfaceSpec, presets};
use tribosim::simulation::{Plan, RunOptions, first_contact, parse_scene_str, run_with};
use tribosim::study::command::StudyArgs;
use tribosim::study::slurm::{CollectArgs, SlurmOptions, collect, write_dir};
use tribosim::surface::{HeightMap, read_file as read_surface};

#[derive(Parser)]
#[command(
    version,
    about = "Ball-on-disc tribocorrosion wear simulation (Dalmau et al., Wear 2018)"
)]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// `tribosim` alone serves, with these options.
    #[command(flatten)]
    serve: tribosim::service::ServeArgs,
}

#[derive(Subcommand)]
enum Command {
    /// Serve the HTTP API and the web page (the default).
    Serve(tribosim::service::ServeArgs),
    /// Run one scene offline and write the result JSON.
    Run {
        /// The scene (JSON; may be {"preset": ..., "overrides": ...}); `-` reads standard
        /// input.
        scene: PathBuf,
        /// Where to write the result; standard output if absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// A measured height map for the disc: Gwyddion .gsf, three columns x y z in m, or
        /// a text matrix of heights in m (with --pixel-um). Sets `disc.surface` to it.
        #[arg(long, value_name = "FILE")]
        surface: Option<PathBuf>,
        /// The pixel size of a text-matrix surface, um.
        #[arg(long, value_name = "UM", requires = "surface")]
        pixel_um: Option<f64>,
        /// Subtract the surface's least-squares plane (its tilt) before use.
        #[arg(long, requires = "surface")]
        remove_tilt: bool,
    },
    /// Solve the first cycle's contact alone and print it as JSON.
    Contact {
        /// The scene (JSON).
        scene: PathBuf,
    },
    /// Print the built-in scenes as JSON.
    Presets,
    /// Fit the model's parameters to a measurement table (CSV or JSON, units in the column
    /// names) and write the fit, with the scene filled in, as JSON.
    Calibrate {
        /// Which fit.
        #[arg(value_enum)]
        fit: FitKind,
        /// The measurements.
        table: PathBuf,
        /// The scene to fill in (JSON); the paper's preset if absent.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Where to write the fit; standard output if absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Hardness: fit the table alone, without the scene's bulk hardness at n = 1.
        #[arg(long)]
        no_bulk: bool,
        /// Tafel: E_corr in V, against the scene's reference electrode (else the scene's own
        /// with `--scene`, else where the measured current changes sign).
        #[arg(long, value_name = "V", allow_hyphen_values = true)]
        e_corr: Option<f64>,
        /// OCP: when the rubbing started, s on the table's clock (the table is then the
        /// whole trace; without it every row is during the rubbing and `time_s` is the
        /// rubbing time).
        #[arg(long, value_name = "S")]
        rubbing_start: Option<f64>,
        /// OCP: when the rubbing stopped, s on the table's clock (the table's end if
        /// absent).
        #[arg(long, value_name = "S")]
        rubbing_stop: Option<f64>,
        /// Archard: also fit a k up to this cycle and another after it (`auto`: the cycle
        /// too), and compare with one k; the scene gets the better model.
        #[arg(long, value_name = "CYCLE|auto")]
        regime_change: Option<ChangeCycle>,
    },
    /// Run a study (a base scene and axes, `docs/study.md`) and write its summary JSON; or
    /// write it as a Slurm job array (`--slurm DIR`) and `collect` it (`docs/cluster.md`).
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Study {
        #[command(subcommand)]
        action: Option<StudyAction>,
        /// The study file (JSON).
        #[arg(required = true)]
        study: Option<PathBuf>,
        /// Worker threads; one per available core by default.
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        workers: Option<u64>,
        /// The most members the study may have.
        #[arg(long, default_value_t = tribosim::study::MAX_MEMBERS)]
        max_members: usize,
        /// Where to write the summary; standard output if absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Also write the summary table as CSV here.
        #[arg(long, value_name = "PATH")]
        csv: Option<PathBuf>,
        #[command(flatten)]
        slurm: SlurmCli,
    },
    /// Print the speed-against-error tables.
    Bench {
        /// Which tables.
        #[arg(value_enum, default_value = "contact")]
        target: BenchTarget,
        /// One JSON object per row instead of a table.
        #[arg(long)]
        json: bool,
        /// Also write a markdown report here, its SVG plots in the folder of the same name
        /// (`docs/accuracy.md` puts them in `docs/accuracy/`).
        #[arg(long, value_name = "PATH")]
        markdown: Option<PathBuf>,
        /// `rough`: also write each grid's height array here as a text matrix in m
        /// (`rough-N.txt`), the arrays `scripts/peers.py` gives the public solvers.
        #[arg(long, value_name = "DIR")]
        surfaces: Option<PathBuf>,
    },
}

/// `tribosim study --slurm`: the study written as a job array instead of run here.
#[derive(Args)]
struct SlurmCli {
    /// Write the members' scenes and a Slurm job-array script to this new directory instead
    /// of running the study, and print the `sbatch` command.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["workers", "output", "csv"])]
    slurm: Option<PathBuf>,
    /// The tribosim the cluster's tasks run, at a path every node reaches; this binary by
    /// default.
    #[arg(long, value_name = "PATH", requires = "slurm")]
    tribosim: Option<PathBuf>,
    /// `#SBATCH --partition` for the tasks.
    #[arg(long, requires = "slurm")]
    partition: Option<String>,
    /// `#SBATCH --time` for each task, in Slurm's format (`30:00`, `1-00:00:00`).
    #[arg(long, requires = "slurm")]
    time: Option<String>,
    /// `#SBATCH --cpus-per-task` (a run uses one core).
    #[arg(long, requires = "slurm", value_parser = clap::value_parser!(u32).range(1..))]
    cpus_per_task: Option<u32>,
    /// Run `sbatch` once written and print the array job's id.
    #[arg(long, requires = "slurm")]
    submit: bool,
}

#[derive(Subcommand)]
enum StudyAction {
    /// Gather the results in a `--slurm` study directory into the study's summary JSON.
    Collect {
        /// The study directory.
        dir: PathBuf,
        /// Where to write the summary; standard output if absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Also write the summary table as CSV here.
        #[arg(long, value_name = "PATH")]
        csv: Option<PathBuf>,
    },
}

/// `tribosim study`: run the study here, write it for Slurm, or collect it.
fn study(
    action: Option<StudyAction>,
    study: Option<PathBuf>,
    args: StudyArgs,
    slurm: SlurmCli,
) -> Result<(), String> {
    if let Some(StudyAction::Collect { dir, output, csv }) = action {
        return collect(&CollectArgs { dir, output, csv })
            .map(drop)
            .map_err(|e| e.to_string());
    }
    let study = study.unwrap_or_default();
    let Some(dir) = slurm.slurm else {
        return tribosim::study::command::study(&StudyArgs { study, ..args })
            .map(drop)
            .map_err(|e| e.to_string());
    };
    let tribosim = match slurm.tribosim {
        Some(path) => std::path::absolute(&path),
        None => std::env::current_exe(),
    }
    .map_err(|e| format!("cannot find the tribosim binary's path: {e}"))?;
    let options = SlurmOptions {
        dir,
        tribosim,
        partition: slurm.partition,
        time: slurm.time,
        cpus_per_task: slurm.cpus_per_task,
        max_members: args.max_members,
        submit: slurm.submit,
    };
    write_dir(&study, &options).map_err(|e| e.to_string())
}

fn read_scene(path: &Path) -> Result<Plan, String> {
    let text = if path == Path::new("-") {
        std::io::read_to_string(std::io::stdin())
            .map_err(|e| format!("cannot read the scene from standard input: {e}"))?
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?
    };
    parse_scene_str(&text).map_err(|errors| {
        let lines: Vec<String> = errors.0.iter().map(|e| format!("  {e}")).collect();
        format!("invalid scene {}:\n{}", path.display(), lines.join("\n"))
    })
}

fn write_json(value: &impl serde::Serialize, output: Option<&Path>) -> Result<(), String> {
    let text = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
    match output {
        Some(path) => write_whole(path, &(text + "\n"))
            .map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => writeln!(std::io::stdout(), "{text}").map_err(|e| e.to_string()),
    }
}

/// Writes `text` to a temporary file beside `path`, then renames it into place: a reader
/// (`tribosim study collect` while a cluster's tasks still run) sees the whole file or none.
fn write_whole(path: &Path, text: &str) -> std::io::Result<()> {
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(format!(".{}.tmp", std::process::id()));
    std::fs::write(&temporary, text)?;
    std::fs::rename(&temporary, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&temporary);
    })
}

/// A measured surface given on the command line.
struct SurfaceFile<'a> {
    path: &'a Path,
    pixel_um: Option<f64>,
    remove_tilt: bool,
}

/// The map of `file`, and `plan`'s scene with `disc.surface` naming it, checked again.
fn with_surface(plan: Plan, file: &SurfaceFile) -> Result<(Plan, HeightMap), String> {
    let (map, _) = read_surface(file.path, file.pixel_um.map(|um| um * 1e-6))
        .map_err(|e| format!("surface {}: {e}", file.path.display()))?;
    let id = file.path.file_name().map_or_else(
        || file.path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut scene = plan.into_scene();
    scene.disc.surface = Some(SurfaceSpec::measured(&id, file.remove_tilt));
    Ok((Plan::new(scene).map_err(|e| e.to_string())?, map))
}

fn run_scene(
    path: &Path,
    output: Option<&Path>,
    surface: Option<&SurfaceFile>,
) -> Result<(), String> {
    let plan = read_scene(path)?;
    let (plan, map) = match surface {
        Some(file) => {
            let (plan, map) = with_surface(plan, file)?;
            (plan, Some(map))
        }
        None => (plan, None),
    };
    // indicatif draws nothing when standard error is not a terminal, so logs stay clean.
    let bar = ProgressBar::new(plan.scene().test.cycles);
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] cycle {pos}/{len}, {per_sec}, {eta} left {msg}",
        )
        .map_err(|e| e.to_string())?,
    );
    let mut on_cycle = |record: &tribosim::simulation::CycleRecord| {
        bar.set_position(record.cycle);
        bar.set_message(format!("V = {:.3e} mm3", record.wear_volume_mm3));
    };
    let options = RunOptions {
        surface: map.as_ref(),
        ..RunOptions::default()
    };
    let result = run_with(&plan, &options, &mut on_cycle, &AtomicBool::new(false));
    bar.finish_and_clear();
    let result = result.map_err(|e| e.to_string())?;
    write_json(&result, output)?;
    for warning in &result.warnings {
        eprintln!("warning: {warning}");
    }
    eprintln!("{}", result.summary);
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command.unwrap_or(Command::Serve(cli.serve)) {
        Command::Serve(args) => tribosim::service::serve(args).map_err(|e| e.to_string()),
        Command::Run {
            scene,
            output,
            surface,
            pixel_um,
            remove_tilt,
        } => {
            let file = surface.as_deref().map(|path| SurfaceFile {
                path,
                pixel_um,
                remove_tilt,
            });
            run_scene(&scene, output.as_deref(), file.as_ref())
        }
        Command::Contact { scene } => read_scene(&scene)
            .and_then(|s| first_contact(&s).map_err(|e| e.to_string()))
            .and_then(|c| write_json(&c, None)),
        Command::Presets => write_json(&presets(), None),
        Command::Calibrate {
            fit,
            table,
            scene,
            output,
            no_bulk,
            e_corr,
            rubbing_start,
            rubbing_stop,
            regime_change,
        } => {
            let options = CommandOptions {
                without_bulk: no_bulk,
                corrosion_potential_v: e_corr,
                scene_given: scene.is_some(),
                rubbing_start_s: rubbing_start,
                rubbing_stop_s: rubbing_stop,
                regime_change,
            };
            calibrate_files(fit, &table, scene.as_deref(), output.as_deref(), options)
                .map_err(|e| e.to_string())
        }
        Command::Study {
            action,
            study: path,
            workers,
            max_members,
            output,
            csv,
            slurm,
        } => {
            let args = StudyArgs {
                study: PathBuf::new(),
                workers: workers.map(|n| usize::try_from(n).unwrap_or(usize::MAX)),
                max_members,
                output,
                csv,
            };
            study(action, path, args, slurm)
        }
        Command::Bench {
            target,
            json,
            markdown,
            surfaces,
        } => bench::print(target, json, markdown.as_deref(), surfaces.as_deref())
            .map_err(|e| e.to_string()),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("tribosim: {message}");
            ExitCode::FAILURE
        }
    }
}
