//! Why an operation on jobs did not do what was asked, one type per operation: submitting
//! (`SubmitError`), deleting (`DeleteError`), reading what a job has (`JobError`, with
//! `PartialError` for what a stopped run computed). They say what happened in the service's
//! terms; `routes.rs` gives each its HTTP answer. Why a job that ran failed (`JobFailure`)
//! is no answer to a request: its text is kept in the job's record.

use std::io;

use thiserror::Error;
use uuid::Uuid;

use super::job::JobStatus;
use crate::scene::SceneErrors;
use crate::service::files::Damage;
use crate::service::surfaces::SurfaceLoadError;
use crate::simulation::SimulationError;

/// Why a job was not accepted.
#[derive(Debug)]
pub enum SubmitError {
    /// The scene names a stored surface there is none of: accepted, it could only fail.
    Unservable(SceneErrors),
    /// The queue holds its capacity; retry after about this many seconds.
    QueueFull {
        /// The queue's capacity.
        capacity: usize,
        /// Places free now (fewer than asked for).
        free: usize,
        /// A hint for Retry-After.
        retry_after_s: u64,
    },
    /// The disk is full: the job could not be made durable, and nothing of it is left.
    DiskFull,
    /// The job could not be made durable.
    Storage(io::Error),
}

/// Why DELETE did not cancel or remove a job.
#[derive(Debug)]
pub enum DeleteError {
    /// No job has this id, or a concurrent DELETE removed it first.
    Unknown(Uuid),
    /// The new status could not be written, or the directory not removed.
    Storage(io::Error),
}

/// Why a job's labels were not changed.
#[derive(Debug)]
pub enum RelabelError {
    /// The job is unknown, or damaged.
    Job(JobError),
    /// The record could not be written; the labels are as they were.
    Storage(io::Error),
}

impl From<JobError> for RelabelError {
    fn from(error: JobError) -> Self {
        Self::Job(error)
    }
}

/// Why a job's record, scene, result or files could not be given.
#[derive(Debug)]
pub enum JobError {
    /// No job has this id, or it was deleted meanwhile.
    Unknown(Uuid),
    /// The job is damaged (its stored scene cannot be read); the message says how.
    Damaged(String),
    /// The job has not finished, so it has no result yet.
    Unfinished(JobStatus),
    /// The stored result was found damaged, so the job was sent back to the queue.
    RunsAgain {
        /// What was wrong with the result.
        damage: Damage,
        /// The job's status now.
        now: JobStatus,
    },
    /// The stored scene does not match what was written.
    SceneDamaged(Damage),
    /// The stored scene could not be read (the machine's fault: the next request may work).
    SceneUnreadable(Damage),
    /// The stored result could not be read (the machine's fault, as above).
    ResultUnreadable(Damage),
    /// A stopped job's partial result cannot be given.
    Partial(PartialError),
    /// The result could not be written as CSV.
    Export(serde_json::Error),
}

/// Why a stopped job's partial result cannot be given.
#[derive(Debug, Error)]
pub enum PartialError {
    /// The stored scene cannot be read back.
    #[error("the stored scene is damaged: {0}")]
    Scene(#[from] Damage),
    /// The cycle log cannot be read.
    #[error("cycles.jsonl cannot be read: {0}")]
    Cycles(#[from] io::Error),
    /// The scene cannot be set up, so the run stopped before its first cycle.
    #[error("{source}")]
    Setup {
        /// Why the setup fails.
        source: SimulationError,
        /// The error the job was recorded with, which says the same in the run's words.
        recorded: Option<String>,
    },
    /// The height map the scene names is gone or damaged.
    #[error("{0}")]
    Surface(#[from] SurfaceLoadError),
    /// The result cannot be written as JSON.
    #[error("the result cannot be written: {0}")]
    Json(#[from] serde_json::Error),
}

/// Why a job that ran failed; its text is the `error` of the job's record.
#[derive(Debug, Error)]
pub enum JobFailure {
    /// The scene was not in memory when a worker took the job.
    #[error("the job's scene is not loaded")]
    SceneNotLoaded,
    /// The job's status, cycle log or result could not be written.
    #[error("storage: {0}")]
    Storage(#[from] io::Error),
    /// A cycle's record cannot be written as JSON.
    #[error("cycle record: {0}")]
    CycleRecord(#[source] serde_json::Error),
    /// The result cannot be written as JSON.
    #[error("result: {0}")]
    Result(#[source] serde_json::Error),
    /// The height map the scene names is gone or damaged.
    #[error(transparent)]
    Surface(#[from] SurfaceLoadError),
    /// The stored scene no longer passes its checks.
    #[error(transparent)]
    Scene(#[from] SceneErrors),
    /// The run stopped without a result.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The simulation panicked, with the panic's message.
    #[error("internal error: the simulation panicked: {0}")]
    Panicked(String),
}
