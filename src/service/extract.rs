//! What handlers take from a request: the ids (and measurement kind) of the path, the
//! body within the body timeout, and what the body is declared to be.

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{FromRequest, FromRequestParts, Path, Request};
use axum::http::request::Parts;
use axum::http::{HeaderMap, header};
use uuid::Uuid;

use super::AppState;
use super::error::ApiError;
use super::measurements::{Format, MeasurementKind};

/// How much of a malformed job id is echoed in an error: a UUID and a little more.
const ECHOED_ID_CHARS: usize = 40;

/// Declares a path extractor for one kind of id: a newtype over the UUID, parsed by
/// [`parse_id`] before any handler sees it, so every kind refuses a malformed id alike.
macro_rules! path_id {
    ($(#[$doc:meta])* $name:ident, $what:literal) => {
        $(#[$doc])*
        pub(super) struct $name(pub(super) uuid::Uuid);

        impl<S: Send + Sync> axum::extract::FromRequestParts<S> for $name {
            type Rejection = $crate::service::error::ApiError;

            async fn from_request_parts(
                parts: &mut axum::http::request::Parts,
                state: &S,
            ) -> Result<Self, Self::Rejection> {
                let axum::extract::Path(raw) =
                    axum::extract::Path::<String>::from_request_parts(parts, state).await?;
                $crate::service::extract::parse_id(&raw, $what).map($name)
            }
        }
    };
}
pub(super) use path_id;

path_id!(
    /// A job id from the path.
    JobId,
    "job"
);

/// A job id and a measurement kind from the path (`.../jobs/{id}/measurements/{kind}`).
pub(super) struct JobMeasurement(pub(super) Uuid, pub(super) MeasurementKind);

impl<S: Send + Sync> FromRequestParts<S> for JobMeasurement {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Path((id, kind)) = Path::<(String, String)>::from_request_parts(parts, state).await?;
        let id = job_id(&id)?;
        let kind = MeasurementKind::from_name(&kind).ok_or_else(|| {
            let kinds: Vec<&str> = MeasurementKind::ALL.iter().map(|k| k.name()).collect();
            ApiError::bad_request(format!(
                "{:?} is not a kind of measurement ({})",
                cut(&kind),
                kinds.join(", ")
            ))
        })?;
        Ok(Self(id, kind))
    }
}

fn job_id(raw: &str) -> Result<Uuid, ApiError> {
    parse_id(raw, "job")
}

/// The id of a `what` (job, study, calibration) from the path, parsed as a UUID before
/// anything else looks at it; a 400 echoing at most [`ECHOED_ID_CHARS`] of it otherwise.
pub(super) fn parse_id(raw: &str, what: &str) -> Result<Uuid, ApiError> {
    Uuid::try_parse(raw)
        .map_err(|_| ApiError::bad_request(format!("{:?} is not a {what} id (a UUID)", cut(raw))))
}

/// The first [`ECHOED_ID_CHARS`] characters of `raw`, with an ellipsis if there were more.
pub(super) fn cut(raw: &str) -> String {
    match raw.char_indices().nth(ECHOED_ID_CHARS) {
        Some((end, _)) => format!("{}...", &raw[..end]),
        None => raw.to_owned(),
    }
}

/// The whole body, within the body timeout: a client sending a byte now and then holds no
/// handler for longer.
pub(super) async fn read_body(app: &AppState, request: Request) -> Result<Bytes, ApiError> {
    let limit = Duration::from_secs(app.body_timeout_s);
    let body: Result<Bytes, BytesRejection> =
        tokio::time::timeout(limit, Bytes::from_request(request, app))
            .await
            .map_err(|_| ApiError::body_timeout(app.body_timeout_s))?;
    Ok(body?)
}

/// The media type's essence (no parameters), lower case.
fn essence(headers: &HeaderMap) -> Option<String> {
    headers
        .get(header::CONTENT_TYPE)
        .and_then(|value| value.to_str().ok())
        .and_then(|value| value.split(';').next())
        .map(|essence| essence.trim().to_ascii_lowercase())
}

/// `application/json`, any parameters, or a `+json` type.
pub(super) fn is_json(headers: &HeaderMap) -> bool {
    essence(headers)
        .is_some_and(|essence| essence == "application/json" || essence.ends_with("+json"))
}

/// A height map's body: `application/octet-stream` or `text/plain`.
pub(super) fn is_map_body(headers: &HeaderMap) -> bool {
    essence(headers)
        .is_some_and(|essence| essence == "application/octet-stream" || essence == "text/plain")
}

/// A measurement table's format: JSON as [`is_json`] has it, or `text/csv`.
pub(super) fn table_format(headers: &HeaderMap) -> Option<Format> {
    if is_json(headers) {
        return Some(Format::Json);
    }
    (essence(headers)? == "text/csv").then_some(Format::Csv)
}
