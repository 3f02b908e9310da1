//! An upload's checks: the query's options (format, pixel size, name) and the height map of
//! its bytes, read by the same readers as `tribosim run --surface` (`crate::surface::read`),
//! each refusal naming what is at fault; then the map stored.

use std::io;

use serde::Deserialize;

use super::store::{CreateError, SurfaceRecord, Surfaces};
use crate::service::extract::cut;
use crate::simulation::check_map;
use crate::surface::{
    Format, HeightMap, HeightUnit, MAX_PIXEL_M, MIN_PIXEL_M, Statistics, SurfaceError,
    declared_pixels, read, read_as,
};
use crate::text::{Lines, NAME_MAX_CHARS, check};

/// The query of an upload: each a string, so a bad value gets this API's own message.
#[derive(Deserialize)]
pub(super) struct UploadQuery {
    format: Option<String>,
    pixel_um: Option<String>,
    height_unit: Option<String>,
    name: Option<String>,
}

/// The format, pixel size, height unit and name an upload's query gives, checked.
pub(super) struct UploadOptions {
    format: Option<Format>,
    pixel_m: Option<f64>,
    /// The heights' unit; `None` for heights in m as the file has them.
    height_unit: Option<HeightUnit>,
    name: String,
}

/// Why an upload was refused or not kept.
#[derive(Debug)]
pub enum UploadError {
    /// A query value or the map is not usable; `path` names it (`format`, `pixel_um`,
    /// `name`, or `body` for the map).
    Invalid {
        /// What is at fault.
        path: &'static str,
        /// Why.
        message: String,
    },
    /// The map has more pixels than a run can use.
    TooLarge(String),
    /// The map could not be stored.
    Storage(io::Error),
}

fn invalid(path: &'static str, message: String) -> UploadError {
    UploadError::Invalid { path, message }
}

impl UploadQuery {
    /// The options the query gives, each checked.
    pub(super) fn options(self) -> Result<UploadOptions, UploadError> {
        let format = match self.format.as_deref() {
            None => None,
            Some("gsf") => Some(Format::Gsf),
            Some("matrix") => Some(Format::Matrix),
            Some("xyz") => Some(Format::Xyz),
            Some(other) => {
                return Err(invalid(
                    "format",
                    format!("{:?} is not a format (gsf, matrix, xyz)", cut(other)),
                ));
            }
        };
        let pixel_m = match self.pixel_um.as_deref() {
            None => None,
            Some(text) => match text.trim().parse::<f64>() {
                Ok(um) if (MIN_PIXEL_M..=MAX_PIXEL_M).contains(&(um * 1e-6)) => Some(um * 1e-6),
                _ => {
                    return Err(invalid(
                        "pixel_um",
                        format!(
                            "{:?} is not a pixel size (a number from {:e} to {:e}, um)",
                            cut(text),
                            MIN_PIXEL_M * 1e6,
                            MAX_PIXEL_M * 1e6
                        ),
                    ));
                }
            },
        };
        let height_unit = match self.height_unit.as_deref() {
            None => None,
            Some(text) => Some(HeightUnit::named(text.trim()).ok_or_else(|| {
                invalid(
                    "height_unit",
                    format!("{:?} is not a unit of height (m, um, nm)", cut(text)),
                )
            })?),
        };
        // A name as a scene's: the same bound and the same rule on characters.
        let name = self.name.unwrap_or_default();
        check(&name, NAME_MAX_CHARS, Lines::One).map_err(|e| invalid("name", e.to_string()))?;
        Ok(UploadOptions {
            format,
            pixel_m,
            height_unit,
            name,
        })
    }
}

/// Reads the map of an upload's bytes and stores it, once the pixels its bytes declare are
/// within the limit. Blocking (parsing, files).
pub(super) fn store(
    surfaces: &Surfaces,
    options: UploadOptions,
    bytes: &[u8],
) -> Result<SurfaceRecord, UploadError> {
    let declared = declared_pixels(bytes, options.format, options.pixel_m)
        .map_err(|e| invalid("body", e.to_string()))?;
    let limit = surfaces.limits.max_pixels;
    if declared > limit {
        return Err(UploadError::TooLarge(format!(
            "the map declares {declared} pixels; at most {limit} are read \
             (--max-surface-pixels)"
        )));
    }
    let (map, format, statistics) = parse(bytes, &options)?;
    surfaces
        .create(options.name, format, &map, statistics)
        .map_err(|e| match e {
            CreateError::Storage(e) => UploadError::Storage(e),
            unreadable => invalid("body", unreadable.to_string()),
        })
}

/// The map of an upload's bytes (in the format given, or as the content tells) and its
/// statistics, which must be finite numbers: JSON has none for the others, and a map too
/// small or too flat to have them gives a run nothing to report.
fn parse(
    bytes: &[u8],
    options: &UploadOptions,
) -> Result<(HeightMap, Format, Statistics), UploadError> {
    let (mut map, format) = read_map(bytes, options.format, options.pixel_m)?;
    if let Some(unit) = options.height_unit {
        unit.apply(&mut map, format)
            .map_err(|e| invalid("height_unit", e.to_string()))?;
    }
    // The run would refuse such a map at its start; refused here, the slip is named where
    // it was made, before any job names the map.
    let label = if options.name.is_empty() {
        "upload"
    } else {
        options.name.as_str()
    };
    check_map(label, &map).map_err(|e| {
        let hint = match options.height_unit {
            None | Some(HeightUnit::M) => "; pass height_unit=um (or nm) with the upload",
            Some(_) => "; check the upload's height_unit",
        };
        invalid("height_unit", format!("{}{hint}", e.message))
    })?;
    let statistics = Statistics::of_measured(&map);
    let numbers = [
        ("rms_height_um", statistics.rms_height_um),
        ("rms_slope", statistics.rms_slope),
        ("psd_slope", statistics.psd_slope),
    ];
    if let Some((name, value)) = numbers.iter().find(|(_, value)| !value.is_finite()) {
        return Err(invalid(
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
) -> Result<(HeightMap, Format), UploadError> {
    let parsed = match format {
        Some(format) => read_as(bytes, format, pixel_m).map(|map| (map, format)),
        None => read(bytes, pixel_m),
    };
    parsed.map_err(|e| match e {
        SurfaceError::TooLarge { .. } => UploadError::TooLarge(e.to_string()),
        SurfaceError::Invalid(_) if pixel_m.is_none() && format == Some(Format::Matrix) => {
            invalid("pixel_um", e.to_string())
        }
        other => invalid("body", other.to_string()),
    })
}
