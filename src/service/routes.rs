//! The route table and its handlers. Handlers only translate between HTTP and the plain
//! functions of `jobs`, `store`, `events` and `export`; the route table is the single list
//! from which the router is built and against which `openapi.yaml` is checked.

use std::sync::Arc;

use axum::Json;
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::middleware::Next;
use axum::response::sse::{KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{MethodFilter, MethodRouter, on};
use serde_json::{Value, json};
use uuid::Uuid;

use super::AppState;
use super::assets;
use super::error::ApiError;
use super::events;
use super::export;
use super::extract::{JobId, is_json, read_body};
use super::job::{Job, JobStatus};
use super::job_routes;
use super::partial::{self, PartialError};
use super::registry::{Deletion, SubmitError};
use super::servable::servable;
use super::store::is_disk_full;
use super::surfaces::surface_id;
use super::{calibration_routes, study_routes, surface_routes};
use crate::json::{self, JsonError};
use crate::scene::{FieldError, SceneErrors, presets};
use crate::simulation::parse_scene;

/// The OpenAPI description, served as is.
pub const OPENAPI_YAML: &str = include_str!("../../openapi.yaml");

/// Longest request target (path and query) accepted: the longest route with a job id is
/// under 70 bytes, and 8 KiB is what common proxies accept. Longer targets get 414 with
/// the JSON body (hyper itself refuses targets over 64 KiB, with an empty body).
pub const MAX_URI_BYTES: usize = 8 * 1024;

/// An HTTP method used by the route table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verb {
    /// GET.
    Get,
    /// POST.
    Post,
    /// PUT.
    Put,
    /// DELETE.
    Delete,
}

impl Verb {
    /// The method's name as OpenAPI spells it (lower case).
    pub fn openapi_name(self) -> &'static str {
        match self {
            Self::Get => "get",
            Self::Post => "post",
            Self::Put => "put",
            Self::Delete => "delete",
        }
    }

    fn filter(self) -> MethodFilter {
        match self {
            Self::Get => MethodFilter::GET,
            Self::Post => MethodFilter::POST,
            Self::Put => MethodFilter::PUT,
            Self::Delete => MethodFilter::DELETE,
        }
    }
}

/// One route of the service.
pub struct Route {
    /// The method.
    pub verb: Verb,
    /// The path; axum's `{id}` syntax is also OpenAPI's, and its catch-all `{*path}` is
    /// OpenAPI's `{path}` ([`Route::openapi_path`]).
    pub path: &'static str,
    /// Whether the bearer token (when configured) is required.
    pub auth: bool,
    handler: fn(MethodFilter) -> MethodRouter<AppState>,
}

impl Route {
    /// The path as `openapi.yaml` writes it: a catch-all's value (which may hold slashes) is
    /// an ordinary path parameter there.
    pub fn openapi_path(&self) -> String {
        self.path.replace("{*", "{")
    }

    /// This route's method router.
    pub(super) fn method_router(&self) -> MethodRouter<AppState> {
        (self.handler)(self.verb.filter())
    }
}

