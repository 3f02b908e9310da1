//! The web page at `/`: the copy built into the binary, so that `serve` works from any
//! directory, or `index.html` of `--static-dir` while the page is being edited.

use axum::extract::State;
use axum::response::Html;
use axum::routing::on;

use super::error::ApiError;
use super::route::{Endpoint, Verb};
use super::state::AppState;

/// The web page, built into the binary.
const PAGE_HTML: &str = include_str!("../../static/index.html");

/// The page's route.
pub(crate) fn endpoints() -> Vec<Endpoint<AppState>> {
    vec![Endpoint::public(Verb::Get, "/", |f| on(f, index))]
}

async fn index(State(app): State<AppState>) -> Result<Html<Vec<u8>>, ApiError> {
    let Some(dir) = &app.static_dir else {
        return Ok(Html(PAGE_HTML.as_bytes().to_vec()));
    };
    let path = dir.join("index.html");
    match tokio::fs::read(&path).await {
        Ok(page) => Ok(Html(page)),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(ApiError::not_found(format!(
            "no page: {} is missing (see --static-dir)",
            path.display()
        ))),
        Err(e) => Err(ApiError::internal("reading the page", &e)),
    }
}
