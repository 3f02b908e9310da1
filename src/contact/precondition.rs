//! A Fourier-space preconditioner for the contact solver: the exact inverse of the kernel
//! wrapped periodically onto the grid itself (no padding), applied by a plain `nx` x `ny`
//! FFT round trip.
//!
//! The half-space operator behaves like `2 / (E* |k|)` in Fourier space, so the conjugate
//! gradient's iteration count grows with the contact's size in cells; multiplying the
//! residual by the inverse symbol flattens that spectrum (Vollebregt, J. Optim. Theory
//! Appl. 2014, uses the same idea in BCCG). The periodic wrap makes the inverse approximate
//! for the non-periodic DC-FFT operator, which only costs iterations, never accuracy: the
//! solver's stopping test is on the true residual. The transform is a quarter of the
//! padded one, so a preconditioned iteration costs about 1.25 applies.
//!
//! The wrapped kernel is real and even in both axes for the normal kernel, so its spectrum
//! is real; the zero wavenumber is dropped (the solver works on zero-mean directions),
//! and any non-positive value (none seen on the grids tested) would be floored so the
//! preconditioner stays positive definite.

use rustfft::num_complex::Complex;

use super::influence::Kernel;
use super::operator::{NEAR_REACH, Preconditioner};
use super::transform::{Passes, Plans, Real, Threads, Transforms};

/// The inverse of a kernel's periodic wrap on its own grid, its transforms computed in `T`.
pub struct FourierInverse<T: Real = f64> {
    nx: usize,
    ny: usize,
    plans: Plans<T>,
    /// `1 / (nx ny K_hat)`, column-major: entry `(kx, ky)` at `kx * ny + ky`.
    inverse_symbol: Vec<T>,
    /// Where the passes run: on one thread, or split across threads.
    passes: Threads<T>,
    /// [`Preconditioner::near_field`].
    near: Vec<f64>,
}

impl<T: Real> std::fmt::Debug for FourierInverse<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FourierInverse")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .finish_non_exhaustive()
    }
}

/// The offset a periodic index stands for: `0..=n/2` forward, the rest backward.
fn wrapped_offset(index: usize, n: usize) -> isize {
    if index <= n / 2 {
        index as isize
    } else {
        index as isize - n as isize
    }
}

impl FourierInverse {
    /// The inverse of `kernel` (an even one, e.g. [`Kernel::normal`]) wrapped onto its
    /// grid, in `f64`.
    pub fn new(kernel: &Kernel) -> Self {
        Self::of(kernel)
    }
}

impl<T: Real> FourierInverse<T> {
    /// The inverse of `kernel` (an even one, e.g. [`Kernel::normal`]) wrapped onto its grid.
    pub fn of(kernel: &Kernel) -> Self {
        let (nx, ny) = kernel.shape();
        let mut inverse = Self::with_symbol(nx, ny, Vec::new());
        let wrapped: Vec<f64> = (0..nx * ny)
            .map(|i| kernel.value(wrapped_offset(i % nx, nx), wrapped_offset(i / nx, ny)))
            .collect();
        let symbol: Vec<f64> = inverse
            .spectrum(&wrapped)
            .iter()
            .map(|c| c.re.widen())
            .collect();
        let floor = symbol
            .iter()
            .skip(1)
            .copied()
            .filter(|&s| s > 0.0)
            .fold(f64::INFINITY, f64::min);
        let scale = 1.0 / (nx * ny) as f64;
        inverse.inverse_symbol = symbol
            .iter()
            .enumerate()
            .map(|(k, &s)| T::narrow(if k == 0 { 0.0 } else { scale / s.max(floor) }))
            .collect();
        inverse.with_near_field()
    }

