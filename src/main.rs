//! The `tribosim` command line: serve the HTTP API and page (the default), run a scene,
//! inspect its first contact, list presets, fit parameters to measurements, run a study,
//! or print the speed-against-error tables.

mod cli;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use tribosim::bench::{self, BenchTarget};
use tribosim::calibration::{ChangeCycle, CommandOptions, FitKind, calibrate_files};
use tribosim::scene::materials::library;
use tribosim::scene::presets;
use tribosim::service::MeasurementKind;
use tribosim::study::command::StudyArgs;
use tribosim::study::slurm::{CollectArgs, SlurmOptions, collect, write_dir};

use cli::error::CliError;
use cli::output::{Destination, FileName, destination, today, write_json};
use cli::report::MeasuredFiles;
use cli::run::{SurfaceFile, contact_scene, run_scene};

/// jemalloc instead of glibc's malloc, so that a server that ran a large job gives the
/// memory back when it ends: with glibc, a 1024-cell job (759 MB peak RSS) left the idle
/// server at 447 MB for good, in the arena of its worker thread. jemalloc's background
/// thread returns freed pages after the decay `.cargo/config.toml` sets, whether or not
/// the server does anything more (`scripts/load_test.py`, item 11; `docs/operations.md`,
/// "Memory").
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

#[derive(Parser)]
#[command(
    version,
    about = "Ball-on-disc tribocorrosion wear simulation (Dalmau et al., Wear 2018)"
)]
#[command(args_conflicts_with_subcommands = true)]
// The verbs first, and the server's options (twenty of them) behind `tribosim serve --help`.
#[command(
    help_template = "{about}\n\n{usage-heading} {usage}\n\nCommands:\n{subcommands}\n{after-help}",
    after_help = "`tribosim` alone serves, as `tribosim serve` does: `tribosim serve --help` lists the \
server's options.

Examples:
  tribosim serve --data-dir data          # the page at http://127.0.0.1:8080
  tribosim run scenes/quick.json -o quick.json
  tribosim report quick.json --wear-volume docs/calibration/table3_wear.csv -o report.html
  tribosim study scenes/study-load-speed.json -o study.json

Each verb's --help has an example and names its guide. A running server serves the guides \
at http://127.0.0.1:8080/docs/<name>: scene.md, result.md, study.md, report.md, calibration.md, \
accuracy.md, operations.md and the others of the docs/ folder of tribosim's source; the HTTP \
API is described at http://127.0.0.1:8080/api/v1/openapi.yaml."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// `tribosim` alone serves, with these options.
    #[command(flatten)]
    serve: tribosim::service::ServeArgs,
}

/// A measured height map for the disc, as `run` and `contact` take it.
#[derive(clap::Args)]
struct SurfaceArgs {
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
    /// The unit of a text map's heights (m when not given).
    #[arg(long, value_enum, value_name = "UNIT", requires = "surface")]
    height_unit: Option<tribosim::surface::HeightUnit>,
}

impl SurfaceArgs {
    /// The file the arguments name, if any.
    fn file(&self) -> Option<SurfaceFile<'_>> {
        self.surface.as_deref().map(|path| SurfaceFile {
            path,
            pixel_um: self.pixel_um,
            remove_tilt: self.remove_tilt,
            height_unit: self.height_unit,
        })
    }
}

