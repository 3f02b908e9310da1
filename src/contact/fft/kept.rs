//! An apply in two halves, for the solver's step under the cap ([`Operator::keep`]): the
//! forward transform of the search direction `t` is kept, its `t . K t` read off the
//! spectrum, and once the step has moved cells onto or off a bound and restored the load,
//! `K (w - tau t)` (`w` those moves) comes from the transform of `w` and the kept one,
//! with one inverse transform. An apply of `t` and a second one of the new pressure took
//! two forward and two inverse transforms; these take two forward and one inverse. Split
//! across threads, the passes do the same to each column and sum the columns' powers in
//! the same order, so the answer does not depend on the threads to the bit.
//!
//! `t . K t` by Parseval: `K t` is the inverse transform of the product of the spectra, so
//! `sum_x t K t = sum_k Re K^(k) |T(k)|^2` over the padded grid's spectrum (`K^` holds the
//! `1 / (4 nx ny)` of the inverse). The odd part of a kernel (the coupling) adds nothing:
//! its quadratic form vanishes. The columns hold the `nx + 1` bins of the real-to-complex
//! row transforms; every other bin mirrors one of them, so the columns between the first
//! and the last count twice.
//!
//! [`Operator::keep`]: crate::contact::Operator::keep

use rustfft::num_complex::Complex;

use super::{DcFft, Spectrum, multiply};
use crate::contact::transform::{Real, Threads, Transforms, each_value};

impl<T: Real> DcFft<T> {
    /// Transforms `input` and keeps its spectrum; returns `input . K input`.
    pub(super) fn keep(&mut self, input: &[f64]) -> Option<f64> {
        let (nx, ny, col_len, stride) = (self.nx, self.ny, self.col_len, self.stride);
        assert_eq!(input.len(), nx * ny, "input does not match the grid");
        if self.kept.weights.is_empty() {
            self.kept = Kept::of(&self.spectrum, (self.half, stride, col_len));
        }
        let mut quadratic = 0.0;
        match &mut self.passes {
            Threads::Split(split, columns) => {
                let weights = self.kept.weights.chunks_exact(stride);
                let shape = (nx, ny, col_len, stride);
                split.passes(shape, &|_, _| {}, columns, Some(input), None);
                // Column by column in order, as on one thread: the same sum to the bit.
                for (column, weights) in columns.chunks_exact(stride).zip(weights) {
                    quadratic += weighted_power(&column[..col_len], &weights[..col_len]);
                }
                std::mem::swap(columns, &mut self.kept.spectrum);
            }
            Threads::One(passes) => {
                passes.forward_rows(&mut self.plans, input);
                let forward = Transforms {
                    forward: true,
                    inverse: false,
                };
                let (spectrum, weights) = (&mut self.kept.spectrum, &self.kept.weights);
                passes.columns(&mut self.plans, forward, Some(spectrum), |k, column| {
                    // Summed while the column is in the cache, in the order of the columns.
                    quadratic += weighted_power(column, &weights[k * stride..][..col_len]);
                });
            }
        }
        Some(quadratic)
    }

    /// Adds `K (extra + scale t)` to `output`, `t` the input of the last [`Self::keep`]
    /// (`extra` zero when `None`).
    pub(super) fn add_kept(&mut self, extra: Option<&[f64]>, scale: f64, output: &mut [f64]) {
        let (nx, ny, col_len, stride) = (self.nx, self.ny, self.col_len, self.stride);
        assert_eq!(output.len(), nx * ny, "output does not match the grid");
        assert!(!self.kept.weights.is_empty(), "nothing kept");
        if let Some(extra) = extra {
            assert_eq!(extra.len(), output.len(), "input does not match the grid");
        }
        let (spectrum, kept) = (&self.spectrum, &self.kept.spectrum);
        let factor = T::narrow(scale);
        // Column `k`, transformed from `extra` or empty, plus the kept one's share, times
        // the kernel's spectrum.
        let combine = |k: usize, column: &mut [Complex<T>]| {
            let kept = &kept[k * stride..][..column.len()];
            let pairs = column.iter_mut().zip(kept);
            if extra.is_some() {
                pairs.for_each(|(c, &t)| *c += t * factor);
            } else {
                pairs.for_each(|(c, &t)| *c = t * factor);
            }
            multiply(spectrum, column, k * stride);
        };
        match &mut self.passes {
            Threads::Split(split, columns) => {
                let shape = (nx, ny, col_len, stride);
                split.passes(shape, &combine, columns, extra, Some((output, add_row)));
            }
            Threads::One(passes) => {
                if let Some(extra) = extra {
                    passes.forward_rows(&mut self.plans, extra);
                }
                let transforms = Transforms {
                    forward: extra.is_some(),
                    inverse: true,
                };
                passes.columns(&mut self.plans, transforms, None, combine);
                passes.inverse_rows(&mut self.plans, output, add_row);
            }
        }
    }
}

/// The transform [`DcFft::keep`] keeps, and the weights of its power in `t . K t`.
#[derive(Default)]
pub(super) struct Kept<T> {
    /// The kept transform, in the layout of the operator's columns.
    spectrum: Vec<Complex<T>>,
    /// `Re K^` at each bin, twice over in the columns that stand for a mirrored one too.
    weights: Vec<T>,
}

