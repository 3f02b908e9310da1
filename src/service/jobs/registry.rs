//! The registry of every job by id: loading it from the store at startup, accepting new
//! jobs, sending a job whose stored result is damaged back to the queue, DELETE, and a job's
//! directory for what is attached to it (measurements).
//!
//! Handlers touch the registry only through short, non-blocking critical sections; anything
//! that writes files runs on tokio's blocking pool. Lock order: a job's disk lock, the queue,
//! the registry map, a job's state; only the disk lock is held across a file write.

use std::collections::HashMap;
use std::io;
use std::path::Path;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use time::OffsetDateTime;
use uuid::Uuid;

use super::error::{DeleteError, JobError, RelabelError, SubmitError};
use super::job::{Job, JobRecord, JobStatus};
use super::labels::LabelChange;
use super::queue::Queue;
use super::store::{Store, StoredJob};
use crate::scene::{FieldError, Scene, SceneErrors};
use crate::service::files::{Damage, is_disk_full};
use crate::service::surfaces::{SurfaceUsers, Surfaces, servable, surface_id};
use crate::simulation::{Plan, describe_size};

/// What DELETE did.
pub enum Deletion {
    /// The job was queued and is now cancelled.
    Cancelled(JobRecord),
    /// The job is running; it stops within a cycle, and is already cancelled on disk.
    Cancelling(JobRecord),
    /// The job had finished; it and its files are gone.
    Removed,
}

/// The registry, the queue and the store, shared by handlers and workers.
pub struct Jobs {
    pub(super) store: Store,
    jobs: Mutex<HashMap<Uuid, Arc<Job>>>,
    pub(super) queue: Queue,
    /// The height maps that scenes with a measured surface name.
    pub(super) surfaces: Arc<Surfaces>,
}

impl Jobs {
    /// Loads every job from `store`: finished ones are served as they are, queued ones are
    /// queued again, and ones that were running are queued to run again from scratch (in
    /// the order they were accepted). A succeeded job whose result is damaged runs again; a
    /// job whose scene is damaged is listed as `damaged`. One job's damage never stops the
    /// others from loading.
    pub fn open(
        store: Store,
        capacity: usize,
        memory_budget_bytes: u64,
        surfaces: Arc<Surfaces>,
    ) -> io::Result<Arc<Self>> {
        let mut stored = store.load()?;
        stored.sort_by_key(|job| {
            job.record
                .as_ref()
                .map(|record| record.created_at)
                .ok()
                .or(job.modified)
        });
        let jobs = Arc::new(Self {
            store,
            jobs: Mutex::new(HashMap::new()),
            queue: Queue::new(capacity, memory_budget_bytes),
            surfaces,
        });
        for job in stored {
            jobs.restore(job);
        }
        Ok(jobs)
    }

    fn restore(&self, stored: StoredJob) {
        let StoredJob {
            id,
            record,
            scene,
            modified,
        } = stored;
        let created_at = modified.unwrap_or_else(OffsetDateTime::now_utc);
        let scene = match scene {
            Ok(scene) => scene,
            Err(damage) => {
                let mut record = record.unwrap_or_else(|_| placeholder(id, created_at));
                tracing::error!(%id, "stored scene damaged: {damage}; the job is listed as damaged");
                record.status = JobStatus::Damaged;
                record.eta_s = None;
                record.error = Some(format!("stored scene damaged: {damage}"));
                self.insert(Arc::new(Job::new(record, None, None)));
                return;
            }
        };
        let mut record = match record {
            Ok(record) => record,
            Err(damage) => {
                tracing::error!(%id, "{damage}; the record is rebuilt from the scene");
                let record = rebuilt(id, &scene, created_at, &damage, &self.store);
                if record.status == JobStatus::Succeeded {
                    if let Err(e) = self.store.write_status(&record) {
                        tracing::error!(%id, "cannot rewrite status.json: {e}");
                    }
                }
                record
            }
        };
        match record.status {
            JobStatus::Succeeded => match self.store.check_result(id) {
                Ok(()) => self.insert(Arc::new(Job::new(record, None, None))),
                Err(damage) => {
                    record.rerun_reason = Some(format!("stored result damaged: {damage}"));
                    self.requeue_at_start(record, scene);
                }
            },
            JobStatus::Failed | JobStatus::Cancelled | JobStatus::Damaged => {
                self.insert(Arc::new(Job::new(record, None, None)));
            }
            JobStatus::Queued | JobStatus::Running => self.requeue_at_start(record, scene),
        }
    }

