//! The handlers of `/api/v1/surfaces`: a height map uploaded as the bytes of its file, read
//! by the same readers as `tribosim run --surface` (`crate::surface::read`), stored by
//! [`super::surfaces`] and referred to by id from a scene's `disc.surface`.

use std::sync::Arc;

use axum::Json;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Query, Request, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;

use super::AppState;
use super::error::ApiError;
use super::extract::{cut, is_map_body, path_id, read_body};
use super::files::is_disk_full;
use super::surfaces::SurfaceDeletion;
use crate::scene::FieldError;
use crate::surface::{Format, HeightMap, Statistics, SurfaceError, read, read_as};

/// Largest height-map body: a 2048 x 2048 map (the contact grid's largest side) as a text
/// matrix at about 15 characters a height is 60 MiB; as a .gsf, 16 MiB.
pub const MAX_SURFACE_BODY_BYTES: usize = 64 << 20;

/// The longest name kept with a surface, in characters.
const MAX_NAME_CHARS: usize = 200;

path_id!(
    /// A surface id from the path.
    SurfaceId,
    "surface"
);

/// The query of an upload: each a string, so a bad value gets this API's own message.
#[derive(Deserialize)]
pub(super) struct UploadQuery {
    format: Option<String>,
    pixel_um: Option<String>,
    name: Option<String>,
}

fn refused(path: &str, message: String) -> ApiError {
    ApiError::unprocessable(
        format!("invalid height map: {message}"),
        vec![FieldError::new(path, message)],
    )
}

/// The format, pixel size (m) and name the query gives, each checked.
fn upload_options(query: UploadQuery) -> Result<(Option<Format>, Option<f64>, String), ApiError> {
    let format = match query.format.as_deref() {
        None => None,
        Some("gsf") => Some(Format::Gsf),
        Some("matrix") => Some(Format::Matrix),
        Some("xyz") => Some(Format::Xyz),
        Some(other) => {
            return Err(refused(
                "format",
                format!("{:?} is not a format (gsf, matrix, xyz)", cut(other)),
            ));
        }
    };
    let pixel_m = match query.pixel_um.as_deref() {
        None => None,
        Some(text) => match text.trim().parse::<f64>() {
            Ok(um) if um > 0.0 && um.is_finite() => Some(um * 1e-6),
            _ => {
                return Err(refused(
                    "pixel_um",
                    format!("{:?} is not a pixel size (a number > 0, um)", cut(text)),
                ));
            }
        },
    };
    let name = query.name.unwrap_or_default();
    if name.chars().count() > MAX_NAME_CHARS {
        return Err(refused(
            "name",
            format!("the name is longer than {MAX_NAME_CHARS} characters"),
        ));
    }
    Ok((format, pixel_m, name))
}

/// The map of an upload's bytes (in the format given, or as the content tells) and its
/// statistics, which must be finite numbers: JSON has none for the others, and a map too
/// small or too flat to have them gives a run nothing to report.
fn parse(
    bytes: &[u8],
    format: Option<Format>,
    pixel_m: Option<f64>,
) -> Result<(HeightMap, Format, Statistics), ApiError> {
    let (map, format) = read_map(bytes, format, pixel_m)?;
    let statistics = Statistics::of_measured(&map);
    let numbers = [
        ("rms_height_um", statistics.rms_height_um),
        ("rms_slope", statistics.rms_slope),
        ("psd_slope", statistics.psd_slope),
    ];
    if let Some((name, value)) = numbers.iter().find(|(_, value)| !value.is_finite()) {
        return Err(refused(
            "body",
            format!(
                "the map's {name} is {value}, not a finite number: its heights must vary, \
                 and it needs more than 8 pixels per side (its spectrum is fitted from half \
                 its side down to four pixels)"
            ),
        ));
    }
    Ok((map, format, statistics))
}

