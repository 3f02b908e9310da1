//! The route table's types. Each resource lists its routes as [`Endpoint`]s beside its
//! handlers (`<resource>/routes.rs`); `router` merges the lists into the one table that the
//! router is built from and that `openapi.yaml` is checked against.

use axum::routing::{MethodFilter, MethodRouter};

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
    /// PATCH.
    Patch,
}

impl Verb {
    /// The method's name as OpenAPI spells it (lower case).
    pub fn openapi_name(self) -> &'static str {
        match self {
            Self::Get => "get",
            Self::Post => "post",
            Self::Put => "put",
            Self::Delete => "delete",
            Self::Patch => "patch",
        }
    }

    fn filter(self) -> MethodFilter {
        match self {
            Self::Get => MethodFilter::GET,
            Self::Post => MethodFilter::POST,
            Self::Put => MethodFilter::PUT,
            Self::Delete => MethodFilter::DELETE,
            Self::Patch => MethodFilter::PATCH,
        }
    }
}

/// One route of the service, as `openapi.yaml` describes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Route {
    /// The method.
    pub verb: Verb,
    /// The path; axum's `{id}` syntax is also OpenAPI's, and its catch-all `{*path}` is
    /// OpenAPI's `{path}` ([`Route::openapi_path`]).
    pub path: &'static str,
    /// Whether the bearer token (when configured) is required.
    pub auth: bool,
}

impl Route {
    /// The path as `openapi.yaml` writes it: a catch-all's value (which may hold slashes) is
    /// an ordinary path parameter there.
    pub fn openapi_path(&self) -> String {
        self.path.replace("{*", "{")
    }
}

/// A route and its handler, on a router whose state is `S`. A resource's table is generic
/// in `S`: its handlers take only their part of the state (`State<Arc<Jobs>>`), so the
/// resource knows nothing of the application's state, which provides the parts.
pub(crate) struct Endpoint<S> {
    pub(crate) route: Route,
    handler: Handler<S>,
}

/// A route's handler: given the route's method filter, its method router.
type Handler<S> = fn(MethodFilter) -> MethodRouter<S>;

impl<S> Endpoint<S> {
    /// An API call, which needs the bearer token when one is configured.
    pub(crate) fn api(verb: Verb, path: &'static str, handler: Handler<S>) -> Self {
        Self::of(verb, path, handler, true)
    }

    /// A route anyone may call: the page, the health check and the API's description carry
    /// no data.
    pub(crate) fn public(verb: Verb, path: &'static str, handler: Handler<S>) -> Self {
        Self::of(verb, path, handler, false)
    }

    fn of(verb: Verb, path: &'static str, handler: Handler<S>, auth: bool) -> Self {
        let route = Route { verb, path, auth };
        Self { route, handler }
    }

    /// This route's method router.
    pub(crate) fn method_router(&self) -> MethodRouter<S> {
        (self.handler)(self.route.verb.filter())
    }
}
