//! Studies run by the service. A study document is expanded by [`crate::study`] into its
//! members, each an ordinary job on the worker pool (listed under `/api/v1/jobs`, with its
//! own events and result); the study record ties them together and is kept in
//! `<data-dir>/studies/<uuid>.json`. Its status and counts are not stored: they are read
//! from the member jobs whenever the record is shown, so they can never disagree.
//!
//! A study's members are accepted all or none: the queue reserves a place for each, their
//! job directories are written, then the study file, and only then do they queue. A crash
//! in between leaves the members written so far as plain jobs, which run.

use std::collections::HashMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use time::OffsetDateTime;
use uuid::Uuid;

use super::files::{quarantine, sweep_temporaries, sync_dir, to_json, write_atomic};
use super::job::JobStatus;
use super::registry::{Deletion, Jobs, SubmitError};
use super::servable::servable;
use super::study_record::{AxisRecord, StudyRecord, record_of};
use super::surfaces::surface_id;
use crate::simulation::Summary;
use crate::study::{MemberRow, Pending, Study, StudyError, StudySummary, describe_values};

/// Where study files live, under the data directory.
const STUDIES_DIR: &str = "studies";

/// A member as the study file stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct StoredMember {
    pub(super) index: usize,
    pub(super) job_id: Uuid,
    pub(super) values: Map<String, Value>,
}

/// What `<uuid>.json` holds: everything of a study that does not change.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct StoredStudy {
    pub(super) id: Uuid,
    pub(super) name: String,
    #[serde(with = "time::serde::rfc3339")]
    pub(super) created_at: OffsetDateTime,
    pub(super) axes: Vec<AxisRecord>,
    pub(super) members: Vec<StoredMember>,
}

/// Why a study was not accepted.
#[derive(Debug)]
pub enum StudySubmitError {
    /// The document is not a valid study (including a member scene the parser refuses, and
    /// more members than the server's limit).
    Invalid(StudyError),
    /// More members than the queue can ever hold.
    OverCapacity {
        /// Members in the study.
        members: usize,
        /// The queue's capacity.
        capacity: usize,
    },
    /// The jobs could not be accepted (queue full now, disk full, storage).
    Submit(SubmitError),
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
    dir: PathBuf,
    quarantine_dir: PathBuf,
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
    /// Loads every study file under `data_dir`. A file that cannot be read or parsed, or
    /// that names another study, is moved to `quarantine_dir` and logged; it never stops
    /// the others from loading. Blocking.
    pub fn open(
        data_dir: &Path,
        quarantine_dir: &Path,
        max_members: usize,
        workers: usize,
    ) -> io::Result<Self> {
        let dir = data_dir.join(STUDIES_DIR);
        fs::create_dir_all(&dir)?;
        sync_dir(data_dir)?;
        if let Err(e) = sweep_temporaries(&dir) {
            // Leftover temporary files are harmless: they are not named as studies.
            tracing::warn!(dir = %dir.display(), "cannot sweep temporary files: {e}");
        }
        let studies = Self {
            dir,
            quarantine_dir: quarantine_dir.to_owned(),
            studies: Mutex::new(HashMap::new()),
            max_members,
            workers,
        };
        for entry in fs::read_dir(&studies.dir)? {
            let Ok(entry) = entry else { continue };
            studies.load(&entry.path());
        }
        Ok(studies)
    }

