//! What a result reports of a surface: rms height, rms slope, and the slope of the power
//! spectrum with the Hurst exponent it implies (Jacobs, Junge & Pastewka, "Quantitative
//! characterization of surface topography using spectral methods", Surf. Topogr.: Metrol.
//! Prop. 5 (2017) 013001: a self-affine surface has C(q) proportional to q^(-2(1+H))).

use rustfft::num_complex::Complex;
use serde::{Deserialize, Serialize};

use super::HeightMap;
use super::spectrum::{fft_2d, wavevector_norms};

/// Logarithmic bins per decade of q in [`psd_slope`]'s radial average.
const BINS_PER_DECADE: f64 = 10.0;

/// A surface's statistics, in the units of their names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Statistics {
    /// Pixels along x and y.
    pub pixels: [usize; 2],
    /// Pixel size along x and y, um.
    pub pixel_um: [f64; 2],
    /// Root mean square height about the mean, um.
    pub rms_height_um: f64,
    /// Root mean square gradient by forward differences (dimensionless).
    pub rms_slope: f64,
    /// Slope of log C(q) against log q between the wavelengths it was fitted over.
    pub psd_slope: f64,
    /// The Hurst exponent that slope implies, `-slope / 2 - 1`.
    pub hurst: f64,
    /// The longest and shortest wavelength of the fit, um.
    pub fit_wavelengths_um: [f64; 2],
}

impl Statistics {
    /// The statistics of `map`, its spectrum fitted between the wavelengths `long_m` and
    /// `short_m`.
    pub fn of(map: &HeightMap, long_m: f64, short_m: f64) -> Self {
        let slope = psd_slope(map, long_m, short_m);
        Self {
            pixels: [map.nx, map.ny],
            pixel_um: [map.dx_m * 1e6, map.dy_m * 1e6],
            rms_height_um: rms_height(map) * 1e6,
            rms_slope: rms_slope(map),
            psd_slope: slope,
            hurst: -slope / 2.0 - 1.0,
            fit_wavelengths_um: [long_m * 1e6, short_m * 1e6],
        }
    }

    /// The statistics of a measured map, fitted over [`measured_fit_range`].
    pub fn of_measured(map: &HeightMap) -> Self {
        let (long, short) = measured_fit_range(map);
        Self::of(map, long, short)
    }
}

/// The `(long, short)` wavelengths, m, a measured map's spectrum is fitted over: half its
/// shorter side down to four pixels, where the Hann window and the pixel's own smoothing
/// bend the spectrum least.
pub fn measured_fit_range(map: &HeightMap) -> (f64, f64) {
    let side = map.width_m().min(map.height_side_m());
    (side / 2.0, 4.0 * map.dx_m.max(map.dy_m))
}

/// Root mean square height about the mean, m.
pub fn rms_height(map: &HeightMap) -> f64 {
    let n = map.heights_m.len() as f64;
    let mean = map.heights_m.iter().sum::<f64>() / n;
    (map.heights_m
        .iter()
        .map(|h| (h - mean).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// Root mean square gradient, `sqrt(<(dh/dx)^2 + (dh/dy)^2>)`, by forward differences:
/// across the edges of a periodic map, within the map otherwise. The same differences are
/// what the contact grid's cells see, so an `rms_slope` request is met on them.
pub fn rms_slope(map: &HeightMap) -> f64 {
    let (nx, ny, h) = (map.nx, map.ny, &map.heights_m);
    let mean_square = |along_x: bool| {
        let (count_x, count_y) = match (along_x, map.periodic) {
            (_, true) => (nx, ny),
            (true, false) => (nx - 1, ny),
            (false, false) => (nx, ny - 1),
        };
        let (step, d) = if along_x {
            (1, map.dx_m)
        } else {
            (0, map.dy_m)
        };
        let mut sum = 0.0;
        for iy in 0..count_y {
            for ix in 0..count_x {
                let (jx, jy) = ((ix + step) % nx, (iy + 1 - step) % ny);
                sum += ((h[jy * nx + jx] - h[iy * nx + ix]) / d).powi(2);
            }
        }
        sum / (count_x * count_y) as f64
    };
    (mean_square(true) + mean_square(false)).sqrt()
}

/// The least-squares slope of log C(q) against log q, C the radially averaged power
/// spectrum in logarithmic bins, over the wavelengths from `long_m` down to `short_m`. A
/// map that is not periodic is windowed (Hann) first, or the step between its opposite
/// edges would add a q^-2 tail (Jacobs et al. 2017, Section 3).
pub fn psd_slope(map: &HeightMap, long_m: f64, short_m: f64) -> f64 {
    let (nx, ny) = (map.nx, map.ny);
    let mean = map.heights_m.iter().sum::<f64>() / (nx * ny) as f64;
    let hann = |i: usize, n: usize| {
        if map.periodic {
            1.0
        } else {
            (std::f64::consts::PI * (i as f64 + 0.5) / n as f64)
                .sin()
                .powi(2)
        }
    };
    let mut field: Vec<Complex<f64>> = map
        .heights_m
        .iter()
        .enumerate()
        .map(|(i, &h)| Complex::new((h - mean) * hann(i % nx, nx) * hann(i / nx, ny), 0.0))
        .collect();
    fft_2d(&mut field, nx, ny, false);
    let q = wavevector_norms(nx, ny, map.width_m(), map.height_side_m());
    let tau = std::f64::consts::TAU;
    let (q_low, q_high) = (tau / long_m, tau / short_m);
    let bins = ((q_high / q_low).log10() * BINS_PER_DECADE).ceil().max(1.0) as usize;
    let mut sums = vec![(0.0, 0.0, 0usize); bins];
    for (c, &qi) in field.iter().zip(&q) {
        if qi < q_low || qi > q_high {
            continue;
        }
        let bin = (((qi / q_low).log10() * BINS_PER_DECADE) as usize).min(bins - 1);
        let entry = &mut sums[bin];
        entry.0 += qi.ln();
        entry.1 += c.norm_sqr();
        entry.2 += 1;
    }
    let points: Vec<(f64, f64)> = sums
        .iter()
        .filter(|s| s.2 > 0 && s.1 > 0.0)
        .map(|&(log_q, power, count)| (log_q / count as f64, (power / count as f64).ln()))
        .collect();
    fit_slope(&points)
}

/// The least-squares slope of `(x, y)` points (NaN for fewer than two distinct x).
fn fit_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_has_the_rms_and_slope_of_its_formulas() {
        // h = A sin(2 pi x / L) over whole periods: rms A / sqrt 2; forward differences of
        // step d give the slope rms A (2 / d) sin(pi d / L) / sqrt 2 exactly.
        let (n, d, a) = (64, 1e-6, 1e-7);
        let l = 16.0 * d;
        let heights = (0..n * n)
            .map(|i| a * (std::f64::consts::TAU * ((i % n) as f64 + 0.5) * d / l).sin())
            .collect();
        let mut map = HeightMap::new(n, n, d, d, heights).expect("valid");
        map.periodic = true;
        assert!((rms_height(&map) / (a / 2f64.sqrt()) - 1.0).abs() < 1e-12);
        let want = a * 2.0 / d * (std::f64::consts::PI * d / l).sin() / 2f64.sqrt();
        assert!((rms_slope(&map) / want - 1.0).abs() < 1e-12);
    }
}
