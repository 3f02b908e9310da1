//! Studies on a Slurm cluster: [`write_dir`] lays a study out as a directory of member
//! scenes and a job-array script, each task a plain `tribosim run`; [`collect()`] reads the
//! results present back into the same [`super::StudySummary`] a local study gives. Slurm
//! itself (`sbatch`) is the only thing run here; the layout is described in
//! `docs/cluster.md`.

mod collect;
mod write;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use serde_json::{Map, Value};
use thiserror::Error;

use super::command::CommandError;

pub use collect::{CollectArgs, collect};
pub use write::{SlurmOptions, write_dir};

/// The manifest's name in a study directory: the study, its members' values and the
/// version that wrote them. Written last, so a directory with one is complete.
pub const MANIFEST: &str = "manifest.json";

/// The job-array script's name in a study directory.
pub const SCRIPT: &str = "study.sbatch";

/// The manifest's `format`, which tells a study directory from any folder with a
/// `manifest.json`.
const FORMAT: &str = "tribosim-slurm-study";

/// This build's version: members must be run and collected by the version that wrote them
/// for the summary to be the local study's.
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// What a study directory holds besides its members' files.
#[derive(Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Manifest {
    /// Always [`FORMAT`].
    format: String,
    /// The version of tribosim that wrote the directory.
    tribosim_version: String,
    /// The study file as written (its axes' order is the members' order).
    study: Box<RawValue>,
    /// Each member's index and values, as the study expanded when the directory was written.
    members: Vec<ManifestMember>,
}

/// One member as the manifest lists it.
#[derive(Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestMember {
    index: usize,
    values: Map<String, Value>,
}

/// Member `index`'s scene, relative to the study directory.
fn scene_path(index: usize) -> String {
    format!("members/{index:04}.scene.json")
}

/// Member `index`'s result, relative to the study directory; `tribosim run -o` writes it
/// whole or not at all.
fn result_path(index: usize) -> String {
    format!("members/{index:04}.result.json")
}

/// Task `index`'s standard error, relative to the study directory (Slurm's `%4a`, the array
/// index padded to four digits as `{index:04}` pads it).
fn log_path(index: usize) -> String {
    format!("logs/{index:04}.err")
}

/// Why a study directory could not be written, submitted or collected.
#[derive(Debug, Error)]
pub enum SlurmError {
    /// The study file was unreadable or refused, or the summary could not be written.
    #[error(transparent)]
    Command(#[from] CommandError),
    /// The directory already holds files, which writing would mix with another study's.
    #[error("{0} exists and is not empty; give a new directory")]
    NotEmpty(PathBuf),
    /// A value for an `#SBATCH` line that would break the script.
    #[error("--{option} {value:?}: must be non-empty, without spaces or quotes")]
    BadOption {
        /// The option's name.
        option: &'static str,
        /// The value given.
        value: String,
    },
    /// A file of the directory could not be written or read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system reported.
        #[source]
        source: std::io::Error,
    },
    /// `sbatch` could not be run or refused the script.
    #[error("sbatch: {0}")]
    Sbatch(String),
    /// The directory has no manifest, or not a study's.
    #[error("{dir} is not a study directory written by `tribosim study --slurm`: {reason}")]
    NotAStudyDir {
        /// The directory.
        dir: PathBuf,
        /// What is missing or wrong.
        reason: String,
    },
    /// Some members have no readable result yet; the summary was written with them marked.
    #[error(
        "{missing} of {members} members have no result; the summary marks them with their logs' last lines"
    )]
    Unfinished {
        /// Members without a result.
        missing: usize,
        /// Members in the study.
        members: usize,
    },
    /// The directory was written by another version, whose members may not run as this
    /// one's would.
    #[error(
        "{dir} was written by tribosim {written}, this is {running}: collect with the version that wrote it"
    )]
    Version {
        /// The directory.
        dir: PathBuf,
        /// The version in the manifest.
        written: String,
        /// This build's version.
        running: String,
    },
}

impl SlurmError {
    fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Io {
            path: path.to_owned(),
            source,
        }
    }
}
