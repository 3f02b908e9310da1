//! The registry of every job by id: loading it from the store at startup, accepting new
//! jobs, and DELETE.
//!
//! Handlers touch the registry only through short, non-blocking critical sections; anything
//! that writes files runs on tokio's blocking pool. Lock order: queue, registry map, a job's
//! state; none is held across a file write.

use std::collections::HashMap;
use std::io;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use time::OffsetDateTime;
use uuid::Uuid;

use super::job::{Job, JobRecord, JobStatus};
use super::queue::Queue;
use super::store::Store;
use crate::scene::Scene;

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

/// The registry, the queue and the store, shared by handlers and workers.
pub struct Jobs {
    pub(super) store: Store,
    jobs: Mutex<HashMap<Uuid, Arc<Job>>>,
    pub(super) queue: Queue,
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
            queue: Queue::new(capacity),
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
        self.queue.push(job);
        Ok(())
    }

    fn insert(&self, job: Arc<Job>) {
        self.lock_jobs().insert(job.id, job);
    }

    pub(super) fn lock_jobs(&self) -> MutexGuard<'_, HashMap<Uuid, Arc<Job>>> {
        self.jobs.lock().unwrap_or_else(PoisonError::into_inner)
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
        if !self.queue.reserve() {
            return Err(SubmitError::QueueFull {
                capacity: self.queue.capacity(),
                retry_after_s: self.retry_after_s(),
            });
        }
        let record = JobRecord::queued(&scene);
        if let Err(e) = self.store.create(&record, &scene) {
            self.queue.release();
            return Err(SubmitError::Storage(e));
        }
        let job = Arc::new(Job::new(record.clone(), Some(scene), Some(Vec::new())));
        self.insert(Arc::clone(&job));
        self.queue.admit(job);
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
        self.queue.remove(id);
        let mut state = job.state();
        let deletion = match state.record.status {
            JobStatus::Queued => {
                state.record.status = JobStatus::Cancelled;
                state.record.finished_at = Some(OffsetDateTime::now_utc());
                let record = state.record.clone();
                drop(state);
                job.notify();
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
}
