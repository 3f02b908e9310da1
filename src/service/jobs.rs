//! Jobs: the in-memory registry, the bounded queue and the pool of worker threads that run
//! simulations.
//!
//! Workers are plain OS threads, not tokio tasks: `simulation::run` is synchronous and
//! CPU-bound for seconds to minutes, and must never sit on the async runtime's threads.
//! Handlers touch the registry only through short, non-blocking critical sections; anything
//! that writes files runs on tokio's blocking pool.
//!
//! Lock order: queue, registry map, a job's state; none is held across a file write.

use std::collections::{HashMap, VecDeque};
use std::io;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::Instant;

use serde::{Deserialize, Serialize};
use time::OffsetDateTime;
use tokio::sync::watch;
use uuid::Uuid;

use super::store::{CyclesWriter, Store};
use crate::scene::Scene;
use crate::simulation::{self, CycleRecord, SimulationError};

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
}

impl JobStatus {
    /// The status as the API spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Queued => "queued",
            Self::Running => "running",
            Self::Succeeded => "succeeded",
            Self::Failed => "failed",
            Self::Cancelled => "cancelled",
        }
    }

    /// Whether the job will not change any more.
    pub fn is_final(self) -> bool {
        matches!(self, Self::Succeeded | Self::Failed | Self::Cancelled)
    }
}

/// A job as the API shows it and as `status.json` stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobRecord {
    /// The job's id.
    pub id: Uuid,
    /// The scene's name.
    pub name: String,
    /// Where the job is in its life.
    pub status: JobStatus,
    /// The last solved cycle (the total once succeeded).
    pub cycles_done: u64,
    /// Cycles the scene asks for.
    pub cycles_total: u64,
    /// Seconds to completion, estimated from the running job's pace; null otherwise.
    pub eta_s: Option<f64>,
    /// Why the job failed; null otherwise.
    pub error: Option<String>,
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

/// One solved cycle, serialised once and shared by every event-stream client.
#[derive(Debug, Clone)]
pub struct Cycle {
    /// The cycle number (the event id).
    pub number: u64,
    /// The cycle record as JSON.
    pub json: Arc<str>,
}

/// A job's mutable state.
struct JobState {
    record: JobRecord,
    /// The cycles solved so far, or `None` once the job has finished (they are then read
    /// from `cycles.jsonl`).
    cycles: Option<Vec<Cycle>>,
    /// When the current run started, for the ETA.
    started: Option<Instant>,
    /// Set by DELETE; distinguishes a client's cancel from a shutdown's interruption.
    cancel_requested: bool,
}

/// One job.
pub struct Job {
    /// The job's id.
    pub id: Uuid,
    /// What to run; `None` for a job that had finished before this process started (its
    /// scene stays on disk, as it never runs again).
    scene: Option<Scene>,
    state: Mutex<JobState>,
    /// Polled by `simulation::run` once per cycle.
    cancel: AtomicBool,
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
    fn new(record: JobRecord, scene: Option<Scene>, cycles: Option<Vec<Cycle>>) -> Self {
        Self {
            id: record.id,
            scene,
            state: Mutex::new(JobState {
                record,
                cycles,
                started: None,
                cancel_requested: false,
            }),
            cancel: AtomicBool::new(false),
            changed: watch::Sender::new(()),
        }
    }

    fn state(&self) -> MutexGuard<'_, JobState> {
        // A panic while holding the lock cannot leave the state half-updated in a way that
        // matters more than losing the service, so a poisoned lock is still used.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
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

    fn update(&self, change: impl FnOnce(&mut JobState)) -> JobRecord {
        let record = {
            let mut state = self.state();
            change(&mut state);
            state.record.clone()
        };
        self.changed.send_replace(());
        record
    }