    /// Queues a job found unfinished (or with a damaged result) at startup. The new status
    /// is written if it can be; if not, the disk still says the job must run, which is what
    /// it does.
    fn requeue_at_start(&self, mut record: JobRecord, scene: Scene) {
        let id = record.id;
        let was = record.status;
        record.status = JobStatus::Queued;
        record.cycles_done = 0;
        record.eta_s = None;
        record.error = None;
        record.started_at = None;
        record.finished_at = None;
        if was != JobStatus::Queued || record.rerun_reason.is_some() {
            if let Err(e) = self.store.write_status(&record) {
                tracing::error!(%id, "cannot rewrite status.json: {e}");
            }
        }
        match &record.rerun_reason {
            Some(reason) => tracing::warn!(%id, was = ?was, %reason, "job queued to run again"),
            None => tracing::info!(%id, was = ?was, "job re-queued after restart"),
        }
        let memory_bytes = peak_memory_bytes(&scene);
        let job = Arc::new(Job::new(record, Some(scene), Some(Vec::new())));
        self.insert(Arc::clone(&job));
        self.queue.push(job, memory_bytes);
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

    /// The job with this id, or why there is none.
    pub fn find(&self, id: Uuid) -> Result<Arc<Job>, JobError> {
        self.get(id).ok_or(JobError::Unknown(id))
    }

    /// A job's record as the API shows it, with its place in the queue.
    pub fn shown(&self, job: &Job) -> JobRecord {
        JobRecord {
            queue_position: self.queue.position(job.id),
            ..job.record()
        }
    }

    /// Every job, in no order, and how the API shows one: its record with its place in
    /// the queue (the places taken once, so showing every job stays linear in the queue).
    pub fn listing(&self) -> (Vec<Arc<Job>>, impl Fn(Arc<Job>) -> JobRecord + use<>) {
        let jobs = self.lock_jobs().values().cloned().collect();
        let positions = self.queue.positions();
        let show = move |job: Arc<Job>| JobRecord {
            queue_position: positions.get(&job.id).copied(),
            ..job.record()
        };
        (jobs, show)
    }

    /// Every job's record as the API shows it, newest first.
    pub fn list(&self) -> Vec<JobRecord> {
        let (jobs, show) = self.listing();
        let mut records: Vec<JobRecord> = jobs.into_iter().map(show).collect();
        records.sort_by(|a, b| b.created_at.cmp(&a.created_at).then(a.id.cmp(&b.id)));
        records
    }

    /// The store the jobs live in.
    pub fn store(&self) -> &Store {
        &self.store
    }

    /// The height maps that scenes with a measured surface name.
    pub fn surfaces(&self) -> &Surfaces {
        &self.surfaces
    }

    /// How many jobs may wait for a worker at once.
    pub fn capacity(&self) -> usize {
        self.queue.capacity()
    }

    /// The estimated peak memory of a validated scene, bytes, if the service can run it: a
    /// stored surface it names must be there, and its estimate within the jobs' memory
    /// budget (refused otherwise with the estimate, the budget and the fields that lower it).
    pub fn admissible(&self, scene: &Scene) -> Result<u64, SceneErrors> {
        servable(scene, &self.surfaces)?;
        let memory_bytes = peak_memory_bytes(scene);
        let budget_bytes = self.queue.memory_budget_bytes();
        if memory_bytes > budget_bytes {
            return Err(SceneErrors(vec![FieldError::new(
                "numerics.grid",
                format!(
                    "the run is estimated to need {} of memory at its peak, over this server's \
                     budget for jobs of {} (`tribosim serve --job-memory-mib`): fewer cells \
                     (`numerics.grid`) or a fixed, smaller `numerics.domain_um` need less",
                    describe_size(memory_bytes as f64),
                    describe_size(budget_bytes as f64)
                ),
            )]));
        }
        Ok(memory_bytes)
    }

    /// Accepts a validated scene that the service can run ([`Jobs::admissible`]): makes it
    /// durable, then queues it. Blocking (file writes).
    pub fn submit(&self, scene: Scene, labels: LabelChange) -> Result<JobRecord, SubmitError> {
        // Only a scene naming a stored surface waits for (and holds off) its deletion.
        let _hold = surface_id(&scene).map(|_| self.surfaces.hold());
        let memory_bytes = self.admissible(&scene).map_err(SubmitError::Unservable)?;
        if !self.queue.reserve() {
            return Err(SubmitError::QueueFull {
                capacity: self.queue.capacity(),
                free: 0,
                retry_after_s: self.retry_after_s(),
            });
        }
        let mut record = JobRecord::queued(&scene);
        labels.apply(&mut record);
        if let Err(e) = self.store.create(&record, &scene) {
            self.queue.release();
            return Err(if is_disk_full(&e) {
                tracing::error!("job refused: {e}");
                SubmitError::DiskFull
            } else {
                SubmitError::Storage(e)
            });
        }
        let job = Arc::new(Job::new(record, Some(scene), Some(Vec::new())));
        self.insert(Arc::clone(&job));
        self.queue.admit(Arc::clone(&job), memory_bytes);
        let record = self.shown(&job);
        tracing::info!(id = %record.id, cycles = record.cycles_total, "job queued");
        Ok(record)
    }

    /// Accepts several validated scenes at once (a study's members), each with its peak
    /// memory as [`Jobs::admissible`] gave it, all or none: places for all of them are reserved, `begin` records the jobs about to be written (so that
    /// a crash before `persist` can be undone), each is made durable, `persist` records
    /// what owns them, and only then are they queued. If any step fails, the jobs already
    /// written are removed. Blocking (file writes).
    pub fn submit_many(
        &self,
        scenes: Vec<(Scene, u64)>,
        begin: impl FnOnce(&[JobRecord]) -> io::Result<()>,
        persist: impl FnOnce(&[JobRecord]) -> io::Result<()>,
    ) -> Result<Vec<JobRecord>, SubmitError> {
        let count = scenes.len();
        if let Err(free) = self.queue.reserve_many(count) {
            return Err(SubmitError::QueueFull {
                capacity: self.queue.capacity(),
                free,
                retry_after_s: self.retry_after_s(),
            });
        }
        let planned: Vec<(JobRecord, Scene, u64)> = scenes
            .into_iter()
            .map(|(scene, memory_bytes)| (JobRecord::queued(&scene), scene, memory_bytes))
            .collect();
        let all: Vec<JobRecord> = planned.iter().map(|(r, ..)| r.clone()).collect();
        let mut created: Vec<(JobRecord, Scene, u64)> = Vec::with_capacity(count);
        let mut written = begin(&all);
        for (record, scene, memory_bytes) in planned {
            if written.is_err() {
                break;
            }
            written = self.store.create(&record, &scene);
            if written.is_ok() {
                created.push((record, scene, memory_bytes));
            }
        }
        let records: Vec<JobRecord> = created.iter().map(|(r, ..)| r.clone()).collect();
        if let Err(e) = written.and_then(|()| persist(&records)) {
            for record in &records {
                if let Err(e) = self.store.remove(record.id) {
                    tracing::error!(id = %record.id, "cannot remove a refused job: {e}");
                }
            }
            self.queue.release_many(count);
            return Err(if is_disk_full(&e) {
                tracing::error!("jobs refused: {e}");
                SubmitError::DiskFull
            } else {
                SubmitError::Storage(e)
            });
        }
        for (record, scene, memory_bytes) in created {
            let job = Arc::new(Job::new(record, Some(scene), Some(Vec::new())));
            self.insert(Arc::clone(&job));
            self.queue.admit(job, memory_bytes);
        }
        tracing::info!(jobs = count, "jobs queued together");
        Ok(records)
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

    /// Sends a succeeded job whose stored result was found damaged back to the queue: the
    /// simulation is deterministic, so the run gives the same numbers again. A job whose
    /// scene is damaged too becomes `damaged`. The job's record afterwards, or `None` when
    /// it has been deleted meanwhile. Blocking (files).
    pub fn rerun(&self, job: &Arc<Job>, damage: &Damage) -> Option<JobRecord> {
        let id = job.id;
        let _disk = job.disk();
        if !self.get(id).is_some_and(|known| Arc::ptr_eq(&known, job)) {
            return None;
        }
        if job.state().record.status != JobStatus::Succeeded {
            // Another request found the damage first.
            return Some(job.record());
        }
        let reason = format!("stored result damaged: {damage}");
        let scene = match self.store.read_scene(id) {
            Ok(scene) => scene,
            Err(scene_damage) => {
                tracing::error!(%id, "{reason}; stored scene damaged: {scene_damage}");
                return Some(job.update(|state| {
                    state.record.status = JobStatus::Damaged;
                    state.record.error =
                        Some(format!("{reason}; stored scene damaged: {scene_damage}"));
                }));
            }
        };
        tracing::warn!(%id, %reason, "job queued to run again");
        let record = job.update(|state| {
            let record = &mut state.record;
            record.status = JobStatus::Queued;
            record.cycles_done = 0;
            record.error = None;
            record.started_at = None;
            record.finished_at = None;
            record.rerun_reason = Some(reason);
            state.scene = Some(Arc::new(scene));
            state.cycles = Some(Vec::new());
        });
        let memory_bytes = job.state().scene.as_deref().map_or(0, peak_memory_bytes);
        if let Err(e) = self.store.write_status(&record) {
            // The disk still says succeeded; the damage is found again at the next start.
            tracing::error!(%id, "cannot rewrite status.json: {e}");
        }
        self.queue.push(Arc::clone(job), memory_bytes);
        Some(record)
    }

    /// DELETE: cancels a queued job at once, asks a running one to stop within a cycle, and
    /// removes a finished one with its files. A cancel is on disk before it is answered, so a
    /// crash cannot bring the job back. Blocking (files).
    pub fn delete(&self, id: Uuid) -> Result<Deletion, DeleteError> {
        let job = self.get(id).ok_or(DeleteError::Unknown(id))?;
        let _disk = job.disk();
        let record = job.record();
        if !record.status.is_final() {
            return self
                .cancel_locked(&job, record)
                .map_err(DeleteError::Storage);
        }
        // Unknown when a concurrent DELETE removed it first.
        self.lock_jobs()
            .remove(&id)
            .ok_or(DeleteError::Unknown(id))?;
        if let Err(e) = self.store.remove(id) {
            self.insert(Arc::clone(&job));
            return Err(DeleteError::Storage(e));
        }
        tracing::info!(%id, "finished job removed");
        Ok(Deletion::Removed)
    }

    /// Cancels a job as DELETE does if it has not finished; leaves a finished one alone
    /// (`Ok(None)`), so that a job ending meanwhile keeps its result. Blocking (files).
    pub fn cancel(&self, id: Uuid) -> Result<Option<Deletion>, DeleteError> {
        let job = self.get(id).ok_or(DeleteError::Unknown(id))?;
        let _disk = job.disk();
        let record = job.record();
        if record.status.is_final() {
            return Ok(None);
        }
        self.cancel_locked(&job, record)
            .map(Some)
            .map_err(DeleteError::Storage)
    }

    /// Changes job `id`'s labels, on disk (its `status.json`, replaced atomically under the
    /// job's disk lock, so that the worker's writes of the record keep them) and then in
    /// memory; the record as shown. Blocking (a file write).
    pub fn relabel(&self, id: Uuid, change: LabelChange) -> Result<JobRecord, RelabelError> {
        let job = self.find(id)?;
        let _disk = job.disk();
        if !self.get(id).is_some_and(|known| Arc::ptr_eq(&known, &job)) {
            return Err(JobError::Unknown(id).into());
        }
        let mut record = job.record();
        if record.status == JobStatus::Damaged {
            return Err(JobError::Damaged(record.error.unwrap_or_default()).into());
        }
        change.apply(&mut record);
        self.store
            .write_status(&record)
            .map_err(RelabelError::Storage)?;
        job.update(|state| {
            state.record.sample = record.sample.clone();
            state.record.note = record.note.clone();
            state.record.tags = record.tags.clone();
        });
        Ok(self.shown(&job))
    }

    /// Runs `act` on the directory of job `id` under the job's disk lock, so that a DELETE of
    /// the job cannot remove the directory meanwhile. Refused for an unknown job (or one
    /// deleted first) and for a damaged one: nothing is attached to a job that cannot run.
    /// Blocking (whatever `act` does to the files).
    pub fn with_files<T>(&self, id: Uuid, act: impl FnOnce(&Path) -> T) -> Result<T, JobError> {
        let job = self.find(id)?;
        let _disk = job.disk();
        if !self.get(id).is_some_and(|known| Arc::ptr_eq(&known, &job)) {
            return Err(JobError::Unknown(id));
        }
        let record = job.record();
        if record.status == JobStatus::Damaged {
            return Err(JobError::Damaged(record.error.unwrap_or_default()));
        }
        Ok(act(&self.store.dir(id)))
    }

    /// Cancels a queued or running job, its disk lock held.
    fn cancel_locked(&self, job: &Arc<Job>, mut record: JobRecord) -> io::Result<Deletion> {
        let id = job.id;
        let was = record.status;
        record.status = JobStatus::Cancelled;
        record.eta_s = None;
        record.finished_at = Some(OffsetDateTime::now_utc());
        self.store.write_status(&record)?;
        if was == JobStatus::Queued {
            self.queue.remove(id);
            tracing::info!(%id, "queued job cancelled");
            Ok(Deletion::Cancelled(
                job.update(|state| state.record = record),
            ))
        } else {
            // On disk the job is cancelled already; in memory it runs until the worker sees
            // the flag, within a cycle.
            job.state().cancel_requested = true;
            job.cancel.store(true, Ordering::Relaxed);
            tracing::info!(%id, "running job asked to cancel");
            Ok(Deletion::Cancelling(job.record()))
        }
    }
}

impl SurfaceUsers for Jobs {
    /// The queued and running jobs whose scene names surface `id`.
    fn using_surface(&self, id: Uuid) -> Vec<Uuid> {
        let jobs: Vec<Arc<Job>> = self.lock_jobs().values().cloned().collect();
        let mut users: Vec<Uuid> = jobs
            .iter()
            .filter(|job| {
                let state = job.state();
                !state.record.status.is_final()
                    && state
                        .scene
                        .as_deref()
                        .and_then(surface_id)
                        .and_then(|named| Uuid::try_parse(named).ok())
                        == Some(id)
            })
            .map(|job| job.id)
            .collect();
        users.sort();
        users
    }
}

/// The record of a job whose scene and record are both unreadable: only its id is known.
fn placeholder(id: Uuid, created_at: OffsetDateTime) -> JobRecord {
    JobRecord {
        id,
        name: String::new(),
        sample: None,
        note: None,
        tags: Vec::new(),
        status: JobStatus::Damaged,
        cycles_done: 0,
        cycles_total: 0,
        eta_s: None,
        error: None,
        rerun_reason: None,
        queue_position: None,
        created_at,
        started_at: None,
        finished_at: None,
    }
}

/// The record of a job whose `status.json` is damaged, rebuilt from its scene: succeeded if
/// its stored result checks out, and otherwise queued to run again, as its status is unknown.
fn rebuilt(
    id: Uuid,
    scene: &Scene,
    created_at: OffsetDateTime,
    damage: &Damage,
    store: &Store,
) -> JobRecord {
    let record = JobRecord {
        id,
        created_at,
        ..JobRecord::queued(scene)
    };
    match store.check_result(id) {
        Ok(()) => JobRecord {
            status: JobStatus::Succeeded,
            cycles_done: record.cycles_total,
            finished_at: Some(created_at),
            ..record
        },
        Err(_) => JobRecord {
            rerun_reason: Some(format!("stored record damaged: {damage}")),
            ..record
        },
    }
}

/// A scene's estimated peak memory, bytes ([`crate::simulation::RunEstimate`]); 0 for one the
/// simulation refuses, which fails at once without holding memory.
fn peak_memory_bytes(scene: &Scene) -> u64 {
    // The estimate is a few floating-point operations from the plan; the cast saturates.
    Plan::new(scene.clone()).map_or(0, |plan| plan.estimate().memory_bytes as u64)
}
