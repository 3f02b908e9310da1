//! `tribosim study`: read a study file, run its members, write the summary. The command
//! line's `main` only parses the arguments and calls [`study`].

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use thiserror::Error;

use super::{Member, MemberOutcome, Study, StudyError, StudySummary, describe_values, run_members};

/// What `tribosim study` was asked to do.
#[derive(Debug, Clone)]
pub struct StudyArgs {
    /// The study file.
    pub study: PathBuf,
    /// Worker threads; one per available core when absent.
    pub workers: Option<usize>,
    /// The member limit ([`super::MAX_MEMBERS`] by default).
    pub max_members: usize,
    /// Where to write the summary JSON; standard output when absent.
    pub output: Option<PathBuf>,
    /// Where to also write the summary as CSV.
    pub csv: Option<PathBuf>,
}

/// Why `tribosim study` stopped.
#[derive(Debug, Error)]
pub enum CommandError {
    /// The study file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the system reported.
        #[source]
        source: std::io::Error,
    },
    /// The study was refused before any member ran.
    #[error("{path}: {source}")]
    Study {
        /// The study file.
        path: PathBuf,
        /// Why.
        #[source]
        source: StudyError,
    },
    /// The study has more members than the limit the command was given.
    #[error("{path}: {source}; raise the limit with --max-members if this is meant")]
    OverLimit {
        /// The study file.
        path: PathBuf,
        /// The counts and the limit.
        #[source]
        source: StudyError,
    },
    /// An output could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file (`-` for standard output).
        path: PathBuf,
        /// What the system reported.
        #[source]
        source: std::io::Error,
    },
    /// The study ran, but some members did not finish; the summary was written.
    #[error("{failed} of {members} members failed; their errors are in the summary")]
    MembersFailed {
        /// Members that did not finish.
        failed: usize,
        /// Members in the study.
        members: usize,
    },
}

/// Reads the study file at `path` and expands its members, refusing a study over
/// `max_members`; gives the file's text with them.
pub fn read_members(
    path: &Path,
    max_members: usize,
) -> Result<(String, Vec<Member>), CommandError> {
    let text = std::fs::read_to_string(path).map_err(|source| CommandError::Read {
        path: path.to_owned(),
        source,
    })?;
    let refused = |source| match source {
        StudyError::TooManyMembers { .. } => CommandError::OverLimit {
            path: path.to_owned(),
            source,
        },
        _ => CommandError::Study {
            path: path.to_owned(),
            source,
        },
    };
    let members = Study::parse(&text)
        .and_then(|study| study.members(max_members))
        .map_err(refused)?;
    Ok((text, members))
}

/// Runs the study `args` names: one line on standard error as each member ends, the
/// summary JSON to `args.output` (or standard output), the markdown table to standard
/// error. Members that fail leave the others running and make the command fail at the end.
pub fn study(args: &StudyArgs) -> Result<StudySummary, CommandError> {
    let (text, members) = read_members(&args.study, args.max_members)?;
    let name = Study::parse(&text)
        .map(|study| study.name())
        .unwrap_or_default();
    let workers = args.workers.unwrap_or_else(|| {
        std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
    });
    let workers = workers.clamp(1, members.len());
    eprintln!(
        "study `{name}`: {} members on {workers} worker threads",
        members.len()
    );
    let started = Instant::now();
    let mut done = 0;
    let total = members.len();
    let outcomes = run_members(
        &members,
        workers,
        &AtomicBool::new(false),
        &mut |member, outcome: &MemberOutcome| {
            done += 1;
            let status = match &outcome.result {
                Ok(result) => format!("done in {:.1} s", result.summary.wall_s),
                Err(error) => format!("failed: {error}"),
            };
            eprintln!(
                "[{done}/{total}] member {} ({}) {status}",
                member.index,
                describe_values(&member.values)
            );
        },
    );
    let summary = StudySummary::new(
        &members,
        &outcomes,
        workers,
        started.elapsed().as_secs_f64(),
    );
    report(summary, args.output.as_deref(), args.csv.as_deref())
}

/// Writes `summary` as JSON to `output` (or standard output) and as CSV to `csv`, and the
/// markdown table to standard error; fails, after writing, when any member did not finish.
pub fn report(
    summary: StudySummary,
    output: Option<&Path>,
    csv: Option<&Path>,
) -> Result<StudySummary, CommandError> {
    let json = serde_json::to_string_pretty(&summary).map_err(|e| CommandError::Write {
        path: output.map_or_else(|| "-".into(), Path::to_owned),
        source: e.into(),
    })? + "\n";
    match output {
        Some(path) => write(path, &json)?,
        None => print!("{json}"),
    }
    if let Some(path) = csv {
        write(path, &summary.to_csv())?;
    }
    eprint!("{}", summary.to_markdown());
    eprintln!("study wall time {:.1} s", summary.wall_s);
    match summary.failed() {
        0 => Ok(summary),
        failed => Err(CommandError::MembersFailed {
            failed,
            members: summary.members.len(),
        }),
    }
}

fn write(path: &Path, text: &str) -> Result<(), CommandError> {
    std::fs::write(path, text).map_err(|source| CommandError::Write {
        path: path.to_owned(),
        source,
    })
}
