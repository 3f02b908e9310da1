//! The job record and its states: what the API shows of a job, what `status.json` stores,
//! and the in-memory state a running job changes cycle by cycle.

use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use serde::{Deserialize, Serialize};
use time::OffsetDateTime;
use tokio::sync::watch;
use uuid::Uuid;

use crate::scene::Scene;
use crate::service::listing::{Filter, Listed};

/// Where a job is in its life.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JobStatus {
    /// Accepted, waiting for a worker.
    Queued,
    /// A worker is running it.
    Running,
    /// Finished with a result.
    Succeeded,
    /// Finished without a result; `error` says why.
    Failed,
    /// Stopped by a client.
    Cancelled,
    /// Its stored scene is damaged, so it cannot run; `error` says what is wrong. DELETE
    /// removes it.
    Damaged,
}

impl JobStatus {
    /// Every status, as the API spells it.
    pub const NAMES: &'static [&'static str] = &[
        "queued",
        "running",
        "succeeded",
        "failed",
        "cancelled",
        "damaged",
    ];

    /// The status as the API spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Queued => "queued",
            Self::Running => "running",
            Self::Succeeded => "succeeded",
            Self::Failed => "failed",
            Self::Cancelled => "cancelled",
            Self::Damaged => "damaged",
        }
    }

    /// Whether the job will not change any more.
    pub fn is_final(self) -> bool {
        matches!(
            self,
            Self::Succeeded | Self::Failed | Self::Cancelled | Self::Damaged
        )
    }
}

/// A job as the API shows it and as `status.json` stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobRecord {
    /// The job's id.
    pub id: Uuid,
    /// The scene's name.
    pub name: String,
    /// The sample the run stands for (a lab's specimen id); null when not given.
    #[serde(default)]
    pub sample: Option<String>,
    /// A note on the run; null when not given.
    #[serde(default)]
    pub note: Option<String>,
    /// Tags to find the run by; empty when not given.
    #[serde(default)]
    pub tags: Vec<String>,
    /// Where the job is in its life.
    pub status: JobStatus,
    /// The last solved cycle (the total once succeeded).
    pub cycles_done: u64,
    /// Cycles the scene asks for.
    pub cycles_total: u64,
    /// Seconds to completion, estimated from the running job's pace; null otherwise.
    pub eta_s: Option<f64>,
    /// Why the job failed or is damaged; null otherwise.
    pub error: Option<String>,
    /// Why a job that had finished was queued to run again (its stored result or record was
    /// damaged); null for a job on its first run.
    #[serde(default)]
    pub rerun_reason: Option<String>,
    /// The job's place among the jobs waiting for a worker, from 1 (the next to run); null
    /// unless it waits. Worked out when the record is shown: stored records hold null.
    #[serde(default, skip_deserializing)]
    pub queue_position: Option<usize>,
    /// When the job was accepted.
    #[serde(with = "time::serde::rfc3339")]
    pub created_at: OffsetDateTime,
    /// When the current run started.
    #[serde(with = "time::serde::rfc3339::option")]
    pub started_at: Option<OffsetDateTime>,
    /// When the job reached its final status.
    #[serde(with = "time::serde::rfc3339::option")]
    pub finished_at: Option<OffsetDateTime>,
}

impl Listed for JobRecord {
    fn created_at(&self) -> OffsetDateTime {
        self.created_at
    }
    fn id(&self) -> Uuid {
        self.id
    }
}

impl Listed for Arc<Job> {
    fn created_at(&self) -> OffsetDateTime {
        self.created_at
    }
    fn id(&self) -> Uuid {
        self.id
    }
}

/// The filters of `GET /api/v1/jobs`.
pub(super) const FILTERS: &[Filter<JobRecord>] = &[
    Filter::OneOf("status", JobStatus::NAMES, |j| j.status.name()),
    Filter::Contains("name", |j| &j.name),
    Filter::AnyContains("q", |j| {
        let labels = [j.sample.as_deref(), j.note.as_deref()]
            .into_iter()
            .flatten();
        std::iter::once(j.name.as_str())
            .chain(labels)
            .chain(j.tags.iter().map(String::as_str))
            .collect()
    }),
    Filter::AnyEqual("tag", |j| j.tags.iter().map(String::as_str).collect()),
];

impl JobRecord {
    /// The first record of a newly accepted scene.
    pub fn queued(scene: &Scene) -> Self {
        Self {
            id: Uuid::new_v4(),
            name: scene.name.clone(),
            sample: None,
            note: None,
            tags: Vec::new(),
            status: JobStatus::Queued,
            cycles_done: 0,
            cycles_total: scene.test.cycles,
            eta_s: None,
            error: None,
            rerun_reason: None,
            queue_position: None,
            created_at: OffsetDateTime::now_utc(),
            started_at: None,
            finished_at: None,
        }
    }
}