#[derive(Subcommand)]
enum Command {
    /// Serve the HTTP API and the web page (the default).
    #[command(
        after_help = "Example:\n  tribosim serve --data-dir data --workers 2\n  \
        (then open http://127.0.0.1:8080; the limits: http://127.0.0.1:8080/docs/operations.md)"
    )]
    Serve(tribosim::service::ServeArgs),
    /// Run one scene offline and write the result JSON.
    #[command(
        after_help = "Examples:\n  tribosim run scenes/quick.json -o quick.json\n  \
        echo '{\"preset\": \"dalmau2018-316l\", \"overrides\": {\"test\": {\"cycles\": 60}}}' \
        | tribosim run - -o sixty.json\n\
        The scene's fields: http://127.0.0.1:8080/docs/scene.md; the result's: \
        http://127.0.0.1:8080/docs/result.md (on a running server)"
    )]
    Run {
        /// The scene (JSON; may be {"preset": ..., "overrides": ...}); `-` reads standard
        /// input.
        scene: PathBuf,
        /// Where to write the result; if absent, standard output when it is a pipe, or a new
        /// `result-<name>-<date>.json` here when it is a terminal.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        surface: SurfaceArgs,
    },
    /// Solve the first cycle's contact alone and print it as JSON.
    #[command(
        after_help = "Example:\n  tribosim contact scenes/quick.json > contact.json\n\
        The scene's fields: http://127.0.0.1:8080/docs/scene.md (on a running server)"
    )]
    Contact {
        /// The scene (JSON); `-` reads standard input.
        scene: PathBuf,
        #[command(flatten)]
        surface: SurfaceArgs,
    },
    /// Print the built-in scenes as JSON, or with --materials the materials library (guide:
    /// /docs/materials.md of a running server).
    #[command(after_help = "Examples:\n  tribosim presets > presets.json\n  \
        tribosim presets --materials > materials.json")]
    Presets {
        /// Print the materials library (discs, balls and their sources) instead.
        #[arg(long)]
        materials: bool,
    },
    /// Write a printable HTML report (guide: /docs/report.md of a running server): of one result, of several results
    /// compared, or of a study's summary.
    #[command(after_help = "Examples:\n  \
        tribosim report quick.json --wear-volume docs/calibration/table3_wear.csv -o report.html\n  \
        tribosim report a.json b.json -o comparison.html\n  \
        tribosim report study.json -o study.html")]
    Report(ReportCli),
    /// Fit the model's parameters to a measurement table (CSV or JSON, units in the column
    /// names) and write the fit, with the scene filled in, as JSON (guide:
    /// /docs/calibration.md of a running server).
    #[command(after_help = "Examples:\n  \
        tribosim calibrate hardness docs/calibration/table3_hardness.csv -o hardness.json\n  \
        tribosim calibrate archard docs/calibration/table3_wear.csv --regime-change auto")]
    Calibrate(CalibrateCli),
    /// Run a study (a base scene and axes; guide: /docs/study.md of a running server) and
    /// write its summary JSON; or write it as a Slurm job array (`--slurm DIR`) and `collect`
    /// it (/docs/cluster.md).
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    #[command(after_help = "Examples:\n  \
        tribosim study scenes/study-load-speed.json -o study.json --csv study.csv\n  \
        tribosim study scenes/study-12.json --slurm runs/ && tribosim study collect runs/")]
    Study(StudyCli),
    /// Print the speed-against-error tables (guide: /docs/accuracy.md of a running server).
    #[command(after_help = "Example:\n  tribosim bench contact --json > contact.jsonl")]
    Bench(BenchCli),
}

/// `tribosim report`'s arguments.
#[derive(Args)]
struct ReportCli {
    /// Result JSON files (one: a run's report; several: a comparison), or one study
    /// summary JSON.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// The measurements attached to a single run, as JSON
    /// (`GET /api/v1/jobs/{id}/measurements`), drawn and compared with the model.
    #[arg(long, value_name = "FILE")]
    measurements: Option<PathBuf>,
    /// A single run's measured wear volumes: a lab's table, CSV (or JSON by its
    /// extension), `time_s` or `cycles`, `volume_mm3`, optionally `spread_mm3`.
    #[arg(long, value_name = "FILE")]
    wear_volume: Option<PathBuf>,
    /// A single run's measured groove profile: a table of `y_mm`, `depth_um`.
    #[arg(long, value_name = "FILE")]
    profile: Option<PathBuf>,
    /// A single run's measured open-circuit potential: a table of `time_s`, `potential_v`.
    #[arg(long, value_name = "FILE")]
    ocp: Option<PathBuf>,
    /// Where to write the report; standard output if absent.
    #[arg(short, long)]
    output: Option<PathBuf>,
}

/// `tribosim calibrate`'s arguments.
#[derive(Args)]
struct CalibrateCli {
    /// Which fit.
    #[arg(value_enum)]
    fit: FitKind,
    /// The measurements.
    table: PathBuf,
    /// The scene to fill in (JSON); the paper's preset if absent.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Where to write the fit; standard output if absent. A readable summary goes to
    /// standard error either way.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Hardness: fit the table alone, without the scene's bulk hardness at n = 1.
    #[arg(long)]
    no_bulk: bool,
    /// Tafel: E_corr in V, against the scene's reference electrode (else the scene's own
    /// with `--scene`, else where the measured current changes sign).
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    e_corr: Option<f64>,
    /// Tafel: the domain's end nearest E_corr, as E - E_corr in V (e.g. -0.15); chosen
    /// from the data if absent.
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    tafel_overpotential_max: Option<f64>,
    /// Tafel: the domain's most cathodic end, as E - E_corr in V (e.g. -1.0); the scan's
    /// end if absent.
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    tafel_overpotential_min: Option<f64>,
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
}

/// `tribosim study`'s arguments.
#[derive(Args)]
struct StudyCli {
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
    /// Where to write the summary; if absent, standard output when it is a pipe, or a
    /// new `study-<file>-<date>.json` here when it is a terminal.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Also write the summary table as CSV here.
    #[arg(long, value_name = "PATH")]
    csv: Option<PathBuf>,
    #[command(flatten)]
    slurm: SlurmCli,
}

