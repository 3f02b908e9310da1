//! The router: every resource's routes merged into the one table ([`routes`]), the token
//! check on the API's, JSON answers for unknown paths and methods and for errors made below
//! the handlers, the limits on a request's target and body, compression, the checks of
//! `Host` and `Origin` and the security headers (`origin`), and one log line per request.

use std::sync::Arc;

use axum::Router;
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{HeaderValue, header};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use tower_http::compression::CompressionLayer;
use tower_http::cors::CorsLayer;
use tower_http::trace::{DefaultMakeSpan, DefaultOnResponse, TraceLayer};
use tracing::Level;

use super::error::ApiError;
use super::origin::{self, Guard};
use super::route::{Endpoint, Route};
use super::state::AppState;
use super::{assets, calibrations, docs, jobs, measurements, meta, reports, studies, surfaces};

/// Largest request body accepted: a scene is a few kilobytes, a measured table some tens
/// (a profilometer trace of a few thousand points). A height map's route takes more.
pub const BODY_LIMIT_BYTES: usize = 1 << 20;

/// Longest request target (path and query) accepted: the longest route with a job id is
/// under 70 bytes, and 8 KiB is what common proxies accept. Longer targets get 414 with
/// the JSON body (hyper itself refuses targets over 64 KiB, with an empty body).
pub const MAX_URI_BYTES: usize = 8 * 1024;

/// Every route with its handler: the page's and its files', the service's own, then each resource's.
fn endpoints() -> Vec<Endpoint<AppState>> {
    [
        assets::endpoints(),
        docs::endpoints(),
        meta::endpoints(),
        jobs::endpoints(),
        measurements::endpoints(),
        studies::endpoints(),
        reports::endpoints(),
        calibrations::endpoints(),
        surfaces::endpoints(),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Every route of the service: the table the router is built from.
pub fn routes() -> Vec<Route> {
    endpoints().iter().map(|endpoint| endpoint.route).collect()
}

/// The router: every route of [`routes`], the token check on those that need it, JSON
/// answers for unknown paths and methods, the body limit, the [`Guard`] of a server without
/// a token, the security headers, one log line per request.
pub(crate) fn router(app: AppState, cors: Option<CorsLayer>, guard: Arc<Guard>) -> Router {
    let (mut public, mut protected) = (Router::new(), Router::new());
    for endpoint in endpoints() {
        let route = endpoint.route;
        if route.auth {
            protected = protected.route(route.path, endpoint.method_router());
        } else {
            public = public.route(route.path, endpoint.method_router());
        }
    }
    let protected = protected.route_layer(axum::middleware::from_fn_with_state(
        app.clone(),
        require_token,
    ));
    let router = public
        .merge(protected)
        .fallback(no_route)
        .method_not_allowed_fallback(wrong_method)
        .layer(DefaultBodyLimit::max(BODY_LIMIT_BYTES))
        .layer(axum::middleware::from_fn(limit_uri))
        .layer(axum::middleware::from_fn(json_error_bodies))
        // Results with pressure maps run to megabytes of JSON (gzip: about a fifth). The
        // default predicate leaves event streams alone, so progress is not buffered.
        .layer(CompressionLayer::new())
        .with_state(app);
    let router = match cors {
        Some(cors) => router.layer(cors),
        None => router,
    };
    // Outside CORS, so that a preflight too is refused under a name that is not the
    // server's; inside the log, so that refusals are logged; and the headers outermost,
    // so that every answer has them, refusals included.
    router
        .layer(axum::middleware::from_fn_with_state(guard, origin::guard))
        .layer(
            TraceLayer::new_for_http()
                .make_span_with(DefaultMakeSpan::new().level(Level::INFO))
                .on_request(())
                .on_response(DefaultOnResponse::new().level(Level::INFO)),
        )
        .layer(axum::middleware::from_fn(origin::security_headers))
}

/// 414 with the JSON body for a request target over [`MAX_URI_BYTES`].
async fn limit_uri(request: Request, next: Next) -> Response {
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
async fn json_error_bodies(request: Request, next: Next) -> Response {
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
async fn require_token(State(app): State<AppState>, request: Request, next: Next) -> Response {
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
async fn no_route() -> ApiError {
    ApiError::not_found("no such route")
}

/// 405 for a known path with another method.
async fn wrong_method() -> ApiError {
    ApiError::method_not_allowed()
}
