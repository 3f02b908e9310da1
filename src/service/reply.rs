//! The shapes of answer that several resources give besides plain JSON.

use axum::Json;
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Serialize;

/// A resource just accepted: `status` (201, or 202 while it runs), its URL in `Location`, and
/// its record.
pub(crate) fn created(status: StatusCode, location: String, record: impl Serialize) -> Response {
    (status, [(header::LOCATION, location)], Json(record)).into_response()
}

/// A file to download as `filename`.
pub(crate) fn attachment(
    content_type: &'static str,
    filename: &str,
    body: impl IntoResponse,
) -> Response {
    let disposition = format!("attachment; filename=\"{filename}\"");
    (
        [
            (header::CONTENT_TYPE, content_type.to_owned()),
            (header::CONTENT_DISPOSITION, disposition),
        ],
        body,
    )
        .into_response()
}
