//! The routes of `/api/v1/studies`, and the API's answer to each error of studies.

use std::sync::Arc;

use axum::Json;
use axum::extract::{FromRef, State};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::on;
use serde_json::Value;

use super::record::{FILTERS, StudyRecord};
use super::registry::{Studies, StudiesError, StudyDeletion, StudySubmitError};
use crate::json::JsonError;
use crate::scene::FieldError;
use crate::service::blocking::blocking;
use crate::service::cursor::CursorKey;
use crate::service::error::ApiError;
use crate::service::extract::{BodyTimeout, JsonBody, JsonRequest, StudyId};
use crate::service::jobs::{Jobs, SubmitError};
use crate::service::listing::{ListQuery, Page};
use crate::service::reply::{attachment, created, download_name};
use crate::service::route::{Endpoint, Verb};
use crate::study::{Study, StudyError};

/// The routes, on any state that provides the studies, the jobs and the body timeout.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Studies>: FromRef<S>,
    Arc<Jobs>: FromRef<S>,
    BodyTimeout: FromRef<S>,
    CursorKey: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Post, "/api/v1/studies", |f| on(f, submit_study)),
        Endpoint::api(Verb::Get, "/api/v1/studies", |f| on(f, list_studies)),
        Endpoint::api(Verb::Get, "/api/v1/studies/{id}", |f| on(f, get_study)),
        Endpoint::api(Verb::Delete, "/api/v1/studies/{id}", |f| {
            on(f, delete_study)
        }),
        Endpoint::api(Verb::Get, "/api/v1/studies/{id}/summary", |f| {
            on(f, study_summary)
        }),
        Endpoint::api(Verb::Get, "/api/v1/studies/{id}/summary.csv", |f| {
            on(f, study_summary_csv)
        }),
    ]
}

/// A study's body is the study document, read from its text so the axes keep their order.
impl JsonRequest for Study {
    const NAME: &'static str = "study";

    fn from_json(_document: Value, text: &str) -> Result<Self, ApiError> {
        Ok(Study::parse(text)?)
    }

    fn duplicate_key(path: String, message: String) -> ApiError {
        invalid(path, message)
    }
}

/// `POST /api/v1/studies`: 201 with the study and its `Location`; its members are queued
/// as jobs, all or none.
async fn submit_study(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    JsonBody(study): JsonBody<Study>,
) -> Result<Response, ApiError> {
    let record = blocking(move || studies.submit(&jobs, &study)).await?;
    let location = format!("/api/v1/studies/{}", record.id);
    Ok(created(StatusCode::CREATED, location, record))
}

/// `GET /api/v1/studies`: every study, newest first.
async fn list_studies(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    query: ListQuery,
) -> Result<Page<StudyRecord>, ApiError> {
    query.page("/api/v1/studies", studies.list(&jobs), FILTERS)
}

/// `GET /api/v1/studies/{id}`.
async fn get_study(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    StudyId(id): StudyId,
) -> Result<Json<StudyRecord>, ApiError> {
    Ok(Json(studies.record(&jobs, id)?))
}

/// `DELETE /api/v1/studies/{id}`: cancels the members that have not ended, or removes the
/// study once all have.
async fn delete_study(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    StudyId(id): StudyId,
) -> Result<StudyDeletion, ApiError> {
    blocking(move || studies.delete(&jobs, id)).await
}

/// `GET /api/v1/studies/{id}/summary`: `tribosim study`'s summary, taken now.
async fn study_summary(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let summary = blocking(move || studies.summary(&jobs, id)).await?;
    Ok(Json(summary).into_response())
}

/// `GET /api/v1/studies/{id}/summary.csv`: the summary's table, as a download.
async fn study_summary_csv(
    State(studies): State<Arc<Studies>>,
    State(jobs): State<Arc<Jobs>>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let (name, summary) = blocking(move || {
        let name = studies.record(&jobs, id)?.name;
        Ok::<_, ApiError>((name, studies.summary(&jobs, id)?))
    })
    .await?;
    let filename = download_name(&name, id, "summary.csv");
    Ok(attachment(
        "text/csv; charset=utf-8",
        &filename,
        summary.to_csv(),
    ))
}

