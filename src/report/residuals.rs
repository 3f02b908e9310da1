//! Measured points against the model: the model's value at each measured abscissa (linear
//! interpolation between the result's points), the residual (measured minus model), and a
//! z-score where the measurement gives its spread.

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::simulation::{Curve, PointScore, score_points};

/// A measured table: column name to values, as `GET /api/v1/jobs/{id}/measurements` gives
/// each kind.
pub type Columns = BTreeMap<String, Vec<f64>>;

/// The measurements attached to a run, each kind absent or a table.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
pub struct Measured {
    /// Wear volumes: `time_s` and/or `cycles`, `volume_mm3`, optionally `spread_mm3`.
    #[serde(default)]
    pub wear_volume: Option<Columns>,
    /// A profile across the track: `y_mm`, `depth_um`.
    #[serde(default)]
    pub profile: Option<Columns>,
    /// The open-circuit potential: `time_s` (the record's clock), `potential_v`; `potential`
    /// is the kind's older name.
    #[serde(default, alias = "potential")]
    pub ocp: Option<Columns>,
}

impl Measured {
    /// Whether nothing is attached.
    pub fn is_empty(&self) -> bool {
        self.wear_volume.is_none() && self.profile.is_none() && self.ocp.is_none()
    }
}

/// One measured point beside the model: [`PointScore`], the API's scores' own type.
pub type Residual = PointScore;

/// Each measured point `(at, value, spread)` against `curve` (points in increasing
/// abscissa), scored as the API scores them ([`score_points`]: linear interpolation, none
/// beyond the curve, a z-score where the spread is above zero).
pub fn residuals(curve: &[(f64, f64)], measured: &[(f64, f64, Option<f64>)]) -> Vec<Residual> {
    let curve = Curve {
        x: curve.iter().map(|p| p.0).collect(),
        y: curve.iter().map(|p| p.1).collect(),
    };
    let x: Vec<f64> = measured.iter().map(|m| m.0).collect();
    let values: Vec<f64> = measured.iter().map(|m| m.1).collect();
    let spread: Vec<f64> = measured.iter().map(|m| m.2.unwrap_or(0.0)).collect();
    score_points(&curve, &x, &values, Some(&spread))
}

/// The column `name` of `table`, or an empty one.
pub fn column<'a>(table: &'a Columns, name: &str) -> &'a [f64] {
    table.get(name).map_or(&[], Vec::as_slice)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn residuals_are_measured_minus_model_with_a_z_score_where_a_spread_is_given() {
        let curve = [(0.0, 0.0), (10.0, 1.0)];
        let points = residuals(
            &curve,
            &[
                (5.0, 0.75, Some(0.125)),
                (10.0, 0.5, None),
                (10.0, 0.5, Some(0.0)),
                (11.0, 2.0, Some(1.0)),
            ],
        );
        assert_eq!(points[0].residual, Some(0.25));
        assert_eq!(points[0].z_score, Some(2.0));
        assert_eq!((points[1].residual, points[1].z_score), (Some(-0.5), None));
        assert_eq!(points[2].z_score, None, "a zero spread gives no z-score");
        assert_eq!((points[3].model, points[3].residual), (None, None));
    }
}
