//! One positive parameter fitted by least squares when the model is a whole computation (a
//! simulated run): golden-section search over its logarithm on a bracket, and the standard
//! error from the residuals' derivative by central differences.

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
