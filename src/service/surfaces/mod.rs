//! Surfaces: height maps uploaded to the service and named by id from a scene's
//! `disc.surface`. Every stored surface, in memory and on disk (`store.rs`), an upload's
//! checks (`upload.rs`), the surface a scene names and the refusal of one not stored
//! (`named.rs`), and the routes (`routes.rs`).

mod named;
mod routes;
mod store;
mod upload;

pub(crate) use named::{servable, surface_id};
pub(crate) use routes::endpoints;
pub(crate) use store::{SurfaceLoadError, SurfaceUsers, Surfaces};
