//! The routes of `/api/v1/surfaces`, and the API's answer to each error of surfaces. A
//! height map is uploaded as the bytes of its file and referred to by id from a scene's
//! `disc.surface`.

use std::sync::Arc;

use axum::Json;
use axum::body::Bytes;
use axum::extract::{
    DefaultBodyLimit, FromRef, FromRequest, FromRequestParts, Query, Request, State,
};
use axum::http::StatusCode;
use axum::http::request::Parts;
use axum::response::Response;
use axum::routing::on;
use tokio::sync::OwnedSemaphorePermit;
use uuid::Uuid;

use super::store::{DeleteError, SurfaceRecord, SurfaceUsers, Surfaces};
use super::upload::{self, UploadError, UploadOptions, UploadQuery};
use crate::scene::FieldError;
use crate::service::blocking::blocking;
use crate::service::error::ApiError;
use crate::service::extract::{Body, BodyTimeout, SurfaceId, essence};
use crate::service::reply::created;
use crate::service::route::{Endpoint, Verb};

/// Largest height-map body: a 2048 x 2048 map (the contact grid's largest side) as a text
/// matrix at about 15 characters a height is 60 MiB; as a .gsf, 16 MiB.
const MAX_SURFACE_BODY_BYTES: usize = 64 << 20;

/// The routes, on any state that provides the surfaces, their users and the body timeout.
pub(crate) fn endpoints<S>() -> Vec<Endpoint<S>>
where
    S: Clone + Send + Sync + 'static,
    Arc<Surfaces>: FromRef<S>,
    Arc<dyn SurfaceUsers>: FromRef<S>,
    BodyTimeout: FromRef<S>,
{
    vec![
        Endpoint::api(Verb::Post, "/api/v1/surfaces", |f| {
            on(f, upload_surface).layer(DefaultBodyLimit::max(MAX_SURFACE_BODY_BYTES))
        }),
        Endpoint::api(Verb::Get, "/api/v1/surfaces", |f| on(f, list_surfaces)),
        Endpoint::api(Verb::Get, "/api/v1/surfaces/{id}", |f| on(f, get_surface)),
        Endpoint::api(Verb::Delete, "/api/v1/surfaces/{id}", |f| {
            on(f, delete_surface)
        }),
    ]
}

impl<S: Send + Sync> FromRequestParts<S> for UploadOptions {
    type Rejection = ApiError;

    async fn from_request_parts(parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let Query(query) = Query::<UploadQuery>::from_request_parts(parts, state).await?;
        Ok(query.options()?)
    }
}

/// Seconds a client is asked to wait when every upload slot is busy: about the time one
/// map at the pixel limit takes to read and store.
const BUSY_RETRY_AFTER_S: u64 = 5;

/// A place among the uploads read at once (`--surface-parses`), taken before the body is
/// read, so that uploads beyond them cost neither the body's memory nor its parse: 429.
struct ParsePermit(OwnedSemaphorePermit);

impl<S> FromRequestParts<S> for ParsePermit
where
    S: Send + Sync,
    Arc<Surfaces>: FromRef<S>,
{
    type Rejection = ApiError;

    async fn from_request_parts(_parts: &mut Parts, state: &S) -> Result<Self, ApiError> {
        let surfaces = Arc::<Surfaces>::from_ref(state);
        let parses = Arc::clone(&surfaces.parses);
        parses.try_acquire_owned().map(Self).map_err(|_| {
            ApiError::too_many_requests(
                format!(
                    "{} height maps are being read, the most at once (--surface-parses); \
                     retry later",
                    surfaces.limits.parses
                ),
                BUSY_RETRY_AFTER_S,
            )
        })
    }
}

/// A height map's body: the bytes of its file, declared `application/octet-stream` (415
/// otherwise), read as every body is ([`Body`]) under this route's limit. Not `text/plain`
/// (nor a form's types): a page of another site may send those without the browser asking
/// the server first (a CORS "simple" request), so a map could be stored from any page.
struct MapBody(Bytes);