/// Every route. The page and its files, the health check and the API description are
/// public (a health check and documentation carry no data); every other API call needs the
/// token when one is configured.
pub const ROUTES: &[Route] = &[
    Route {
        verb: Verb::Get,
        path: "/",
        auth: false,
        handler: |f| on(f, assets::index),
    },
    Route {
        verb: Verb::Get,
        path: "/static/{*path}",
        auth: false,
        handler: |f| on(f, assets::asset),
    },
    Route {
        verb: Verb::Get,
        path: "/healthz",
        auth: false,
        handler: |f| on(f, healthz),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/openapi.yaml",
        auth: false,
        handler: |f| on(f, openapi),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/presets",
        auth: true,
        handler: |f| on(f, list_presets),
    },
    Route {
        verb: Verb::Post,
        path: "/api/v1/jobs",
        auth: true,
        handler: |f| on(f, submit),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs",
        auth: true,
        handler: |f| on(f, list_jobs),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}",
        auth: true,
        handler: |f| on(f, get_job),
    },
    Route {
        verb: Verb::Delete,
        path: "/api/v1/jobs/{id}",
        auth: true,
        handler: |f| on(f, delete_job),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}/events",
        auth: true,
        handler: |f| on(f, job_events),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}/result",
        auth: true,
        handler: |f| on(f, job_result),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}/result.csv",
        auth: true,
        handler: |f| on(f, job_result_csv),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}/scene",
        auth: true,
        handler: |f| on(f, job_routes::job_scene),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/jobs/{id}/measurements",
        auth: true,
        handler: |f| on(f, job_routes::get_measurements),
    },
    Route {
        verb: Verb::Put,
        path: "/api/v1/jobs/{id}/measurements/{kind}",
        auth: true,
        handler: |f| on(f, job_routes::put_measurement),
    },
    Route {
        verb: Verb::Delete,
        path: "/api/v1/jobs/{id}/measurements/{kind}",
        auth: true,
        handler: |f| on(f, job_routes::delete_measurement),
    },
    Route {
        verb: Verb::Post,
        path: "/api/v1/studies",
        auth: true,
        handler: |f| on(f, study_routes::submit_study),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/studies",
        auth: true,
        handler: |f| on(f, study_routes::list_studies),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/studies/{id}",
        auth: true,
        handler: |f| on(f, study_routes::get_study),
    },
    Route {
        verb: Verb::Delete,
        path: "/api/v1/studies/{id}",
        auth: true,
        handler: |f| on(f, study_routes::delete_study),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/studies/{id}/summary",
        auth: true,
        handler: |f| on(f, study_routes::study_summary),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/studies/{id}/summary.csv",
        auth: true,
        handler: |f| on(f, study_routes::study_summary_csv),
    },
    Route {
        verb: Verb::Post,
        path: "/api/v1/calibrations",
        auth: true,
        handler: |f| on(f, calibration_routes::submit_calibration),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/calibrations/{id}",
        auth: true,
        handler: |f| on(f, calibration_routes::get_calibration),
    },
    Route {
        verb: Verb::Post,
        path: "/api/v1/surfaces",
        auth: true,
        handler: |f| {
            on(f, surface_routes::upload_surface).layer(DefaultBodyLimit::max(
                surface_routes::MAX_SURFACE_BODY_BYTES,
            ))
        },
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/surfaces",
        auth: true,
        handler: |f| on(f, surface_routes::list_surfaces),
    },
    Route {
        verb: Verb::Get,
        path: "/api/v1/surfaces/{id}",
        auth: true,
        handler: |f| on(f, surface_routes::get_surface),
    },
    Route {
        verb: Verb::Delete,
        path: "/api/v1/surfaces/{id}",
        auth: true,
        handler: |f| on(f, surface_routes::delete_surface),
    },
];

/// 414 with the JSON body for a request target over [`MAX_URI_BYTES`].
pub(super) async fn limit_uri(request: Request, next: Next) -> Response {
    let target = request
        .uri()
        .path_and_query()
        .map_or(0, |target| target.as_str().len());
    if target > MAX_URI_BYTES {
        return ApiError::uri_too_long(MAX_URI_BYTES).into_response();
    }
    next.run(request).await
}

/// Gives the JSON body to an error answer that has no body of its own (one made by a layer
/// rather than a handler), so every error a client sees has the same shape.
pub(super) async fn json_error_bodies(request: Request, next: Next) -> Response {
    let response = next.run(request).await;
    let status = response.status();
    let bare = !response.headers().contains_key(header::CONTENT_TYPE);
    if (status.is_client_error() || status.is_server_error()) && bare {
        let mut json = ApiError::from_status(status).into_response();
        for (name, value) in response.headers() {
            if !json.headers().contains_key(name) && name != header::CONTENT_LENGTH {
                json.headers_mut().insert(name.clone(), value.clone());
            }
        }
        return json;
    }
    response
}

/// Rejects API calls without the configured bearer token.
pub(super) async fn require_token(
    State(app): State<AppState>,
    request: Request,
    next: Next,
) -> Response {
    if let Some(token) = &app.token {
        let given = request
            .headers()
            .get(header::AUTHORIZATION)
            .and_then(|value| value.to_str().ok())
            .and_then(bearer_credentials);
        if !given.is_some_and(|given| constant_time_eq(given.as_bytes(), token.as_bytes())) {
            let mut response = ApiError::unauthorized().into_response();
            response
                .headers_mut()
                .insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
            return response;
        }
    }
    next.run(request).await
}

