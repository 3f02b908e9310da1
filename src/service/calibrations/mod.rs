//! Calibrations: fits of the model's parameters to a lab's tables, run by `calibration`'s
//! `check` and `calibrate`. The registry of fits and the threads they run on
//! (`registry.rs`), the ended fits on disk (`store.rs`), the request and its checks
//! (`request.rs`) and the routes (`routes.rs`).

mod registry;
mod request;
mod routes;
mod store;

pub(crate) use registry::{Calibrations, FitLimits};
pub(crate) use routes::endpoints;
pub(crate) use store::CalibrationStore;
