//! Positive parameters fitted by least squares when the model is a whole computation (a
//! simulated run), over their logarithms: one by golden-section search on a bracket, two by
//! Gauss-Newton inside a box; standard errors from the residuals' derivatives by central
//! differences.

use serde::Serialize;

use super::CalibrationError;

/// One value tried by a search, and the residual sum of squares it gave.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Trial {
    /// The parameter.
    pub value: f64,
    /// The residual sum of squares at it.
    pub rss: f64,
}

/// 1 / golden ratio: each step keeps this fraction of the bracket.
const INVERSE_PHI: f64 = 0.618_033_988_749_894_8;

/// Minimises `rss(p)` over `p` in `[low, high]` by golden section on ln p, until the
/// bracket is narrower than `tolerance` in ln p (a relative tolerance on p). Refused as not
/// converged when the minimum sits at an edge of the bracket: the bracket did not hold it.
pub(super) fn golden_section(
    parameter: &'static str,
    (low, high): (f64, f64),
    tolerance: f64,
    rss: &mut dyn FnMut(f64) -> Result<f64, CalibrationError>,
) -> Result<(f64, Vec<Trial>), CalibrationError> {
    let mut tried = Vec::new();
    let mut evaluate = |theta: f64| -> Result<f64, CalibrationError> {
        let value = theta.exp();
        let r = rss(value)?;
        tried.push(Trial { value, rss: r });
        Ok(r)
    };
    let (mut a, mut b) = (low.ln(), high.ln());
    let mut c = b - INVERSE_PHI * (b - a);
    let mut d = a + INVERSE_PHI * (b - a);
    let (mut fc, mut fd) = (evaluate(c)?, evaluate(d)?);
    while b - a > tolerance {
        if fc < fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - INVERSE_PHI * (b - a);
            fc = evaluate(c)?;
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + INVERSE_PHI * (b - a);
            fd = evaluate(d)?;
        }
    }
    let best = if fc < fd { c } else { d };
    // Within two final brackets of an edge: the search only ever moved towards it.
    let (edge_low, edge_high) = (low.ln() + 2.0 * tolerance, high.ln() - 2.0 * tolerance);
    if best < edge_low || best > edge_high {
        return Err(CalibrationError::NotConverged {
            parameter,
            low,
            high,
            tried,
        });
    }
    Ok((best.exp(), tried))
}

/// Standard error of a fitted positive `value` from its `residuals` there and the residuals
/// at `value * exp(+-step)`: s^2 / (J^T J) in ln p, with J by central differences and
/// s^2 = RSS / (points - 1), scaled back to p.
pub(super) fn standard_error(
    value: f64,
    residuals: &[f64],
    step: f64,
    residuals_at: &mut dyn FnMut(f64) -> Result<Vec<f64>, CalibrationError>,
) -> Result<f64, CalibrationError> {
    let up = residuals_at(value * step.exp())?;
    let down = residuals_at(value * (-step).exp())?;
    let jtj: f64 = up
        .iter()
        .zip(&down)
        .map(|(u, d)| ((u - d) / (2.0 * step)).powi(2))
        .sum();
    let scatter = residuals.iter().map(|r| r * r).sum::<f64>() / (residuals.len() as f64 - 1.0);
    Ok(value * (scatter / jtj).sqrt())
}

/// Relative step of the forward differences of [`gauss_newton`]'s Jacobian: 1% of k moves
/// a simulated volume by far more than the cycle stepping's 1e-4 noise, and the volume is
/// nearly linear in k across it.
pub(super) const JACOBIAN_STEP: f64 = 0.01;

/// Gauss-Newton iterations before giving up: a nearly linear model takes two or three.
const MAX_ITERATIONS: usize = 40;

/// Two positive parameters fitted by [`gauss_newton`].
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PairFit {
    /// The parameters.
    pub values: [f64; 2],
    /// The residuals there.
    pub residuals: Vec<f64>,
    /// Their sum of squares.
    pub rss: f64,
}