/// One solved cycle, serialised once and shared by every event-stream client.
#[derive(Debug, Clone)]
pub struct Cycle {
    /// The cycle number (the event id).
    pub number: u64,
    /// The cycle record as JSON.
    pub json: Arc<str>,
}

/// A job's mutable state.
pub(super) struct JobState {
    pub(super) record: JobRecord,
    /// What to run; `None` for a finished job (its scene stays on disk, and is read back
    /// only if the job must run again).
    pub(super) scene: Option<Arc<Scene>>,
    /// The cycles solved so far, or `None` once the job has finished (they are then read
    /// from `cycles.jsonl`).
    pub(super) cycles: Option<Vec<Cycle>>,
    /// When the current run started, for the ETA.
    pub(super) started: Option<Instant>,
    /// Set by DELETE; distinguishes a client's cancel from a shutdown's interruption.
    pub(super) cancel_requested: bool,
}

/// One job.
pub struct Job {
    /// The job's id.
    pub id: Uuid,
    /// When it was created, outside the state's lock, so that a list is ordered without
    /// taking every job's lock.
    created_at: OffsetDateTime,
    state: Mutex<JobState>,
    /// Held across every file write of this job and the state change it records, so that
    /// concurrent requests on one job (two DELETEs, a DELETE and the worker finishing) act
    /// one after the other on both the disk and the memory. Taken before any other lock.
    disk: Mutex<()>,
    /// Polled by `simulation::run` once per cycle.
    pub(super) cancel: AtomicBool,
    /// Bumped at every change (cycle or status), waking event-stream clients.
    changed: watch::Sender<()>,
}

/// What an event-stream client sees of a job at one moment.
pub struct Progress {
    /// The job record.
    pub record: JobRecord,
    /// Cycles after the one asked for, or `None` when they are only on disk.
    pub cycles: Option<Vec<Cycle>>,
}

impl Job {
    pub(super) fn new(record: JobRecord, scene: Option<Scene>, cycles: Option<Vec<Cycle>>) -> Self {
        Self {
            id: record.id,
            created_at: record.created_at,
            state: Mutex::new(JobState {
                record,
                scene: scene.map(Arc::new),
                cycles,
                started: None,
                cancel_requested: false,
            }),
            disk: Mutex::new(()),
            cancel: AtomicBool::new(false),
            changed: watch::Sender::new(()),
        }
    }

    pub(super) fn state(&self) -> MutexGuard<'_, JobState> {
        // A panic while holding the lock cannot leave the state half-updated in a way that
        // matters more than losing the service, so a poisoned lock is still used.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The job's disk lock (see [`Job`]).
    pub(super) fn disk(&self) -> MutexGuard<'_, ()> {
        self.disk.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The job record, with the ETA of a running job.
    pub fn record(&self) -> JobRecord {
        let state = self.state();
        let mut record = state.record.clone();
        record.eta_s = eta_s(&state);
        record
    }

    /// The record and the cycles after `after`.
    pub fn progress_after(&self, after: u64) -> Progress {
        let state = self.state();
        let mut record = state.record.clone();
        record.eta_s = eta_s(&state);
        let cycles = state.cycles.as_ref().map(|cycles| {
            let start = cycles.partition_point(|cycle| cycle.number <= after);
            cycles[start..].to_vec()
        });
        Progress { record, cycles }
    }

    /// A receiver woken at every change of this job.
    pub fn subscribe(&self) -> watch::Receiver<()> {
        self.changed.subscribe()
    }

    /// Wakes every event-stream client of this job.
    pub(super) fn notify(&self) {
        self.changed.send_replace(());
    }

    /// Changes the state, then wakes the job's clients; returns the new record.
    pub(super) fn update(&self, change: impl FnOnce(&mut JobState)) -> JobRecord {
        let record = {
            let mut state = self.state();
            change(&mut state);
            state.record.clone()
        };
        self.notify();
        record
    }

    pub(super) fn push_cycle(&self, number: u64, json: Arc<str>) {
        self.update(|state| {
            state.record.cycles_done = number;
            state
                .cycles
                .get_or_insert_with(Vec::new)
                .push(Cycle { number, json });
        });
    }
}

fn eta_s(state: &JobState) -> Option<f64> {
    let record = &state.record;
    let started = state.started?;
    if record.status != JobStatus::Running || record.cycles_done == 0 {
        return None;
    }
    let per_cycle = started.elapsed().as_secs_f64() / record.cycles_done as f64;
    Some(per_cycle * record.cycles_total.saturating_sub(record.cycles_done) as f64)
}
