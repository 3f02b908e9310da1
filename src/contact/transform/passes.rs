//! The passes of a 2D FFT convolution on one thread, and the buffers they work in, for the
//! DC-FFT operator (rows and columns zero-padded to twice the grid) and the periodic
//! [`crate::contact::FourierInverse`] (no padding). How they run on several threads:
//! [`super::Split`]; which of the two an operator runs: [`Threads`].
//!
//! The row transforms go into the row spectra, a row-major buffer of `ny` rows of
//! `row_len / 2 + 1` bins. The columns are gathered from it [`BLOCK`] at a time into a block
//! of columns `stride` apart, zero-padded to `col_len`, transformed, multiplied by the
//! kernel's spectrum and transformed back, and the first `ny` entries of each (the rows
//! whose output is kept) are scattered back to where they came from. The inverse row
//! transforms then read the row spectra again.
//!
//! Why the row spectra and not a buffer of all the padded columns (for the DC-FFT
//! operator): they take half its memory, so on a rough disc's windows they stay in the
//! core's 1 MB of L2 where all the columns would not (a 288-cell window: 0.67 MB of row
//! spectra against 1.35 MB of padded columns 584 apart, `Complex<f32>`), and each column's
//! zero half is filled in the block of 16 columns (75 KB at that size). The 4 um rough disc
//! took 0.891 of the CPU time of the buffer of all the columns, with the same results to
//! the bit (`docs/accuracy.md`, "The columns a block at a time, through the row spectra").

use rustfft::num_complex::Complex;

use super::split::{ColumnProduct, RowPut};
use super::{
    BLOCK, Plans, Real, Split, column_stride, forward_row, inverse_row, packed_len, store_row,
    transpose,
};

/// Where an operator's passes run, with their buffers: on one thread, or split across
/// threads with the buffer of all the columns the split passes work in, `stride` apart.
pub(crate) enum Threads<T: Real> {
    One(Passes<T>),
    Split(Split<T>, Vec<Complex<T>>),
}

impl<T: Real> Threads<T> {
    /// The passes of an `nx` x `ny` grid transformed at `row_len` x `col_len` (the grid's
    /// size, or more when zero-padded), with `plans` planned at those lengths, on `threads`
    /// threads.
    pub(crate) fn new(
        (nx, ny): (usize, usize),
        (row_len, col_len): (usize, usize),
        plans: &Plans<T>,
        threads: usize,
    ) -> Self {
        if threads > 1 {
            let half = row_len / 2 + 1;
            let split = Split::new(threads, plans, row_len, ny);
            Self::Split(
                split,
                vec![Complex::default(); half * column_stride(col_len)],
            )
        } else {
            Self::One(Passes::new((nx, ny), (row_len, col_len)))
        }
    }

    /// The number of threads.
    pub(crate) fn threads(&self) -> usize {
        match self {
            Self::One(_) => 1,
            Self::Split(split, _) => split.threads(),
        }
    }

    /// `output = K input` on the `nx` x `ny` grid, its columns transformed at `col_len`:
    /// the rows forward, `product` on each column of the spectrum between its forward and
    /// inverse transforms, the rows back; on one thread or split, as these passes run.
    pub(crate) fn convolve(
        &mut self,
        plans: &mut Plans<T>,
        ((nx, ny), col_len): ((usize, usize), usize),
        product: ColumnProduct<T>,
        (input, output): (&[f64], &mut [f64]),
    ) {
        match self {
            Self::Split(split, columns) => {
                let shape = (nx, ny, col_len, column_stride(col_len));
                split.apply(shape, product, columns, input, output);
            }
            Self::One(passes) => {
                passes.forward_rows(plans, input);
                let both = Transforms {
                    forward: true,
                    inverse: true,
                };
                passes.columns(plans, both, None, product);
                passes.inverse_rows(plans, output, store_row);
            }
        }
    }
}

