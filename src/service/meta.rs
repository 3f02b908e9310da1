//! The routes about the service itself: its health, its description, the built-in scenes
//! and the materials library.

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use axum::Json;
use axum::extract::{FromRef, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::on;
use serde_json::json;
use uuid::Uuid;

use super::error::os_reason;
use super::route::{Endpoint, Verb};
use crate::scene::materials::library;
use crate::scene::presets;

/// The OpenAPI description, served as is.
pub const OPENAPI_YAML: &str = include_str!("../../openapi.yaml");

/// The folder the server keeps its data in, which `/healthz` checks can be written.
#[derive(Clone)]
pub(crate) struct DataDir(pub(crate) Arc<Path>);

/// The routes; `/healthz` needs the data folder.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    DataDir: FromRef<S>,
{
    vec![
        Endpoint::public(Verb::Get, "/healthz", |f| on(f, healthz)),
        Endpoint::public(Verb::Get, "/api/v1/openapi.yaml", |f| on(f, openapi)),
        Endpoint::api(Verb::Get, "/api/v1/presets", |f| on(f, list_presets)),
        Endpoint::api(Verb::Get, "/api/v1/materials", |f| on(f, list_materials)),
    ]
}

/// `GET /healthz`: 200 `ok` when the data folder takes a write; 503 `degraded`, with the
/// system's reason, when it does not (read-only, failing, full), since every submission
/// would fail then while the process itself answers.
async fn healthz(State(DataDir(dir)): State<DataDir>) -> Response {
    let probe = tokio::task::spawn_blocking(move || probe_write(&dir)).await;
    match probe {
        Ok(Ok(())) => Json(json!({"status": "ok"})).into_response(),
        Ok(Err(error)) => degraded(&os_reason(&error)),
        Err(join) => degraded(&join.to_string()),
    }
}

fn degraded(reason: &str) -> Response {
    let body = json!({"status": "degraded", "storage": format!("the data directory cannot be written: {reason}")});
    (StatusCode::SERVICE_UNAVAILABLE, Json(body)).into_response()
}

/// Writes a byte to a new file in `dir` and removes it: a byte rather than an empty file,
/// so a full disk fails as a submission would. A temporary name of the store's kind
/// (`.*.tmp`), unique per call, so concurrent probes never meet.
fn probe_write(dir: &Path) -> std::io::Result<()> {
    let path = dir.join(format!(".healthz.{}.tmp", Uuid::new_v4()));
    let written = std::fs::File::create(&path).and_then(|mut file| file.write_all(b"1"));
    let removed = std::fs::remove_file(&path);
    written.and(removed)
}

async fn openapi() -> impl IntoResponse {
    ([(header::CONTENT_TYPE, "application/yaml")], OPENAPI_YAML)
}

async fn list_presets() -> impl IntoResponse {
    Json(presets())
}

async fn list_materials() -> impl IntoResponse {
    Json(library())
}
