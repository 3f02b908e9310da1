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

/// The floating-point type a transform computes in: `f64`, or `f32` where a solve's
/// tolerance leaves room for its round-off (`SINGLE_PRECISION_MIN_TOLERANCE`). Fields go in
/// and come out as `f64` either way (`load_row`, `store_row`).
pub trait Real: rustfft::FftNum + rustfft::num_traits::NumAssign + Default {
    /// `value` rounded to this type.
    fn narrow(value: f64) -> Self;
    /// This value as an `f64`, exactly.
    fn widen(self) -> f64;
}

impl Real for f64 {
    fn narrow(value: f64) -> Self {
        value
    }
    fn widen(self) -> f64 {
        self
    }
}

impl Real for f32 {
    fn narrow(value: f64) -> Self {
        value as f32
    }
    fn widen(self) -> f64 {
        f64::from(self)
    }
}

/// Rows moved per block between the row and the column layouts.
pub(crate) const BLOCK: usize = 16;

/// Padding of the column stride, in complex entries (128 bytes).
pub(crate) const STRIDE_PAD: usize = 8;

/// The complex-to-real transform of one row's half spectrum `row` into `real`.
pub(crate) fn inverse_row<T: Real>(plans: &mut Plans<T>, row: &mut [Complex<T>], real: &mut [T]) {
    // The DC and (at an even length) Nyquist bins of a real signal are real; round-off
    // leaves tiny imaginary parts that realfft rejects.
    row[0].im = T::default();
    if real.len().is_multiple_of(2) {
        if let Some(nyquist) = row.last_mut() {
            nyquist.im = T::default();
        }
    }
    plans
        .row_inverse
        .process_with_scratch(row, real, &mut plans.real_scratch)
        .expect("imaginary parts of DC and Nyquist zeroed above");
}

/// `row` into the start of `padded` in its precision, the rest of `padded` zero.
pub(crate) fn load_row<T: Real>(padded: &mut [T], row: &[f64]) {
    let (head, tail) = padded.split_at_mut(row.len());
    head.iter_mut()
        .zip(row)
        .for_each(|(p, &v)| *p = T::narrow(v));
    tail.fill(T::default());
}

/// The first `out.len()` values of `real` into `out`.
pub(crate) fn store_row<T: Real>(out: &mut [f64], real: &[T]) {
    out.iter_mut().zip(real).for_each(|(o, &v)| *o = v.widen());
}