/// 200 with the study once every member is cancelled, 202 while running ones stop, 204 once
/// removed.
impl IntoResponse for StudyDeletion {
    fn into_response(self) -> Response {
        match self {
            Self::Cancelled(record) => (StatusCode::OK, Json(record)).into_response(),
            Self::Cancelling(record) => (StatusCode::ACCEPTED, Json(record)).into_response(),
            Self::Removed => StatusCode::NO_CONTENT.into_response(),
        }
    }
}

/// 422 for a study refused at `path`.
fn invalid(path: String, message: String) -> ApiError {
    ApiError::unprocessable(
        format!("invalid study: {message}"),
        vec![FieldError::new(path, message)],
    )
}

/// 400 for text that is not JSON, 422 naming the axis or field.
impl From<StudyError> for ApiError {
    fn from(error: StudyError) -> Self {
        match error {
            StudyError::Json(e) => match &e {
                JsonError::Syntax(_) => Self::bad_request(format!("malformed JSON: {e}")),
                JsonError::DuplicateKey { path, .. } => invalid(path.clone(), e.to_string()),
            },
            StudyError::Member {
                index,
                values,
                source,
            } => Self::unprocessable(
                format!("invalid study: member {index} ({values}) has an invalid scene"),
                source
                    .0
                    .into_iter()
                    .map(|field| FieldError::new(format!("base.{}", field.path), field.message))
                    .collect(),
            ),
            e @ StudyError::TooManyMembers { .. } => invalid("axes".into(), e.to_string()),
            e @ (StudyError::NoAxes | StudyError::TooManyAxes { .. }) => {
                invalid("axes".into(), e.to_string())
            }
            StudyError::Name(e) => invalid("name".into(), format!("`name`: {e}")),
            StudyError::Shape(e) => invalid(
                String::new(),
                format!("a study is {{\"base\": SCENE, \"axes\": {{...}}}}: {e}"),
            ),
            e @ StudyError::BaseNotObject => invalid("base".into(), e.to_string()),
            StudyError::Axis { axis, message } => {
                invalid(format!("axes.{axis}"), format!("axis `{axis}`: {message}"))
            }
        }
    }
}

/// The study's own refusals, 422 when the queue could never hold it, 429 when it has no
/// room for every member now, 507 when the disk is full, 503 when the store cannot be
/// written.
impl From<StudySubmitError> for ApiError {
    fn from(error: StudySubmitError) -> Self {
        match error {
            StudySubmitError::Invalid(e) => e.into(),
            StudySubmitError::OverLimit { source, set_by } => invalid(
                "axes".into(),
                format!("{source}; the server's limit is set by {set_by}"),
            ),
            StudySubmitError::Submit(SubmitError::QueueFull {
                capacity,
                free,
                retry_after_s,
            }) => Self::too_many_requests(
                format!(
                    "the job queue has room for {free} of the study's members now (capacity {capacity}); retry later"
                ),
                retry_after_s,
            ),
            StudySubmitError::Submit(SubmitError::DiskFull) => {
                Self::disk_full("the study was not accepted")
            }
            StudySubmitError::Submit(SubmitError::Storage(e)) => {
                Self::storage(&e, "the study was not accepted", "storing the study")
            }
            // The members' scenes were checked before they were submitted.
            StudySubmitError::Submit(SubmitError::Unservable(errors)) => errors.into(),
        }
    }
}

impl From<StudiesError> for ApiError {
    fn from(error: StudiesError) -> Self {
        match error {
            StudiesError::Unknown(id) => Self::not_found(format!("no study {id}")),
            StudiesError::NotChanged(e) => {
                Self::storage(&e, "the study was not changed", "deleting a study")
            }
            StudiesError::ResultUnreadable(damage) => {
                Self::internal("reading a member's result", &damage)
            }
        }
    }
}
