//! What the handlers share: each resource's registry, and the settings bodies and event
//! streams are read with. A handler takes only its part (`State<Arc<Jobs>>`, ...) through
//! the `FromRef` impls here, axum's substates (`axum::extract::State`, "Substates"): a
//! resource's routes name their own state, never the whole of it, so no resource imports
//! the state that imports it.

use std::path::Path;
use std::sync::Arc;

use axum::extract::FromRef;

use super::calibrations::Calibrations;
use super::cursor::CursorKey;
use super::extract::BodyTimeout;
use super::jobs::{Jobs, Streams};
use super::meta::DataDir;
use super::studies::Studies;
use super::surfaces::{SurfaceUsers, Surfaces};

/// The state of the router.
#[derive(Clone)]
pub(crate) struct AppState {
    pub(crate) jobs: Arc<Jobs>,
    pub(crate) studies: Arc<Studies>,
    pub(crate) calibrations: Arc<Calibrations>,
    pub(crate) surfaces: Arc<Surfaces>,
    /// The bearer token API calls need, if any.
    pub(crate) token: Option<Arc<str>>,
    /// Where the page's files are read from; the built-in copies when `None`.
    pub(crate) static_dir: Option<Arc<Path>>,
    pub(crate) body_timeout: BodyTimeout,
    pub(crate) streams: Streams,
    /// The data folder, whose health `/healthz` reports.
    pub(crate) data_dir: DataDir,
    /// The key the lists' cursors are signed with, drawn at start.
    pub(crate) cursor_key: CursorKey,
}

impl FromRef<AppState> for Arc<Jobs> {
    fn from_ref(app: &AppState) -> Self {
        Arc::clone(&app.jobs)
    }
}

impl FromRef<AppState> for Arc<Studies> {
    fn from_ref(app: &AppState) -> Self {
        Arc::clone(&app.studies)
    }
}

impl FromRef<AppState> for Arc<Calibrations> {
    fn from_ref(app: &AppState) -> Self {
        Arc::clone(&app.calibrations)
    }
}

impl FromRef<AppState> for Arc<Surfaces> {
    fn from_ref(app: &AppState) -> Self {
        Arc::clone(&app.surfaces)
    }
}

/// A surface's users are the jobs that name it.
impl FromRef<AppState> for Arc<dyn SurfaceUsers> {
    fn from_ref(app: &AppState) -> Self {
        Arc::clone(&app.jobs) as Arc<dyn SurfaceUsers>
    }
}

impl FromRef<AppState> for BodyTimeout {
    fn from_ref(app: &AppState) -> Self {
        app.body_timeout
    }
}

impl FromRef<AppState> for Streams {
    fn from_ref(app: &AppState) -> Self {
        app.streams.clone()
    }
}

impl FromRef<AppState> for DataDir {
    fn from_ref(app: &AppState) -> Self {
        app.data_dir.clone()
    }
}

impl FromRef<AppState> for CursorKey {
    fn from_ref(app: &AppState) -> Self {
        app.cursor_key.clone()
    }
}
