//! Measured points a lab attaches to a job, to draw beside the model: the kinds and their
//! tables, read and checked as the calibration checks its own (`table.rs`), their files in
//! the job's directory (`store.rs`), their scores against the job's result (`score.rs`) and
//! their routes (`routes.rs`).

mod routes;
mod score;
mod store;
mod table;

pub(crate) use routes::endpoints;
pub(crate) use store::read_of as read;
pub use table::{Format, MeasurementError, MeasurementKind, parse};