fn read_map(
    bytes: &[u8],
    format: Option<Format>,
    pixel_m: Option<f64>,
) -> Result<(HeightMap, Format), ApiError> {
    let parsed = match format {
        Some(format) => read_as(bytes, format, pixel_m).map(|map| (map, format)),
        None => read(bytes, pixel_m),
    };
    parsed.map_err(|e| match e {
        SurfaceError::TooLarge { .. } => ApiError::too_large(e.to_string()),
        SurfaceError::Invalid(_) if pixel_m.is_none() && format == Some(Format::Matrix) => {
            refused("pixel_um", e.to_string())
        }
        other => refused("body", other.to_string()),
    })
}

pub(super) async fn upload_surface(
    State(app): State<AppState>,
    query: Result<Query<UploadQuery>, QueryRejection>,
    request: Request,
) -> Result<Response, ApiError> {
    let Query(query) = query.map_err(|e| ApiError::bad_request(e.body_text()))?;
    let (format, pixel_m, name) = upload_options(query)?;
    if !is_map_body(request.headers()) {
        return Err(ApiError::unsupported_map_type());
    }
    let body = read_body(&app, request).await.map_err(|e| {
        if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::too_large(format!(
                "the height map is larger than {MAX_SURFACE_BODY_BYTES} bytes"
            ))
        } else {
            e
        }
    })?;
    let jobs = Arc::clone(&app.jobs);
    let record = tokio::task::spawn_blocking(move || {
        let (map, format, statistics) = parse(&body, format, pixel_m)?;
        jobs.surfaces
            .create(name, format, &map, statistics)
            .map_err(|e| {
                if is_disk_full(&e) {
                    ApiError::disk_full("the surface was not stored")
                } else {
                    ApiError::internal("storing a surface", &e)
                }
            })
    })
    .await
    .map_err(|e| ApiError::internal("storing a surface", &e))??;
    let location = format!("/api/v1/surfaces/{}", record.id);
    Ok((
        StatusCode::CREATED,
        [(header::LOCATION, location)],
        Json(record),
    )
        .into_response())
}

pub(super) async fn list_surfaces(State(app): State<AppState>) -> Response {
    Json(app.jobs.surfaces.list()).into_response()
}

fn unknown_surface(id: uuid::Uuid) -> ApiError {
    ApiError::not_found(format!("no surface {id}"))
}

pub(super) async fn get_surface(
    State(app): State<AppState>,
    SurfaceId(id): SurfaceId,
) -> Result<Response, ApiError> {
    let record = app
        .jobs
        .surfaces
        .get(id)
        .ok_or_else(|| unknown_surface(id))?;
    Ok(Json(record).into_response())
}

/// 204 when removed; 409 while a queued or running job needs the map (a finished job keeps
/// its result, which carries the surface's statistics, so it does not hold the map).
pub(super) async fn delete_surface(
    State(app): State<AppState>,
    SurfaceId(id): SurfaceId,
) -> Result<Response, ApiError> {
    let jobs = Arc::clone(&app.jobs);
    let deletion =
        tokio::task::spawn_blocking(move || jobs.surfaces.delete(id, || jobs.using_surface(id)))
            .await
            .map_err(|e| ApiError::internal("deleting a surface", &e))?
            .map_err(|e| {
                if is_disk_full(&e) {
                    ApiError::disk_full("the surface was not deleted")
                } else {
                    ApiError::internal("deleting a surface", &e)
                }
            })?;
    match deletion {
        SurfaceDeletion::Removed => Ok(StatusCode::NO_CONTENT.into_response()),
        SurfaceDeletion::Unknown => Err(unknown_surface(id)),
        SurfaceDeletion::InUse(users) => {
            let users: Vec<String> = users.iter().map(ToString::to_string).collect();
            Err(ApiError::conflict(format!(
                "surface {id} is used by queued or running jobs ({}); delete (cancel) them \
                 first, or wait until they finish",
                users.join(", ")
            )))
        }
    }
}