/// `tribosim bench`'s arguments.
#[derive(Args)]
struct BenchCli {
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
    /// `kappa`: also press this measured height map (.gsf, x y z columns, or a text
    /// matrix of heights in m with --pixel-um) on the periodic flat.
    #[arg(long, value_name = "FILE")]
    map: Option<PathBuf>,
    /// The pixel size of a text-matrix `--map`, um.
    #[arg(long, value_name = "UM", requires = "map")]
    pixel_um: Option<f64>,
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
    #[command(after_help = "Example:\n  tribosim study collect runs/ -o study.json")]
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

impl ReportCli {
    /// `tribosim report`: the measured tables named by kind, then the report.
    fn report(self) -> Result<(), CliError> {
        let tables = [
            (MeasurementKind::WearVolume, self.wear_volume.as_deref()),
            (MeasurementKind::Profile, self.profile.as_deref()),
            (MeasurementKind::Ocp, self.ocp.as_deref()),
        ];
        let measured = MeasuredFiles {
            all: self.measurements.as_deref(),
            tables: tables
                .into_iter()
                .filter_map(|(kind, path)| Some((kind, path?)))
                .collect(),
        };
        cli::report::report(&self.inputs, &measured, self.output.as_deref())
    }
}

impl CalibrateCli {
    /// `tribosim calibrate`: the fit's JSON to `output` (or standard output), its readable
    /// summary to standard error.
    fn calibrate(self) -> Result<(), CliError> {
        let options = CommandOptions {
            without_bulk: self.no_bulk,
            corrosion_potential_v: self.e_corr,
            tafel_overpotential_max_v: self.tafel_overpotential_max,
            tafel_overpotential_min_v: self.tafel_overpotential_min,
            scene_given: self.scene.is_some(),
            rubbing_start_s: self.rubbing_start,
            rubbing_stop_s: self.rubbing_stop,
            regime_change: self.regime_change,
        };
        let (scene, output) = (self.scene.as_deref(), self.output.as_deref());
        let fitted = calibrate_files(self.fit, &self.table, scene, output, options)?;
        eprint!("{}", cli::summary::readable(&fitted));
        Ok(())
    }
}

impl BenchCli {
    /// `tribosim bench`: the tables, with a measured map where one is given.
    fn print(self) -> Result<(), CliError> {
        let map = self.map.as_deref().map(|path| bench::MeasuredMap {
            path,
            pixel_m: self.pixel_um.map(|um| um * 1e-6),
        });
        let (markdown, surfaces) = (self.markdown.as_deref(), self.surfaces.as_deref());
        bench::print(self.target, self.json, markdown, surfaces, map).map_err(CliError::from)
    }
}

impl StudyCli {
    /// `tribosim study`: run the study here, write it for Slurm, or collect it.
    fn study(self) -> Result<(), CliError> {
        if let Some(StudyAction::Collect { dir, output, csv }) = self.action {
            collect(&CollectArgs { dir, output, csv })?;
            return Ok(());
        }
        let study = self.study.unwrap_or_default();
        let Some(dir) = self.slurm.slurm else {
            let output = study_output(&study, self.output.as_deref());
            tribosim::study::command::study(&StudyArgs {
                study,
                workers: self
                    .workers
                    .map(|n| usize::try_from(n).unwrap_or(usize::MAX)),
                max_members: self.max_members,
                output,
                csv: self.csv,
            })?;
            return Ok(());
        };
        let tribosim = match self.slurm.tribosim {
            Some(path) => std::path::absolute(&path),
            None => std::env::current_exe(),
        }
        .map_err(CliError::Binary)?;
        let options = SlurmOptions {
            dir,
            tribosim,
            partition: self.slurm.partition,
            time: self.slurm.time,
            cpus_per_task: self.slurm.cpus_per_task,
            max_members: self.max_members,
            submit: self.slurm.submit,
        };
        Ok(write_dir(&study, &options)?)
    }
}

/// Where a local study's summary goes: `output`, standard output when it is a pipe, or a
/// new file named after the study file when it is a terminal (said on standard error).
fn study_output(study: &Path, output: Option<&Path>) -> Option<PathBuf> {
    let label = study.file_stem().map(|s| s.to_string_lossy().into_owned());
    let name = FileName {
        kind: "study",
        label: label.as_deref().unwrap_or("study"),
        date: today(),
    };
    let terminal = std::io::stdout().is_terminal();
    match destination(output, terminal, Path::new("."), &name) {
        Destination::Asked(path) => Some(path),
        Destination::Chosen(path) => {
            eprintln!(
                "the summary goes to {} (standard output is a terminal: `-o FILE` names the \
                 file, a pipe gets the JSON)",
                path.display()
            );
            Some(path)
        }
        Destination::Stdout => None,
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command.unwrap_or(Command::Serve(cli.serve)) {
        Command::Serve(args) => tribosim::service::serve(args).map_err(CliError::from),
        Command::Run {
            scene,
            output,
            surface,
        } => run_scene(&scene, output.as_deref(), surface.file().as_ref()),
        Command::Contact { scene, surface } => contact_scene(&scene, surface.file().as_ref()),
        Command::Presets { materials: false } => write_json(&presets(), &Destination::Stdout),
        Command::Presets { materials: true } => write_json(&library(), &Destination::Stdout),
        Command::Report(args) => args.report(),
        Command::Calibrate(args) => args.calibrate(),
        Command::Study(args) => args.study(),
        Command::Bench(args) => args.print(),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("tribosim: {message}");
            ExitCode::FAILURE
        }
    }
}
