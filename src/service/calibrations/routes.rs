//! The routes of `/api/v1/calibrations`, and the API's answer to each error of a fit. A bad
//! table is a 422 naming its column and row, found by the fit's own check before anything
//! runs; the fit then runs on [`Calibrations`]' threads.

use std::sync::Arc;

use axum::Json;
use axum::extract::{FromRef, State};
use axum::http::StatusCode;
use axum::response::Response;
use axum::routing::on;
use serde_json::Value;

use super::registry::{CalibrationRecord, Calibrations, MAX_RUNNING, StartError};
use super::request::{CalibrationRequest, Inputs, invalid};
use crate::calibration::{CalibrationError, check};
use crate::service::blocking::blocking;
use crate::service::error::ApiError;
use crate::service::extract::{BodyTimeout, CalibrationId, JsonBody, JsonRequest};
use crate::service::reply::created;
use crate::service::route::{Endpoint, Verb};

/// Seconds a client is asked to wait when every fit slot is busy: about one Archard fit of
/// Table 3 (7.5 s on a shared two-core machine, docs/calibration.md).
const BUSY_RETRY_AFTER_S: u64 = 10;

/// The routes, on any state that provides the calibrations and the body timeout.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Calibrations>: FromRef<S>,
    BodyTimeout: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Post, "/api/v1/calibrations", |f| {
            on(f, submit_calibration)
        }),
        Endpoint::api(Verb::Get, "/api/v1/calibrations/{id}", |f| {
            on(f, get_calibration)
        }),
    ]
}

impl JsonRequest for CalibrationRequest {
    const NAME: &'static str = "calibration request";

    fn from_json(document: Value, _text: &str) -> Result<Self, ApiError> {
        Self::from_document(document)
    }

    fn duplicate_key(path: String, message: String) -> ApiError {
        invalid(&path, message)
    }
}

/// `POST /api/v1/calibrations`: checks the request and the table, then starts the fit; 202
/// with its record and `Location`.
async fn submit_calibration(
    State(calibrations): State<Arc<Calibrations>>,
    JsonBody(request): JsonBody<CalibrationRequest>,
) -> Result<Response, ApiError> {
    let record = blocking(move || {
        let Inputs {
            kind,
            table,
            scene,
            options,
        } = request.inputs()?;
        check(kind, &table, &scene, options)?;
        Ok::<_, ApiError>(calibrations.start(kind, table, scene, options)?)
    })
    .await?;
    let location = format!("/api/v1/calibrations/{}", record.id);
    Ok(created(StatusCode::ACCEPTED, location, record))
}

/// `GET /api/v1/calibrations/{id}`: the fit, with its result once it has one.
async fn get_calibration(
    State(calibrations): State<Arc<Calibrations>>,
    CalibrationId(id): CalibrationId,
) -> Result<Json<CalibrationRecord>, ApiError> {
    let record = calibrations.get(id);
    record
        .map(Json)
        .ok_or_else(|| ApiError::not_found(format!("no calibration {id}")))
}

/// 422 at the scene or at the table, wherever the fit's check found the fault.
impl From<CalibrationError> for ApiError {
    fn from(error: CalibrationError) -> Self {
        let path = match error {
            CalibrationError::MissingSection(_)
            | CalibrationError::Scene(_)
            | CalibrationError::Hardness(_) => "scene",
            _ => "table",
        };
        invalid(path, error.to_string())
    }
}

/// 429 with Retry-After while every fit slot is busy.
impl From<StartError> for ApiError {
    fn from(error: StartError) -> Self {
        match error {
            StartError::Busy => Self::too_many_requests(
                format!("{MAX_RUNNING} calibrations are running, the most at once; retry later"),
                BUSY_RETRY_AFTER_S,
            ),
            StartError::Thread(e) => Self::internal("starting a calibration", &e),
        }
    }
}
