//! The routes of `/api/v1/jobs`, and the API's answer to each error of jobs. The handlers
//! only translate between HTTP and [`Jobs`]: what a request needs is extracted before they
//! run, blocking work goes through [`blocking`], and errors leave by `?`.

use std::sync::Arc;

use axum::Json;
use axum::extract::rejection::QueryRejection;
use axum::extract::{FromRef, Query, State};
use axum::http::{HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::on;
use serde::Deserialize;
use serde_json::Value;

use super::error::{DeleteError, JobError, PartialError, RelabelError, SubmitError};
use super::events::{self, Streams};
use super::job::{FILTERS, JobRecord};
use super::labels::LabelChange;
use super::registry::{Deletion, Jobs};
use crate::scene::{FieldError, Scene, SceneErrors};
use crate::service::blocking::blocking;
use crate::service::cursor::CursorKey;
use crate::service::error::ApiError;
use crate::service::extract::{BodyTimeout, JobId, JsonBody, JsonRequest};
use crate::service::listing::{ListQuery, Page};
use crate::service::reply::{attachment, created, download_name};
use crate::service::route::{Endpoint, Verb};
use crate::simulation::parse_scene;

/// The routes, on any state that provides the jobs, the event streams' settings and the
/// body timeout.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Jobs>: FromRef<S>,
    Streams: FromRef<S>,
    BodyTimeout: FromRef<S>,
    CursorKey: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Post, "/api/v1/jobs", |f| on(f, submit_job)),
        Endpoint::api(Verb::Get, "/api/v1/jobs", |f| on(f, list_jobs)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}", |f| on(f, get_job)),
        Endpoint::api(Verb::Delete, "/api/v1/jobs/{id}", |f| on(f, delete_job)),
        Endpoint::api(Verb::Patch, "/api/v1/jobs/{id}", |f| on(f, patch_job)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/events", |f| on(f, job_events)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/result", |f| on(f, job_result)),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/result.csv", |f| {
            on(f, job_result_csv)
        }),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/profiles.csv", |f| {
            on(f, job_profiles_csv)
        }),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/pressure.csv", |f| {
            on(f, job_pressure_csv)
        }),
        Endpoint::api(Verb::Get, "/api/v1/jobs/{id}/scene", |f| on(f, job_scene)),
    ]
}

/// A job's body is a scene: checked field by field, as `tribosim run` checks it.
impl JsonRequest for Scene {
    const NAME: &'static str = "scene";

    fn from_json(document: Value, _text: &str) -> Result<Self, ApiError> {
        Ok(parse_scene(&document)?.into_scene())
    }

    fn duplicate_key(path: String, message: String) -> ApiError {
        SceneErrors(vec![FieldError::new(path, message)]).into()
    }
}

/// The query of `POST /api/v1/jobs`: the job's labels.
#[derive(Debug, Default, Deserialize)]
struct SubmitQuery {
    sample: Option<String>,
    note: Option<String>,
    /// Separated by commas.
    tags: Option<String>,
}

/// `POST /api/v1/jobs`: 202 with the queued job and its `Location`.
async fn submit_job(
    State(jobs): State<Arc<Jobs>>,
    query: Result<Query<SubmitQuery>, QueryRejection>,
    JsonBody(scene): JsonBody<Scene>,
) -> Result<Response, ApiError> {
    let Query(query) = query?;
    let labels = LabelChange::from_query(
        query.sample.as_deref(),
        query.note.as_deref(),
        query.tags.as_deref(),
    )?;
    let record = blocking(move || jobs.submit(scene, labels)).await?;
    let location = format!("/api/v1/jobs/{}", record.id);
    Ok(created(StatusCode::ACCEPTED, location, record))
}

/// `GET /api/v1/jobs`: every job, newest first.
async fn list_jobs(
    State(jobs): State<Arc<Jobs>>,
    query: ListQuery,
) -> Result<Page<JobRecord>, ApiError> {
    let (handles, show) = jobs.listing();
    query.page_shown("/api/v1/jobs", handles, show, FILTERS)
}