/// The sizes of a one-thread apply and the buffers it works in.
pub(crate) struct Passes<T> {
    nx: usize,
    ny: usize,
    /// Half-spectrum row length `row_len / 2 + 1`.
    half: usize,
    /// Column length, `ny` or more when zero-padded.
    col_len: usize,
    /// Distance between column starts in the block ([`column_stride`]).
    stride: usize,
    /// The row transforms, row-major: `ny` rows of `half` bins.
    spectra: Vec<Complex<T>>,
    /// [`BLOCK`] columns in flight, `stride` apart.
    block: Vec<Complex<T>>,
    /// One zero-padded real row, held in pairs.
    row_packed: Vec<Complex<T>>,
}

/// Which transforms of the column pass run: the forward one (the columns gathered from the
/// row spectra first), and the inverse one (the columns scattered back after).
#[derive(Clone, Copy)]
pub(crate) struct Transforms {
    pub(crate) forward: bool,
    pub(crate) inverse: bool,
}

impl<T: Real> Passes<T> {
    /// Buffers for an `nx` x `ny` grid transformed at `row_len` x `col_len`.
    pub(crate) fn new((nx, ny): (usize, usize), (row_len, col_len): (usize, usize)) -> Self {
        let (half, stride) = (row_len / 2 + 1, column_stride(col_len));
        Self {
            nx,
            ny,
            half,
            col_len,
            stride,
            spectra: vec![Complex::default(); ny * half],
            block: vec![Complex::default(); BLOCK * stride],
            row_packed: vec![Complex::default(); packed_len(row_len)],
        }
    }

    /// The row transforms of `input` into the row spectra.
    pub(crate) fn forward_rows(&mut self, plans: &mut Plans<T>, input: &[f64]) {
        let rows = input.chunks_exact(self.nx);
        for (row, out) in rows.zip(self.spectra.chunks_exact_mut(self.half)) {
            forward_row(plans, row, &mut self.row_packed, out);
        }
    }

    /// The column pass, [`BLOCK`] columns at a time: `each` gets every column's index and
    /// its `col_len` entries, transformed forward from the row spectra if `forward` (else as
    /// the last block left them, for `each` to fill), and the inverse transform of what it
    /// leaves goes back into the row spectra if `inverse`. The blocks are worked on in the
    /// block buffer, or in place in `all` (every column, `stride` apart), which keeps them.
    pub(crate) fn columns(
        &mut self,
        plans: &mut Plans<T>,
        transforms: Transforms,
        mut all: Option<&mut [Complex<T>]>,
        mut each: impl FnMut(usize, &mut [Complex<T>]),
    ) {
        let (ny, half, stride) = (self.ny, self.half, self.stride);
        for k0 in (0..half).step_by(BLOCK) {
            let width = BLOCK.min(half - k0);
            let block = match all.as_deref_mut() {
                Some(all) => &mut all[k0 * stride..][..width * stride],
                None => &mut self.block[..width * stride],
            };
            if transforms.forward {
                transpose(&self.spectra[k0..], half, (ny, width), block, stride);
            }
            for (j, column) in block.chunks_mut(stride).enumerate() {
                let column = &mut column[..self.col_len];
                if transforms.forward {
                    column[ny..].fill(Complex::default());
                    plans
                        .col_forward
                        .process_with_scratch(column, &mut plans.complex_scratch);
                }
                each(k0 + j, column);
                if transforms.inverse {
                    plans
                        .col_inverse
                        .process_with_scratch(column, &mut plans.complex_scratch);
                }
            }
            if transforms.inverse {
                transpose(block, stride, (width, ny), &mut self.spectra[k0..], half);
            }
        }
    }

    /// The inverse row transforms of the row spectra, each row `put` into `output`.
    pub(crate) fn inverse_rows(
        &mut self,
        plans: &mut Plans<T>,
        output: &mut [f64],
        put: RowPut<T>,
    ) {
        let rows = self.spectra.chunks_exact_mut(self.half);
        for (row, out) in rows.zip(output.chunks_exact_mut(self.nx)) {
            inverse_row(plans, row, &mut self.row_packed);
            put(out, &self.row_packed);
        }
    }
}
