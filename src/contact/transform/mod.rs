//! The 2D FFT machinery the DC-FFT operator ([`super::DcFft`]), its Fourier preconditioner
//! ([`super::FourierInverse`]) and the benchmark's FFT pair share: the planned transforms
//! ([`Plans`]), the transposed layout they move rows and columns through (blocks of
//! [`BLOCK`] rows, columns [`STRIDE_PAD`] entries apart beyond their length), the inverse
//! row transform, and the passes split across threads ([`Split`]) with the thread counts
//! that choose them. It knows neither operator, so both use it without using each other.
//!
//! Rows move between the row and the column layouts in blocks of [`BLOCK`] rows, so each
//! transposed write touches `BLOCK` consecutive entries instead of one. Columns are
//! [`STRIDE_PAD`] entries longer than the transform: a power-of-two stride maps every
//! column start to the same cache sets, which made the transposes several times slower.

mod plans;
mod split;

use rustfft::num_complex::Complex;

pub(crate) use plans::Plans;
pub use plans::fft_friendly;
pub use split::{MAX_SPLIT_THREADS, SPLIT_MIN_CELLS, split_threads};
pub(crate) use split::{Split, periodic_threads};

/// Rows moved per block between the row and the column layouts.
pub(crate) const BLOCK: usize = 16;

/// Padding of the column stride, in complex entries (128 bytes).
pub(crate) const STRIDE_PAD: usize = 8;

/// The complex-to-real transform of one row's half spectrum `row` into `real`.
pub(crate) fn inverse_row(plans: &mut Plans, row: &mut [Complex<f64>], real: &mut [f64]) {
    // The DC and (at an even length) Nyquist bins of a real signal are real; round-off
    // leaves tiny imaginary parts that realfft rejects.
    row[0].im = 0.0;
    if real.len().is_multiple_of(2) {
        if let Some(nyquist) = row.last_mut() {
            nyquist.im = 0.0;
        }
    }
    plans
        .row_inverse
        .process_with_scratch(row, real, &mut plans.real_scratch)
        .expect("imaginary parts of DC and Nyquist zeroed above");
}
