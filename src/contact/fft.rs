//! DC-FFT (Liu, Wang & Liu, Wear 2000): the linear (not circular) convolution of a kernel
//! with an `nx` x `ny` field, computed on a zero-padded `2nx` x `2ny` grid.
//!
//! Layout and costs, per [`Operator::apply`]:
//! - row pass: real-to-complex FFTs of length `2nx` on the `ny` data rows only; the other
//!   `ny` padded rows are zero and their transforms are zero, so they are skipped;
//! - column pass: for each of the `nx + 1` half-spectrum columns, gathered a block at a time
//!   into a transposed (column-contiguous) buffer, the forward FFT of length `2ny`, the
//!   product with the kernel spectrum (stored in the same transposed order) and the inverse
//!   FFT, one after the other while the column is still in the L1 cache;
//! - complex-to-real FFTs on the `ny` rows whose output is kept.
//!
//! The passes run on one thread or split across threads, as [`super::transform`]'s
//! `Threads` lays them out.
//!
//! The kernel spectrum is computed once per operator and includes the `1 / (4 nx ny)`
//! normalisation. Arranged by wrap-around, an even kernel is a real even sequence, so its
//! spectrum is real; an odd one gives a purely imaginary spectrum. Only that one part is
//! stored and the product is two real multiplications, not a complex one (the part
//! dropped is round-off; the direct-summation test bounds the result). Nothing is allocated
//! per apply.

mod kept;
mod sparse;

use rustfft::num_complex::Complex;

use self::sparse::KernelRows;
use super::influence::{Kernel, Symmetry, offset_index};
use super::operator::{Operator, Preconditioner};
use super::precondition::FourierInverse;
use super::transform::{
    Plans, Real, Threads, column_stride, forward_row, packed_len, periodic_threads, transpose,
};

/// The smallest solver tolerance a run solves in single precision (`DcFft<f32>`) at: the
/// f32 apply errs by at most [`SINGLE_PRECISION_ROUNDOFF`] of the largest displacement, 1/250
/// of it, within
/// [`SINGLE_PRECISION_HEADROOM`], so the solver's stopping test (a relative residual)
/// measures the solve, not the round-off. On the 4 um rough disc over 600 cycles (tolerance
/// 1e-4) single precision took 0.73 of double's CPU time, its errors against the 1e-8
/// reference no larger (`docs/accuracy.md`, "Rough wear: single precision").
pub const SINGLE_PRECISION_MIN_TOLERANCE: f64 = 1e-4;

/// The least ratio of a single-precision solve's tolerance to the f32 apply's round-off.
pub const SINGLE_PRECISION_HEADROOM: f64 = 100.0;

/// The f32 apply's largest error over the largest displacement, as measured
/// (`single_precision_errs_by_its_round_off`): the round-off the rule's headroom is of.
pub const SINGLE_PRECISION_ROUNDOFF: f64 = 4.0e-7;

// The rule's tolerance leaves the measured round-off its headroom.
const _: () = assert!(
    SINGLE_PRECISION_ROUNDOFF * SINGLE_PRECISION_HEADROOM <= SINGLE_PRECISION_MIN_TOLERANCE
);

/// The DC-FFT convolution operator of one kernel on one grid, its transforms computed in
/// `T` ([`Real`]).
pub struct DcFft<T: Real = f64> {
    nx: usize,
    ny: usize,
    /// Padded column length `2 ny`.
    col_len: usize,
    /// Distance between column starts in the transposed buffers ([`column_stride`]).
    stride: usize,
    /// Half-spectrum row length `nx + 1`.
    half: usize,
    plans: Plans<T>,
    /// The kernel spectrum, transposed: entry `(kx, ky)` at `kx * stride + ky`.
    spectrum: Spectrum<T>,
    /// Where the passes run: on one thread, or split across threads.
    passes: Threads<T>,
    /// The preconditioner: the inverse of the normal kernel's periodic wrap.
    inverse: Option<FourierInverse<T>>,
    /// The kernel in real space, for updates at a few cells (`None` on large grids).
    sparse: Option<KernelRows>,
    /// The transform of the input of [`Operator::keep`] (empty until the first).
    kept: kept::Kept<T>,
    /// Whether every coefficient of the (summed) kernel is nonnegative.
    nonnegative: bool,
}

/// The kernel spectrum, stored by what it can hold: real for an even kernel, imaginary for
/// an odd one, complex for their sum.
enum Spectrum<T> {
    Real(Vec<T>),
    Imaginary(Vec<T>),
    Complex(Vec<Complex<T>>),
}

