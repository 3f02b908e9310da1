//! Measured points scored against a run: the model's value at each measured abscissa
//! (linear interpolation between the result's points, none outside their range: a model is
//! not extrapolated), the residual measured − model and, where the lab gave a spread, the
//! z-score residual / spread. Plain functions of a [`SimulationResult`] and the measured
//! columns; the service reads the tables and the result and serves what these return.

use serde::Serialize;

use super::result::SimulationResult;

/// A model's values against an abscissa, in increasing order of the abscissa (equal
/// neighbours allowed: a jump, as the OCP trace's at the start of the rubbing).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// The abscissas, not decreasing.
    pub x: Vec<f64>,
    /// The values.
    pub y: Vec<f64>,
}

impl Curve {
    /// The value at `x`, interpolated linearly; `None` outside the curve's range or for an
    /// empty curve. At a jump (two points at one abscissa) the later point's value.
    pub fn at(&self, x: f64) -> Option<f64> {
        let (first, last) = (*self.x.first()?, *self.x.last()?);
        if !(first..=last).contains(&x) {
            return None;
        }
        // The last point at or before x (at a jump, the later of the two); x is below the
        // next one, so the segment has a length.
        let k = self.x.partition_point(|&v| v <= x) - 1;
        let Some((&x1, &y1)) = self.x.get(k + 1).zip(self.y.get(k + 1)) else {
            return Some(self.y[k]);
        };
        let (x0, y0) = (self.x[k], self.y[k]);
        Some(y0 + (y1 - y0) * (x - x0) / (x1 - x0))
    }
}

/// One measured point against the model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointScore {
    /// The abscissa, in the unit of the score's `x_column`.
    pub x: f64,
    /// The measured value, in the unit of the score's `column`.
    pub measured: f64,
    /// The model's value at `x`; null outside the run's range.
    pub model: Option<f64>,
    /// `measured − model`; null without a model value.
    pub residual: Option<f64>,
    /// `residual / spread`; null without a positive spread or a residual.
    pub z_score: Option<f64>,
}

/// Each measured point (`x`, `measured`, with an optional `spread` per point) against
/// `curve`.
pub fn score_points(
    curve: &Curve,
    x: &[f64],
    measured: &[f64],
    spread: Option<&[f64]>,
) -> Vec<PointScore> {
    x.iter()
        .zip(measured)
        .enumerate()
        .map(|(i, (&x, &measured))| {
            let model = curve.at(x);
            let residual = model.map(|m| measured - m);
            let z_score = residual
                .zip(spread.and_then(|s| s.get(i)).filter(|&&s| s > 0.0))
                .map(|(r, s)| r / s);
            PointScore {
                x,
                measured,
                model,
                residual,
                z_score,
            }
        })
        .collect()
}

/// The root mean square of the residuals there are; `None` when there is none.
pub fn rms_residual(points: &[PointScore]) -> Option<f64> {
    let residuals: Vec<f64> = points.iter().filter_map(|p| p.residual).collect();
    (!residuals.is_empty())
        .then(|| (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len() as f64).sqrt())
}

/// The abscissa of a measured wear volume.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VolumeAbscissa {
    /// Cycles of the ball.
    Cycles,
    /// Time since the rubbing started, s.
    TimeS,
}

/// The volume a profilometer measures (`total_volume_mm3`, wear and corrosion, when the
/// run has corrosion; `wear_volume_mm3` otherwise), from 0 at the start of the rubbing,
/// with that quantity's name.
pub fn volume_curve(result: &SimulationResult, abscissa: VolumeAbscissa) -> (Curve, &'static str) {
    let total =
        result.cycles.iter().all(|c| c.total_volume_mm3.is_some()) && !result.cycles.is_empty();
    let mut curve = Curve {
        x: vec![0.0],
        y: vec![0.0],
    };
    for c in &result.cycles {
        curve.x.push(match abscissa {
            VolumeAbscissa::Cycles => c.cycle as f64,
            VolumeAbscissa::TimeS => c.time_s,
        });
        curve.y.push(
            c.total_volume_mm3
                .filter(|_| total)
                .unwrap_or(c.wear_volume_mm3),
        );
    }
    let name = if total {
        "total_volume_mm3"
    } else {
        "wear_volume_mm3"
    };
    (curve, name)
}

