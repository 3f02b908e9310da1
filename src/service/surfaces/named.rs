//! The surface a scene names, and what the service refuses that the core accepts: a scene
//! naming a surface that is not stored, which it could accept but never run.

use uuid::Uuid;

use super::store::Surfaces;
use crate::scene::{FieldError, Scene, SceneErrors, SurfaceKind};
use crate::service::extract::cut;

/// The id of the stored surface `scene` names, if its surface is measured.
pub fn surface_id(scene: &Scene) -> Option<&str> {
    let surface = scene.disc.surface.as_ref()?;
    (surface.kind == SurfaceKind::Measured)
        .then_some(surface.id.as_deref())
        .flatten()
}

/// Refuses a scene whose measured surface names no stored surface (422 at
/// `disc.surface.id`): the map reaches a worker only from the surfaces uploaded with
/// `POST /api/v1/surfaces`, so such a job could only fail on its worker after being
/// accepted. Call it holding [`Surfaces::hold`] until the job is queued.
pub fn servable(scene: &Scene, surfaces: &Surfaces) -> Result<(), SceneErrors> {
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
            cut(id)
        ),
    )]))
}
