//! The 2D FFT machinery the DC-FFT operator ([`super::DcFft`]), its Fourier preconditioner
//! ([`super::FourierInverse`]) and the benchmark's FFT pair share: the planned transforms
//! ([`Plans`]), the transposed layout they move rows and columns through (blocks of
//! [`BLOCK`] rows or columns, columns [`STRIDE_PAD`] entries apart beyond their length), the
//! row transforms ([`RealRows`]), and the passes of a convolution on one thread ([`Passes`]) or split across
//! threads ([`Split`]), held as [`Threads`], with the thread counts that choose them. It
//! knows neither operator, so both use it without using each other.
//!
//! Rows (or columns) move between the row and the column layouts in blocks of [`BLOCK`], so
//! each transposed write touches `BLOCK` consecutive entries instead of one. Columns are
//! [`STRIDE_PAD`] entries longer than the transform: a power-of-two stride maps every
//! column start to the same cache sets, which made the transposes several times slower.

mod passes;
mod plans;
mod rows;
mod split;

use rustfft::num_complex::Complex;

pub(crate) use passes::{Passes, Threads, Transforms};
pub(crate) use plans::Plans;
pub use plans::fft_friendly;
pub(crate) use rows::{RealRows, each_value, pack, packed_len};
pub use split::{MAX_SPLIT_THREADS, SPLIT_MIN_CELLS, split_threads};
pub(crate) use split::{Split, periodic_threads};

/// The floating-point type a transform computes in: `f64`, or `f32` where a solve's
/// tolerance leaves room for its round-off (`SINGLE_PRECISION_MIN_TOLERANCE`). Fields go in
/// and come out as `f64` either way (`pack`, `store_row`).
pub trait Real: rustfft::FftNum + rustfft::num_traits::NumAssign + Default {
    /// `value` rounded to this type.
    fn narrow(value: f64) -> Self;
    /// This value as an `f64`, exactly.
    fn widen(self) -> f64;

    /// The forward real-row transform's untangling of the pairs of bins `(k, m - k)`,
    /// `k = 1..=twiddles.len()`, of `bins` (`m + 1` of them) with their `twiddles`
    /// (the real rows' transforms, `transform::rows`): one pair at a time.
    fn untangle(bins: &mut [Complex<Self>], twiddles: &[Complex<Self>]) {
        rows::each_pair(bins, twiddles, rows::untangle_pair);
    }

    /// The inverse real-row transform's tangling of the pairs of bins `(k, m - k)` of
    /// `bins`, as [`Self::untangle`] takes them.
    fn tangle(bins: &mut [Complex<Self>], twiddles: &[Complex<Self>]) {
        rows::each_pair(bins, twiddles, rows::tangle_pair);
    }
}

impl Real for f64 {
    fn narrow(value: f64) -> Self {
        value
    }
    fn widen(self) -> f64 {
        self
    }
}

/// Two pairs of bins at a time in `f32x4` lanes (the measurement in `transform::rows`).
impl Real for f32 {
    fn narrow(value: f64) -> Self {
        value as f32
    }
    fn widen(self) -> f64 {
        f64::from(self)
    }
    fn untangle(bins: &mut [Complex<Self>], twiddles: &[Complex<Self>]) {
        rows::lanes::untangle(bins, twiddles);
    }
    fn tangle(bins: &mut [Complex<Self>], twiddles: &[Complex<Self>]) {
        rows::lanes::tangle(bins, twiddles);
    }
}

/// Rows, or columns, moved per block between the row and the column layouts.
pub(crate) const BLOCK: usize = 16;

/// Padding of the column stride, in complex entries (128 bytes).
const STRIDE_PAD: usize = 8;

/// The distance between column starts of columns `col_len` long in a transposed buffer:
/// [`STRIDE_PAD`] entries beyond their length.
pub(crate) const fn column_stride(col_len: usize) -> usize {
    col_len + STRIDE_PAD
}

/// The inverse transform of one row's half spectrum `row` (used up) into `packed`, the real
/// row held in pairs ([`pack`]).
pub(crate) fn inverse_row<T: Real>(
    plans: &mut Plans<T>,
    row: &mut [Complex<T>],
    packed: &mut [Complex<T>],
) {
    plans.rows.inverse(row, packed, &mut plans.row_scratch);
}

/// The forward transform of `row`, zero-padded to the transform's length in its precision
/// (`packed`, its work buffer, holds it in pairs), into `out`. A row without load
/// transforms to zero and is not transformed: the windowed solver's check applies a
/// window's pressure on the whole grid, where most rows carry none, and the
/// preconditioner's input is zero off the free cells.
pub(crate) fn forward_row<T: Real>(
    plans: &mut Plans<T>,
    row: &[f64],
    packed: &mut [Complex<T>],
    out: &mut [Complex<T>],
) {
    if row.iter().all(|&v| v == 0.0) {
        out.fill(Complex::default());
        return;
    }
    pack(row, packed);
    plans.rows.forward(packed, out, &mut plans.row_scratch);
}

