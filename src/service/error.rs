//! The one error type of the HTTP API. Every error leaves the server as JSON
//! `{"error": "...", "fields": [{"path": "...", "message": "..."}]}`; `fields` is empty except
//! for a refused body (422), where it names every field at fault.
//!
//! Handlers return `Result<_, ApiError>` and use `?`: each error of the service has a `From`
//! that gives its answer. The errors of the request's plumbing (a body, a path, a query, a
//! scene, a blocking task) have theirs here; each resource's own errors have theirs in the
//! resource's `routes.rs`, beside the handlers that meet them, so this file knows no resource.

use std::convert::Infallible;
use std::io;

use axum::Json;
use axum::extract::rejection::{BytesRejection, PathRejection, QueryRejection};
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;
use tokio::task::JoinError;

use super::files::is_disk_full;
use crate::scene::{FieldError, SceneErrors, listed};

/// An HTTP error answer: status, message, located fields and an optional Retry-After.
#[derive(Debug)]
pub struct ApiError {
    status: StatusCode,
    message: String,
    fields: Vec<FieldError>,
    retry_after_s: Option<u64>,
}

/// The JSON body of every error.
#[derive(Serialize)]
struct ErrorBody<'a> {
    error: &'a str,
    fields: &'a [FieldError],
}

impl ApiError {
    fn new(status: StatusCode, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
            fields: Vec::new(),
            retry_after_s: None,
        }
    }

    /// 400: the request is malformed (not JSON, not an id, ...).
    pub fn bad_request(message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, message)
    }

    /// 401: the bearer token is missing or wrong.
    pub fn unauthorized() -> Self {
        Self::new(
            StatusCode::UNAUTHORIZED,
            "missing or wrong bearer token (send `Authorization: Bearer <token>`)",
        )
    }

    /// 403: the request may not be made from where it comes (a page of another origin).
    pub fn forbidden(message: impl Into<String>) -> Self {
        Self::new(StatusCode::FORBIDDEN, message)
    }

    /// 404: no such job, study, ..., or no such route.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, message)
    }

    /// 405: the path exists but not with this method.
    pub fn method_not_allowed() -> Self {
        Self::new(
            StatusCode::METHOD_NOT_ALLOWED,
            "method not allowed on this path",
        )
    }

    /// 408: the request's body did not arrive within `limit_s` seconds.
    pub fn body_timeout(limit_s: u64) -> Self {
        Self::new(
            StatusCode::REQUEST_TIMEOUT,
            format!("the request body did not arrive within {limit_s} s"),
        )
    }

    /// 409: the resource exists but is not in a state that has what was asked for.
    pub fn conflict(message: impl Into<String>) -> Self {
        Self::new(StatusCode::CONFLICT, message)
    }

    /// 413: the request's body, or what it describes, is beyond a limit the message names.
    pub fn too_large(message: impl Into<String>) -> Self {
        Self::new(StatusCode::PAYLOAD_TOO_LARGE, message)
    }

    /// 414: the request's target is longer than `limit_bytes`.
    pub fn uri_too_long(limit_bytes: usize) -> Self {
        Self::new(
            StatusCode::URI_TOO_LONG,
            format!("the request target is longer than {limit_bytes} bytes"),
        )
    }

    /// 415: the body is not declared as what the route reads; `message` says what it must be.
    pub fn unsupported_media_type(message: impl Into<String>) -> Self {
        Self::new(StatusCode::UNSUPPORTED_MEDIA_TYPE, message)
    }

    /// 421: the request names a host (`Host`) the server does not answer to.
    pub fn misdirected(message: impl Into<String>) -> Self {
        Self::new(StatusCode::MISDIRECTED_REQUEST, message)
    }

    /// 422: a well-formed request whose content is refused, with the fields at fault as
    /// [`listed`] lists them (the first [`crate::scene::MAX_LISTED_PROBLEMS`] and a count of
    /// the others), so a body of a hundred thousand faults is not echoed back a hundred
    /// times larger.
    pub fn unprocessable(message: impl Into<String>, fields: Vec<FieldError>) -> Self {
        Self {
            fields: listed(fields),
            ..Self::new(StatusCode::UNPROCESSABLE_ENTITY, message)
        }
    }

    /// 429: no room now (a full queue, every fit slot busy); retry after `retry_after_s`.
    pub fn too_many_requests(message: impl Into<String>, retry_after_s: u64) -> Self {
        Self {
            retry_after_s: Some(retry_after_s),
            ..Self::new(StatusCode::TOO_MANY_REQUESTS, message)
        }
    }

    /// Any other status, with its standard reason as the message: for answers made by layers
    /// below the handlers, which would otherwise leave with an empty body.
    pub fn from_status(status: StatusCode) -> Self {
        Self::new(status, status.canonical_reason().unwrap_or("error"))
    }

    /// A write of the server's store that failed, with `kept` saying what became of the
    /// request: 507 when the disk (or the quota) is full; otherwise 503 with the system's
    /// reason ("Read-only file system", "Input/output error"), which is the store's state
    /// rather than the request's fault, and which the operator, reading it, can mend.
    pub fn storage(error: &io::Error, kept: &str, doing: &str) -> Self {
        if is_disk_full(error) {
            return Self::disk_full(kept);
        }
        tracing::error!("{doing}: {error}");
        Self::new(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the server cannot write its data directory ({}) while {doing}: {kept}; \
                 retry once its operator has mended the storage",
                os_reason(error)
            ),
        )
    }

    /// 507: the server's disk is full; `kept` says what became of the request.
    pub fn disk_full(kept: &str) -> Self {
        Self::new(
            StatusCode::INSUFFICIENT_STORAGE,
            format!("the server's disk is full: {kept}; retry once space is freed"),
        )
    }

    /// 500: a fault of the server (its storage, a thread), never of the request. The cause
    /// goes to the log; the client learns only what the server was doing.
    pub fn internal(doing: &str, cause: &dyn std::fmt::Display) -> Self {
        tracing::error!("{doing}: {cause}");
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("internal error: {doing}"),
        )
    }

    /// The answer's status.
    pub fn status(&self) -> StatusCode {
        self.status
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = ErrorBody {
            error: &self.message,
            fields: &self.fields,
        };
        let mut response = (self.status, Json(body)).into_response();
        if let Some(seconds) = self.retry_after_s {
            response
                .headers_mut()
                .insert(header::RETRY_AFTER, HeaderValue::from(seconds));
        }
        response
    }
}

