//! Jobs: a scene accepted to run, its record and states (`job.rs`), the bounded queue it
//! waits in (`queue.rs`), the registry of every job by id with submission and DELETE
//! (`registry.rs`), the worker threads that run it (`worker.rs`), its durable directory
//! (`store.rs`), its event stream (`events.rs`), what it gives back (`results.rs`, with the
//! CSV of `export.rs`), why an operation on it failed (`error.rs`) and its routes
//! (`routes.rs`). `impl Jobs` has one block per concern: the registry, the workers, the
//! results.

mod error;
mod events;
mod export;
mod job;
mod labels;
mod queue;
mod registry;
mod results;
mod routes;
mod store;
mod worker;

pub(crate) use error::{DeleteError, JobError, SubmitError};
pub(crate) use events::Streams;
pub(crate) use job::{JobRecord, JobStatus};
pub(crate) use registry::{Deletion, Jobs};
pub(crate) use routes::endpoints;
pub(crate) use store::Store;