/// `GET /api/v1/jobs/{id}`.
async fn get_job(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Json<JobRecord>, ApiError> {
    let job = jobs.find(id)?;
    Ok(Json(jobs.shown(&job)))
}

/// A PATCH's body: the labels to change.
impl JsonRequest for LabelChange {
    const NAME: &'static str = "job's labels";

    fn from_json(document: Value, _text: &str) -> Result<Self, ApiError> {
        Ok(LabelChange::from_json(&document)?)
    }

    fn duplicate_key(path: String, message: String) -> ApiError {
        ApiError::unprocessable(
            format!("invalid job labels: {message}"),
            vec![FieldError::new(path, message)],
        )
    }
}

/// `PATCH /api/v1/jobs/{id}`: changes the job's `sample`, `note` or `tags`, at any status
/// but damaged; the job as it is now.
async fn patch_job(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
    JsonBody(change): JsonBody<LabelChange>,
) -> Result<Json<JobRecord>, ApiError> {
    Ok(Json(blocking(move || jobs.relabel(id, change)).await?))
}

/// `DELETE /api/v1/jobs/{id}`: cancels a queued or running job, removes a finished one.
async fn delete_job(State(jobs): State<Arc<Jobs>>, JobId(id): JobId) -> Result<Deletion, ApiError> {
    blocking(move || jobs.delete(id)).await
}

/// `GET /api/v1/jobs/{id}/events`: the cycles after `Last-Event-ID` and then as they come.
async fn job_events(
    State(jobs): State<Arc<Jobs>>,
    State(streams): State<Streams>,
    JobId(id): JobId,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let job = jobs.find(id)?;
    // An unreadable Last-Event-ID is treated as absent: the client gets the whole stream,
    // which is more useful than an error from a reconnecting EventSource.
    let after = headers
        .get("last-event-id")
        .and_then(|value| value.to_str().ok())
        .and_then(|value| value.trim().parse::<u64>().ok())
        .unwrap_or(0);
    Ok(events::response(jobs, job, after, &streams))
}

/// The query of `GET /api/v1/jobs/{id}/result`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ResultQuery {
    /// Leave the pressure maps out.
    #[serde(default)]
    compact: bool,
}

/// `GET /api/v1/jobs/{id}/result`: the result JSON, as a download; `?compact=true` without
/// its pressure maps.
async fn job_result(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
    query: Result<Query<ResultQuery>, QueryRejection>,
) -> Result<Response, ApiError> {
    let Query(ResultQuery { compact }) = query?;
    let name = jobs.find(id)?.record().name;
    let bytes = blocking(move || {
        if compact {
            jobs.compact_result_json(id)
        } else {
            jobs.result_json(id)
        }
    })
    .await?;
    let suffix = if compact {
        "result.compact.json"
    } else {
        "result.json"
    };
    let filename = download_name(&name, id, suffix);
    Ok(attachment("application/json", &filename, bytes))
}

/// A CSV download of job `id` called `<name>.<suffix>`, made by `csv` on the blocking pool.
async fn csv_download(
    jobs: Arc<Jobs>,
    id: uuid::Uuid,
    suffix: &str,
    csv: fn(&Jobs, uuid::Uuid) -> Result<String, JobError>,
) -> Result<Response, ApiError> {
    let name = jobs.find(id)?.record().name;
    let body = blocking(move || csv(&jobs, id)).await?;
    let filename = download_name(&name, id, suffix);
    Ok(attachment("text/csv; charset=utf-8", &filename, body))
}

/// `GET /api/v1/jobs/{id}/result.csv`: the result's cycles as CSV, as a download.
async fn job_result_csv(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    csv_download(jobs, id, "result.csv", Jobs::result_csv).await
}

/// `GET /api/v1/jobs/{id}/profiles.csv`: the result's profiles as CSV, as a download.
async fn job_profiles_csv(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    csv_download(jobs, id, "profiles.csv", Jobs::profiles_csv).await
}

/// `GET /api/v1/jobs/{id}/pressure.csv`: the result's pressure maps as CSV, as a download.
async fn job_pressure_csv(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    csv_download(jobs, id, "pressure.csv", Jobs::pressure_csv).await
}