/// `column *= spectrum` over the column that starts at `start` in the spectrum's layout.
fn multiply<T: Real>(spectrum: &Spectrum<T>, column: &mut [Complex<T>], start: usize) {
    let range = start..start + column.len();
    match spectrum {
        Spectrum::Real(s) => column.iter_mut().zip(&s[range]).for_each(|(c, &k)| *c *= k),
        Spectrum::Imaginary(s) => column.iter_mut().zip(&s[range]).for_each(|(c, &k)| {
            *c = Complex::new(-c.im * k, c.re * k);
        }),
        Spectrum::Complex(s) => column.iter_mut().zip(&s[range]).for_each(|(c, k)| *c *= k),
    }
}

impl<T: Real> std::fmt::Debug for DcFft<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DcFft")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .finish_non_exhaustive()
    }
}

impl DcFft {
    /// Plans the transforms and computes the spectrum of `kernel`, in `f64`.
    pub fn new(kernel: &Kernel) -> Self {
        Self::of(kernel)
    }

    /// The operator of `first + second` (e.g. the normal and the coupling kernels), for the
    /// cost of one, in `f64`.
    pub fn sum(first: &Kernel, second: &Kernel) -> Self {
        Self::of_sum(first, second)
    }
}

impl<T: Real> DcFft<T> {
    /// Plans the transforms and computes the spectrum of `kernel`.
    pub fn of(kernel: &Kernel) -> Self {
        let mut op = Self::planned(kernel.shape());
        let columns = op.kernel_spectrum(&[kernel]);
        op.spectrum = match kernel.symmetry() {
            Symmetry::EvenInX => Spectrum::Real(columns.iter().map(|c| c.re).collect()),
            Symmetry::OddInX => Spectrum::Imaginary(columns.iter().map(|c| c.im).collect()),
        };
        if kernel.symmetry() == Symmetry::EvenInX {
            op.inverse = Some(FourierInverse::of(kernel));
        }
        op.sparse = KernelRows::of(&[kernel]);
        op.nonnegative = kernel.values().iter().all(|&k| k >= 0.0);
        op
    }

    /// The operator of `first + second` (e.g. the normal and the coupling kernels), for the
    /// cost of one: the sum of the two spectra is applied in one pass.
    pub fn of_sum(first: &Kernel, second: &Kernel) -> Self {
        assert_eq!(first.shape(), second.shape(), "kernel shapes differ");
        let mut op = Self::planned(first.shape());
        // The transform is linear: one of the summed kernel, not the sum of two.
        op.spectrum = Spectrum::Complex(op.kernel_spectrum(&[first, second]));
        // The normal kernel dominates the sum (the coupling carries mu delta-nu / 2).
        if first.symmetry() == Symmetry::EvenInX {
            op.inverse = Some(FourierInverse::of(first));
        }
        op.sparse = KernelRows::of(&[first, second]);
        op.nonnegative = (first.values().iter().zip(second.values())).all(|(a, b)| a + b >= 0.0);
        op
    }

    fn planned((nx, ny): (usize, usize)) -> Self {
        let (row_len, col_len, half) = (2 * nx, 2 * ny, nx + 1);
        let stride = column_stride(col_len);
        let plans = Plans::new(row_len, col_len);
        Self {
            nx,
            ny,
            col_len,
            stride,
            half,
            passes: Threads::new((nx, ny), (row_len, col_len), &plans, 1),
            plans,
            spectrum: Spectrum::Real(Vec::new()),
            inverse: None,
            sparse: None,
            kept: kept::Kept::default(),
            nonnegative: false,
        }
    }

    /// The same operator applying on `threads` threads (1: on the caller's thread alone);
    /// its preconditioner too where its transform, a quarter of the apply's, is long enough
    /// (`periodic_threads`).
    pub fn threaded(mut self, threads: usize) -> Self {
        let (shape, lengths) = ((self.nx, self.ny), (2 * self.nx, self.col_len));
        self.passes = Threads::new(shape, lengths, &self.plans, threads);
        let inverse_threads = periodic_threads(threads, self.nx * self.ny);
        self.inverse = self
            .inverse
            .map(|inverse| inverse.threaded(inverse_threads));
        self
    }

    /// The threads an apply runs on.
    pub fn threads(&self) -> usize {
        self.passes.threads()
    }

