//! The one error type of the HTTP API. Every error leaves the server as JSON
//! `{"error": "...", "fields": [{"path": "...", "message": "..."}]}`; `fields` is empty except
//! for an invalid scene (422), where it lists every bad field with its allowed range.

use axum::Json;
use axum::extract::rejection::{BytesRejection, PathRejection};
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;

use crate::scene::{FieldError, SceneErrors};

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

    /// 400: the request is malformed (not JSON, not a job id, ...).
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

    /// 404: no such job, or no such route.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self::new(StatusCode::NOT_FOUND, message)
    }

    /// 404: no job has this id.
    pub fn unknown_job(id: uuid::Uuid) -> Self {
        Self::not_found(format!("no job {id}"))
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

    /// 409: the job exists but is not in a state that has what was asked for.
    pub fn conflict(message: impl Into<String>) -> Self {
        Self::new(StatusCode::CONFLICT, message)
    }

    /// 415: the body is not declared as JSON.
    pub fn unsupported_media_type() -> Self {
        Self::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "the scene must be sent with `Content-Type: application/json`",
        )
    }

    /// 415: a measurement table that is declared neither CSV nor JSON.
    pub fn unsupported_table_type() -> Self {
        Self::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "a measurement table must be sent with `Content-Type: text/csv` or `application/json`",
        )
    }

    /// 415: a height map that is declared neither binary nor text.
    pub fn unsupported_map_type() -> Self {
        Self::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "a height map must be sent with `Content-Type: application/octet-stream` or \
             `text/plain`",
        )
    }

    /// 413: the request's body, or what it describes, is beyond a limit the message names.
    pub fn too_large(message: impl Into<String>) -> Self {
        Self::new(StatusCode::PAYLOAD_TOO_LARGE, message)
    }

    /// The answer's status.
    pub fn status(&self) -> StatusCode {
        self.status
    }

    /// 414: the request's target is longer than `limit_bytes`.
    pub fn uri_too_long(limit_bytes: usize) -> Self {
        Self::new(
            StatusCode::URI_TOO_LONG,
            format!("the request target is longer than {limit_bytes} bytes"),
        )
    }

    /// 422: the scene is well-formed JSON but has invalid fields, all of them listed.
    pub fn invalid_scene(errors: SceneErrors) -> Self {
        let message = match errors.0.len() {
            1 => "invalid scene: 1 problem".to_owned(),
            n => format!("invalid scene: {n} problems"),
        };
        Self {
            fields: errors.0,
            ..Self::new(StatusCode::UNPROCESSABLE_ENTITY, message)
        }
    }

    /// 422: a well-formed request whose content is refused, with the fields at fault.
    pub fn unprocessable(message: impl Into<String>, fields: Vec<FieldError>) -> Self {
        Self {
            fields,
            ..Self::new(StatusCode::UNPROCESSABLE_ENTITY, message)
        }
    }

    /// 429 with its own message: a study needs more places than the queue has free now.
    pub fn no_room(message: impl Into<String>, retry_after_s: u64) -> Self {
        Self {
            retry_after_s: Some(retry_after_s),
            ..Self::new(StatusCode::TOO_MANY_REQUESTS, message)
        }
    }

    /// 422: a measurement table of `kind` that cannot be used; `column` names the column at
    /// fault (empty for the whole table).
    pub fn invalid_table(kind: &str, column: String, message: &str) -> Self {
        Self {
            fields: vec![FieldError::new(column, message)],
            ..Self::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                format!("invalid {kind} table: {message}"),
            )
        }
    }

    /// 429: the queue is full; try again after `retry_after_s` seconds.
    pub fn queue_full(capacity: usize, retry_after_s: u64) -> Self {
        Self {
            retry_after_s: Some(retry_after_s),
            ..Self::new(
                StatusCode::TOO_MANY_REQUESTS,
                format!("the job queue is full ({capacity} jobs waiting); retry later"),
            )
        }
    }

    /// Any other status, with its standard reason as the message: for answers made by layers
    /// below the handlers, which would otherwise leave with an empty body.
    pub fn from_status(status: StatusCode) -> Self {
        Self::new(status, status.canonical_reason().unwrap_or("error"))
    }

    /// 507: the server's disk is full; nothing of the request was kept.
    pub fn insufficient_storage(message: impl Into<String>) -> Self {
        Self::new(StatusCode::INSUFFICIENT_STORAGE, message)
    }

    /// 507 for a request that needed the disk: `what` says what became of the request.
    pub fn disk_full(what: &str) -> Self {
        Self::insufficient_storage(format!(
            "the server's disk is full: {what}; retry once space is freed"
        ))
    }

    /// 500: a fault of the server (its storage), never of the request. The cause goes to the
    /// log; the client learns only that the server failed.
    pub fn internal(context: &str, cause: &dyn std::fmt::Display) -> Self {
        tracing::error!("{context}: {cause}");
        Self::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("internal error: {context}"),
        )
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