    /// The multiplication by `symbol(qx, qy)` in Fourier space on an `nx` x `ny` grid of
    /// `dx` x `dy` cells, the wavenumbers in rad/m; the zero wavenumber maps to zero. Used
    /// with the inverse symbol as the periodic half-space operator and its exact inverse.
    pub(crate) fn multiplier(
        nx: usize,
        ny: usize,
        (dx, dy): (f64, f64),
        symbol: impl Fn(f64, f64) -> f64,
    ) -> Self {
        let half = nx / 2 + 1;
        let scale = 1.0 / (nx * ny) as f64;
        let q = |k: usize, n: usize, d: f64| {
            std::f64::consts::TAU * wrapped_offset(k, n) as f64 / (n as f64 * d)
        };
        let mut values = vec![T::default(); half * ny];
        for kx in 0..half {
            for ky in 0..ny {
                if kx + ky > 0 {
                    values[kx * ny + ky] = T::narrow(scale * symbol(q(kx, nx, dx), q(ky, ny, dy)));
                }
            }
        }
        Self::with_symbol(nx, ny, values).with_near_field()
    }

    /// Measures [`Preconditioner::near_field`]: the response to a unit value on cell 0,
    /// read around it with the periodic wrap.
    fn with_near_field(mut self) -> Self {
        let (nx, ny) = (self.nx, self.ny);
        let mut unit = vec![0.0; nx * ny];
        unit[0] = 1.0;
        let mut response = vec![0.0; nx * ny];
        self.apply(&unit, &mut response);
        let reach = NEAR_REACH as isize;
        let wrap = |d: isize, n: usize| d.rem_euclid(n as isize) as usize;
        self.near = (-reach..=reach)
            .flat_map(|dy| (-reach..=reach).map(move |dx| (dx, dy)))
            .map(|(dx, dy)| response[wrap(dy, ny) * nx + wrap(dx, nx)])
            .collect();
        self
    }

    /// The buffers of an `nx` x `ny` grid around `inverse_symbol`.
    fn with_symbol(nx: usize, ny: usize, inverse_symbol: Vec<T>) -> Self {
        let plans = Plans::new(nx, ny);
        Self {
            nx,
            ny,
            passes: Threads::new((nx, ny), (nx, ny), &plans, 1),
            plans,
            inverse_symbol,
            near: Vec::new(),
        }
    }

    /// The same transform applying on `threads` threads (1: on the caller's thread alone),
    /// split as the DC-FFT apply is ([`super::DcFft::threaded`]), equal to the last bit.
    pub(crate) fn threaded(mut self, threads: usize) -> Self {
        let shape = (self.nx, self.ny);
        self.passes = Threads::new(shape, shape, &self.plans, threads);
        self
    }

    /// The threads an apply runs on.
    pub(crate) fn threads(&self) -> usize {
        self.passes.threads()
    }

    /// The transform of `input`, column by column (`kx` major, as the symbol is stored).
    fn spectrum(&mut self, input: &[f64]) -> Vec<Complex<T>> {
        let shape = (self.nx, self.ny);
        let mut passes = Passes::new(shape, shape);
        passes.forward_rows(&mut self.plans, input);
        let forward = Transforms {
            forward: true,
            inverse: false,
        };
        let mut spectrum = Vec::with_capacity((self.nx / 2 + 1) * self.ny);
        passes.columns(&mut self.plans, forward, None, |_, column| {
            spectrum.extend_from_slice(column);
        });
        spectrum
    }
}

impl<T: Real> Preconditioner for FourierInverse<T> {
    /// The mean of the symbol over the whole spectrum (the half stored counts twice but for
    /// the columns that are their own mirror image, `kx = 0` and `kx = nx / 2`).
    fn diagonal(&self) -> f64 {
        self.inverse_symbol
            .chunks_exact(self.ny)
            .enumerate()
            .map(|(kx, column)| {
                let mirrored = kx > 0 && 2 * kx != self.nx;
                let weight = if mirrored { 2.0 } else { 1.0 };
                weight * column.iter().map(|s| s.widen()).sum::<f64>()
            })
            .sum()
    }

    fn near_field(&self) -> &[f64] {
        &self.near
    }

