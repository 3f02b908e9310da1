//! Planned 2D FFTs: the row (real, [`RealRows`]) and column (complex) transforms with their
//! scratch, planned once per grid and shared by the DC-FFT operator, its preconditioner and
//! the benchmark's FFT pair.

use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::{Real, RealRows};

/// Planned row (real, forward and inverse) and column (complex) transforms of a 2D FFT,
/// with the scratch they need. A clone shares the transforms and has its own scratch.
#[derive(Clone)]
pub(crate) struct Plans<T: Real = f64> {
    pub(crate) rows: Arc<RealRows<T>>,
    pub(crate) col_forward: Arc<dyn Fft<T>>,
    pub(crate) col_inverse: Arc<dyn Fft<T>>,
    pub(crate) row_scratch: Vec<Complex<T>>,
    pub(crate) complex_scratch: Vec<Complex<T>>,
}

impl<T: Real> Plans<T> {
    /// Plans rows of `row_len` reals and columns of `col_len` complex values.
    pub(crate) fn new(row_len: usize, col_len: usize) -> Self {
        let mut planner = FftPlanner::<T>::new();
        let rows = RealRows::new(row_len, &mut planner);
        let col_forward = planner.plan_fft_forward(col_len);
        let col_inverse = planner.plan_fft_inverse(col_len);
        let complex_scratch_len = col_forward
            .get_inplace_scratch_len()
            .max(col_inverse.get_inplace_scratch_len());
        Self {
            row_scratch: vec![Complex::default(); rows.scratch_len()],
            rows: Arc::new(rows),
            col_forward,
            col_inverse,
            complex_scratch: vec![Complex::default(); complex_scratch_len],
        }
    }
}

/// Smallest even `2^i 3^j >= n` (`i >= 1`): sizes rustfft transforms fastest, and even so
/// the apex sits on a cell corner and a grown grid adds the same cells on both sides.
pub fn fft_friendly(n: usize) -> usize {
    let mut best = usize::MAX;
    let mut three = 1;
    while three < 2 * n {
        let mut size = 2 * three;
        while size < n {
            size *= 2;
        }
        best = best.min(size);
        three *= 3;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fft_friendly_sizes() {
        assert_eq!(fft_friendly(255), 256);
        assert_eq!(fft_friendly(257), 288);
        assert_eq!(fft_friendly(100), 108);
        assert_eq!(fft_friendly(8), 8);
        assert_eq!(fft_friendly(80), 96, "81 = 3^4 is odd");
        assert_eq!(fft_friendly(3), 4);
    }
}
