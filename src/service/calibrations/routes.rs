//! The routes of `/api/v1/calibrations`, and the API's answer to each error of a fit. A bad
//! table is a 422 naming its column and row, found by the fit's own check before anything
//! runs; the fit then runs on [`Calibrations`]' threads.

use std::sync::Arc;

use axum::Json;
use axum::extract::{FromRef, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::on;
use serde_json::Value;

use super::registry::{
    CalibrationDeletion, CalibrationInfo, CalibrationRecord, Calibrations, FILTERS, FitLimits,
    MAX_RUNNING, StartError,
};
use super::request::{CalibrationRequest, Inputs, invalid};
use crate::calibration::{CalibrationError, FitKind, Table, check, run_size};
use crate::scene::Scene;
use crate::service::blocking::blocking;
use crate::service::cursor::CursorKey;
use crate::service::error::ApiError;
use crate::service::extract::{BodyTimeout, CalibrationId, JsonBody, JsonRequest};
use crate::service::listing::{ListQuery, Page};
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
    CursorKey: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Post, "/api/v1/calibrations", |f| {
            on(f, submit_calibration)
        }),
        Endpoint::api(Verb::Get, "/api/v1/calibrations", |f| {
            on(f, list_calibrations)
        }),
        Endpoint::api(Verb::Get, "/api/v1/calibrations/{id}", |f| {
            on(f, get_calibration)
        }),
        Endpoint::api(Verb::Delete, "/api/v1/calibrations/{id}", |f| {
            on(f, delete_calibration)
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
        within_limits(kind, &table, &scene, calibrations.limits)?;
        Ok::<_, ApiError>(calibrations.start(kind, table, scene, options)?)
    })
    .await?;
    let location = format!("/api/v1/calibrations/{}", record.id);
    let record = CalibrationRecord {
        info: record,
        result: None,
    };
    Ok(created(StatusCode::ACCEPTED, location, record))
}

/// 422 for a fit whose runs are larger than the server's limits allow, naming the flag that
/// raises each.
fn within_limits(
    kind: FitKind,
    table: &Table,
    scene: &Scene,
    limits: FitLimits,
) -> Result<(), ApiError> {
    let Some(size) = run_size(kind, table, scene)? else {
        return Ok(());
    };
    if size.cells > limits.max_grid {
        return Err(invalid(
            "scene.numerics.grid",
            format!(
                "the fit's runs would use {} cells per side; this server allows at most {} \
                 (--calibration-max-grid)",
                size.cells, limits.max_grid
            ),
        ));
    }
    if size.cell_cycles() > limits.max_cell_cycles {
        return Err(invalid(
            "table",
            format!(
                "each of the fit's runs would go to cycle {} on {} x {} cells, {} cell-cycles; \
                 this server allows at most {} a run (--calibration-max-cell-cycles): a \
                 coarser grid or fewer cycles fit",
                size.cycles,
                size.cells,
                size.cells,
                size.cell_cycles(),
                limits.max_cell_cycles
            ),
        ));
    }
    Ok(())
}

/// `GET /api/v1/calibrations`: a page of fits, newest first, without their results.
async fn list_calibrations(
    State(calibrations): State<Arc<Calibrations>>,
    query: ListQuery,
) -> Result<Page<CalibrationInfo>, ApiError> {
    query.page("/api/v1/calibrations", calibrations.list(), FILTERS)
}

/// `DELETE /api/v1/calibrations/{id}`: 202 with the record of a running fit, now
/// cancelled; 204 once an ended one is forgotten.
async fn delete_calibration(
    State(calibrations): State<Arc<Calibrations>>,
    CalibrationId(id): CalibrationId,
) -> Result<Response, ApiError> {
    match calibrations.delete(id) {
        Some(CalibrationDeletion::Cancelled(info)) => {
            Ok((StatusCode::ACCEPTED, Json(info)).into_response())
        }
        Some(CalibrationDeletion::Removed) => Ok(StatusCode::NO_CONTENT.into_response()),
        None => Err(ApiError::not_found(format!("no calibration {id}"))),
    }
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
            | CalibrationError::Hardness(_) => "scene".to_owned(),
            CalibrationError::DomainOption { option, .. } => format!("options.{option}"),
            CalibrationError::NotFittable { field, .. } => format!("scene.corrosion.{field}"),
            _ => "table".to_owned(),
        };
        invalid(&path, error.to_string())
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