    fn push_cycle(&self, number: u64, json: Arc<str>) {
        self.update(|state| {
            state.record.cycles_done = number;
            state
                .cycles
                .get_or_insert_with(Vec::new)
                .push(Cycle { number, json });
        });
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    let message = payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("no message");
    format!("internal error: the simulation panicked: {message}")
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

/// Why a job was not accepted.
#[derive(Debug)]
pub enum SubmitError {
    /// The queue holds its capacity; retry after about this many seconds.
    QueueFull {
        /// The queue's capacity.
        capacity: usize,
        /// A hint for Retry-After.
        retry_after_s: u64,
    },
    /// The job could not be made durable.
    Storage(io::Error),
}

/// What DELETE did.
pub enum Deletion {
    /// The job was queued and is now cancelled.
    Cancelled(JobRecord),
    /// The job is running; it stops within a cycle.
    Cancelling(JobRecord),
    /// The job had finished; it and its files are gone.
    Removed,
}

struct Queue {
    pending: VecDeque<Arc<Job>>,
    /// Places promised to submissions still writing their files.
    reserved: usize,
    stopping: bool,
}

/// The registry, the queue and the store, shared by handlers and workers.
pub struct Jobs {
    store: Store,
    jobs: Mutex<HashMap<Uuid, Arc<Job>>>,
    queue: Mutex<Queue>,
    ready: Condvar,
    capacity: usize,
}

impl Jobs {
    /// Loads every job from `store`: finished ones are served as they are, queued ones are
    /// queued again, and ones that were running are queued to run again from scratch (in
    /// the order they were accepted). Unreadable scenes fail their job.
    pub fn open(store: Store, capacity: usize) -> io::Result<Arc<Self>> {
        let mut stored = store.load()?;
        stored.sort_by_key(|job| job.record.created_at);
        let jobs = Arc::new(Self {
            store,
            jobs: Mutex::new(HashMap::new()),
            queue: Mutex::new(Queue {
                pending: VecDeque::new(),
                reserved: 0,
                stopping: false,
            }),
            ready: Condvar::new(),
            capacity,
        });
        for job in stored {
            jobs.restore(job.record, job.scene)?;
        }
        Ok(jobs)
    }

    fn restore(&self, mut record: JobRecord, scene: Result<Scene, String>) -> io::Result<()> {
        let id = record.id;
        if record.status.is_final() {
            let job = Arc::new(Job::new(record, None, None));
            self.insert(job);
            return Ok(());
        }
        let scene = match scene {
            Ok(scene) => scene,
            Err(e) => {
                tracing::error!(%id, "stored scene unreadable: {e}; job failed");
                record.status = JobStatus::Failed;
                record.error = Some(format!("stored scene unreadable: {e}"));
                record.finished_at = Some(OffsetDateTime::now_utc());
                self.store.write_status(&record)?;
                self.insert(Arc::new(Job::new(record, None, None)));
                return Ok(());
            }
        };
        let was = record.status;
        record.status = JobStatus::Queued;
        record.cycles_done = 0;
        record.started_at = None;
        if was == JobStatus::Running {
            self.store.write_status(&record)?;
        }
        tracing::info!(%id, was = ?was, "job re-queued after restart");
        let job = Arc::new(Job::new(record, Some(scene), Some(Vec::new())));
        self.insert(Arc::clone(&job));
        // Accepted jobs are never dropped, so the restored queue may exceed its capacity.
        self.lock_queue().pending.push_back(job);
        Ok(())
    }

    fn insert(&self, job: Arc<Job>) {
        self.lock_jobs().insert(job.id, job);
    }

    fn lock_jobs(&self) -> MutexGuard<'_, HashMap<Uuid, Arc<Job>>> {
        self.jobs.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn lock_queue(&self) -> MutexGuard<'_, Queue> {
        self.queue.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The job with this id.
    pub fn get(&self, id: Uuid) -> Option<Arc<Job>> {
        self.lock_jobs().get(&id).cloned()
    }

    /// Every job's record, newest first.
    pub fn list(&self) -> Vec<JobRecord> {
        let jobs: Vec<Arc<Job>> = self.lock_jobs().values().cloned().collect();
        let mut records: Vec<JobRecord> = jobs.iter().map(|job| job.record()).collect();
        records.sort_by(|a, b| b.created_at.cmp(&a.created_at).then(a.id.cmp(&b.id)));
        records
    }

    /// The store the jobs live in.
    pub fn store(&self) -> &Store {
        &self.store
    }

    /// Accepts a validated scene: makes it durable, then queues it. Blocking (file writes).
    pub fn submit(&self, scene: Scene) -> Result<JobRecord, SubmitError> {
        {
            let mut queue = self.lock_queue();
            if queue.pending.len() + queue.reserved >= self.capacity {
                return Err(SubmitError::QueueFull {
                    capacity: self.capacity,
                    retry_after_s: self.retry_after_s(),
                });
            }
            queue.reserved += 1;
        }
        let record = JobRecord {
            id: Uuid::new_v4(),
            name: scene.name.clone(),
            status: JobStatus::Queued,
            cycles_done: 0,
            cycles_total: scene.test.cycles,
            eta_s: None,
            error: None,
            created_at: OffsetDateTime::now_utc(),
            started_at: None,
            finished_at: None,
        };
        let created = self.store.create(&record, &scene);
        let mut queue = self.lock_queue();
        queue.reserved -= 1;
        created.map_err(SubmitError::Storage)?;
        let job = Arc::new(Job::new(record.clone(), Some(scene), Some(Vec::new())));
        self.insert(Arc::clone(&job));
        queue.pending.push_back(job);
        drop(queue);
        self.ready.notify_one();
        tracing::info!(id = %record.id, cycles = record.cycles_total, "job queued");
        Ok(record)
    }

    /// Seconds until a place in the queue is likely to free up: the soonest running job's
    /// ETA, within [1, 300] s; 5 s when no running job has an estimate yet.
    fn retry_after_s(&self) -> u64 {
        let soonest = self
            .list()
            .iter()
            .filter_map(|record| record.eta_s)
            .fold(f64::INFINITY, f64::min);
        if soonest.is_finite() {
            // Clamped first, so the cast cannot truncate.
            soonest.ceil().clamp(1.0, 300.0) as u64
        } else {
            5
        }
    }

    /// DELETE: cancels a queued job at once, asks a running one to stop within a cycle, and
    /// removes a finished one with its files. `None` for an unknown id. Blocking (files).
    pub fn delete(&self, id: Uuid) -> Option<io::Result<Deletion>> {
        let job = self.get(id)?;
        let mut queue = self.lock_queue();
        let mut state = job.state();
        let deletion = match state.record.status {
            JobStatus::Queued => {
                queue.pending.retain(|queued| queued.id != id);
                drop(queue);
                state.record.status = JobStatus::Cancelled;
                state.record.finished_at = Some(OffsetDateTime::now_utc());
                let record = state.record.clone();
                drop(state);
                job.changed.send_replace(());
                tracing::info!(%id, "queued job cancelled");
                if let Err(e) = self.store.write_status(&record) {
                    return Some(Err(e));
                }
                Deletion::Cancelled(record)
            }
            JobStatus::Running => {
                state.cancel_requested = true;
                job.cancel.store(true, Ordering::Relaxed);
                tracing::info!(%id, "running job asked to cancel");
                Deletion::Cancelling(state.record.clone())
            }
            JobStatus::Succeeded | JobStatus::Failed | JobStatus::Cancelled => {
                drop(queue);
                drop(state);
                // `None` when a concurrent DELETE removed it first.
                self.lock_jobs().remove(&id)?;
                tracing::info!(%id, "finished job removed");
                if let Err(e) = self.store.remove(id) {
                    return Some(Err(e));
                }
                Deletion::Removed
            }
        };
        Some(Ok(deletion))
    }

    /// Starts `workers` threads that take jobs from the queue until [`Jobs::stop`].
    pub fn start_workers(self: &Arc<Self>, workers: usize) -> io::Result<Vec<JoinHandle<()>>> {
        (0..workers)
            .map(|n| {
                let jobs = Arc::clone(self);
                std::thread::Builder::new()
                    .name(format!("tribosim-worker-{n}"))
                    .spawn(move || {
                        while let Some(job) = jobs.next_job() {
                            jobs.run_job(&job);
                        }
                    })
            })
            .collect()
    }

    /// Stops the workers: no new job starts, and running ones are interrupted within a
    /// cycle. Interrupted jobs keep their persisted status and run again at the next start.
    pub fn stop(&self) {
        let mut queue = self.lock_queue();
        queue.stopping = true;
        drop(queue);
        self.ready.notify_all();
        for job in self.lock_jobs().values() {
            if job.state().record.status == JobStatus::Running {
                job.cancel.store(true, Ordering::Relaxed);
            }
        }
    }

    /// The next queued job, marked running; `None` once stopping.
    fn next_job(&self) -> Option<Arc<Job>> {
        let mut queue = self.lock_queue();
        loop {
            if queue.stopping {
                return None;
            }
            if let Some(job) = queue.pending.pop_front() {
                let mut state = job.state();
                if state.record.status != JobStatus::Queued {
                    continue;
                }
                state.record.status = JobStatus::Running;
                state.record.started_at = Some(OffsetDateTime::now_utc());
                state.started = Some(Instant::now());
                drop(state);
                return Some(job);
            }
            queue = self
                .ready
                .wait(queue)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }

    fn run_job(&self, job: &Job) {
        let id = job.id;
        let record = job.record();
        job.changed.send_replace(());
        tracing::info!(%id, "job running");
        let outcome = self
            .store
            .write_status(&record)
            .and_then(|()| self.store.cycles_writer(id))
            .map_err(|e| format!("storage: {e}"))
            .and_then(|writer| {
                // A panic in the simulation must fail its job, not kill the worker and leave
                // the job `running` for ever.
                panic::catch_unwind(AssertUnwindSafe(|| self.simulate(job, writer)))
                    .unwrap_or_else(|payload| Err(panic_message(payload.as_ref())))
            });
        match outcome {
            Ok(true) => self.finish(job, JobStatus::Succeeded, None),
            Ok(false) => {
                if job.state().cancel_requested {
                    self.finish(job, JobStatus::Cancelled, None);
                } else {
                    tracing::info!(%id, "job interrupted by shutdown; it runs again at the next start");
                }
            }
            Err(error) => self.finish(job, JobStatus::Failed, Some(error)),
        }
    }

    /// Runs the simulation, logging each cycle, and stores the result. `Ok(true)` when the
    /// job succeeded, `Ok(false)` when it was cancelled, `Err` with the reason when it failed.
    fn simulate(&self, job: &Job, mut writer: CyclesWriter) -> Result<bool, String> {
        let Some(scene) = &job.scene else {
            return Err("the job's scene is not loaded".to_owned());
        };
        let mut storage_error: Option<String> = None;
        let outcome = simulation::run(
            scene,
            &mut |record: &CycleRecord| {
                let line = match serde_json::to_string(record) {
                    Ok(line) => line,
                    Err(e) => {
                        storage_error.get_or_insert(format!("cycle record: {e}"));
                        job.cancel.store(true, Ordering::Relaxed);
                        return;
                    }
                };
                if storage_error.is_none() {
                    if let Err(e) = writer.append(&line) {
                        // The run cannot be made durable: stop it and fail the job.
                        storage_error = Some(format!("storage: {e}"));
                        job.cancel.store(true, Ordering::Relaxed);
                    }
                }
                job.push_cycle(record.cycle, line.into());
            },
            &job.cancel,
        );
        if let Some(error) = storage_error {
            return Err(error);
        }
        // Whatever the outcome, the final status will say the log is complete.
        writer.finish().map_err(|e| format!("storage: {e}"))?;
        match outcome {
            Ok(result) => {
                let json = serde_json::to_vec(&result).map_err(|e| format!("result: {e}"))?;
                self.store
                    .write_result(job.id, &json)
                    .map_err(|e| format!("storage: {e}"))?;
                Ok(true)
            }
            Err(SimulationError::Cancelled { .. }) => Ok(false),
            Err(e) => Err(e.to_string()),
        }
    }

    /// Persists a final status, then shows it: a client that sees `succeeded` can download
    /// the result.
    fn finish(&self, job: &Job, status: JobStatus, error: Option<String>) {
        let mut record = job.record();
        record.status = status;
        record.eta_s = None;
        record.error = error;
        record.finished_at = Some(OffsetDateTime::now_utc());
        if status == JobStatus::Succeeded {
            record.cycles_done = record.cycles_total;
        }
        if let Err(e) = self.store.write_status(&record) {
            // The disk still says queued/running, so the job runs again at the next start.
            tracing::error!(id = %job.id, "cannot persist final status: {e}");
        }
        match &record.error {
            Some(error) => tracing::warn!(id = %job.id, status = ?status, %error, "job finished"),
            None => tracing::info!(id = %job.id, status = ?status, "job finished"),
        }
        // The cycles are in `cycles.jsonl` now; event streams read them from there, so memory
        // holds the cycles of running jobs only.
        job.update(|state| {
            state.record = record;
            state.started = None;
            state.cycles = None;
        });
    }
}
