//! Measured points against the model: the model's value at each measured abscissa (linear
//! interpolation between the result's points), the residual (measured minus model), and a
//! z-score where the measurement gives its spread.

use std::collections::BTreeMap;

use serde::Deserialize;

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
    /// Potentials: `time_s` (the record's clock), `potential_v`.
    #[serde(default)]
    pub potential: Option<Columns>,
}

impl Measured {
    /// Whether nothing is attached.
    pub fn is_empty(&self) -> bool {
        self.wear_volume.is_none() && self.profile.is_none() && self.potential.is_none()
    }
}

/// One measured point beside the model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// Where it was measured, in the model's abscissa.
    pub at: f64,
    /// The measured value.
    pub measured: f64,
    /// The model's value there; `None` outside the model's points.
    pub model: Option<f64>,
    /// `measured - model`.
    pub residual: Option<f64>,
    /// The residual over the measurement's spread (one standard deviation), when it has
    /// a spread above zero.
    pub z: Option<f64>,
}

/// `curve` (points in increasing abscissa) linearly interpolated at `x`; `None` outside it.
pub fn interpolate(curve: &[(f64, f64)], x: f64) -> Option<f64> {
    let first = curve.first()?;
    let last = curve.last()?;
    if !(first.0..=last.0).contains(&x) {
        return None;
    }
    let i = curve.partition_point(|p| p.0 < x);
    if i == 0 {
        return Some(first.1);
    }
    let (a, b) = (curve[i - 1], curve[i.min(curve.len() - 1)]);
    // Two records at one abscissa (sorted, so b.0 >= a.0): the later one.
    if b.0 <= a.0 {
        return Some(b.1);
    }
    Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
}

/// Each measured point `(at, value, spread)` against `curve`.
pub fn residuals(curve: &[(f64, f64)], measured: &[(f64, f64, Option<f64>)]) -> Vec<Residual> {
    measured
        .iter()
        .map(|&(at, value, spread)| {
            let model = interpolate(curve, at);
            let residual = model.map(|m| value - m);
            let z = residual
                .zip(spread.filter(|s| *s > 0.0))
                .map(|(r, s)| r / s);
            Residual {
                at,
                measured: value,
                model,
                residual,
                z,
            }
        })
        .collect()
}

/// The root mean square of the residuals that have one; `None` without any.
pub fn rms(points: &[Residual]) -> Option<f64> {
    let values: Vec<f64> = points.iter().filter_map(|p| p.residual).collect();
    (!values.is_empty())
        .then(|| (values.iter().map(|r| r * r).sum::<f64>() / values.len() as f64).sqrt())
}

/// The column `name` of `table`, or an empty one.
pub fn column<'a>(table: &'a Columns, name: &str) -> &'a [f64] {
    table.get(name).map_or(&[], Vec::as_slice)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_is_interpolated_between_its_points_and_not_beyond() {
        let curve = [(0.0, 0.0), (10.0, 1.0), (20.0, 3.0)];
        assert_eq!(interpolate(&curve, 5.0), Some(0.5));
        assert_eq!(interpolate(&curve, 15.0), Some(2.0));
        assert_eq!(interpolate(&curve, 20.0), Some(3.0));
        assert_eq!(interpolate(&curve, 0.0), Some(0.0));
        assert_eq!(interpolate(&curve, 20.5), None);
        assert_eq!(interpolate(&curve, -1.0), None);
        assert_eq!(interpolate(&[], 1.0), None);
    }

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
        assert_eq!(points[0].z, Some(2.0));
        assert_eq!((points[1].residual, points[1].z), (Some(-0.5), None));
        assert_eq!(points[2].z, None, "a zero spread gives no z-score");
        assert_eq!((points[3].model, points[3].residual), (None, None));
        // The three residuals that have a model value.
        let expected = ((0.0625 + 0.25 + 0.25) / 3.0_f64).sqrt();
        assert_eq!(rms(&points), Some(expected));
        assert_eq!(rms(&points[3..]), None);
    }
}
