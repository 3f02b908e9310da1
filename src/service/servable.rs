//! What the service refuses that the core accepts: a scene it could accept but never run.

use crate::scene::{FieldError, Scene, SceneErrors, SurfaceKind};

/// Refuses a scene whose disc is a measured height map: the map reaches the core only
/// through `tribosim run --surface FILE`, and the service has no upload of maps, so such a
/// job could only fail on its worker after being accepted.
pub(super) fn servable(scene: &Scene) -> Result<(), SceneErrors> {
    match scene.disc.surface.as_ref().map(|surface| surface.kind) {
        Some(SurfaceKind::Measured) => Err(SceneErrors(vec![FieldError::new(
            "disc.surface.kind",
            "a measured surface cannot be run by the service (it has no upload of height \
             maps); run the scene with `tribosim run SCENE --surface FILE`, or give a \
             synthetic surface",
        )])),
        Some(SurfaceKind::Synthetic) | None => Ok(()),
    }
}