    /// The transform of the sum of `kernels` arranged by wrap-around on the padded grid
    /// (index `i < n` holds offset `i`, `i > n` holds offset `i - 2n`; the entry at `i = n`
    /// multiplies only padding and is set to zero, which also keeps odd kernels odd), in the
    /// spectrum's transposed layout. Each padded row is copied from the kernels' rows of
    /// offsets as two slices. Once per operator, so its buffers are its own.
    fn kernel_spectrum(&mut self, kernels: &[&Kernel]) -> Vec<Complex<T>> {
        let (nx, ny, half, stride) = (self.nx, self.ny, self.half, self.stride);
        let scale = 1.0 / (4 * nx * ny) as f64;
        let mut row = vec![0.0; 2 * nx];
        let mut packed = vec![Complex::default(); packed_len(2 * nx)];
        let mut rows = vec![Complex::default(); self.col_len * half];
        for (iy, out) in rows.chunks_exact_mut(half).enumerate() {
            row.fill(0.0);
            let dj = match iy.cmp(&ny) {
                std::cmp::Ordering::Less => Some(iy as isize),
                std::cmp::Ordering::Equal => None,
                std::cmp::Ordering::Greater => Some(iy as isize - 2 * ny as isize),
            };
            if let Some(dj) = dj {
                for kernel in kernels {
                    add_wrapped_row(&mut row, kernel, dj, scale);
                }
            }
            forward_row(&mut self.plans, &row, &mut packed, out);
        }
        let mut columns = vec![Complex::default(); half * stride];
        transpose(&rows, half, (self.col_len, half), &mut columns, stride);
        for column in columns.chunks_exact_mut(stride) {
            self.plans
                .col_forward
                .process_with_scratch(&mut column[..self.col_len], &mut self.plans.complex_scratch);
        }
        columns
    }
}

impl<T: Real> Operator for DcFft<T> {
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    fn preconditioner(&mut self) -> Option<&mut dyn Preconditioner> {
        self.inverse
            .as_mut()
            .map(|inverse| inverse as &mut dyn Preconditioner)
    }

    fn is_nonnegative(&self) -> bool {
        self.nonnegative
    }

    fn threads(&self) -> usize {
        DcFft::threads(self)
    }

    fn add_sparse(&mut self, cells: &[(usize, f64)], output: &mut [f64]) -> bool {
        self.sparse
            .as_ref()
            .is_some_and(|sparse| sparse.add(cells, output))
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        assert_eq!(input.len(), nx * ny, "input does not match the grid");
        assert_eq!(output.len(), nx * ny, "output does not match the grid");
        let (spectrum, stride) = (&self.spectrum, self.stride);
        let product = |k: usize, column: &mut [Complex<T>]| {
            multiply(spectrum, column, k * stride);
        };
        let shape = ((nx, ny), self.col_len);
        self.passes
            .convolve(&mut self.plans, shape, &product, (input, output));
    }

    fn keep(&mut self, input: &[f64]) -> Option<f64> {
        DcFft::keep(self, input)
    }

    fn add_kept(&mut self, extra: Option<&[f64]>, scale: f64, output: &mut [f64]) {
        DcFft::add_kept(self, extra, scale, output);
    }
}

