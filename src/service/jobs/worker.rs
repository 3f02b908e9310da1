//! The worker threads that run simulations, and the glue between a run and its job: each
//! cycle is logged to disk and shown to event-stream clients, the result is stored, and the
//! final status is persisted before it is shown.
//!
//! Workers are plain OS threads, not tokio tasks: `simulation::run` is synchronous and
//! CPU-bound for seconds to minutes, and must never sit on the async runtime's threads.

use std::io;
use std::num::NonZeroUsize;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::thread::JoinHandle;
use std::time::Instant;

use time::OffsetDateTime;

use super::error::JobFailure;
use super::job::{Job, JobStatus};
use super::registry::Jobs;
use super::store::CyclesWriter;
use crate::scene::Scene;
use crate::service::surfaces::surface_id;
use crate::simulation::{self, CycleRecord, Plan, RunOptions, SimulationError};

impl Jobs {
    /// Starts `workers` threads that take jobs from the queue until [`Jobs::stop`].
    pub fn start_workers(self: &Arc<Self>, workers: usize) -> io::Result<Vec<JoinHandle<()>>> {
        (0..workers)
            .map(|n| {
                let jobs = Arc::clone(self);
                std::thread::Builder::new()
                    .name(format!("tribosim-worker-{n}"))
                    .spawn(move || {
                        // The lease holds the job's memory in the budget until it ends.
                        while let Some((job, _lease)) = jobs.queue.next() {
                            jobs.run_job(&job, workers);
                        }
                    })
            })
            .collect()
    }

    /// Stops the workers: no new job starts, and running ones are interrupted within a
    /// cycle. Interrupted jobs keep their persisted status and run again at the next start.
    pub fn stop(&self) {
        self.queue.stop();
        for job in self.lock_jobs().values() {
            if job.state().record.status == JobStatus::Running {
                job.cancel.store(true, Ordering::Relaxed);
            }
        }
    }

    /// Marks a job taken from the queue running, on disk and in memory, and opens its cycle
    /// log; `None` when it is no longer queued (cancelled while it waited).
    fn start(&self, job: &Job) -> Option<Result<(Arc<Scene>, CyclesWriter), JobFailure>> {
        let _disk = job.disk();
        let mut record = job.record();
        if record.status != JobStatus::Queued {
            return None;
        }
        let scene = job.state().scene.clone();
        record.status = JobStatus::Running;
        record.started_at = Some(OffsetDateTime::now_utc());
        job.update(|state| {
            state.record = record.clone();
            state.started = Some(Instant::now());
        });
        tracing::info!(id = %job.id, "job running");
        let Some(scene) = scene else {
            return Some(Err(JobFailure::SceneNotLoaded));
        };
        Some(
            self.store
                .write_status(&record)
                .and_then(|()| self.store.cycles_writer(job.id))
                .map(|writer| (scene, writer))
                .map_err(JobFailure::Storage),
        )
    }

    fn run_job(&self, job: &Job, workers: usize) {
        let Some(started) = self.start(job) else {
            return;
        };
        let outcome = started.and_then(|(scene, writer)| {
            // A panic in the simulation must fail its job, not kill the worker and leave the
            // job `running` for ever.
            panic::catch_unwind(AssertUnwindSafe(|| {
                self.simulate(job, &scene, writer, workers)
            }))
            .unwrap_or_else(|payload| Err(panic_message(payload.as_ref())))
        });
        match outcome {
            Ok(true) => self.finish(job, JobStatus::Succeeded, None),
            Ok(false) => {
                if job.state().cancel_requested {
                    self.finish(job, JobStatus::Cancelled, None);
                } else {
                    tracing::info!(id = %job.id, "job interrupted by shutdown; it runs again at the next start");
                }
            }
            Err(error) => self.finish(job, JobStatus::Failed, Some(error.to_string())),
        }
    }

    /// Runs the simulation, logging each cycle, and stores the result. `Ok(true)` when the
    /// job succeeded, `Ok(false)` when it was cancelled, `Err` with the reason when it failed.
    fn simulate(
        &self,
        job: &Job,
        scene: &Scene,
        mut writer: CyclesWriter,
        workers: usize,
    ) -> Result<bool, JobFailure> {
        let mut storage_error: Option<JobFailure> = None;
        let map = match surface_id(scene) {
            Some(id) => Some(self.surfaces.load(id)?),
            None => None,
        };
        // Each worker's solves get their share of the cores (`numerics.threads: "auto"`).
        let options = RunOptions {
            surface: map.as_ref(),
            concurrent_runs: NonZeroUsize::new(workers).unwrap_or(NonZeroUsize::MIN),
        };
        // The scene was checked when submitted; kept on disk, it is checked again here.
        let plan = Plan::new(scene.clone())?;
        let outcome = simulation::run_with(
            &plan,
            &options,
            &mut |record: &CycleRecord| {
                let line = match serde_json::to_string(record) {
                    Ok(line) => line,
                    Err(e) => {
                        storage_error.get_or_insert(JobFailure::CycleRecord(e));
                        job.cancel.store(true, Ordering::Relaxed);
                        return;
                    }
                };
                if storage_error.is_none() {
                    if let Err(e) = writer.append(&line) {
                        // The run cannot be made durable: stop it and fail the job.
                        storage_error = Some(JobFailure::Storage(e));
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
        let cycles = writer.finish()?;
        match outcome {
            Ok(result) => {
                let json = serde_json::to_vec(&result).map_err(JobFailure::Result)?;
                self.store.write_result(job.id, &json, cycles)?;
                Ok(true)
            }
            Err(SimulationError::Cancelled { .. }) => Ok(false),
            Err(e) => Err(e.into()),
        }
    }

    /// Persists a final status, then shows it: a client that sees `succeeded` can download
    /// the result.
    fn finish(&self, job: &Job, status: JobStatus, error: Option<String>) {
        let _disk = job.disk();
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
            state.scene = None;
        });
    }
}

fn panic_message(payload: &(dyn std::any::Any + Send)) -> JobFailure {
    let message = payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("no message");
    JobFailure::Panicked(message.to_owned())
}
