//! The handlers of `/api/v1/calibrations`: they read the request, check the table as the fit
//! would (a bad table is a 422 naming its column and row, before anything runs), and hand
//! the fit to [`super::calibrations`].

use axum::Json;
use axum::extract::{Request, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde::Deserialize;
use serde_json::Value;

use super::AppState;
use super::calibrations::StartError;
use super::error::ApiError;
use super::extract::{is_json, path_id, read_body};
use crate::calibration::{
    CalibrationError, ChangeCycle, ChangeCycleError, CommandOptions, FitKind, Table, check,
    default_scene,
};
use crate::json::{self, JsonError};
use crate::scene::{FieldError, Scene};
use crate::simulation::{Plan, parse_scene};

/// Seconds a client is asked to wait when every fit slot is busy: about one Archard fit of
/// Table 3 (7.5 s on a shared two-core machine, docs/calibration.md).
const BUSY_RETRY_AFTER_S: u64 = 10;

path_id!(
    /// A calibration id from the path.
    CalibrationId,
    "calibration"
);

/// The request body.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CalibrationRequest {
    kind: FitKind,
    /// CSV text, or a JSON table (an array of row objects, an object of column arrays).
    table: Value,
    /// The scene fitted with; the paper's preset when absent.
    #[serde(default)]
    scene: Option<Value>,
    #[serde(default)]
    options: RequestOptions,
}

/// The command line's options, by their JSON names.
#[derive(Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RequestOptions {
    /// Hardness: whether the scene's bulk value takes part in the fit (default true).
    include_bulk: Option<bool>,
    /// Tafel: E_corr, V, instead of the potential of the smallest current.
    e_corr_v: Option<f64>,
    /// Archard: also fit a change of regime at this cycle, or `"auto"` for the best one.
    regime_change: Option<Value>,
}

/// The change cycle as the command line spells it: a whole number >= 1, or `auto`.
fn change_cycle(value: &Value) -> Result<ChangeCycle, ApiError> {
    let text = match value {
        Value::String(text) => text.clone(),
        other => other.to_string(),
    };
    text.parse()
        .map_err(|e: ChangeCycleError| invalid("options.regime_change", e.to_string()))
}

fn invalid(path: &str, message: String) -> ApiError {
    ApiError::unprocessable(
        format!("invalid calibration: {message}"),
        vec![FieldError::new(path, message)],
    )
}

/// The checked inputs of a fit, or the 4xx that refuses them.
fn inputs(body: &[u8]) -> Result<(FitKind, Table, Scene, CommandOptions), ApiError> {
    let document = json::from_slice(body).map_err(|e| match &e {
        JsonError::Syntax(_) => ApiError::bad_request(format!("malformed JSON: {e}")),
        JsonError::DuplicateKey { path, .. } => invalid(path, e.to_string()),
    })?;
    let request: CalibrationRequest =
        serde_json::from_value(document).map_err(|e| invalid("", e.to_string()))?;
    let kind = request.kind;
    let options = request.options;
    if options.include_bulk.is_some() && kind != FitKind::Hardness {
        return Err(invalid(
            "options.include_bulk",
            "applies to the hardness fit only".into(),
        ));
    }
    if options.regime_change.is_some() && kind != FitKind::Archard {
        return Err(invalid(
            "options.regime_change",
            "applies to the archard fit only".into(),
        ));
    }
    let regime_change = options
        .regime_change
        .as_ref()
        .map(change_cycle)
        .transpose()?;
    if options.e_corr_v.is_some() && kind != FitKind::Tafel {
        return Err(invalid(
            "options.e_corr_v",
            "applies to the tafel fit only".into(),
        ));
    }
    let text = match &request.table {
        Value::String(text) => text.clone(),
        table @ (Value::Array(_) | Value::Object(_)) => table.to_string(),
        other => {
            return Err(invalid(
                "table",
                format!("must be CSV text or a JSON table (rows or columns), got {other}"),
            ));
        }
    };
    let table = Table::parse(&text).map_err(|e| invalid("table", e.to_string()))?;
    let scene = match &request.scene {
        None => default_scene(),
        Some(document) => parse_scene(document)
            .map(Plan::into_scene)
            .map_err(|errors| {
                ApiError::unprocessable(
                    "invalid calibration: the scene has invalid fields",
                    errors
                        .0
                        .into_iter()
                        .map(|f| FieldError::new(format!("scene.{}", f.path), f.message))
                        .collect(),
                )
            })?,
    };
    let options = CommandOptions {
        without_bulk: !options.include_bulk.unwrap_or(true),
        corrosion_potential_v: options.e_corr_v,
        scene_given: request.scene.is_some(),
        regime_change,
        ..CommandOptions::default()
    };
    Ok((kind, table, scene, options))
}

/// Where a fit's refusal lies: in the scene, or in the table.
fn refused(error: &CalibrationError) -> ApiError {
    let path = match error {
        CalibrationError::MissingSection(_)
        | CalibrationError::Scene(_)
        | CalibrationError::Hardness(_) => "scene",
        _ => "table",
    };
    invalid(path, error.to_string())
}

pub(super) async fn submit_calibration(
    State(app): State<AppState>,
    request: Request,
) -> Result<Response, ApiError> {
    if !is_json(request.headers()) {
        return Err(ApiError::unsupported_media_type());
    }
    let body = read_body(&app, request).await?;
    let calibrations = std::sync::Arc::clone(&app.calibrations);
    let record = tokio::task::spawn_blocking(move || {
        let (kind, table, scene, options) = inputs(&body)?;
        check(kind, &table, &scene, options).map_err(|e| refused(&e))?;
        calibrations
            .start(kind, table, scene, options)
            .map_err(|e| match e {
                StartError::Busy => ApiError::no_room(
                    format!(
                        "{} calibrations are running, the most at once; retry later",
                        super::calibrations::MAX_RUNNING
                    ),
                    BUSY_RETRY_AFTER_S,
                ),
                StartError::Thread(e) => ApiError::internal("starting a calibration", &e),
            })
    })
    .await
    .map_err(|e| ApiError::internal("submitting a calibration", &e))??;
    let location = format!("/api/v1/calibrations/{}", record.id);
    Ok((
        StatusCode::ACCEPTED,
        [(header::LOCATION, location)],
        Json(record),
    )
        .into_response())
}

pub(super) async fn get_calibration(
    State(app): State<AppState>,
    CalibrationId(id): CalibrationId,
) -> Result<Response, ApiError> {
    let record = app
        .calibrations
        .get(id)
        .ok_or_else(|| ApiError::not_found(format!("no calibration {id}")))?;
    Ok(Json(record).into_response())
}