    /// `output = M^-1 input`: the inverse of the wrapped kernel, without its mean.
    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        assert_eq!(input.len(), nx * ny, "input does not match the grid");
        assert_eq!(output.len(), nx * ny, "output does not match the grid");
        let symbol = &self.inverse_symbol;
        let product = |k: usize, column: &mut [Complex<T>]| {
            let symbol = &symbol[k * ny..(k + 1) * ny];
            column.iter_mut().zip(symbol).for_each(|(c, &s)| *c *= s);
        };
        let shape = ((nx, ny), ny);
        self.passes
            .convolve(&mut self.plans, shape, &product, (input, output));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{ElasticPair, Grid, Material};

    fn kernel(nx: usize, ny: usize) -> Kernel {
        let grid = Grid::new(nx, ny, 1e-6 * nx as f64, 1.5e-6 * ny as f64).expect("valid grid");
        let steel = Material {
            youngs_modulus_pa: 205e9,
            poisson_ratio: 0.28,
        };
        Kernel::normal(&grid, &ElasticPair::new(steel, steel))
    }

    /// Circular convolution by direct summation with the wrapped kernel.
    fn circulant(kernel: &Kernel, input: &[f64]) -> Vec<f64> {
        let (nx, ny) = kernel.shape();
        (0..nx * ny)
            .map(|i| {
                (0..nx * ny)
                    .map(|j| {
                        let dx = (i % nx + nx - j % nx) % nx;
                        let dy = (i / nx + ny - j / nx) % ny;
                        kernel.value(wrapped_offset(dx, nx), wrapped_offset(dy, ny)) * input[j]
                    })
                    .sum()
            })
            .collect()
    }

    /// The preconditioner inverts the periodic operator exactly on zero-mean fields, on
    /// even and odd sizes; the bound is round-off of FFTs of a few hundred points.
    #[test]
    fn inverts_the_periodic_operator() {
        for (nx, ny) in [(16, 12), (9, 14), (15, 7)] {
            let k = kernel(nx, ny);
            let mut field: Vec<f64> = (0..nx * ny)
                .map(|i| ((i * 37 % 101) as f64 / 101.0 - 0.5) * 1e6)
                .collect();
            let mean = field.iter().sum::<f64>() / field.len() as f64;
            field.iter_mut().for_each(|v| *v -= mean);
            let displacement = circulant(&k, &field);
            let mut back = vec![0.0; nx * ny];
            let mut inverse = FourierInverse::new(&k);
            inverse.apply(&displacement, &mut back);
            let scale = field.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (b, f) in back.iter().zip(&field) {
                assert!((b - f).abs() <= 1e-10 * scale, "{nx}x{ny}: {b} vs {f}");
            }
        }
    }

    /// The diagonal is the response of a cell to a unit value on itself, and the near field
    /// its neighbours', on even and odd sizes and for a multiplier; the bound is the
    /// round-off of one FFT round trip.
    #[test]
    fn diagonal_is_the_response_of_a_cell_to_itself() {
        for (nx, ny) in [(16, 12), (9, 14), (15, 7)] {
            let symbol = |qx: f64, qy: f64| qx.hypot(qy);
            for mut inverse in [
                FourierInverse::new(&kernel(nx, ny)),
                FourierInverse::multiplier(nx, ny, (1e-6, 2e-6), symbol),
            ] {
                let cell = nx * (ny / 2) + nx / 3;
                let mut unit = vec![0.0; nx * ny];
                unit[cell] = 1.0;
                let mut response = vec![0.0; nx * ny];
                inverse.apply(&unit, &mut response);
                let diagonal = inverse.diagonal();
                assert!(diagonal > 0.0);
                let error = (response[cell] - diagonal).abs();
                assert!(error <= 1e-12 * diagonal, "{nx}x{ny}: {error:e}");
                // The near field is the same response around the cell, wrapped.
                let (side, reach) = (2 * NEAR_REACH + 1, NEAR_REACH as isize);
                for (k, &near) in inverse.near_field().iter().enumerate() {
                    let (dx, dy) = ((k % side) as isize - reach, (k / side) as isize - reach);
                    let x = (cell % nx) as isize + dx;
                    let y = (cell / nx) as isize + dy;
                    let at = y.rem_euclid(ny as isize) as usize * nx
                        + x.rem_euclid(nx as isize) as usize;
                    let error = (response[at] - near).abs();
                    assert!(
                        error <= 1e-12 * diagonal,
                        "{nx}x{ny} ({dx}, {dy}): {error:e}"
                    );
                }
            }
        }
    }