/// The potential on the potentiostat's clock (s since the record started), V: the result's
/// OCP trace, or for a result without one the cycles' potentials, placed after
/// `test.ocp_before_s` as the trace places them.
pub fn potential_curve(result: &SimulationResult) -> Curve {
    if !result.ocp_trace.is_empty() {
        return Curve {
            x: result.ocp_trace.iter().map(|s| s.time_s).collect(),
            y: result.ocp_trace.iter().map(|s| s.potential_v).collect(),
        };
    }
    let start = result.scene.test.ocp_before_s;
    let (x, y) = result
        .cycles
        .iter()
        .filter_map(|c| Some((start + c.time_s, c.potential_v?)))
        .unzip();
    Curve { x, y }
}

/// The groove's depth across the track at the last profile (positive into the disc, um)
/// against y in mm; empty without profiles.
pub fn depth_curve(result: &SimulationResult) -> Curve {
    result.profiles.last().map_or(
        Curve {
            x: Vec::new(),
            y: Vec::new(),
        },
        |p| Curve {
            x: p.y_um.iter().map(|y| y / 1e3).collect(),
            y: p.depth_um.clone(),
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(x: f64, measured: f64, model: f64, spread: Option<f64>) -> PointScore {
        let residual = measured - model;
        PointScore {
            x,
            measured,
            model: Some(model),
            residual: Some(residual),
            z_score: spread.map(|s| residual / s),
        }
    }

    #[test]
    fn a_linear_model_gives_known_residuals_and_z_scores() {
        // y = 2x + 1 on [0, 10], sampled at its ends and one inner point: linear
        // interpolation is exact on a line, so the model values are 2x + 1 to the last bit
        // at these small integers and halves.
        let curve = Curve {
            x: vec![0.0, 4.0, 10.0],
            y: vec![1.0, 9.0, 21.0],
        };
        let x = [1.0, 2.5, 10.0, 11.0];
        let measured = [3.5, 5.0, 20.0, 30.0];
        let spread = [0.5, 0.0, 2.0, 1.0];
        let scores = score_points(&curve, &x, &measured, Some(&spread));
        assert_eq!(scores[0], point(1.0, 3.5, 3.0, Some(0.5)));
        assert_eq!(scores[0].z_score, Some(1.0));
        // A zero spread gives no z-score.
        assert_eq!(scores[1], point(2.5, 5.0, 6.0, None));
        assert_eq!(scores[2], point(10.0, 20.0, 21.0, Some(2.0)));
        assert_eq!(scores[2].z_score, Some(-0.5));
        // Past the run: no model value, so nothing to score.
        assert_eq!(
            scores[3],
            PointScore {
                x: 11.0,
                measured: 30.0,
                model: None,
                residual: None,
                z_score: None
            }
        );
        // rms of 0.5, -1, -1.
        let rms = rms_residual(&scores).expect("three residuals");
        assert!((rms - (2.25_f64 / 3.0).sqrt()).abs() < 1e-15, "{rms}");
        assert_eq!(rms_residual(&scores[3..]), None);
        let without = score_points(&curve, &x[..1], &measured[..1], None);
        assert_eq!(without[0].z_score, None);
    }

    #[test]
    fn a_jump_takes_the_later_value_and_an_empty_curve_none() {
        let curve = Curve {
            x: vec![0.0, 5.0, 5.0, 10.0],
            y: vec![-0.2, -0.2, -0.6, -0.5],
        };
        assert_eq!(curve.at(5.0), Some(-0.6));
        assert_eq!(curve.at(0.0), Some(-0.2));
        assert_eq!(curve.at(7.5), Some(-0.55));
        assert_eq!(curve.at(-1.0), None);
        let empty = Curve {
            x: Vec::new(),
            y: Vec::new(),
        };
        assert_eq!(empty.at(0.0), None);
    }
}