impl<T: Real> Kept<T> {
    /// Room for a transform of an operator of `spectrum` with `half` columns `stride` apart,
    /// `col_len` long.
    fn of(spectrum: &Spectrum<T>, (half, stride, col_len): (usize, usize, usize)) -> Self {
        let mut weights = vec![T::default(); half * stride];
        let two = T::narrow(2.0);
        for (k, column) in weights.chunks_exact_mut(stride).enumerate() {
            let start = k * stride;
            let twice = k != 0 && k != half - 1;
            for (ky, weight) in column[..col_len].iter_mut().enumerate() {
                let even = match spectrum {
                    Spectrum::Real(s) => s[start + ky],
                    Spectrum::Complex(s) => s[start + ky].re,
                    Spectrum::Imaginary(_) => T::default(),
                };
                *weight = if twice { two * even } else { even };
            }
        }
        Self {
            spectrum: vec![Complex::default(); half * stride],
            weights,
        }
    }
}

/// `sum weights |c|^2` over `column`. Summed in eight lanes of `T`, widened per column: in
/// `f32` a lane's sum of the 2 ny / 8 terms errs by at most about 2 ny / 8 units of
/// round-off (4e-6 at ny = 256), each term's own error being that of the f32 transform.
fn weighted_power<T: Real>(column: &[Complex<T>], weights: &[T]) -> f64 {
    let mut lanes = [T::default(); 8];
    let (columns, weights_8) = (column.chunks_exact(8), weights.chunks_exact(8));
    let tail: T = columns
        .remainder()
        .iter()
        .zip(&weights[weights.len() - weights.len() % 8..])
        .fold(T::default(), |sum, (c, &w)| sum + c.norm_sqr() * w);
    for (c, w) in columns.zip(weights_8) {
        for lane in 0..8 {
            lanes[lane] += c[lane].norm_sqr() * w[lane];
        }
    }
    lanes.iter().map(|v| v.widen()).sum::<f64>() + tail.widen()
}

/// Adds the first `out.len()` values of the row held in pairs in `packed` to `out`.
fn add_row<T: Real>(out: &mut [f64], packed: &[Complex<T>]) {
    each_value(out, packed, |o, v| *o += v.widen());
}

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};

    use crate::contact::transform::Real;
    use crate::contact::{
        DcFft, ElasticPair, Grid, Kernel, Material, Operator, SINGLE_PRECISION_ROUNDOFF,
    };

    /// The largest errors of `op`'s kept halves against two f64 applies of `exact` (the
    /// same kernel), on random `t` and `w` of `grid`: of `t . K t` relative to it, and of
    /// `u + K (w - tau t)` relative to the largest of `K t` and `K w`.
    fn kept_errors<T: Real>(op: &mut DcFft<T>, exact: &mut DcFft, grid: &Grid) -> (f64, f64) {
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        let mut random = |n| -> Vec<f64> { (0..n).map(|_| rng.random_range(-1e8..1e9)).collect() };
        let (t, w) = (random(grid.len()), random(grid.len()));
        let (mut kt, mut kw) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
        exact.apply(&t, &mut kt);
        exact.apply(&w, &mut kw);
        let quadratic: f64 = t.iter().zip(&kt).map(|(a, b)| a * b).sum();
        let kept = op.keep(&t).expect("one thread");
        // A displacement to add to, as the solver adds to its own.
        let base: Vec<f64> = kw.iter().rev().copied().collect();
        let tau = 0.37;
        let (mut both, mut alone) = (base.clone(), base.clone());
        op.add_kept(Some(&w), -tau, &mut both);
        op.add_kept(None, -tau, &mut alone);
        let largest = kt.iter().chain(&kw).fold(0.0f64, |m, v| m.max(v.abs()));
        let worst = (0..grid.len()).fold(0.0f64, |m, i| {
            let both = (both[i] - (base[i] + kw[i] - tau * kt[i])).abs();
            let alone = (alone[i] - (base[i] - tau * kt[i])).abs();
            m.max(both).max(alone)
        });
        ((kept - quadratic).abs() / quadratic.abs(), worst / largest)
    }

    #[test]
    fn kept_halves_equal_two_applies() {
        let pair = ElasticPair::new(
            Material::new(300e9, 0.21).expect("valid"),
            Material::new(205e9, 0.28).expect("valid"),
        );
        for (nx, ny) in [(16, 16), (13, 9), (32, 20)] {
            let grid = Grid::new(nx, ny, 1e-6, 1.3e-6).expect("valid");
            let normal = Kernel::normal(&grid, &pair);
            let coupling = Kernel::coupling(&grid, &pair, 0.45);
            for (mut op, mut exact) in [
                (DcFft::new(&normal), DcFft::new(&normal)),
                (
                    DcFft::sum(&normal, &coupling),
                    DcFft::sum(&normal, &coupling),
                ),
            ] {
                // The same products summed in another order: round-off.
                let (quadratic, add) = kept_errors(&mut op, &mut exact, &grid);
                assert!(
                    quadratic < 1e-12 && add < 1e-13,
                    "{nx}x{ny}: {quadratic:e}, {add:e}"
                );
            }
            // In f32: an apply's round-off (`SINGLE_PRECISION_ROUNDOFF` of its largest
            // value), twice that relative in the power of `t . K t`. Measured at these
            // sizes: at most 5.1e-8 and 1.3e-7.
            let mut single = DcFft::<f32>::of_sum(&normal, &coupling);
            let mut exact = DcFft::sum(&normal, &coupling);
            let (quadratic, add) = kept_errors(&mut single, &mut exact, &grid);
            assert!(
                quadratic < 2.0 * SINGLE_PRECISION_ROUNDOFF && add < SINGLE_PRECISION_ROUNDOFF,
                "{nx}x{ny}: {quadratic:e}, {add:e}"
            );
            // Split across threads, the same bits (`tests/contact_threads.rs` for a solve).
            let mut split = DcFft::<f32>::of_sum(&normal, &coupling).threaded(2);
            let errors = kept_errors(&mut split, &mut exact, &grid);
            assert_eq!(errors, (quadratic, add), "{nx}x{ny} split");
        }
    }
}
