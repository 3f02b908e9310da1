//! The handlers of what a job carries besides its run: the scene as run and the measured
//! points attached to it. Like the other handlers they only translate between HTTP and the
//! registry's plain functions.

use std::sync::Arc;

use axum::Json;
use axum::extract::{Request, State};
use axum::response::{IntoResponse, Response};

use super::AppState;
use super::error::ApiError;
use super::extract::{JobId, JobMeasurement, read_body, table_format};
use super::files::is_disk_full;
use super::job::JobStatus;
use super::measurements::{self, Measurements};
use super::registry::{Jobs, MeasuredError};

/// `PUT /api/v1/jobs/{id}/measurements/{kind}`: reads, checks and stores a table; answers
/// every table of the job.
pub(super) async fn put_measurement(
    State(app): State<AppState>,
    JobMeasurement(id, kind): JobMeasurement,
    request: Request,
) -> Result<Response, ApiError> {
    let format = table_format(request.headers()).ok_or_else(ApiError::unsupported_table_type)?;
    let body = read_body(&app, request).await?;
    let columns = measurements::parse(kind, format, &body)
        .map_err(|e| ApiError::invalid_table(kind.name(), e.column(), &e.to_string()))?;
    measured(
        &app,
        move |jobs| jobs.put_measurement(id, kind, columns),
        id,
    )
    .await
}

/// `GET /api/v1/jobs/{id}/measurements`: every table of the job, null where none.
pub(super) async fn get_measurements(
    State(app): State<AppState>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    measured(&app, move |jobs| jobs.measurements(id), id).await
}

/// `DELETE /api/v1/jobs/{id}/measurements/{kind}`: removes a table (if there is one);
/// answers every table left.
pub(super) async fn delete_measurement(
    State(app): State<AppState>,
    JobMeasurement(id, kind): JobMeasurement,
) -> Result<Response, ApiError> {
    measured(&app, move |jobs| jobs.delete_measurement(id, kind), id).await
}

/// Runs a registry call on the blocking pool and answers its measurements.
async fn measured(
    app: &AppState,
    call: impl FnOnce(&Jobs) -> Option<Result<Measurements, MeasuredError>> + Send + 'static,
    id: uuid::Uuid,
) -> Result<Response, ApiError> {
    let jobs = Arc::clone(&app.jobs);
    let measurements = tokio::task::spawn_blocking(move || call(&jobs))
        .await
        .map_err(|e| ApiError::internal("measurements", &e))?
        .ok_or_else(|| ApiError::unknown_job(id))?
        .map_err(|e| match e {
            MeasuredError::JobDamaged(error) => {
                ApiError::conflict(format!("job is damaged: {error}"))
            }
            MeasuredError::Damaged(damage) if damage.is_read_failure() => {
                ApiError::internal("reading measurements", &damage)
            }
            MeasuredError::Damaged(damage) => ApiError::conflict(format!(
                "a stored measurement table is damaged ({damage}); PUT or DELETE it again"
            )),
            MeasuredError::Storage(e) if is_disk_full(&e) => {
                ApiError::disk_full("the measurements were not changed")
            }
            MeasuredError::Storage(e) => ApiError::internal("storing measurements", &e),
        })?;
    Ok(Json(measurements).into_response())
}

/// `GET /api/v1/jobs/{id}/scene`: the scene as run, every default filled in, as stored
/// when the job was accepted.
pub(super) async fn job_scene(
    State(app): State<AppState>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    let job = app.jobs.get(id).ok_or_else(|| ApiError::unknown_job(id))?;
    let record = job.record();
    if record.status == JobStatus::Damaged {
        let error = record.error.unwrap_or_default();
        return Err(ApiError::conflict(format!("job is damaged: {error}")));
    }
    let jobs = Arc::clone(&app.jobs);
    let scene = tokio::task::spawn_blocking(move || jobs.store().read_scene(id))
        .await
        .map_err(|e| ApiError::internal("reading a scene", &e))?
        .map_err(|damage| {
            if app.jobs.get(id).is_none() {
                // Deleted since it was looked up.
                ApiError::unknown_job(id)
            } else if damage.is_read_failure() {
                ApiError::internal("reading a scene", &damage)
            } else {
                ApiError::conflict(format!("the stored scene is damaged: {damage}"))
            }
        })?;
    Ok(Json(scene).into_response())
}
