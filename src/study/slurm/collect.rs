//! `tribosim study collect DIR`: the results present in a study directory, gathered into
//! the summary a local study gives; a member with no result is marked with the tail of its
//! task's log.

use std::path::{Path, PathBuf};
use std::time::SystemTime;

use serde::Deserialize;

use crate::simulation::Summary;
use crate::study::command::{CommandError, report};
use crate::study::{Study, StudySummary};

use super::{
    FORMAT, MANIFEST, Manifest, ManifestMember, SlurmError, VERSION, log_path, result_path,
};

/// What `tribosim study collect` was asked to do.
#[derive(Debug, Clone)]
pub struct CollectArgs {
    /// The study directory.
    pub dir: PathBuf,
    /// Where to write the summary JSON; standard output when absent.
    pub output: Option<PathBuf>,
    /// Where to also write the summary as CSV.
    pub csv: Option<PathBuf>,
}

/// The lines of a task's log a missing member's error quotes: Slurm's own messages (a time
/// limit, a node failure) and `tribosim run`'s error are its last lines.
const LOG_TAIL_LINES: usize = 3;

/// Reads the study directory `args.dir` and writes its summary as `tribosim study` does:
/// JSON, CSV, the markdown table on standard error, and failure (after writing) when a
/// member has no result. `workers` is the most members that ran at once and `wall_s` the
/// span from the first member's start to the last one's end, both from the results' file
/// times less their runs' wall times.
pub fn collect(args: &CollectArgs) -> Result<StudySummary, SlurmError> {
    let dir = &args.dir;
    let manifest = read_manifest(dir)?;
    let not_study = |reason: String| SlurmError::NotAStudyDir {
        dir: dir.clone(),
        reason,
    };
    let members = Study::parse(manifest.study.get())
        .and_then(|study| study.members(manifest.members.len()))
        .map_err(|e| not_study(format!("its study is refused: {e}")))?;
    let expanded: Vec<ManifestMember> = members
        .iter()
        .map(|m| ManifestMember {
            index: m.index,
            values: m.values.iter().cloned().collect(),
        })
        .collect();
    if expanded != manifest.members {
        return Err(not_study(format!(
            "its study does not expand to the {} members it lists",
            manifest.members.len()
        )));
    }
    let mut spans = Vec::new();
    let results = members
        .iter()
        .map(|member| {
            let read = read_result(dir, member.index);
            if let Ok((summary, ended)) = &read {
                spans.push((ended - summary.wall_s, *ended));
            }
            read.map(|(summary, _)| summary)
        })
        .collect();
    let (workers, wall_s) = concurrency(&spans);
    let summary = StudySummary::from_results(&members, results, workers, wall_s);
    report(summary, args.output.as_deref(), args.csv.as_deref()).map_err(|e| match e {
        CommandError::MembersFailed { failed, members } => SlurmError::Unfinished {
            missing: failed,
            members,
        },
        other => SlurmError::Command(other),
    })
}

fn read_manifest(dir: &Path) -> Result<Manifest, SlurmError> {
    let not_study = |reason: String| SlurmError::NotAStudyDir {
        dir: dir.to_owned(),
        reason,
    };
    let path = dir.join(MANIFEST);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| not_study(format!("cannot read {MANIFEST} ({e})")))?;
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|e| not_study(format!("{MANIFEST} is not a study's manifest ({e})")))?;
    if manifest.format != FORMAT {
        return Err(not_study(format!(
            "{MANIFEST} has format {:?}, not {FORMAT:?}",
            manifest.format
        )));
    }
    if manifest.tribosim_version != VERSION {
        return Err(SlurmError::Version {
            dir: dir.to_owned(),
            written: manifest.tribosim_version,
            running: VERSION.to_owned(),
        });
    }
    Ok(manifest)
}

/// The part of a result the summary needs.
#[derive(Deserialize)]
struct ResultSummary {
    summary: Summary,
}

/// Why a member has no result; its text is the member's `error` in the summary.
#[derive(Debug, thiserror::Error)]
enum NoResult {
    /// No result file, and its task's log is absent or empty.
    #[error("no result and no log: not run yet, still running, or lost ({log})")]
    NotRun {
        /// The task's log, relative to the study directory.
        log: String,
    },
    /// No result file; its task's log says why.
    #[error("no result; {log} ends: {}", tail.join(" / "))]
    Logged {
        /// The task's log, relative to the study directory.
        log: String,
        /// The log's last non-empty lines, at most [`LOG_TAIL_LINES`].
        tail: Vec<String>,
    },
    /// The result file exists but cannot be read.
    #[error("cannot read {path}: {source}")]
    Unreadable {
        /// The result file, relative to the study directory.
        path: String,
        /// What the system reported.
        source: std::io::Error,
    },
    /// The result file is not a run's result.
    #[error("{path} is not a result: {source}")]
    NotAResult {
        /// The result file, relative to the study directory.
        path: String,
        /// Why it does not read as one.
        source: serde_json::Error,
    },
}

