//! A job's measurements scored against its result ([`crate::simulation::score_points`]):
//! per kind, the columns compared, each point's model value, residual and z-score, and the
//! rms residual; as JSON (`GET .../scores`) and as one long CSV (`GET .../scores.csv`).

use serde::Serialize;

use super::table::{Columns, MeasurementKind, Measurements};
use crate::simulation::{
    Curve, PointScore, SimulationResult, VolumeAbscissa, depth_curve, potential_curve,
    rms_residual, score_points, volume_curve,
};

/// One kind's table against the model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KindScore {
    /// The measured abscissa's column (its unit is the points' `x` unit).
    pub x_column: &'static str,
    /// The measured column (its unit is the points' `measured`, `model` and `residual`
    /// unit).
    pub column: &'static str,
    /// The result's quantity the points are compared with.
    pub model_column: &'static str,
    /// The column of spreads the z-scores divide by; null without one.
    pub spread_column: Option<&'static str>,
    /// The root mean square of the residuals; null when no point lies within the run.
    pub rms_residual: Option<f64>,
    /// Each measured point, in the table's order.
    pub points: Vec<PointScore>,
}

/// Every kind's score, null where no table is attached.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Scores {
    /// The wear volume against the volume a profilometer sees.
    pub wear_volume: Option<KindScore>,
    /// The groove's depth against the last profile.
    pub profile: Option<KindScore>,
    /// The open-circuit potential against the result's OCP trace.
    pub ocp: Option<KindScore>,
}

/// The measurements of a job scored against its `result`.
pub fn scores(result: &SimulationResult, measurements: &Measurements) -> Scores {
    Scores {
        wear_volume: measurements.wear_volume.as_ref().map(|t| wear(result, t)),
        profile: measurements.profile.as_ref().map(|t| {
            kind(
                &depth_curve(result),
                t,
                ("y_mm", "depth_um", None),
                "depth_um",
            )
        }),
        ocp: measurements.ocp.as_ref().map(|t| {
            let columns = ("time_s", "potential_v", None);
            kind(
                &potential_curve(result),
                t,
                columns,
                "ocp_trace.potential_v",
            )
        }),
    }
}

/// A wear volume table: at its cycles when it has them, else at its times.
fn wear(result: &SimulationResult, table: &Columns) -> KindScore {
    let (abscissa, x_column) = if table.contains_key("cycles") {
        (VolumeAbscissa::Cycles, "cycles")
    } else {
        (VolumeAbscissa::TimeS, "time_s")
    };
    let (curve, model) = volume_curve(result, abscissa);
    let columns = (x_column, "volume_mm3", Some("spread_mm3"));
    kind(&curve, table, columns, model)
}

/// `table`'s columns `(x, measured, spread)` against `curve`, called `model_column`.
fn kind(
    curve: &Curve,
    table: &Columns,
    (x_column, column, spread): (&'static str, &'static str, Option<&'static str>),
    model_column: &'static str,
) -> KindScore {
    let values = |name: &str| table.get(name).map_or(&[][..], Vec::as_slice);
    let spread_column = spread.filter(|name| table.contains_key(*name));
    let points = score_points(
        curve,
        values(x_column),
        values(column),
        spread_column.map(values),
    );
    KindScore {
        x_column,
        column,
        model_column,
        spread_column,
        rms_residual: rms_residual(&points),
        points,
    }
}

/// The CSV header: one row per measured point of every kind.
const HEADER: [&str; 9] = [
    "kind",
    "x_column",
    "x",
    "column",
    "measured",
    "model",
    "residual",
    "z_score",
    "model_column",
];

/// Every kind's points as one CSV, each cell through [`crate::csv::line`]; an empty cell
/// where the JSON has null.
pub fn scores_csv(scores: &Scores) -> String {
    let mut csv = crate::csv::line(&HEADER, "\r\n");
    let kinds = [
        (MeasurementKind::WearVolume, &scores.wear_volume),
        (MeasurementKind::Profile, &scores.profile),
        (MeasurementKind::Ocp, &scores.ocp),
    ];
    let optional = |value: Option<f64>| value.map(|v| v.to_string()).unwrap_or_default();
    for (kind, score) in kinds {
        let Some(score) = score else { continue };
        for p in &score.points {
            let cells = [
                kind.name().to_owned(),
                score.x_column.to_owned(),
                p.x.to_string(),
                score.column.to_owned(),
                p.measured.to_string(),
                optional(p.model),
                optional(p.residual),
                optional(p.z_score),
                score.model_column.to_owned(),
            ];
            csv.push_str(&crate::csv::line(&cells, "\r\n"));
        }
    }
    csv
}
