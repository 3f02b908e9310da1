//! The handlers of `/api/v1/studies`: they translate between HTTP and [`super::studies`].

use std::sync::Arc;

use axum::Json;
use axum::extract::{Request, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use uuid::Uuid;

use super::AppState;
use super::error::ApiError;
use super::extract::{is_json, path_id, read_body};
use super::files::is_disk_full;
use super::registry::SubmitError;
use super::studies::{StudyDeletion, StudySubmitError};
use crate::json::JsonError;
use crate::scene::FieldError;
use crate::study::StudyError;

path_id!(
    /// A study id from the path.
    StudyId,
    "study"
);

fn unknown_study(id: Uuid) -> ApiError {
    ApiError::not_found(format!("no study {id}"))
}

/// The API's answer to a refused study: 400 for text that is not JSON, 422 naming the axis
/// or field, 429 when the queue has no room for every member now.
fn refused(error: StudySubmitError) -> ApiError {
    let invalid = |path: String, message: String| {
        ApiError::unprocessable(
            format!("invalid study: {message}"),
            vec![FieldError::new(path, message)],
        )
    };
    match error {
        StudySubmitError::Invalid(StudyError::Json(e)) => match &e {
            JsonError::Syntax(_) => ApiError::bad_request(format!("malformed JSON: {e}")),
            JsonError::DuplicateKey { path, .. } => invalid(path.clone(), e.to_string()),
        },
        StudySubmitError::Invalid(StudyError::Member {
            index,
            values,
            source,
        }) => ApiError::unprocessable(
            format!("invalid study: member {index} ({values}) has an invalid scene"),
            source
                .0
                .into_iter()
                .map(|field| FieldError::new(format!("base.{}", field.path), field.message))
                .collect(),
        ),
        StudySubmitError::Invalid(e @ StudyError::TooManyMembers { .. }) => invalid(
            "axes".into(),
            format!("{e}; the server's limit is set by --max-study-members"),
        ),
        StudySubmitError::Invalid(e @ StudyError::NoAxes) => invalid("axes".into(), e.to_string()),
        StudySubmitError::Invalid(StudyError::Shape(e)) => invalid(
            String::new(),
            format!("a study is {{\"base\": SCENE, \"axes\": {{...}}}}: {e}"),
        ),
        StudySubmitError::Invalid(e @ StudyError::BaseNotObject) => {
            invalid("base".into(), e.to_string())
        }
        StudySubmitError::Invalid(StudyError::Axis { axis, message }) => {
            invalid(format!("axes.{axis}"), format!("axis `{axis}`: {message}"))
        }
        StudySubmitError::OverCapacity { members, capacity } => invalid(
            "axes".into(),
            format!(
                "the axes give {members} members, more than the job queue holds ({capacity}, set by --queue-capacity)"
            ),
        ),
        StudySubmitError::Submit(SubmitError::QueueFull {
            capacity,
            free,
            retry_after_s,
        }) => ApiError::no_room(
            format!(
                "the job queue has room for {free} of the study's members now (capacity {capacity}); retry later"
            ),
            retry_after_s,
        ),
        StudySubmitError::Submit(SubmitError::DiskFull) => {
            ApiError::disk_full("the study was not accepted")
        }
        StudySubmitError::Submit(SubmitError::Storage(e)) => {
            ApiError::internal("storing the study", &e)
        }
    }
}

pub(super) async fn submit_study(
    State(app): State<AppState>,
    request: Request,
) -> Result<Response, ApiError> {
    if !is_json(request.headers()) {
        return Err(ApiError::unsupported_media_type());
    }
    let body = read_body(&app, request).await?;
    let text = String::from_utf8(body.to_vec())
        .map_err(|_| ApiError::bad_request("malformed JSON: the body is not UTF-8"))?;
    let (studies, jobs) = (Arc::clone(&app.studies), Arc::clone(&app.jobs));
    let record = tokio::task::spawn_blocking(move || studies.submit(&jobs, &text))
        .await
        .map_err(|e| ApiError::internal("submitting a study", &e))?
        .map_err(refused)?;
    let location = format!("/api/v1/studies/{}", record.id);
    Ok((
        StatusCode::CREATED,
        [(header::LOCATION, location)],
        Json(record),
    )
        .into_response())
}

pub(super) async fn list_studies(State(app): State<AppState>) -> Response {
    Json(app.studies.list(&app.jobs)).into_response()
}

pub(super) async fn get_study(
    State(app): State<AppState>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let record = app
        .studies
        .record(&app.jobs, id)
        .ok_or_else(|| unknown_study(id))?;
    Ok(Json(record).into_response())
}

pub(super) async fn delete_study(
    State(app): State<AppState>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let (studies, jobs) = (Arc::clone(&app.studies), Arc::clone(&app.jobs));
    let deletion = tokio::task::spawn_blocking(move || studies.delete(&jobs, id))
        .await
        .map_err(|e| ApiError::internal("deleting a study", &e))?
        .ok_or_else(|| unknown_study(id))?
        .map_err(|e| {
            if is_disk_full(&e) {
                ApiError::disk_full("the study was not changed")
            } else {
                ApiError::internal("deleting a study", &e)
            }
        })?;
    Ok(match deletion {
        StudyDeletion::Cancelled(record) => (StatusCode::OK, Json(record)).into_response(),
        StudyDeletion::Cancelling(record) => (StatusCode::ACCEPTED, Json(record)).into_response(),
        StudyDeletion::Removed => StatusCode::NO_CONTENT.into_response(),
    })
}

async fn summary(app: &AppState, id: Uuid) -> Result<crate::study::StudySummary, ApiError> {
    let (studies, jobs) = (Arc::clone(&app.studies), Arc::clone(&app.jobs));
    tokio::task::spawn_blocking(move || studies.summary(&jobs, id))
        .await
        .map_err(|e| ApiError::internal("summarising a study", &e))?
        .ok_or_else(|| unknown_study(id))?
        .map_err(|e| ApiError::internal("reading a member's result", &e))
}

pub(super) async fn study_summary(
    State(app): State<AppState>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    Ok(Json(summary(&app, id).await?).into_response())
}

pub(super) async fn study_summary_csv(
    State(app): State<AppState>,
    StudyId(id): StudyId,
) -> Result<Response, ApiError> {
    let csv = summary(&app, id).await?.to_csv();
    let disposition = format!("attachment; filename=\"tribosim-study-{id}.csv\"");
    Ok((
        [
            (header::CONTENT_TYPE, "text/csv; charset=utf-8".to_owned()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        csv,
    )
        .into_response())
}
