//! What handlers take from a request besides the state: the ids of the path, each parsed
//! before a handler sees it, and the body, read within the body timeout and the size limit
//! ([`Body`]) and, on a JSON route, parsed with no key given twice ([`JsonBody`]). Each is an
//! axum extractor whose rejection is an [`ApiError`], so a handler that runs has its inputs.

use std::time::Duration;

use axum::body::Bytes;
use axum::extract::{FromRef, FromRequest, FromRequestParts, Path, Request};
use axum::http::request::Parts;
use axum::http::{HeaderMap, header};
use serde_json::Value;
use uuid::Uuid;

use super::blocking::blocking;
use super::error::ApiError;
use crate::json::{self, JsonError};

/// How much of a malformed id is echoed in an error: a UUID and a little more.
const ECHOED_ID_CHARS: usize = 40;

/// Declares a path extractor for one kind of id: a newtype over the UUID, so a handler
/// cannot take one kind for another, parsed by [`parse_id`] so every kind refuses a
/// malformed id alike.
macro_rules! path_id {
    ($(#[$doc:meta])* $name:ident, $what:literal) => {
        $(#[$doc])*
        pub(crate) struct $name(pub(crate) Uuid);

        impl<S: Send + Sync> FromRequestParts<S> for $name {
            type Rejection = ApiError;

            async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
                let Path(raw) = Path::<String>::from_request_parts(parts, state).await?;
                parse_id(&raw, $what).map($name)
            }
        }
    };
}

path_id!(
    /// A job id from the path.
    JobId,
    "job"
);

path_id!(
    /// A study id from the path.
    StudyId,
    "study"
);

path_id!(
    /// A calibration id from the path.
    CalibrationId,
    "calibration"
);

path_id!(
    /// A surface id from the path.
    SurfaceId,
    "surface"
);

/// The id of a `what` (job, study, ...) from the path, parsed as a UUID before anything
/// else looks at it; a 400 echoing at most [`ECHOED_ID_CHARS`] of it otherwise.
pub(crate) fn parse_id(raw: &str, what: &str) -> Result<Uuid, ApiError> {
    Uuid::try_parse(raw)
        .map_err(|_| ApiError::bad_request(format!("{:?} is not a {what} id (a UUID)", cut(raw))))
}

/// The first [`ECHOED_ID_CHARS`] characters of `raw`, with an ellipsis if there were more.
pub(crate) fn cut(raw: &str) -> String {
    crate::text::cut(raw, ECHOED_ID_CHARS)
}

/// Seconds a request's body may take to arrive (`--body-timeout-s`), the part of the state
/// every body extractor reads.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyTimeout(pub(crate) u64);

/// A request's whole body, arrived within the [`BodyTimeout`] (a client sending a byte now
/// and then holds no handler for longer) and under the size limit of the route
/// (`DefaultBodyLimit`: the router's, or the route's own where it takes more).
pub(crate) struct Body(pub(crate) Bytes);

impl<S> FromRequest<S> for Body
where
    S: Send + Sync,
    BodyTimeout: FromRef<S>,
{
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &S) -> Result<Self, ApiError> {
        let BodyTimeout(limit_s) = BodyTimeout::from_ref(state);
        let read = Bytes::from_request(request, state);
        match tokio::time::timeout(Duration::from_secs(limit_s), read).await {
            Ok(bytes) => Ok(Self(bytes?)),
            Err(_) => Err(ApiError::body_timeout(limit_s)),
        }
    }
}

/// The media type's essence (no parameters), lower case.
pub(crate) fn essence(headers: &HeaderMap) -> Option<String> {
    headers
        .get(header::CONTENT_TYPE)
        .and_then(|value| value.to_str().ok())
        .and_then(|value| value.split(';').next())
        .map(|essence| essence.trim().to_ascii_lowercase())
}

/// `application/json`, any parameters, or a `+json` type.
pub(crate) fn is_json(headers: &HeaderMap) -> bool {
    essence(headers)
        .is_some_and(|essence| essence == "application/json" || essence.ends_with("+json"))
}

/// What a JSON route reads from its body, and the words of its refusals.
pub(crate) trait JsonRequest: Sized + Send + 'static {
    /// What the body is, for the 415 answer: "the {NAME} must be sent with ...".
    const NAME: &'static str;

    /// The request from its document, which has no key twice, and the document's text.
    fn from_json(document: Value, text: &str) -> Result<Self, ApiError>;

    /// The 422 for a key given twice, at its dotted `path`, in this body's words.
    fn duplicate_key(path: String, message: String) -> ApiError;
}

/// The body of a JSON route: declared as JSON (415 otherwise), read as [`Body`] is, then
/// parsed by [`crate::json`] so a key given twice is refused (400 for text that is not JSON)
/// and made into a `T`, on the blocking pool: a megabyte of JSON with a hundred thousand
/// keys is tens of milliseconds of parsing and checking, which on a runtime thread would
/// hold up every other request (`/healthz` included) behind it.
pub(crate) struct JsonBody<T>(pub(crate) T);

impl<S, T> FromRequest<S> for JsonBody<T>
where
    S: Send + Sync,
    BodyTimeout: FromRef<S>,
    T: JsonRequest,
{
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &S) -> Result<Self, ApiError> {
        if !is_json(request.headers()) {
            return Err(ApiError::unsupported_media_type(format!(
                "the {} must be sent with `Content-Type: application/json`",
                T::NAME
            )));
        }
        let Body(bytes) = Body::from_request(request, state).await?;
        blocking(move || parse_body::<T>(&bytes)).await.map(Self)
    }
}

/// A `T` from a JSON body's bytes, as [`JsonBody`] reads it.
fn parse_body<T: JsonRequest>(bytes: &[u8]) -> Result<T, ApiError> {
    let document = json::from_slice(bytes).map_err(|e| match e {
        JsonError::Syntax(_) => ApiError::bad_request(format!("malformed JSON: {e}")),
        JsonError::DuplicateKey { ref path, .. } => T::duplicate_key(path.clone(), e.to_string()),
    })?;
    // Text that parses as JSON is UTF-8 (serde_json checks every string, and JSON's other
    // characters are ASCII), so nothing is replaced here.
    let text = String::from_utf8_lossy(bytes);
    T::from_json(document, &text)
}