/// Adds `scale` times the kernel's row of offsets `dj` to the padded row `row` by
/// wrap-around: offsets `0..nx` first, then `-(nx - 1)..0` after the zero at `nx`; two
/// slice copies, no lookup per entry.
fn add_wrapped_row(row: &mut [f64], kernel: &Kernel, dj: isize, scale: f64) {
    let (nx, ny) = kernel.shape();
    let start = offset_index(nx, ny, 1 - nx as isize, dj);
    let (negative, forward) = kernel.values()[start..start + 2 * nx - 1].split_at(nx - 1);
    let (head, tail) = row.split_at_mut(nx);
    head.iter_mut()
        .zip(forward)
        .for_each(|(r, &k)| *r += scale * k);
    tail[1..]
        .iter_mut()
        .zip(negative)
        .for_each(|(r, &k)| *r += scale * k);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{DenseOperator, ElasticPair, Grid, Material, SPLIT_MIN_CELLS};
    use rand::{Rng, SeedableRng};

    fn pair(nu1: f64, nu2: f64, e2: f64) -> ElasticPair {
        ElasticPair::new(
            Material::new(300e9, nu1).expect("valid"),
            Material::new(e2, nu2).expect("valid"),
        )
    }

    fn max_relative_difference(kernel: &Kernel, nx: usize, ny: usize, seed: u64) -> f64 {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        let input: Vec<f64> = (0..nx * ny).map(|_| rng.random_range(0.0..1e9)).collect();
        let (mut fast, mut slow) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        DcFft::new(kernel).apply(&input, &mut fast);
        DenseOperator::new(kernel.clone()).apply(&input, &mut slow);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        fast.iter()
            .zip(&slow)
            .map(|(f, s)| (f - s).abs() / scale)
            .fold(0.0, f64::max)
    }

    #[test]
    fn equals_direct_summation_on_small_grids() {
        // Both kernels, square and rectangular, odd and even sizes (the wrap-around
        // differs). The worst disagreement measured is 3.7e-15 of the largest displacement
        // (coupling, 32 x 32); 1e-12 is the allowance the contact tests add to the solver's
        // tolerance when they recheck a solution by another operator.
        for (nx, ny) in [(32, 32), (16, 8), (7, 12), (2, 2), (31, 17)] {
            let grid = Grid::new(nx, ny, 1e-6, 1.3e-6).expect("valid");
            let pair = pair(0.21, 0.28, 205e9);
            let normal = Kernel::normal(&grid, &pair);
            let coupling = Kernel::coupling(&grid, &pair, 0.45);
            for (name, kernel) in [("normal", &normal), ("coupling", &coupling)] {
                let error = max_relative_difference(kernel, nx, ny, 7);
                assert!(error < 1e-12, "{name} {nx}x{ny}: {error:e}");
            }
        }
    }

    #[test]
    fn single_precision_errs_by_its_round_off() {
        // An FFT's round-off grows as the unit round-off times the log of its length; the
        // padded 2D transform of N x N cells is 4 N^2 long. Measured at N = 16 ... 1024 on
        // random and dome-shaped pressures: 1.7e-7 to 4.0e-7 of the largest displacement,
        // under the bound (2.1e-6 at N = 256), and far above f64's (the test sees f32).
        for n in [16usize, 64, 256] {
            let grid = Grid::square(n, 1e-6 * n as f64).expect("valid");
            let pair = pair(0.21, 0.28, 205e9);
            let normal = Kernel::normal(&grid, &pair);
            let coupling = Kernel::coupling(&grid, &pair, 0.45);
            let mut rng = rand::rngs::StdRng::seed_from_u64(3);
            let random: Vec<f64> = (0..n * n).map(|_| rng.random_range(0.0..1e9)).collect();
            let c = n as f64 / 2.0;
            let dome: Vec<f64> = (0..n * n)
                .map(|i| {
                    let (x, y) = ((i % n) as f64 - c, (i / n) as f64 - c);
                    1e9 * (1.0 - (x * x + y * y) / (c * c / 4.0)).max(0.0).sqrt()
                })
                .collect();
            let bound = f64::from(f32::EPSILON) / 2.0 * ((4 * n * n) as f64).log2();
            for input in [&random, &dome] {
                let (mut wide, mut narrow) = (vec![0.0; n * n], vec![0.0; n * n]);
                DcFft::sum(&normal, &coupling).apply(input, &mut wide);
                DcFft::<f32>::of_sum(&normal, &coupling).apply(input, &mut narrow);
                let scale = wide.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let error = (wide.iter().zip(&narrow))
                    .map(|(w, s)| (w - s).abs())
                    .fold(0.0, f64::max)
                    / scale;
                assert!(error < bound, "N = {n}: {error:e} against {bound:e}");
                assert!(error > 1e-9, "N = {n}: {error:e} is not single precision");
                assert!(error <= SINGLE_PRECISION_ROUNDOFF, "N = {n}: {error:e}");
            }
        }
    }

    #[test]
    fn rows_without_load_are_skipped_exactly() {
        // Load on a band of rows only, as a window's pressure on the whole grid.
        let grid = Grid::new(12, 20, 1e-6, 1.2e-6).expect("valid");
        let kernel = Kernel::normal(&grid, &pair(0.3, 0.3, 200e9));
        let input: Vec<f64> = (0..240)
            .map(|i| {
                if (60..132).contains(&i) {
                    ((i * 37) % 11) as f64 * 1e8
                } else {
                    0.0
                }
            })
            .collect();
        let (mut fast, mut slow) = (vec![0.0; 240], vec![0.0; 240]);
        DcFft::new(&kernel).apply(&input, &mut fast);
        DenseOperator::new(kernel).apply(&input, &mut slow);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // The bound of the direct-summation test above.
        for (f, s) in fast.iter().zip(&slow) {
            assert!((f - s).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn summed_operator_equals_the_sum_of_direct_summations() {
        let grid = Grid::new(12, 10, 1e-6, 1.2e-6).expect("valid");
        let pair = pair(0.21, 0.28, 205e9);
        let normal = Kernel::normal(&grid, &pair);
        let coupling = Kernel::coupling(&grid, &pair, 0.45);
        let input: Vec<f64> = (0..120).map(|i| ((i * 37) % 11) as f64 * 1e8).collect();
        let mut fast = vec![0.0; 120];
        DcFft::sum(&normal, &coupling).apply(&input, &mut fast);
        let mut slow = vec![0.0; 120];
        crate::contact::SumOperator::new(DenseOperator::new(normal), DenseOperator::new(coupling))
            .apply(&input, &mut slow);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (f, s) in fast.iter().zip(&slow) {
            assert!((f - s).abs() < 1e-12 * scale);
        }
    }

    #[test]
    fn the_split_apply_equals_the_one_thread_apply() {
        // Same transforms and products in another order of rows and columns: equal to the
        // last bit, on even and odd sizes, for each kind of spectrum.
        let grid = Grid::new(37, 20, 1e-6, 1.3e-6).expect("valid");
        let pair = pair(0.21, 0.28, 205e9);
        let normal = Kernel::normal(&grid, &pair);
        let coupling = Kernel::coupling(&grid, &pair, 0.45);
        let input: Vec<f64> = (0..grid.len()).map(|i| ((i * 31) % 13) as f64).collect();
        for threads in [2, 3] {
            let pairs = [
                (DcFft::new(&normal), DcFft::new(&normal).threaded(threads)),
                (
                    DcFft::new(&coupling),
                    DcFft::new(&coupling).threaded(threads),
                ),
                (
                    DcFft::sum(&normal, &coupling),
                    DcFft::sum(&normal, &coupling).threaded(threads),
                ),
            ];
            for (mut one, mut split) in pairs {
                assert_eq!(split.threads(), threads);
                let (mut a, mut b) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
                one.apply(&input, &mut a);
                split.apply(&input, &mut b);
                assert_eq!(a, b);
            }
            // And in single precision, the split's own code path for each type.
            let mut one = DcFft::<f32>::of_sum(&normal, &coupling);
            let mut split = DcFft::<f32>::of_sum(&normal, &coupling).threaded(threads);
            let (mut a, mut b) = (vec![0.0; grid.len()], vec![0.0; grid.len()]);
            one.apply(&input, &mut a);
            split.apply(&input, &mut b);
            assert_eq!(a, b);
        }
    }

    #[test]
    fn a_periodic_transform_splits_from_the_dc_fft_threshold() {
        // The preconditioner's transforms run on the apply's window.
        if let Some(min) = SPLIT_MIN_CELLS {
            assert_eq!(periodic_threads(3, min), 3);
            assert_eq!(periodic_threads(3, min - 1), 1);
        }
        let grid = Grid::square(32, 32e-6).expect("valid");
        let op = DcFft::new(&Kernel::normal(&grid, &pair(0.21, 0.28, 205e9))).threaded(2);
        let inverse = op.inverse.as_ref().map(FourierInverse::threads);
        assert_eq!((op.threads(), inverse), (2, Some(1)));
    }

    #[test]
    fn a_kernel_knows_whether_it_is_nonnegative() {
        // The paper's pair: the coupling term (odd) has both signs, and its sum with the
        // normal term stays nonnegative at the paper's mu = 0.45 and well beyond; a
        // coupling 220 times stronger (mu = 100, out of any scene's range) turns it.
        let grid = Grid::square(32, 300e-6).expect("valid");
        let pair = pair(0.21, 0.28, 205e9);
        let normal = Kernel::normal(&grid, &pair);
        let sum = |mu| DcFft::sum(&normal, &Kernel::coupling(&grid, &pair, mu));
        assert!(DcFft::new(&normal).is_nonnegative());
        assert!(!DcFft::new(&Kernel::coupling(&grid, &pair, 0.45)).is_nonnegative());
        assert!(sum(0.45).is_nonnegative());
        assert!(!sum(100.0).is_nonnegative());
    }

    #[test]
    fn applying_twice_gives_the_same_answer() {
        // The work buffers are reused; a stale padding row would change the second result.
        let grid = Grid::square(16, 16e-6).expect("valid");
        let kernel = Kernel::normal(&grid, &pair(0.21, 0.28, 205e9));
        let mut op = DcFft::new(&kernel);
        let input: Vec<f64> = (0..256).map(|i| (i % 7) as f64).collect();
        let (mut first, mut second) = (vec![0.0; 256], vec![0.0; 256]);
        op.apply(&input, &mut first);
        op.apply(&input, &mut second);
        assert_eq!(first, second);
    }
}
