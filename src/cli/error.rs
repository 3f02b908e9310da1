//! Why a command failed: one type for every verb, each failure in the words the user reads
//! after `tribosim:`.

use std::fmt;
use std::path::PathBuf;

use tribosim::bench::BenchError;
use tribosim::report::FigureError;
use tribosim::scene::SceneErrors;
use tribosim::service::ServeError;
use tribosim::simulation::SimulationError;
use tribosim::study::slurm::SlurmError;
use tribosim::surface::SurfaceError;

/// A command's failure.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The scene could not be read from standard input.
    #[error("cannot read the scene from standard input: {0}")]
    Stdin(std::io::Error),
    /// A scene's text was given where the name of its file belongs.
    #[error(
        "`{0}` is not a file: the scene is read from a file, or from standard input with \
         `-`: echo '{0}' | tribosim run -"
    )]
    SceneAsArgument(String),
    /// A file could not be read or written.
    #[error("cannot {action} {}: {source}", path.display())]
    File {
        /// `read` or `write`.
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// What the file system said.
        source: std::io::Error,
    },
    /// The scene read is not a valid scene.
    #[error("invalid scene {}:{}", path.display(), Listed(errors))]
    Scene {
        /// Where the scene came from (`-` for standard input).
        path: PathBuf,
        /// Every problem found.
        errors: SceneErrors,
    },
    /// The scene with a measured map given on the command line is not valid.
    #[error(transparent)]
    Checked(#[from] SceneErrors),
    /// A measured map given on the command line could not be read.
    #[error("surface {}: {source}", path.display())]
    Surface {
        /// The map's file.
        path: PathBuf,
        /// Why it could not be read.
        source: SurfaceError,
    },
    /// The run or the first contact failed.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The progress bar's template is not one indicatif accepts.
    #[error("progress bar: {0}")]
    Progress(#[from] indicatif::style::TemplateError),
    /// Standard output could not be written.
    #[error("cannot write to standard output: {0}")]
    Stdout(std::io::Error),
    /// A value could not be written as JSON.
    #[error("JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// The server could not start or stopped with an error.
    #[error(transparent)]
    Serve(#[from] ServeError),
    /// A fit failed.
    #[error(transparent)]
    Calibrate(#[from] tribosim::calibration::CommandError),
    /// A study run here failed.
    #[error(transparent)]
    Study(#[from] tribosim::study::command::CommandError),
    /// A study for Slurm could not be written or collected.
    #[error(transparent)]
    Slurm(#[from] SlurmError),
    /// The path of this binary, which the cluster's tasks run, could not be found.
    #[error("cannot find the tribosim binary's path: {0}")]
    Binary(std::io::Error),
    /// A benchmark failed.
    #[error(transparent)]
    Bench(#[from] BenchError),
    /// A file is not the document the command reads.
    #[error("{} is not {what}: {source}", path.display())]
    NotA {
        /// The file.
        path: PathBuf,
        /// What it should have been.
        what: &'static str,
        /// Why it is not.
        source: serde_json::Error,
    },
    /// Measurements given with more than one run's result.
    #[error(
        "--measurements, --wear-volume, --profile and --ocp go with a single run's result, \
         not {0}"
    )]
    MeasurementsAlone(&'static str),
    /// A measured table given on the command line was refused.
    #[error("--{kind} {}: {source}", path.display())]
    Table {
        /// The option, as the kind is spelt there (`wear-volume`).
        kind: String,
        /// The table's file.
        path: PathBuf,
        /// Why it was refused (boxed: a refusal carries the accepted names, and every
        /// `CliError` would otherwise be as large).
        source: Box<tribosim::service::MeasurementError>,
    },
    /// `--measurements` given a lab's CSV, which the per-kind options read.
    #[error(
        "--measurements {} reads the JSON the service answers \
         (`GET /api/v1/jobs/{{id}}/measurements`); a lab's table (CSV or JSON, units in the \
         column names) goes in with --wear-volume, --profile or --ocp",
        .0.display()
    )]
    MeasurementsCsv(PathBuf),
    /// A report's figure could not be drawn.
    #[error(transparent)]
    Figure(#[from] FigureError),
}

/// A scene's problems, each on a line of its own, indented.
struct Listed<'a>(&'a SceneErrors);

impl fmt::Display for Listed<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for error in &self.0.0 {
            write!(f, "\n  {error}")?;
        }
        Ok(())
    }
}