/// Minimises the sum of squares of `residuals_at(p)` over two positive parameters from
/// `start`, by Gauss-Newton on p itself with forward differences ([`JACOBIAN_STEP`] of each
/// p) and step halving, inside `bounds`; stops once a step changes neither parameter by more
/// than `tolerance` of itself. On p rather than ln p because a simulated wear volume is
/// nearly linear in k: Gauss-Newton then lands in a step or two, while on ln k the
/// exponential bent the residuals and a two-regime search on a six-point table took about
/// 40 runs per candidate cycle (1043 runs for 24 candidates). Refused as not converged when
/// a parameter ends at an edge of its bounds, or after [`MAX_ITERATIONS`]; `tried` then holds
/// each value of that parameter the fit tried, with its residual sum of squares.
pub(super) fn gauss_newton(
    names: [&'static str; 2],
    start: [f64; 2],
    bounds: [(f64, f64); 2],
    tolerance: f64,
    residuals_at: &mut dyn FnMut([f64; 2]) -> Result<Vec<f64>, CalibrationError>,
) -> Result<PairFit, CalibrationError> {
    let clamp = |p: [f64; 2]| [0, 1].map(|j| p[j].clamp(bounds[j].0, bounds[j].1));
    let mut tried: Vec<([f64; 2], f64)> = Vec::new();
    let mut evaluate = |p: [f64; 2]| -> Result<(Vec<f64>, f64), CalibrationError> {
        let r = residuals_at(p)?;
        let rss = sum_of_squares(&r);
        tried.push((p, rss));
        Ok((r, rss))
    };
    let mut p = clamp(start);
    let (mut r, mut rss) = evaluate(p)?;
    let mut converged = false;
    for _ in 0..MAX_ITERATIONS {
        let mut columns = [Vec::new(), Vec::new()];
        for (j, column) in columns.iter_mut().enumerate() {
            let mut moved = p;
            let h = JACOBIAN_STEP * p[j];
            moved[j] += h;
            let (shifted, _) = evaluate(moved)?;
            *column = shifted.iter().zip(&r).map(|(a, b)| (a - b) / h).collect();
        }
        let Some(step) = normal_step(&columns, &r) else {
            break;
        };
        let relative = |scale: f64| {
            (scale * step[0] / p[0])
                .abs()
                .max((scale * step[1] / p[1]).abs())
        };
        if relative(1.0) < tolerance {
            converged = true;
            break;
        }
        let mut scale = 1.0;
        let mut accepted = false;
        while relative(scale) >= tolerance {
            let candidate = clamp([p[0] + scale * step[0], p[1] + scale * step[1]]);
            let (r_new, rss_new) = evaluate(candidate)?;
            if rss_new <= rss {
                (p, r, rss, accepted) = (candidate, r_new, rss_new, true);
                break;
            }
            scale /= 2.0;
        }
        if !accepted {
            // No step longer than the tolerance lowers the sum: the minimum is here.
            converged = true;
            break;
        }
    }
    let edge = (0..2).find(|&j| {
        p[j] < bounds[j].0 * (1.0 + 2.0 * tolerance) || p[j] > bounds[j].1 * (1.0 - 2.0 * tolerance)
    });
    if let Some(j) = edge.or((!converged).then_some(0)) {
        return Err(CalibrationError::NotConverged {
            parameter: names[j],
            low: bounds[j].0,
            high: bounds[j].1,
            tried: tried
                .iter()
                .map(|(values, rss)| Trial {
                    value: values[j],
                    rss: *rss,
                })
                .collect(),
        });
    }
    Ok(PairFit {
        values: p,
        residuals: r,
        rss,
    })
}

/// The Gauss-Newton step -(J^T J)^-1 J^T r for the Jacobian's two `columns`; `None` when
/// J^T J is singular (a parameter the residuals do not depend on).
fn normal_step(columns: &[Vec<f64>; 2], r: &[f64]) -> Option<[f64; 2]> {
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let (a, b, d) = (
        dot(&columns[0], &columns[0]),
        dot(&columns[0], &columns[1]),
        dot(&columns[1], &columns[1]),
    );
    let (g0, g1) = (dot(&columns[0], r), dot(&columns[1], r));
    let det = a * d - b * b;
    // Below round-off of the products the matrix has no inverse worth using.
    if det.is_nan() || det <= 1e-12 * a * d {
        return None;
    }
    Some([-(d * g0 - b * g1) / det, -(a * g1 - b * g0) / det])
}

/// Standard errors of two fitted positive `values`, from their `residuals` and the residuals
/// at `values` moved by `exp(+-step)` one at a time: s^2 (J^T J)^-1 in ln p, with J by central
/// differences and s^2 = RSS / `freedom`, scaled back to p.
pub(super) fn standard_errors(
    values: [f64; 2],
    residuals: &[f64],
    step: f64,
    freedom: usize,
    residuals_at: &mut dyn FnMut([f64; 2]) -> Result<Vec<f64>, CalibrationError>,
) -> Result<[f64; 2], CalibrationError> {
    let mut columns = [Vec::new(), Vec::new()];
    for (j, column) in columns.iter_mut().enumerate() {
        let (mut up, mut down) = (values, values);
        up[j] *= step.exp();
        down[j] *= (-step).exp();
        let (u, d) = (residuals_at(up)?, residuals_at(down)?);
        *column = u
            .iter()
            .zip(&d)
            .map(|(a, b)| (a - b) / (2.0 * step))
            .collect();
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let (a, b, d) = (
        dot(&columns[0], &columns[0]),
        dot(&columns[0], &columns[1]),
        dot(&columns[1], &columns[1]),
    );
    let det = a * d - b * b;
    let scatter = sum_of_squares(residuals) / freedom as f64;
    Ok([
        values[0] * (scatter * d / det).sqrt(),
        values[1] * (scatter * a / det).sqrt(),
    ])
}

/// The sum of the squares of `values`.
pub(super) fn sum_of_squares(values: &[f64]) -> f64 {
    values.iter().map(|v| v * v).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residuals of y = p x against data made with p = 2.5 and fixed offsets.
    fn residuals(p: f64) -> Vec<f64> {
        let xs = [1.0, 2.0, 3.0, 4.0];
        let offsets = [0.1, -0.2, 0.15, -0.05];
        xs.iter()
            .zip(offsets)
            .map(|(x, o)| 2.5 * x + o - p * x)
            .collect()
    }

    #[test]
    fn recovers_a_linear_least_squares_slope_and_its_error() {
        let mut rss = |p: f64| Ok(residuals(p).iter().map(|r| r * r).sum());
        let (p, tried) = golden_section("p", (0.1, 100.0), 1e-9, &mut rss).expect("minimum inside");
        // Closed form: p = sum(x y) / sum(x^2) = 2.5 + (0.1 - 0.4 + 0.45 - 0.2) / 30
        // = 2.5 - 0.05 / 30. Golden section stops within 1e-9 in ln p of it.
        let exact = 2.5 - 0.05 / 30.0;
        assert!(((p - exact) / exact).abs() < 1e-8, "{p}");
        assert!(tried.len() > 10);
        let r = residuals(p);
        let se = standard_error(p, &r, 1e-3, &mut |q| Ok(residuals(q))).expect("finite");
        // Linear model: se = sqrt(RSS / 3 / sum(x^2)); central differences of a linear map
        // are exact up to round-off and the 1e-8 offset of p.
        let rss_min: f64 = r.iter().map(|v| v * v).sum();
        let want = (rss_min / 3.0 / 30.0).sqrt();
        assert!(((se - want) / want).abs() < 1e-6, "{se} vs {want}");
    }

    /// Residuals of y = a x + b x^2 against data made with a = 2, b = 0.5 and fixed offsets.
    fn pair_residuals(p: [f64; 2]) -> Vec<f64> {
        let xs = [1.0, 2.0, 3.0, 4.0, 5.0];
        let offsets = [0.1, -0.2, 0.15, -0.05, 0.02];
        xs.iter()
            .zip(offsets)
            .map(|(x, o)| 2.0 * x + 0.5 * x * x + o - p[0] * x - p[1] * x * x)
            .collect()
    }

    #[test]
    fn gauss_newton_recovers_a_linear_least_squares_pair_and_its_errors() {
        let bounds = [(0.01, 100.0), (0.01, 100.0)];
        let fit = gauss_newton(["a", "b"], [1.0, 1.0], bounds, 1e-10, &mut |p| {
            Ok(pair_residuals(p))
        })
        .expect("converges");
        // Closed form by the normal equations of the design [x, x^2] (x = 1..5: sums 55,
        // 225, 979) against the offsets o: [55 225; 225 979] d = [x.o, x^2.o].
        let (xo, x2o) = (0.1 - 0.4 + 0.45 - 0.2 + 0.1, 0.1 - 0.8 + 1.35 - 0.8 + 0.5);
        let det = 55.0 * 979.0 - 225.0 * 225.0;
        let exact = [
            2.0 + (979.0 * xo - 225.0 * x2o) / det,
            0.5 + (55.0 * x2o - 225.0 * xo) / det,
        ];
        // The model is linear in p, so forward differences are exact up to round-off and
        // the first Gauss-Newton step lands on the minimum; the next is round-off.
        for (got, want) in fit.values.iter().zip(exact) {
            assert!(((got - want) / want).abs() < 1e-9, "{:?}", fit.values);
        }
        let se = standard_errors(fit.values, &fit.residuals, 1e-3, 3, &mut |p| {
            Ok(pair_residuals(p))
        })
        .expect("finite");
        // s^2 = RSS / 3 times the diagonal of the inverse normal matrix; central differences
        // of a linear map are exact up to round-off.
        let s2 = fit.rss / 3.0;
        let want = [(s2 * 979.0 / det).sqrt(), (s2 * 55.0 / det).sqrt()];
        for j in 0..2 {
            assert!(
                ((se[j] - want[j]) / want[j]).abs() < 1e-6,
                "{se:?} vs {want:?}"
            );
        }
    }

    #[test]
    fn a_pair_minimum_outside_the_box_is_not_converged() {
        let bounds = [(0.01, 100.0), (0.01, 0.1)];
        let err = gauss_newton(["a", "b"], [1.0, 0.05], bounds, 1e-6, &mut |p| {
            Ok(pair_residuals(p))
        })
        .expect_err("b = 0.5 lies outside");
        assert!(
            matches!(err, CalibrationError::NotConverged { parameter: "b", .. }),
            "{err}"
        );
    }

    #[test]
    fn a_minimum_outside_the_bracket_is_not_converged() {
        let mut rss = |p: f64| Ok(residuals(p).iter().map(|r| r * r).sum());
        let err = golden_section("p", (10.0, 100.0), 1e-6, &mut rss).expect_err("outside");
        match err {
            CalibrationError::NotConverged { tried, .. } => assert!(!tried.is_empty()),
            other => panic!("expected NotConverged, got {other}"),
        }
    }
}