impl<S> FromRequest<S> for MapBody
where
    S: Send + Sync,
    BodyTimeout: FromRef<S>,
{
    type Rejection = ApiError;

    async fn from_request(request: Request, state: &S) -> Result<Self, ApiError> {
        match essence(request.headers()).as_deref() {
            Some("application/octet-stream") => {}
            Some(
                simple @ ("text/plain"
                | "application/x-www-form-urlencoded"
                | "multipart/form-data"),
            ) => {
                return Err(ApiError::unsupported_media_type(format!(
                    "a height map must be sent with `Content-Type: application/octet-stream`, \
                     whatever its format; not `{simple}`, which a page of another site may \
                     send without the server's consent"
                )));
            }
            _ => {
                return Err(ApiError::unsupported_media_type(
                    "a height map must be sent with `Content-Type: application/octet-stream`, \
                     whatever its format",
                ));
            }
        }
        match Body::from_request(request, state).await {
            Ok(Body(bytes)) => Ok(Self(bytes)),
            Err(e) if e.status() == StatusCode::PAYLOAD_TOO_LARGE => Err(ApiError::too_large(
                format!("the height map is larger than {MAX_SURFACE_BODY_BYTES} bytes"),
            )),
            Err(e) => Err(e),
        }
    }
}

/// `POST /api/v1/surfaces`: 201 with the stored surface and its `Location`.
async fn upload_surface(
    State(surfaces): State<Arc<Surfaces>>,
    options: UploadOptions,
    ParsePermit(permit): ParsePermit,
    MapBody(bytes): MapBody,
) -> Result<Response, ApiError> {
    let record = blocking(move || {
        let stored = upload::store(&surfaces, options, &bytes);
        drop(permit);
        stored
    })
    .await?;
    let location = format!("/api/v1/surfaces/{}", record.id);
    Ok(created(StatusCode::CREATED, location, record))
}

/// `GET /api/v1/surfaces`: every surface, oldest first.
async fn list_surfaces(State(surfaces): State<Arc<Surfaces>>) -> Json<Vec<SurfaceRecord>> {
    Json(surfaces.list())
}

/// `GET /api/v1/surfaces/{id}`.
async fn get_surface(
    State(surfaces): State<Arc<Surfaces>>,
    SurfaceId(id): SurfaceId,
) -> Result<Json<SurfaceRecord>, ApiError> {
    surfaces.get(id).map(Json).ok_or_else(|| unknown(id))
}

/// `DELETE /api/v1/surfaces/{id}`: 204 once removed.
async fn delete_surface(
    State(surfaces): State<Arc<Surfaces>>,
    State(users): State<Arc<dyn SurfaceUsers>>,
    SurfaceId(id): SurfaceId,
) -> Result<StatusCode, ApiError> {
    blocking(move || surfaces.delete(id, users.as_ref())).await?;
    Ok(StatusCode::NO_CONTENT)
}

/// 404 for an id no surface has.
fn unknown(id: Uuid) -> ApiError {
    ApiError::not_found(format!("no surface {id}"))
}

/// 422 naming the query value or the map at fault, 413 for a map too large to run, 507 when
/// the disk is full.
impl From<UploadError> for ApiError {
    fn from(error: UploadError) -> Self {
        match error {
            UploadError::Invalid { path, message } => Self::unprocessable(
                format!("invalid height map: {message}"),
                vec![FieldError::new(path, message)],
            ),
            UploadError::TooLarge(message) => Self::too_large(message),
            UploadError::Storage(e) => {
                Self::storage(&e, "the surface was not stored", "storing a surface")
            }
        }
    }
}

/// 404, 409 while queued or running jobs need the map, 507 when the disk is full.
impl From<DeleteError> for ApiError {
    fn from(error: DeleteError) -> Self {
        match error {
            DeleteError::Unknown(id) => unknown(id),
            DeleteError::InUse { id, users } => {
                let users: Vec<String> = users.iter().map(ToString::to_string).collect();
                Self::conflict(format!(
                    "surface {id} is used by queued or running jobs ({}); delete (cancel) them \
                     first, or wait until they finish",
                    users.join(", ")
                ))
            }
            DeleteError::Storage(e) => {
                Self::storage(&e, "the surface was not deleted", "deleting a surface")
            }
        }
    }
}