    /// The split transform makes the same transforms and products as the one-thread one,
    /// rows and columns in another order: equal to the last bit, on even and odd sizes, for
    /// the wrapped kernel's inverse and for a multiplier.
    #[test]
    fn the_split_apply_equals_the_one_thread_apply() {
        for (nx, ny) in [(16, 12), (9, 14), (15, 7), (37, 20)] {
            let k = kernel(nx, ny);
            let symbol = |qx: f64, qy: f64| 1.0 / qx.hypot(qy);
            let input: Vec<f64> = (0..nx * ny).map(|i| ((i * 31) % 13) as f64).collect();
            for threads in [2, 3] {
                let pairs = [
                    (
                        FourierInverse::new(&k),
                        FourierInverse::new(&k).threaded(threads),
                    ),
                    (
                        FourierInverse::multiplier(nx, ny, (1e-6, 2e-6), symbol),
                        FourierInverse::multiplier(nx, ny, (1e-6, 2e-6), symbol).threaded(threads),
                    ),
                ];
                for (mut one, mut split) in pairs {
                    assert_eq!(split.threads(), threads);
                    let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
                    one.apply(&input, &mut a);
                    split.apply(&input, &mut b);
                    assert_eq!(a, b, "{nx}x{ny} on {threads} threads");
                }
                let mut one = FourierInverse::<f32>::of(&k);
                let mut split = FourierInverse::<f32>::of(&k).threaded(threads);
                let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
                one.apply(&input, &mut a);
                split.apply(&input, &mut b);
                assert_eq!(a, b, "{nx}x{ny} on {threads} threads, f32");
            }
        }
    }

    /// The DC-FFT preconditioner's apply on one and on two threads at N = 256 ... 2048, the
    /// medians of 11 applies, for the choice of splitting it with the DC-FFT apply. Speed is
    /// printed, never asserted: `cargo test --release --lib -- --ignored --nocapture
    /// split_preconditioner_time`.
    #[test]
    #[ignore = "a timing, not a test"]
    fn split_preconditioner_time() {
        for n in [256, 512, 1024, 2048] {
            let k = kernel(n, n);
            let input: Vec<f64> = (0..n * n).map(|i| ((i * 31) % 13) as f64).collect();
            let mut output = vec![0.0; n * n];
            let mut median = |mut inverse: FourierInverse| {
                let mut times: Vec<f64> = (0..11)
                    .map(|_| {
                        let started = std::time::Instant::now();
                        inverse.apply(&input, &mut output);
                        started.elapsed().as_secs_f64()
                    })
                    .collect();
                times.sort_by(f64::total_cmp);
                times[5]
            };
            let one = median(FourierInverse::new(&k));
            let two = median(FourierInverse::new(&k).threaded(2));
            println!(
                "N = {n}: one thread {one:.5} s, two {two:.5} s, ratio {:.2}",
                one / two
            );
        }
    }

    /// The wrapped normal kernel's spectrum is positive away from zero, so no floor was
    /// needed on these grids and the preconditioner is positive definite.
    #[test]
    fn symbol_is_positive() {
        for (nx, ny) in [(16, 12), (64, 64), (9, 14)] {
            let k = kernel(nx, ny);
            let mut inverse = FourierInverse::new(&k);
            let wrapped: Vec<f64> = (0..nx * ny)
                .map(|i| k.value(wrapped_offset(i % nx, nx), wrapped_offset(i / nx, ny)))
                .collect();
            assert!(
                inverse
                    .spectrum(&wrapped)
                    .iter()
                    .skip(1)
                    .all(|c| c.re > 0.0)
            );
        }
    }
}