/// `GET /api/v1/jobs/{id}/scene`: the scene as run, every default filled in.
async fn job_scene(
    State(jobs): State<Arc<Jobs>>,
    JobId(id): JobId,
) -> Result<Json<Scene>, ApiError> {
    Ok(Json(blocking(move || jobs.scene(id)).await?))
}

/// 200 with the cancelled job, 202 while a running one stops, 204 once removed.
impl IntoResponse for Deletion {
    fn into_response(self) -> Response {
        match self {
            Self::Cancelled(record) => (StatusCode::OK, Json(record)).into_response(),
            Self::Cancelling(record) => (StatusCode::ACCEPTED, Json(record)).into_response(),
            Self::Removed => StatusCode::NO_CONTENT.into_response(),
        }
    }
}

/// 404 for an id no job has.
fn unknown(id: uuid::Uuid) -> ApiError {
    ApiError::not_found(format!("no job {id}"))
}

/// 422 for a scene the service cannot run, 429 with Retry-After when the queue is full, 507
/// when the disk is, 503 when the store cannot be written.
impl From<SubmitError> for ApiError {
    fn from(error: SubmitError) -> Self {
        match error {
            SubmitError::Unservable(errors) => errors.into(),
            SubmitError::QueueFull {
                capacity,
                retry_after_s,
                ..
            } => Self::too_many_requests(
                format!("the job queue is full ({capacity} jobs waiting); retry later"),
                retry_after_s,
            ),
            SubmitError::DiskFull => Self::disk_full("the job was not accepted"),
            SubmitError::Storage(e) => {
                Self::storage(&e, "the job was not accepted", "storing the job")
            }
        }
    }
}

impl From<DeleteError> for ApiError {
    fn from(error: DeleteError) -> Self {
        match error {
            DeleteError::Unknown(id) => unknown(id),
            DeleteError::Storage(e) => {
                Self::storage(&e, "the job was not changed", "deleting a job")
            }
        }
    }
}

/// The job's own answers, 507 or 503 when the record could not be written.
impl From<RelabelError> for ApiError {
    fn from(error: RelabelError) -> Self {
        match error {
            RelabelError::Job(e) => e.into(),
            RelabelError::Storage(e) => {
                Self::storage(&e, "the labels were not changed", "changing a job's labels")
            }
        }
    }
}

/// 404 for an unknown job, 409 for one that has no such thing now (with why), 500 when the
/// server could not read its own files.
impl From<JobError> for ApiError {
    fn from(error: JobError) -> Self {
        match error {
            JobError::Unknown(id) => unknown(id),
            JobError::Damaged(error) => Self::conflict(format!("job is damaged: {error}")),
            JobError::Unfinished(status) => Self::conflict(format!(
                "job is {}; a result comes once it has finished",
                status.name()
            )),
            JobError::RunsAgain { damage, now } => Self::conflict(format!(
                "the stored result was damaged ({damage}); the job runs again (now {})",
                now.name()
            )),
            JobError::SceneDamaged(damage) => {
                Self::conflict(format!("the stored scene is damaged: {damage}"))
            }
            JobError::SceneUnreadable(damage) => Self::internal("reading a scene", &damage),
            JobError::ResultUnreadable(damage) => Self::internal("reading a result", &damage),
            JobError::Partial(e) => e.into(),
            JobError::Export(e) => Self::internal("exporting a result", &e),
        }
    }
}

/// 409 when what a stopped run computed cannot be rebuilt from what is stored, 500 when the
/// server could not read it.
impl From<PartialError> for ApiError {
    fn from(error: PartialError) -> Self {
        match error {
            PartialError::Scene(ref damage) if !damage.is_read_failure() => {
                Self::conflict(error.to_string())
            }
            PartialError::Surface(e) => {
                Self::conflict(format!("the surface this job ran on cannot be read: {e}"))
            }
            PartialError::Setup { source, recorded } => Self::conflict(format!(
                "job failed before its first cycle: {}",
                recorded.unwrap_or_else(|| source.to_string())
            )),
            _ => Self::internal("reading a partial result", &error),
        }
    }
}
