//! The straight line y = a + b x by ordinary least squares, and its covariance
//! s^2 (X^T X)^-1 with s^2 = RSS / (n - 2), in the centred form that keeps round-off small
//! when x sits far from 0 (ln n up to 8, potentials near -0.5 V).

/// The covariance of the intercept and slope of a straight-line fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Covariance {
    /// Variance of the intercept a.
    pub(super) intercept: f64,
    /// Variance of the slope b.
    pub(super) slope: f64,
    /// Covariance of a and b.
    pub(super) cross: f64,
}

/// A fitted line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Line {
    /// a.
    pub(super) intercept: f64,
    /// b.
    pub(super) slope: f64,
    /// Of a and b.
    pub(super) covariance: Covariance,
}

impl Line {
    /// The least-squares line through `(xs, ys)`; at least 3 points with two distinct x
    /// (callers check), so that the scatter s^2 is defined.
    pub(super) fn fit(xs: &[f64], ys: &[f64]) -> Self {
        let n = xs.len() as f64;
        let mean_x = xs.iter().sum::<f64>() / n;
        let mean_y = ys.iter().sum::<f64>() / n;
        let sxx: f64 = xs.iter().map(|x| (x - mean_x).powi(2)).sum();
        let sxy: f64 = xs
            .iter()
            .zip(ys)
            .map(|(x, y)| (x - mean_x) * (y - mean_y))
            .sum();
        let slope = sxy / sxx;
        let intercept = mean_y - slope * mean_x;
        let rss: f64 = xs
            .iter()
            .zip(ys)
            .map(|(x, y)| (y - intercept - slope * x).powi(2))
            .sum();
        Self {
            intercept,
            slope,
            covariance: covariance(xs, rss),
        }
    }

    /// The line at `x`.
    pub(super) fn at(&self, x: f64) -> f64 {
        self.intercept + self.slope * x
    }
}

/// The covariance of a straight-line fit over abscissae `xs` whose residuals sum to `rss`
/// in squares: s^2 (1/n + mean^2 / Sxx), s^2 / Sxx and -mean s^2 / Sxx.
pub(super) fn covariance(xs: &[f64], rss: f64) -> Covariance {
    let n = xs.len() as f64;
    let mean_x = xs.iter().sum::<f64>() / n;
    let sxx: f64 = xs.iter().map(|x| (x - mean_x).powi(2)).sum();
    let scatter = rss / (n - 2.0);
    Covariance {
        intercept: scatter * (1.0 / n + mean_x * mean_x / sxx),
        slope: scatter / sxx,
        cross: -mean_x * scatter / sxx,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_line_comes_back_with_zero_spread() {
        let xs = [0.5, 1.0, 2.5, 4.0];
        let ys: Vec<f64> = xs.iter().map(|x| 3.0 - 0.25 * x).collect();
        let line = Line::fit(&xs, &ys);
        // Exact data: only a few roundings separate the fit from (3, -0.25).
        assert!((line.intercept - 3.0).abs() < 1e-14);
        assert!((line.slope + 0.25).abs() < 1e-14);
        assert!(line.covariance.slope < 1e-28);
    }

    #[test]
    fn covariance_matches_the_textbook_formula() {
        // y = 1, 2, 2 at x = 0, 1, 2: b = 0.5, a = 7/6, residuals -1/6, 1/3, -1/6, RSS = 1/6,
        // s^2 = 1/6, Sxx = 2: var b = 1/12, var a = (1/6)(1/3 + 1/2) = 5/36, cov = -1/12.
        let line = Line::fit(&[0.0, 1.0, 2.0], &[1.0, 2.0, 2.0]);
        assert!((line.slope - 0.5).abs() < 1e-15);
        assert!((line.intercept - 7.0 / 6.0).abs() < 1e-15);
        assert!((line.covariance.slope - 1.0 / 12.0).abs() < 1e-15);
        assert!((line.covariance.intercept - 5.0 / 36.0).abs() < 1e-15);
        assert!((line.covariance.cross + 1.0 / 12.0).abs() < 1e-15);
        assert!((line.at(2.0) - 13.0 / 6.0).abs() < 1e-15);
    }
}
