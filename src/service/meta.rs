//! The routes about the service itself: its health, its description and the built-in
//! scenes.

use axum::Json;
use axum::http::header;
use axum::response::IntoResponse;
use axum::routing::on;
use serde_json::{Value, json};

use super::route::{Endpoint, Verb};
use crate::scene::presets;

/// The OpenAPI description, served as is.
pub const OPENAPI_YAML: &str = include_str!("../../openapi.yaml");

/// The routes; they need nothing of the state.
pub(crate) fn endpoints<S: Clone + Send + Sync + 'static>() -> Vec<Endpoint<S>> {
    vec![
        Endpoint::public(Verb::Get, "/healthz", |f| on(f, healthz)),
        Endpoint::public(Verb::Get, "/api/v1/openapi.yaml", |f| on(f, openapi)),
        Endpoint::api(Verb::Get, "/api/v1/presets", |f| on(f, list_presets)),
    ]
}

async fn healthz() -> Json<Value> {
    Json(json!({"status": "ok"}))
}

async fn openapi() -> impl IntoResponse {
    ([(header::CONTENT_TYPE, "application/yaml")], OPENAPI_YAML)
}

async fn list_presets() -> impl IntoResponse {
    Json(presets())
}