/// What the system says of `error`, without the error number: "Read-only file system".
pub fn os_reason(error: &io::Error) -> String {
    let text = error.to_string();
    match text.rfind(" (os error ") {
        Some(end) => text[..end].to_owned(),
        None => text,
    }
}

/// 422 naming every invalid field of a scene, each with its allowed range.
impl From<SceneErrors> for ApiError {
    fn from(errors: SceneErrors) -> Self {
        let message = match errors.0.len() {
            1 => "invalid scene: 1 problem".to_owned(),
            n => format!("invalid scene: {n} problems"),
        };
        Self::unprocessable(message, errors.0)
    }
}

/// axum's own body rejections (413 over the size limit, 400 for an unreadable body) keep
/// their status but get the JSON shape.
impl From<BytesRejection> for ApiError {
    fn from(rejection: BytesRejection) -> Self {
        let status = rejection.status();
        let message = if status == StatusCode::PAYLOAD_TOO_LARGE {
            "request body too large".to_owned()
        } else {
            rejection.body_text()
        };
        Self::new(status, message)
    }
}

/// A path segment that is not valid UTF-8 or percent-encoding.
impl From<PathRejection> for ApiError {
    fn from(rejection: PathRejection) -> Self {
        Self::bad_request(rejection.body_text())
    }
}

/// A query string that does not have the route's shape.
impl From<QueryRejection> for ApiError {
    fn from(rejection: QueryRejection) -> Self {
        Self::bad_request(rejection.body_text())
    }
}

/// Blocking work that panicked (or was cancelled at shutdown): the server's fault. The
/// request's log span names the route, so the log line says which.
impl From<JoinError> for ApiError {
    fn from(error: JoinError) -> Self {
        Self::internal("the request's work stopped", &error)
    }
}

/// For blocking work that cannot fail.
impl From<Infallible> for ApiError {
    fn from(never: Infallible) -> Self {
        match never {}
    }
}
