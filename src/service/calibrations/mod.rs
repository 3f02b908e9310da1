//! Calibrations: fits of the model's parameters to a lab's tables, run by `calibration`'s
//! `check` and `calibrate`. The registry of fits and the threads they run on
//! (`registry.rs`), the request and its checks (`request.rs`) and the routes (`routes.rs`).

mod registry;
mod request;
mod routes;

pub(crate) use registry::Calibrations;
pub(crate) use routes::endpoints;
