//! Studies run by the service. A study document is expanded by [`crate::study`] into its
//! members, each an ordinary job on the worker pool (listed under `/api/v1/jobs`, with its
//! own events and result); the study record ties them together and is kept in
//! `<data-dir>/studies/<uuid>.json`. Its status and counts are not stored: they are read
//! from the member jobs whenever the record is shown, so they can never disagree.
//!
//! A study's members are accepted all or none: the queue reserves a place for each, the
//! study is marked as being accepted, their job directories are written, then the study
//! file, and only then do they queue. A crash in between leaves the mark, and the next start
//! removes the members written so far (`store.rs`).

use std::collections::HashMap;
use std::io;
use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use serde::Deserialize;
use serde_json::{Map, Value};
use time::OffsetDateTime;
use uuid::Uuid;

use super::record::{StudyRecord, record_of};
use super::store::{AxisRecord, StoredMember, StoredStudy, StudyFiles};
use crate::service::files::Damage;
use crate::service::jobs::{DeleteError, Deletion, JobRecord, JobStatus, Jobs, Store, SubmitError};
use crate::service::surfaces::surface_id;
use crate::simulation::{Build, Summary};
use crate::study::{Member, MemberRow, Pending, Study, StudyError, StudySummary, describe_values};

/// Why a study was not accepted.
#[derive(Debug)]
pub enum StudySubmitError {
    /// The document is not a valid study (including a member scene the parser refuses).
    Invalid(StudyError),
    /// More members than the server's limit: the smaller of `--max-study-members` and the
    /// queue's capacity, which could never hold more.
    OverLimit {
        /// The counts and the limit ([`StudyError::TooManyMembers`]).
        source: StudyError,
        /// The option that sets the limit in force.
        set_by: &'static str,
    },
    /// The jobs could not be accepted (queue full now, disk full, storage).
    Submit(SubmitError),
}

/// Why a request on one study failed.
#[derive(Debug)]
pub enum StudiesError {
    /// No study has this id, or a concurrent DELETE removed it.
    Unknown(Uuid),
    /// DELETE could not write a member's new status or remove a file.
    NotChanged(io::Error),
    /// A member's stored result could not be read (the machine's fault: the next request
    /// may work).
    ResultUnreadable(Damage),
}

/// What DELETE did to a study.
pub enum StudyDeletion {
    /// Every member that had not ended is cancelled.
    Cancelled(StudyRecord),
    /// Some running members stop within a cycle; the rest are cancelled.
    Cancelling(StudyRecord),
    /// Every member had ended: the study, its members' jobs and their files are gone.
    Removed,
}

/// One study in memory.
struct Entry {
    stored: StoredStudy,
    /// Held across the study's file changes and its DELETE.
    disk: Mutex<()>,
    /// The summaries of succeeded members, read once from their results.
    summaries: Mutex<HashMap<Uuid, Summary>>,
}