    fn load(&self, path: &Path) {
        let id = path
            .file_name()
            .and_then(|name| name.to_str())
            .and_then(|name| name.strip_suffix(".json"))
            .and_then(|stem| Uuid::parse_str(stem).ok());
        let Some(id) = id else {
            tracing::warn!(path = %path.display(), "not a study; left alone");
            return;
        };
        let stored = fs::read(path)
            .map_err(|e| e.to_string())
            .and_then(|bytes| {
                serde_json::from_slice::<StoredStudy>(&bytes).map_err(|e| e.to_string())
            })
            .and_then(|stored| {
                if stored.id == id {
                    Ok(stored)
                } else {
                    Err(format!("it names study {}", stored.id))
                }
            });
        match stored {
            Ok(stored) => self.insert(stored),
            Err(damage) => {
                tracing::error!(%id, "study file damaged: {damage}");
                quarantine(&self.quarantine_dir, path);
            }
        }
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

    fn path(&self, id: Uuid) -> PathBuf {
        self.dir.join(format!("{id}.json"))
    }

    /// Accepts a study document: expands it (refusing it whole, with the axis or field
    /// named, if anything is wrong), then submits its members as jobs and keeps the study.
    /// Blocking (file writes).
    pub fn submit(&self, jobs: &Jobs, text: &str) -> Result<StudyRecord, StudySubmitError> {
        let study = Study::parse(text).map_err(StudySubmitError::Invalid)?;
        let members = study
            .members(self.max_members)
            .map_err(StudySubmitError::Invalid)?;
        // Held until the members are queued, so no surface they name is deleted meanwhile.
        let names_surface = members.iter().any(|m| surface_id(&m.scene).is_some());
        let _hold = names_surface.then(|| jobs.surfaces.hold());
        for member in &members {
            servable(&member.scene, &jobs.surfaces).map_err(|source| {
                StudySubmitError::Invalid(StudyError::Member {
                    index: member.index,
                    values: describe_values(&member.values),
                    source,
                })
            })?;
        }
        let capacity = jobs.queue.capacity();
        if members.len() > capacity {
            return Err(StudySubmitError::OverCapacity {
                members: members.len(),
                capacity,
            });
        }
        let id = Uuid::new_v4();
        let name = members
            .first()
            .map(|member| member.scene.name.clone())
            .unwrap_or_default();
        let axes = study
            .axes
            .iter()
            .map(|axis| AxisRecord {
                path: axis.path.clone(),
                values: axis.values.clone(),
            })
            .collect();
        let values: Vec<Map<String, Value>> = members
            .iter()
            .map(|member| member.values.iter().cloned().collect())
            .collect();
        let scenes = members.into_iter().map(|member| member.scene).collect();
        let mut stored = None;
        jobs.submit_many(scenes, |records| {
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
            write_atomic(&self.dir, &format!("{id}.json"), &to_json(&study)?)?;
            stored = Some(study);
            Ok(())
        })
        .map_err(StudySubmitError::Submit)?;
        let stored = stored.ok_or_else(|| {
            StudySubmitError::Submit(SubmitError::Storage(io::Error::other(
                "the study was not recorded",
            )))
        })?;
        tracing::info!(%id, members = stored.members.len(), "study queued");
        self.insert(stored);
        self.record(jobs, id).ok_or_else(|| {
            StudySubmitError::Submit(SubmitError::Storage(io::Error::other(
                "the study vanished as it was accepted",
            )))
        })
    }

    /// The study's record with its members' current statuses.
    pub fn record(&self, jobs: &Jobs, id: Uuid) -> Option<StudyRecord> {
        self.get(id).map(|entry| record_of(&entry.stored, jobs))
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
    /// member has ended, removes the members' jobs and the study. `None` for an unknown id,
    /// including one a concurrent DELETE removed. Blocking (files).
    pub fn delete(&self, jobs: &Jobs, id: Uuid) -> Option<io::Result<StudyDeletion>> {
        let entry = self.get(id)?;
        let _disk = lock(&entry.disk);
        // `None` when a concurrent DELETE removed it while this one waited for the lock.
        self.get(id)?;
        let members = &entry.stored.members;
        let unfinished = members.iter().any(|member| {
            jobs.get(member.job_id)
                .is_some_and(|job| !job.record().status.is_final())
        });
        if unfinished {
            return Some(cancel_members(jobs, &entry.stored));
        }
        for member in members {
            if let Some(Err(e)) = jobs.delete(member.job_id) {
                return Some(Err(e));
            }
        }
        lock(&self.studies).remove(&id);
        let path = self.path(id);
        let removed = fs::remove_file(&path).and_then(|()| sync_dir(&self.dir));
        if let Err(e) = removed {
            if e.kind() != io::ErrorKind::NotFound {
                self.insert(entry.stored.clone());
                return Some(Err(e));
            }
        }
        tracing::info!(%id, "finished study removed");
        Some(Ok(StudyDeletion::Removed))
    }

    /// The study's summary as `tribosim study -o` writes it, taken now: succeeded members
    /// with their summaries, ended ones with why, the others marked `pending`. `wall_s` runs
    /// from acceptance to the last member's end (or to now). `None` for an unknown id; an
    /// error when a result cannot be read (the machine's fault, not the result's). Blocking.
    pub fn summary(&self, jobs: &Jobs, id: Uuid) -> Option<io::Result<StudySummary>> {
        let entry = self.get(id)?;
        let mut last_end = entry.stored.created_at;
        let mut unfinished = false;
        let mut rows = Vec::with_capacity(entry.stored.members.len());
        for member in &entry.stored.members {
            let (row, ended) = match member_row(jobs, &entry, member) {
                Ok(row) => row,
                Err(e) => return Some(Err(e)),
            };
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
        Some(Ok(StudySummary {
            axes: entry.stored.axes.iter().map(|a| a.path.clone()).collect(),
            workers: self.workers,
            wall_s: (end - entry.stored.created_at).as_seconds_f64().max(0.0),
            members: rows,
        }))
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
        if let Some(cancelled) = jobs.cancel(job_id) {
            stopping |= matches!(cancelled?, Some(Deletion::Cancelling(_)));
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
) -> io::Result<(MemberRow, Option<OffsetDateTime>)> {
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
                        return Err(io::Error::other(damage.to_string()));
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
