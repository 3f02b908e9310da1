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

/// The name a download of job or study `id` is saved under, the one rule for every
/// download (`<name>.<what>.<extension>`): its `name` made safe for a file name
/// on any system (lower case; letters, digits, `-`, `_` and `.` kept, every other run of
/// characters one `-`; at most 80 characters), then `.suffix`; `tribosim-<id>.suffix` for a
/// name with nothing left. `paper test, 3600 cycles` gives `paper-test-3600-cycles.suffix`.
pub(crate) fn download_name(name: &str, id: uuid::Uuid, suffix: &str) -> String {
    let mut safe = String::new();
    for c in name.chars().flat_map(char::to_lowercase) {
        if c.is_ascii_alphanumeric() || matches!(c, '_' | '.') {
            safe.push(c);
        } else if !safe.ends_with('-') {
            safe.push('-');
        }
    }
    let safe: String = safe.trim_matches(['-', '.']).chars().take(80).collect();
    let safe = safe.trim_end_matches(['-', '.']);
    if safe.is_empty() {
        format!("tribosim-{id}.{suffix}")
    } else {
        format!("{safe}.{suffix}")
    }
}

/// JSON shown in a browser, saved as `filename` (not `scores`, the route's last segment).
pub(crate) fn inline_json(filename: &str, body: impl IntoResponse) -> Response {
    let disposition = format!("inline; filename=\"{filename}\"");
    ([(header::CONTENT_DISPOSITION, disposition)], body).into_response()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn download_names_are_the_run_s_name_made_safe() {
        let id = uuid::Uuid::nil();
        let name = |n: &str| download_name(n, id, "result.json");
        assert_eq!(
            name("Paper test, 3600 cycles"),
            "paper-test-3600-cycles.result.json"
        );
        assert_eq!(name("../etc/passwd"), "etc-passwd.result.json");
        assert_eq!(name("a\"b\r\nc; é"), "a-b-c.result.json");
        assert_eq!(
            name("  ---  "),
            "tribosim-00000000-0000-0000-0000-000000000000.result.json"
        );
        assert_eq!(name(&"x".repeat(200)).len(), 80 + ".result.json".len());
    }
}