/// Member `index`'s run summary and when its result was written (s since the epoch), or
/// why there is none.
fn read_result(dir: &Path, index: usize) -> Result<(Summary, f64), NoResult> {
    let path = dir.join(result_path(index));
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(no_result(dir, index)),
        Err(source) => {
            return Err(NoResult::Unreadable {
                path: result_path(index),
                source,
            });
        }
    };
    let result: ResultSummary =
        serde_json::from_str(&text).map_err(|source| NoResult::NotAResult {
            path: result_path(index),
            source,
        })?;
    let ended = std::fs::metadata(&path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.duration_since(SystemTime::UNIX_EPOCH).ok())
        .map_or(0.0, |t| t.as_secs_f64());
    Ok((result.summary, ended))
}

/// Why member `index` has no result: its task's log tail, or that it has not run.
fn no_result(dir: &Path, index: usize) -> NoResult {
    let log = std::fs::read_to_string(dir.join(log_path(index))).unwrap_or_default();
    let lines: Vec<&str> = log.lines().filter(|l| !l.trim().is_empty()).collect();
    if lines.is_empty() {
        return NoResult::NotRun {
            log: log_path(index),
        };
    }
    let tail = &lines[lines.len().saturating_sub(LOG_TAIL_LINES)..];
    NoResult::Logged {
        log: log_path(index),
        tail: tail.iter().map(|line| (*line).to_owned()).collect(),
    }
}

/// The most spans open at once and the span from the first start to the last end, in s;
/// (0, 0) with no spans.
fn concurrency(spans: &[(f64, f64)]) -> (usize, f64) {
    let start = spans.iter().map(|s| s.0).fold(f64::INFINITY, f64::min);
    let end = spans.iter().map(|s| s.1).fold(f64::NEG_INFINITY, f64::max);
    if spans.is_empty() {
        return (0, 0.0);
    }
    // Ends sort before starts at the same instant: one member following another on a
    // worker is not two at once.
    let mut events: Vec<(f64, i32)> = spans
        .iter()
        .flat_map(|&(from, to)| [(from, 1), (to, -1)])
        .collect();
    events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut open = 0i32;
    let mut most = 0i32;
    for (_, step) in events {
        open += step;
        most = most.max(open);
    }
    (usize::try_from(most).unwrap_or(0), end - start)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn members_one_after_another_on_one_worker_count_once() {
        let spans = [(0.0, 1.0), (1.0, 2.0), (0.5, 1.5)];
        assert_eq!(concurrency(&spans), (2, 2.0));
        assert_eq!(concurrency(&[]), (0, 0.0));
    }

    /// A member's `error` in the summary JSON is the text of [`NoResult`]; scripts and
    /// users read it, so its wording is pinned here.
    #[test]
    fn a_member_without_result_says_why_in_the_summary_words() {
        let dir = std::env::temp_dir().join(format!("tribosim-collect-{}", uuid::Uuid::new_v4()));
        std::fs::create_dir_all(dir.join("logs")).expect("logs");
        std::fs::create_dir_all(dir.join("members")).expect("members");
        std::fs::write(dir.join(log_path(1)), "a\n\nb\nc\n  \nd\n").expect("a log");
        std::fs::write(dir.join(result_path(2)), "{}").expect("a result");
        let why = |index| {
            read_result(&dir, index)
                .map(|_| ())
                .err()
                .map(|e| e.to_string())
        };
        assert_eq!(
            why(0).as_deref(),
            Some("no result and no log: not run yet, still running, or lost (logs/0000.err)")
        );
        assert_eq!(
            why(1).as_deref(),
            Some("no result; logs/0001.err ends: b / c / d")
        );
        let not_a_result = why(2).expect("member 2 has no result");
        assert!(
            not_a_result.starts_with("members/0002.result.json is not a result: missing field"),
            "{not_a_result}"
        );
        std::fs::remove_dir_all(&dir).expect("clean up");
    }
}
