//! The yardstick of the contact benchmark: one forward and one inverse real 2D FFT of the
//! full zero-padded `2N x 2N` grid, done the plain way (every row transformed, no pruning,
//! no kernel product) but with the same blocked transposes and padded column stride as the
//! operator, so the ratio measures the solver's work, not a slow baseline.

use rustfft::num_complex::Complex;

use crate::contact::{BLOCK, Plans, column_stride, each_value, pack, packed_len, transpose};

/// A planned padded FFT round trip for an `N x N` grid.
pub struct FftPair {
    len: usize,
    half: usize,
    stride: usize,
    plans: Plans,
    data: Vec<f64>,
    /// One row held in pairs.
    packed: Vec<Complex<f64>>,
    block: Vec<Complex<f64>>,
    columns: Vec<Complex<f64>>,
}

impl FftPair {
    /// Plans the transforms of the `2n x 2n` padded grid.
    pub fn new(n: usize) -> Self {
        let (len, half) = (2 * n, n + 1);
        let stride = column_stride(len);
        Self {
            len,
            half,
            stride,
            plans: Plans::new(len, len),
            data: (0..len * len).map(|i| (i % 17) as f64).collect(),
            packed: vec![Complex::default(); packed_len(len)],
            block: vec![Complex::default(); BLOCK * half],
            columns: vec![Complex::default(); half * stride],
        }
    }

    /// One forward and one inverse transform of the whole padded grid.
    pub fn round_trip(&mut self) {
        let (len, half, stride) = (self.len, self.half, self.stride);
        for first in (0..len).step_by(BLOCK) {
            for slot in 0..BLOCK {
                pack(&self.data[(first + slot) * len..][..len], &mut self.packed);
                let out = &mut self.block[slot * half..][..half];
                let scratch = &mut self.plans.row_scratch;
                self.plans.rows.forward(&mut self.packed, out, scratch);
            }
            let columns = &mut self.columns[first..];
            transpose(&self.block, half, (BLOCK, half), columns, stride);
        }
        for column in self.columns.chunks_exact_mut(stride) {
            let column = &mut column[..len];
            self.plans
                .col_forward
                .process_with_scratch(column, &mut self.plans.complex_scratch);
            self.plans
                .col_inverse
                .process_with_scratch(column, &mut self.plans.complex_scratch);
        }
        for first in (0..len).step_by(BLOCK) {
            let columns = &self.columns[first..];
            transpose(columns, stride, (half, BLOCK), &mut self.block, half);
            for slot in 0..BLOCK {
                let spectrum = &mut self.block[slot * half..][..half];
                let scratch = &mut self.plans.row_scratch;
                self.plans.rows.inverse(spectrum, &mut self.packed, scratch);
                let row = &mut self.data[(first + slot) * len..][..len];
                each_value(row, &self.packed, |v, re| *v = re);
            }
        }
        // Undo the unnormalised round trip's growth so repeated calls stay finite.
        let scale = 1.0 / (len * len) as f64;
        self.data.iter_mut().for_each(|v| *v *= scale);
    }
}