/// The credentials of an `Authorization: Bearer <token>` header. The scheme's name is
/// case-insensitive (RFC 7235, section 2.1); spaces around the token are not part of it.
fn bearer_credentials(value: &str) -> Option<&str> {
    let (scheme, credentials) = value.trim_start().split_once(' ')?;
    scheme
        .eq_ignore_ascii_case("bearer")
        .then(|| credentials.trim())
}

/// Compares `given` with `secret` without an early exit: the time taken depends on the
/// length of `given` alone, so it reveals neither how much of a guess was right nor the
/// secret's length.
fn constant_time_eq(given: &[u8], secret: &[u8]) -> bool {
    if secret.is_empty() {
        return given.is_empty();
    }
    let mut difference = given.len() ^ secret.len();
    for (i, byte) in given.iter().enumerate() {
        difference |= usize::from(byte ^ secret[i % secret.len()]);
    }
    std::hint::black_box(difference) == 0
}

/// 404 for paths no route matches.
pub(super) async fn no_route() -> ApiError {
    ApiError::not_found("no such route")
}

/// 405 for a known path with another method.
pub(super) async fn wrong_method() -> ApiError {
    ApiError::method_not_allowed()
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

async fn submit(State(app): State<AppState>, request: Request) -> Result<Response, ApiError> {
    if !is_json(request.headers()) {
        return Err(ApiError::unsupported_media_type());
    }
    let body = read_body(&app, request).await?;
    let document = json::from_slice(&body).map_err(|e| match e {
        JsonError::Syntax(_) => ApiError::bad_request(format!("malformed JSON: {e}")),
        JsonError::DuplicateKey { ref path, .. } => {
            ApiError::invalid_scene(SceneErrors(vec![FieldError::new(
                path.clone(),
                e.to_string(),
            )]))
        }
    })?;
    let scene = parse_scene(&document).map_err(ApiError::invalid_scene)?;
    let jobs = Arc::clone(&app.jobs);
    let record = tokio::task::spawn_blocking(move || {
        // Only a scene naming a stored surface waits for (and holds off) its deletion.
        let _hold = surface_id(&scene).map(|_| jobs.surfaces.hold());
        servable(&scene, &jobs.surfaces).map_err(ApiError::invalid_scene)?;
        Ok::<_, ApiError>(jobs.submit(scene))
    })
    .await
    .map_err(|e| ApiError::internal("submitting a job", &e))??
    .map_err(|e| match e {
        SubmitError::QueueFull {
            capacity,
            retry_after_s,
            ..
        } => ApiError::queue_full(capacity, retry_after_s),
        SubmitError::DiskFull => ApiError::disk_full("the job was not accepted"),
        SubmitError::Storage(e) => ApiError::internal("storing the job", &e),
    })?;
    let location = format!("/api/v1/jobs/{}", record.id);
    Ok((
        StatusCode::ACCEPTED,
        [(header::LOCATION, location)],
        Json(record),
    )
        .into_response())
}

async fn list_jobs(State(app): State<AppState>) -> impl IntoResponse {
    Json(app.jobs.list())
}

async fn get_job(State(app): State<AppState>, JobId(id): JobId) -> Result<Response, ApiError> {
    let job = app.jobs.get(id).ok_or_else(|| ApiError::unknown_job(id))?;
    Ok(Json(app.jobs.shown(&job)).into_response())
}

async fn delete_job(State(app): State<AppState>, JobId(id): JobId) -> Result<Response, ApiError> {
    let jobs = Arc::clone(&app.jobs);
    let deletion = tokio::task::spawn_blocking(move || jobs.delete(id))
        .await
        .map_err(|e| ApiError::internal("deleting a job", &e))?
        .ok_or_else(|| ApiError::unknown_job(id))?
        .map_err(|e| {
            if is_disk_full(&e) {
                ApiError::disk_full("the job was not changed")
            } else {
                ApiError::internal("deleting a job", &e)
            }
        })?;
    Ok(match deletion {
        Deletion::Cancelled(record) => (StatusCode::OK, Json(record)).into_response(),
        Deletion::Cancelling(record) => (StatusCode::ACCEPTED, Json(record)).into_response(),
        Deletion::Removed => StatusCode::NO_CONTENT.into_response(),
    })
}

async fn job_events(
    State(app): State<AppState>,
    JobId(id): JobId,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let job = app.jobs.get(id).ok_or_else(|| ApiError::unknown_job(id))?;
    // An unreadable Last-Event-ID is treated as absent: the client gets the whole stream,
    // which is more useful than an error from a reconnecting EventSource.
    let after = headers
        .get("last-event-id")
        .and_then(|value| value.to_str().ok())
        .and_then(|value| value.trim().parse::<u64>().ok())
        .unwrap_or(0);
    let stream = events::follow(Arc::clone(&app.jobs), job, after, app.shutdown.clone());
    Ok(Sse::new(stream)
        .keep_alive(KeepAlive::default().interval(app.keep_alive))
        .into_response())
}

/// The bytes of a succeeded job's `result.json`, checked against its manifest; 409 while it
/// has none. A damaged result sends the job back to the queue (409 too).
async fn result_bytes(app: &AppState, id: Uuid) -> Result<Vec<u8>, ApiError> {
    let job = app.jobs.get(id).ok_or_else(|| ApiError::unknown_job(id))?;
    let record = job.record();
    match (record.status, record.error) {
        (JobStatus::Succeeded, _) => {}
        (JobStatus::Failed | JobStatus::Cancelled, error) => {
            return partial_bytes(app, job, error).await;
        }
        (JobStatus::Damaged, Some(error)) => {
            return Err(ApiError::conflict(format!("job is damaged: {error}")));
        }
        (status, _) => {
            return Err(ApiError::conflict(format!(
                "job is {}; a result comes once it has finished",
                status.name()
            )));
        }
    }
    let jobs = Arc::clone(&app.jobs);
    tokio::task::spawn_blocking(move || {
        jobs.store().read_result(id).map_err(|damage| {
            if damage.is_read_failure() {
                return ApiError::internal("reading a result", &damage);
            }
            match jobs.rerun(&job, &damage) {
                // Deleted between the status check and the read.
                None => ApiError::unknown_job(id),
                Some(record) => ApiError::conflict(match record.error {
                    Some(error) if record.status == JobStatus::Damaged => {
                        format!("job is damaged: {error}")
                    }
                    _ => format!(
                        "the stored result was damaged ({damage}); the job runs again (now {})",
                        record.status.name()
                    ),
                }),
            }
        })
    })
    .await
    .map_err(|e| ApiError::internal("reading a result", &e))?
    .map(partial::marked_complete)
}

/// What a failed or cancelled job computed, as a result with `"complete": false`.
async fn partial_bytes(
    app: &AppState,
    job: Arc<Job>,
    error: Option<String>,
) -> Result<Vec<u8>, ApiError> {
    let jobs = Arc::clone(&app.jobs);
    tokio::task::spawn_blocking(move || jobs.partial_result(&job))
        .await
        .map_err(|e| ApiError::internal("reading a partial result", &e))?
        .map_err(|e| match e {
            PartialError::Scene(ref damage) if !damage.is_read_failure() => {
                ApiError::conflict(e.to_string())
            }
            PartialError::Surface(ref e) => {
                ApiError::conflict(format!("the surface this job ran on cannot be read: {e}"))
            }
            PartialError::Setup(_) => ApiError::conflict(format!(
                "job failed before its first cycle: {}",
                error.unwrap_or_else(|| e.to_string())
            )),
            _ => ApiError::internal("reading a partial result", &e),
        })
}

fn attachment(content_type: &'static str, filename: &str, body: impl IntoResponse) -> Response {
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

async fn job_result(State(app): State<AppState>, JobId(id): JobId) -> Result<Response, ApiError> {
    let bytes = result_bytes(&app, id).await?;
    Ok(attachment(
        "application/json",
        &format!("tribosim-{id}.json"),
        bytes,
    ))
}

async fn job_result_csv(
    State(app): State<AppState>,
    JobId(id): JobId,
) -> Result<Response, ApiError> {
    let bytes = result_bytes(&app, id).await?;
    let csv = tokio::task::spawn_blocking(move || export::cycles_csv(&bytes))
        .await
        .map_err(|e| ApiError::internal("exporting a result", &e))?
        .map_err(|e| ApiError::internal("exporting a result", &e))?;
    Ok(attachment(
        "text/csv; charset=utf-8",
        &format!("tribosim-{id}.csv"),
        csv,
    ))
}
