//! Studies: a study document expanded by [`crate::study`] into its members, each submitted
//! as an ordinary job (all or none, `Jobs::submit_many`); the registry of studies by id
//! (`registry.rs`), their files under `<data-dir>/studies/` (`store.rs`), the record the API
//! shows, with statuses read from the member jobs (`record.rs`), and the routes
//! (`routes.rs`).

mod record;
mod registry;
mod routes;
mod store;

pub(crate) use registry::Studies;
pub(crate) use routes::endpoints;