/// Every study by id, with the limits studies are accepted under.
pub struct Studies {
    files: StudyFiles,
    studies: Mutex<HashMap<Uuid, Arc<Entry>>>,
    /// The most members a study may have (`--max-study-members`).
    max_members: usize,
    /// The worker pool's size, reported in summaries.
    workers: usize,
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Studies {
    /// Loads every study file under `data_dir` (see `store`). Blocking.
    /// Studies whose acceptance a crash interrupted are removed with their member jobs
    /// first, so call this before the jobs load from `jobs`.
    pub fn open(
        data_dir: &Path,
        quarantine_dir: &Path,
        jobs: &Store,
        max_members: usize,
        workers: usize,
    ) -> io::Result<Self> {
        let files = StudyFiles::open(data_dir, quarantine_dir)?;
        files.sweep_pending(jobs)?;
        let stored = files.load()?;
        let studies = Self {
            files,
            studies: Mutex::new(HashMap::new()),
            max_members,
            workers,
        };
        for study in stored {
            studies.insert(study);
        }
        Ok(studies)
    }

    fn insert(&self, stored: StoredStudy) {
        let entry = Entry {
            stored,
            disk: Mutex::new(()),
            summaries: Mutex::new(HashMap::new()),
        };
        lock(&self.studies).insert(entry.stored.id, Arc::new(entry));
    }

    fn get(&self, id: Uuid) -> Option<Arc<Entry>> {
        lock(&self.studies).get(&id).cloned()
    }

    /// Accepts a study: expands it (refusing it whole, with the axis or field named, if
    /// anything is wrong), then submits its members as jobs and keeps the study. Blocking
    /// (file writes).
    pub fn submit(&self, jobs: &Jobs, study: &Study) -> Result<StudyRecord, StudySubmitError> {
        let members = self.members_of(jobs, study)?;
        // Held until the members are queued, so no surface they name is deleted meanwhile.
        let names_surface = members.iter().any(|m| surface_id(&m.scene).is_some());
        let _hold = names_surface.then(|| jobs.surfaces().hold());
        let memory_bytes = memory_of(jobs, &members)?;
        let id = Uuid::new_v4();
        let name = study.name();
        let axes = study
            .axes
            .iter()
            .map(|axis| AxisRecord {
                path: axis.path.clone(),
                values: axis.values.to_vec(),
            })
            .collect();
        let values: Vec<Map<String, Value>> = members
            .iter()
            .map(|member| member.values.iter().cloned().collect())
            .collect();
        let scenes = members
            .into_iter()
            .map(|member| member.scene)
            .zip(memory_bytes)
            .collect();
        let mut stored = None;
        let begin = |records: &[_]| {
            let ids = records.iter().map(|record: &JobRecord| record.id).collect();
            self.files.begin(id, ids)
        };
        jobs.submit_many(scenes, begin, |records| {
            let study = StoredStudy {
                id,
                name,
                created_at: OffsetDateTime::now_utc(),
                axes,
                members: records
                    .iter()
                    .zip(values)
                    .enumerate()
                    .map(|(index, (record, values))| StoredMember {
                        index,
                        job_id: record.id,
                        values,
                    })
                    .collect(),
            };
            self.files.commit(&study)?;
            stored = Some(study);
            Ok(())
        })
        .map_err(|e| {
            // The members are removed by now; their study's mark goes with them.
            self.files.abandon(id);
            StudySubmitError::Submit(e)
        })?;
        let stored = stored.ok_or_else(|| {
            StudySubmitError::Submit(SubmitError::Storage(io::Error::other(
                "the study was not recorded",
            )))
        })?;
        tracing::info!(%id, members = stored.members.len(), "study queued");
        self.insert(stored);
        self.record(jobs, id).map_err(|_| {
            StudySubmitError::Submit(SubmitError::Storage(io::Error::other(
                "the study vanished as it was accepted",
            )))
        })
    }

    /// The study's members, refused past the queue's capacity or the server's limit on a
    /// study's members, whichever is lower (named by the flag that sets it).
    fn members_of(&self, jobs: &Jobs, study: &Study) -> Result<Vec<Member>, StudySubmitError> {
        let capacity = jobs.capacity();
        let (limit, set_by) = if capacity < self.max_members {
            (capacity, "--queue-capacity")
        } else {
            (self.max_members, "--max-study-members")
        };
        study.members(limit).map_err(|source| match source {
            StudyError::TooManyMembers { .. } => StudySubmitError::OverLimit { source, set_by },
            other => StudySubmitError::Invalid(other),
        })
    }

    /// The study's record with its members' current statuses.
    pub fn record(&self, jobs: &Jobs, id: Uuid) -> Result<StudyRecord, StudiesError> {
        let entry = self.get(id).ok_or(StudiesError::Unknown(id))?;
        Ok(record_of(&entry.stored, jobs))
    }

    /// Every study's record, newest first.
    pub fn list(&self, jobs: &Jobs) -> Vec<StudyRecord> {
        let entries: Vec<Arc<Entry>> = lock(&self.studies).values().cloned().collect();
        let mut records: Vec<StudyRecord> = entries
            .iter()
            .map(|entry| record_of(&entry.stored, jobs))
            .collect();
        records.sort_by(|a, b| b.created_at.cmp(&a.created_at).then(a.id.cmp(&b.id)));
        records
    }

    /// DELETE: cancels every member that has not ended, as a job's DELETE does; once every
    /// member has ended, removes the members' jobs and the study. Blocking (files).
    pub fn delete(&self, jobs: &Jobs, id: Uuid) -> Result<StudyDeletion, StudiesError> {
        let unknown = || StudiesError::Unknown(id);
        let entry = self.get(id).ok_or_else(unknown)?;
        let _disk = lock(&entry.disk);
        // Unknown when a concurrent DELETE removed it while this one waited for the lock.
        self.get(id).ok_or_else(unknown)?;
        let members = &entry.stored.members;
        let unfinished = members.iter().any(|member| {
            jobs.get(member.job_id)
                .is_some_and(|job| !job.record().status.is_final())
        });
        if unfinished {
            return cancel_members(jobs, &entry.stored).map_err(StudiesError::NotChanged);
        }
        for member in members {
            match jobs.delete(member.job_id) {
                // Removed now, or deleted on its own before.
                Ok(_) | Err(DeleteError::Unknown(_)) => {}
                Err(DeleteError::Storage(e)) => return Err(StudiesError::NotChanged(e)),
            }
        }
        lock(&self.studies).remove(&id);
        if let Err(e) = self.files.remove(id) {
            self.insert(entry.stored.clone());
            return Err(StudiesError::NotChanged(e));
        }
        tracing::info!(%id, "finished study removed");
        Ok(StudyDeletion::Removed)
    }

    /// The study's summary as `tribosim study -o` writes it, taken now: succeeded members
    /// with their summaries, ended ones with why, the others marked `pending`. `wall_s` runs
    /// from acceptance to the last member's end (or to now). An error when a result cannot
    /// be read (the machine's fault, not the result's). Blocking.
    pub fn summary(&self, jobs: &Jobs, id: Uuid) -> Result<StudySummary, StudiesError> {
        let entry = self.get(id).ok_or(StudiesError::Unknown(id))?;
        let mut last_end = entry.stored.created_at;
        let mut unfinished = false;
        let mut rows = Vec::with_capacity(entry.stored.members.len());
        for member in &entry.stored.members {
            let (row, ended) = member_row(jobs, &entry, member)?;
            match ended {
                Some(at) => last_end = last_end.max(at),
                None => unfinished = true,
            }
            rows.push(row);
        }
        let end = if unfinished {
            OffsetDateTime::now_utc()
        } else {
            last_end
        };
        Ok(StudySummary {
            axes: entry.stored.axes.iter().map(|a| a.path.clone()).collect(),
            workers: self.workers,
            wall_s: (end - entry.stored.created_at).as_seconds_f64().max(0.0),
            members: rows,
            provenance: Some(Build::now()),
        })
    }
}

/// Cancels every member that has not ended: queued ones first, so a worker freed by a
/// cancelled run does not start one that is about to be cancelled.
fn cancel_members(jobs: &Jobs, stored: &StoredStudy) -> io::Result<StudyDeletion> {
    let queued_first = {
        let mut ids: Vec<(bool, Uuid)> = stored
            .members
            .iter()
            .map(|member| {
                let running = jobs
                    .get(member.job_id)
                    .is_some_and(|job| job.record().status == JobStatus::Running);
                (running, member.job_id)
            })
            .collect();
        ids.sort_by_key(|(running, _)| *running);
        ids
    };
    let mut stopping = false;
    for (_, job_id) in queued_first {
        match jobs.cancel(job_id) {
            Ok(cancelled) => stopping |= matches!(cancelled, Some(Deletion::Cancelling(_))),
            // Deleted on its own: nothing to cancel.
            Err(DeleteError::Unknown(_)) => {}
            Err(DeleteError::Storage(e)) => return Err(e),
        }
    }
    let record = record_of(stored, jobs);
    tracing::info!(id = %stored.id, "study cancelled");
    Ok(if stopping {
        StudyDeletion::Cancelling(record)
    } else {
        StudyDeletion::Cancelled(record)
    })
}

/// The result's summary, the only part of a result a study summary needs.
#[derive(Deserialize)]
struct ResultSummary {
    summary: Summary,
}

/// A member's summary row, and when it ended (`None` while it has not).
fn member_row(
    jobs: &Jobs,
    entry: &Entry,
    member: &StoredMember,
) -> Result<(MemberRow, Option<OffsetDateTime>), StudiesError> {
    let mut row = MemberRow {
        index: member.index,
        values: member.values.clone(),
        summary: None,
        error: None,
        pending: None,
    };
    let Some(job) = jobs.get(member.job_id) else {
        row.error = Some("the member's job was deleted".to_owned());
        return Ok((row, Some(entry.stored.created_at)));
    };
    let record = job.record();
    let ended = record.finished_at;
    match record.status {
        JobStatus::Queued => row.pending = Some(Pending::Queued),
        JobStatus::Running => row.pending = Some(Pending::Running),
        JobStatus::Cancelled => row.error = Some("cancelled".to_owned()),
        JobStatus::Failed | JobStatus::Damaged => {
            row.error = Some(record.error.unwrap_or_else(|| record.status.name().into()));
        }
        JobStatus::Succeeded => {
            let cached = lock(&entry.summaries).get(&job.id).cloned();
            let summary = match cached {
                Some(summary) => summary,
                None => match jobs.store().read_result(job.id) {
                    Ok(bytes) => match serde_json::from_slice::<ResultSummary>(&bytes) {
                        Ok(result) => result.summary,
                        Err(e) => {
                            row.error = Some(format!("the stored result is not valid: {e}"));
                            return Ok((row, ended));
                        }
                    },
                    Err(damage) if damage.is_read_failure() => {
                        return Err(StudiesError::ResultUnreadable(damage));
                    }
                    Err(damage) => {
                        // Runs again, deterministically, to the same numbers.
                        return Ok(match jobs.rerun(&job, &damage) {
                            Some(again) if again.status == JobStatus::Queued => {
                                row.pending = Some(Pending::Queued);
                                (row, None)
                            }
                            again => {
                                let again = again.and_then(|r| r.error);
                                row.error = Some(again.unwrap_or_else(|| damage.to_string()));
                                (row, ended)
                            }
                        });
                    }
                },
            };
            lock(&entry.summaries).insert(job.id, summary.clone());
            row.summary = Some(summary);
        }
    }
    let ended = if row.pending.is_some() { None } else { ended };
    Ok((row, ended))
}

/// Each member's memory bound, as the jobs queue admits it: the first member it would
/// refuse refuses the study, named by its index and its values.
fn memory_of(jobs: &Jobs, members: &[Member]) -> Result<Vec<u64>, StudySubmitError> {
    members
        .iter()
        .map(|member| {
            jobs.admissible(&member.scene).map_err(|source| {
                StudySubmitError::Invalid(StudyError::Member {
                    index: member.index,
                    values: describe_values(&member.values),
                    source,
                })
            })
        })
        .collect()
}
