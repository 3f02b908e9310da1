//! What the service refuses that the core accepts: a scene it could accept but never run.

use uuid::Uuid;

use super::surfaces::{Surfaces, surface_id};
use crate::scene::{FieldError, Scene, SceneErrors};

/// Refuses a scene whose measured surface names no stored surface (422 at
/// `disc.surface.id`): the map reaches a worker only from the surfaces uploaded with
/// `POST /api/v1/surfaces`, so such a job could only fail on its worker after being
/// accepted. Call it holding [`Surfaces::hold`] until the job is queued.
pub(super) fn servable(scene: &Scene, surfaces: &Surfaces) -> Result<(), SceneErrors> {
    let Some(id) = surface_id(scene) else {
        return Ok(());
    };
    if Uuid::try_parse(id).is_ok_and(|uuid| surfaces.get(uuid).is_some()) {
        return Ok(());
    }
    Err(SceneErrors(vec![FieldError::new(
        "disc.surface.id",
        format!(
            "no stored surface {:?}: upload the height map with POST /api/v1/surfaces and \
             give the id it answers",
            super::extract::cut(id)
        ),
    )]))
}
