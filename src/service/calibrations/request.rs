//! The body of `POST /api/v1/calibrations` and its checks: which fit, the table (CSV text or
//! a JSON table), the scene fitted with and the command line's options, each refused with
//! its field named (422) before anything runs.

use serde::Deserialize;
use serde_json::Value;

use crate::calibration::{
    ChangeCycle, ChangeCycleError, CommandOptions, FitKind, Table, default_scene,
};
use crate::scene::{FieldError, Scene};
use crate::service::error::ApiError;
use crate::simulation::{Plan, parse_scene};

/// The most rows a table may have, counted before it is parsed: a Tafel scan at 1 mV steps
/// has about a thousand and an OCP log at 1 Hz over an hour 3600; a fit's result holds a
/// residual per row (about 150 bytes), so this bounds one result near 3 MB.
pub(super) const MAX_TABLE_ROWS: usize = 20_000;

/// The request body.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CalibrationRequest {
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
    /// Tafel: E_corr, V, against the scene's reference electrode.
    e_corr_v: Option<f64>,
    /// Tafel: the domain's least cathodic end, E - E_corr, V.
    tafel_overpotential_max_v: Option<f64>,
    /// Tafel: the domain's most cathodic end, E - E_corr, V.
    tafel_overpotential_min_v: Option<f64>,
    /// OCP: when the rubbing started, s on the table's clock.
    rubbing_start_s: Option<f64>,
    /// OCP: when the rubbing stopped, s on the table's clock.
    rubbing_stop_s: Option<f64>,
    /// Archard: also fit a change of regime at this cycle, or `"auto"` for the best one.
    regime_change: Option<Value>,
}

/// What a fit runs on, checked.
pub(super) struct Inputs {
    pub(super) kind: FitKind,
    pub(super) table: Table,
    pub(super) scene: Scene,
    pub(super) options: CommandOptions,
}

/// 422 for a calibration request refused at `path`.
pub(super) fn invalid(path: &str, message: String) -> ApiError {
    ApiError::unprocessable(
        format!("invalid calibration: {message}"),
        vec![FieldError::new(path, message)],
    )
}

impl CalibrationRequest {
    /// The request of a JSON document, or the 422 naming what does not fit its shape.
    pub(super) fn from_document(document: Value) -> Result<Self, ApiError> {
        serde_json::from_value(document).map_err(|e| invalid("", e.to_string()))
    }

    /// The checked inputs of the fit, or the 422 that refuses them.
    pub(super) fn inputs(self) -> Result<Inputs, ApiError> {
        let kind = self.kind;
        let options = self.options;
        options.refuse_misplaced(kind)?;
        let regime_change = options
            .regime_change
            .as_ref()
            .map(change_cycle)
            .transpose()?;
        let text = match &self.table {
            Value::String(text) => text.clone(),
            table @ (Value::Array(_) | Value::Object(_)) => table.to_string(),
            other => {
                return Err(invalid(
                    "table",
                    format!("must be CSV text or a JSON table (rows or columns), got {other}"),
                ));
            }
        };
        let rows = declared_rows(&self.table);
        if rows > MAX_TABLE_ROWS {
            return Err(invalid(
                "table",
                format!("the table has {rows} rows; a fit takes at most {MAX_TABLE_ROWS}"),
            ));
        }
        let table = Table::parse(&text).map_err(|e| invalid("table", e.to_string()))?;
        let scene = match &self.scene {
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
            tafel_overpotential_max_v: options.tafel_overpotential_max_v,
            tafel_overpotential_min_v: options.tafel_overpotential_min_v,
            scene_given: self.scene.is_some(),
            rubbing_start_s: options.rubbing_start_s,
            rubbing_stop_s: options.rubbing_stop_s,
            regime_change,
        };
        Ok(Inputs {
            kind,
            table,
            scene,
            options,
        })
    }
}

/// The rows a table declares, counted without reading a cell: a CSV text's data lines (not
/// blank, not `#` comments, after the header), a JSON array's rows, a JSON object's longest
/// column.
fn declared_rows(table: &Value) -> usize {
    match table {
        Value::String(text) => text
            .lines()
            .map(str::trim)
            .filter(|line| !line.is_empty() && !line.starts_with('#'))
            .count()
            .saturating_sub(1),
        Value::Array(rows) => rows.len(),
        Value::Object(columns) => columns
            .values()
            .map(|column| column.as_array().map_or(0, Vec::len))
            .max()
            .unwrap_or(0),
        _ => 0,
    }
}

impl RequestOptions {
    /// Refuses an option given to a fit it does not apply to, naming it.
    fn refuse_misplaced(&self, kind: FitKind) -> Result<(), ApiError> {
        let given = [
            (
                "include_bulk",
                self.include_bulk.is_some(),
                FitKind::Hardness,
            ),
            ("e_corr_v", self.e_corr_v.is_some(), FitKind::Tafel),
            (
                "tafel_overpotential_max_v",
                self.tafel_overpotential_max_v.is_some(),
                FitKind::Tafel,
            ),
            (
                "tafel_overpotential_min_v",
                self.tafel_overpotential_min_v.is_some(),
                FitKind::Tafel,
            ),
            (
                "rubbing_start_s",
                self.rubbing_start_s.is_some(),
                FitKind::Ocp,
            ),
            (
                "rubbing_stop_s",
                self.rubbing_stop_s.is_some(),
                FitKind::Ocp,
            ),
            (
                "regime_change",
                self.regime_change.is_some(),
                FitKind::Archard,
            ),
        ];
        match given.iter().find(|&&(_, set, fit)| set && fit != kind) {
            Some(&(name, _, fit)) => {
                let fit = serde_json::to_value(fit).unwrap_or_default();
                Err(invalid(
                    &format!("options.{name}"),
                    format!(
                        "applies to the {} fit only",
                        fit.as_str().unwrap_or("other")
                    ),
                ))
            }
            None => Ok(()),
        }
    }
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