/// The first `out.len()` values of the row held in pairs in `packed` into `out`.
pub(crate) fn store_row<T: Real>(out: &mut [f64], packed: &[Complex<T>]) {
    each_value(out, packed, |o, v| *o = v.widen());
}

/// `to[c * to_stride + r] = from[r * from_stride + c]` for `r < rows` and `c < cols`: a
/// block moved between the row and the column layouts (rows of a block into the columns,
/// the columns back into a block's rows, a block of columns from every row's spectrum).
///
/// The long side goes in tiles of [`TILE`]: each of the short side's entries reads or
/// writes `TILE` consecutive entries of the long side as one slice, into or out of `TILE`
/// runs of the short side held as slices, where one entry at a time computed and checked a
/// strided index per entry. Measured on blocks of 16 rows of 289 columns (`Complex<f32>`,
/// columns 584 apart, as the split passes move a 288-cell window's; a throwaway loop of
/// 20,000 copies each way, built at `opt-level = 3`, four rounds): 0.3 to 0.8 of the time
/// of one entry at a time, both ways; tiles of 4 took 0.9 to 1.4 times the time of tiles
/// of 8.
pub(crate) fn transpose<T: Copy>(
    from: &[T],
    from_stride: usize,
    (rows, cols): (usize, usize),
    to: &mut [T],
    to_stride: usize,
) {
    if rows <= cols {
        let tiled = cols - cols % TILE;
        for c in (0..tiled).step_by(TILE) {
            let mut runs = runs_mut(&mut to[c * to_stride..], to_stride, rows);
            for r in 0..rows {
                let tile = &from[r * from_stride + c..][..TILE];
                runs.iter_mut().zip(tile).for_each(|(run, &x)| run[r] = x);
            }
        }
        if tiled < cols {
            let (from, to) = (&from[tiled..], &mut to[tiled * to_stride..]);
            transpose_entries(from, from_stride, (rows, cols - tiled), to, to_stride);
        }
    } else {
        let tiled = rows - rows % TILE;
        for r in (0..tiled).step_by(TILE) {
            let runs: [&[T]; TILE] =
                std::array::from_fn(|k| &from[(r + k) * from_stride..][..cols]);
            for c in 0..cols {
                let tile = &mut to[c * to_stride + r..][..TILE];
                tile.iter_mut().zip(&runs).for_each(|(x, run)| *x = run[c]);
            }
        }
        if tiled < rows {
            let (from, to) = (&from[tiled * from_stride..], &mut to[tiled..]);
            transpose_entries(from, from_stride, (rows - tiled, cols), to, to_stride);
        }
    }
}

/// Entries of the long side moved at once by [`transpose`].
const TILE: usize = 8;

/// The first `rows` entries of each of the [`TILE`] runs that start `stride` apart in `to`.
fn runs_mut<T>(mut to: &mut [T], stride: usize, rows: usize) -> [&mut [T]; TILE] {
    std::array::from_fn(|_| {
        let taken = std::mem::take(&mut to);
        let (run, rest) = taken.split_at_mut(stride.min(taken.len()));
        to = rest;
        &mut run[..rows]
    })
}

/// [`transpose`] one entry at a time, for the sides shorter than a tile. The inner loop
/// runs along the shorter side, so the long side's runs are read or written whole.
fn transpose_entries<T: Copy>(
    from: &[T],
    from_stride: usize,
    (rows, cols): (usize, usize),
    to: &mut [T],
    to_stride: usize,
) {
    if rows <= cols {
        for c in 0..cols {
            let run = &mut to[c * to_stride..][..rows];
            for (r, x) in run.iter_mut().enumerate() {
                *x = from[r * from_stride + c];
            }
        }
    } else {
        for r in 0..rows {
            let run = &from[r * from_stride..][..cols];
            for (c, &x) in run.iter().enumerate() {
                to[c * to_stride + r] = x;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transpose_moves_every_entry_along_either_side() {
        // Both loop orders (rows <= cols and rows > cols), with and without whole tiles and
        // with a tile's remainder, strides past the block's side as the column buffers' are,
        // against the definition entry by entry; the cells between runs keep their sentinel.
        let shapes = [
            (3, 7),
            (7, 3),
            (1, 5),
            (5, 1),
            (4, 4),
            (16, 8),
            (8, 16),
            (3, 19),
            (19, 3),
            (16, 33),
            (33, 16),
        ];
        for (rows, cols) in shapes {
            // Both buffers end at their last run's last entry, as a block of the column
            // buffer does when it holds the last columns.
            let (from_stride, to_stride) = (cols + 2, rows + 3);
            let from: Vec<usize> = (0..(rows - 1) * from_stride + cols).collect();
            let mut to = vec![usize::MAX; (cols - 1) * to_stride + rows];
            transpose(&from, from_stride, (rows, cols), &mut to, to_stride);
            for c in 0..cols {
                for r in (0..to_stride).filter(|r| c * to_stride + r < to.len()) {
                    let expected = if r < rows {
                        r * from_stride + c
                    } else {
                        usize::MAX
                    };
                    assert_eq!(
                        to[c * to_stride + r],
                        expected,
                        "{rows} x {cols}: ({r}, {c})"
                    );
                }
            }
        }
    }
}
