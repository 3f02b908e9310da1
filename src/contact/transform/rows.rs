//! The real rows' transforms: a real row of even length `2m` as the complex transform of
//! length `m` of its values taken in pairs, untangled into the row's `m + 1` bins (and
//! tangled back for the inverse); a row of odd length as a complex transform of its full
//! length. The algorithm and its arithmetic are realfft's (3.5, `RealToComplexEven` and
//! its kin), operation for operation, so the bins are the same to the bit (`tests`).
//!
//! Why not realfft itself: the untangling is a loop over the pairs of bins `(k, m - k)`
//! that realfft writes one pair at a time, and in single precision it cost more than the
//! complex transform it follows. Measured with a throwaway benchmark (rows of 576 reals,
//! `f32`, 200,000 transforms, `opt-level = 3`, the SSE2 the default build targets): the
//! complex transform took 212 ns, realfft's untangling about 300 ns, and the same
//! arithmetic two pairs at a time in `f32x4` lanes 145 ns. In double precision a lane
//! holds one bin, and the lanes took 221 to 234 ns against 224 to 268 ns one pair at a
//! time, so `f64` keeps the pair-at-a-time loop ([`Real::untangle`]). In the runs: 0.961
//! of realfft's CPU time on the 4 um rough disc (f32) and 1.003 on the smooth disc (f64),
//! the same results to the bit (`docs/accuracy.md`, "The real rows' untangling").

use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

use super::Real;

/// The planned transforms of real rows of one length, forward and inverse.
pub(crate) struct RealRows<T: Real> {
    len: usize,
    forward: Arc<dyn Fft<T>>,
    inverse: Arc<dyn Fft<T>>,
    /// Even lengths: `e^(-2 pi i k / len) / 2` for `k = 1..`, one per pair the forward
    /// transform untangles.
    untangling: Vec<Complex<T>>,
    /// Even lengths: `e^(2 pi i k / len)`, one per pair the inverse transform tangles.
    tangling: Vec<Complex<T>>,
    scratch_len: usize,
}

impl<T: Real> RealRows<T> {
    /// The transforms of real rows of `len` values, planned with `planner`.
    pub(crate) fn new(len: usize, planner: &mut FftPlanner<T>) -> Self {
        let even = len.is_multiple_of(2);
        let complex_len = if even { len / 2 } else { len };
        let forward = planner.plan_fft_forward(complex_len);
        let inverse = planner.plan_fft_inverse(complex_len);
        let (untangling, tangling, scratch_len) = if even {
            // The pairs (k, m - k) below the middle: k < len / 4.
            let pairs = len.div_ceil(4).saturating_sub(1);
            let half = T::narrow(0.5);
            let turn = |k| twiddle::<T>(k, len);
            (
                (1..=pairs).map(|k| turn(k) * half).collect(),
                (1..=pairs).map(|k| turn(k).conj()).collect(),
                forward
                    .get_outofplace_scratch_len()
                    .max(inverse.get_outofplace_scratch_len()),
            )
        } else {
            let inplace = forward
                .get_inplace_scratch_len()
                .max(inverse.get_inplace_scratch_len());
            (Vec::new(), Vec::new(), len + inplace)
        };
        Self {
            len,
            forward,
            inverse,
            untangling,
            tangling,
            scratch_len,
        }
    }

    /// The scratch [`Self::forward`] and [`Self::inverse`] need.
    pub(crate) fn scratch_len(&self) -> usize {
        self.scratch_len
    }

    /// The `len / 2 + 1` bins of the row held in pairs in `packed` (used up as work space)
    /// into `out`.
    pub(crate) fn forward(
        &self,
        packed: &mut [Complex<T>],
        out: &mut [Complex<T>],
        scratch: &mut [Complex<T>],
    ) {
        let m = packed.len();
        if !self.len.is_multiple_of(2) {
            let (full, scratch) = scratch.split_at_mut(self.len);
            for (slots, z) in full.chunks_mut(2).zip(packed.iter()) {
                slots[0] = Complex::new(z.re, T::default());
                if let Some(slot) = slots.get_mut(1) {
                    *slot = Complex::new(z.im, T::default());
                }
            }
            self.forward.process_with_scratch(full, scratch);
            out.copy_from_slice(&full[..out.len()]);
            out[0].im = T::default();
            return;
        }
        self.forward
            .process_outofplace_with_scratch(packed, &mut out[..m], scratch);
        // The first bin's real and imaginary parts are the sums of the even and the odd
        // values: their sum and difference are the bins 0 and m, both real.
        let first = out[0];
        out[0] = Complex::new(first.re + first.im, T::default());
        out[m] = Complex::new(first.re - first.im, T::default());
        T::untangle(out, &self.untangling);
        if m.is_multiple_of(2) {
            out[m / 2].im = -out[m / 2].im;
        }
    }

    /// The real row of the `len / 2 + 1` bins `spectrum` (used up as work space), held in
    /// pairs into `packed`. The imaginary parts the bins of a real row cannot have (of
    /// bin 0, and of bin `len / 2` at an even length) are taken as zero.
    pub(crate) fn inverse(
        &self,
        spectrum: &mut [Complex<T>],
        packed: &mut [Complex<T>],
        scratch: &mut [Complex<T>],
    ) {
        spectrum[0].im = T::default();
        if !self.len.is_multiple_of(2) {
            let (full, scratch) = scratch.split_at_mut(self.len);
            full[..spectrum.len()].copy_from_slice(spectrum);
            let mirrored = full.iter_mut().rev().take(self.len / 2);
            mirrored
                .zip(&spectrum[1..])
                .for_each(|(z, bin)| *z = bin.conj());
            self.inverse.process_with_scratch(full, scratch);
            for (pair, values) in packed.iter_mut().zip(full.chunks(2)) {
                let second = values.get(1).map_or(T::default(), |z| z.re);
                *pair = Complex::new(values[0].re, second);
            }
            return;
        }
        let m = packed.len();
        spectrum[m].im = T::default();
        let (first, last) = (spectrum[0], spectrum[m]);
        let (sum, diff) = (first + last, first - last);
        spectrum[0] = Complex::new(sum.re - sum.im, diff.re - diff.im);
        T::tangle(spectrum, &self.tangling);
        if m.is_multiple_of(2) {
            let middle = spectrum[m / 2];
            spectrum[m / 2] = (middle + middle).conj();
        }
        self.inverse
            .process_outofplace_with_scratch(&mut spectrum[..m], packed, scratch);
    }
}

/// `e^(-2 pi i index / len)`, computed in `f64` and rounded, as realfft computes its.
fn twiddle<T: Real>(index: usize, len: usize) -> Complex<T> {
    let angle = -2.0 * std::f64::consts::PI / len as f64 * index as f64;
    Complex::new(T::narrow(angle.cos()), T::narrow(angle.sin()))
}

/// The length of a row of `len` values held in pairs ([`pack`]): `len / 2`, rounded up.
pub(crate) fn packed_len(len: usize) -> usize {
    len.div_ceil(2)
}

/// `row` held in pairs in `packed`, in its precision: `packed[j]` is
/// `row[2j] + i row[2j + 1]`, zero past the row's end (a row zero-padded to the
/// transform's length).
pub(crate) fn pack<T: Real>(row: &[f64], packed: &mut [Complex<T>]) {
    let pairs = row.chunks_exact(2);
    let last = pairs.remainder().first();
    let whole = pairs.len();
    for (z, pair) in packed.iter_mut().zip(pairs) {
        *z = Complex::new(T::narrow(pair[0]), T::narrow(pair[1]));
    }
    let rest = &mut packed[whole..];
    rest.fill(Complex::default());
    if let (Some(&value), Some(z)) = (last, rest.first_mut()) {
        z.re = T::narrow(value);
    }
}

/// Each of the first `out.len()` values of the row held in pairs in `packed`, `put` into
/// its place in `out`.
pub(crate) fn each_value<T: Real>(
    out: &mut [f64],
    packed: &[Complex<T>],
    put: impl Fn(&mut f64, T),
) {
    let last = out.len() / 2;
    let mut pairs = out.chunks_exact_mut(2);
    for (slots, z) in (&mut pairs).zip(packed) {
        put(&mut slots[0], z.re);
        put(&mut slots[1], z.im);
    }
    if let [slot] = pairs.into_remainder() {
        put(slot, packed[last].re);
    }
}

/// Two bins, `k` and `m - k`.
pub(super) type Pair<T> = (Complex<T>, Complex<T>);

/// The forward transform's untangling of bins `k` (`a`) and `m - k` (`b`) of the packed
/// transform, with the halved twiddle `w`: bins `k` and `m - k` of the real row.
#[inline(always)]
pub(super) fn untangle_pair<T: Real>(a: Complex<T>, b: Complex<T>, w: Complex<T>) -> Pair<T> {
    let (sum, diff, (turned_re, turned_im)) = sum_diff_turned(a, b, w);
    let half = T::narrow(0.5);
    let (half_sum_re, half_diff_im) = (half * sum.re, half * diff.im);
    (
        Complex::new(half_sum_re + turned_re, half_diff_im + turned_im),
        Complex::new(half_sum_re - turned_re, turned_im - half_diff_im),
    )
}

/// The inverse transform's tangling of bins `k` (`a`) and `m - k` (`b`) of a real row's
/// spectrum with the twiddle `w`: bins `k` and `m - k` of the packed transform.
#[inline(always)]
pub(super) fn tangle_pair<T: Real>(a: Complex<T>, b: Complex<T>, w: Complex<T>) -> Pair<T> {
    let (sum, diff, (turned_re, turned_im)) = sum_diff_turned(a, b, w);
    (
        Complex::new(sum.re - turned_re, diff.im - turned_im),
        Complex::new(sum.re + turned_re, -turned_im - diff.im),
    )
}

/// What both directions share: the bins' sum and difference, and the twiddled part
/// `sum.im w.re + diff.re w.im`, `sum.im w.im - diff.re w.re`.
#[inline(always)]
fn sum_diff_turned<T: Real>(
    a: Complex<T>,
    b: Complex<T>,
    w: Complex<T>,
) -> (Complex<T>, Complex<T>, (T, T)) {
    let (sum, diff) = (a + b, a - b);
    let turned = (
        sum.im * w.re + diff.re * w.im,
        sum.im * w.im - diff.re * w.re,
    );
    (sum, diff, turned)
}

/// Each pair of bins `(k, m - k)`, `k = 1..=twiddles.len()`, of `bins` (`m + 1` of them)
/// through `pair` with its twiddle, one pair at a time.
pub(super) fn each_pair<T: Real>(
    bins: &mut [Complex<T>],
    twiddles: &[Complex<T>],
    pair: impl Fn(Complex<T>, Complex<T>, Complex<T>) -> Pair<T>,
) {
    // Bins 1.. below the middle with bins m - 1, m - 2, ... above it, as slices (indexed
    // pair by pair, the smooth disc's 600 cycles took 1.058 of the CPU time of realfft's
    // loop in f64, `scripts/rough_ab.py --scene`, 9 pairs).
    let (low, high) = bins.split_at_mut(bins.len() / 2);
    let high_len = high.len();
    let pairs = low[1..]
        .iter_mut()
        .zip(high[..high_len - 1].iter_mut().rev());
    for ((a, b), &w) in pairs.zip(twiddles) {
        (*a, *b) = pair(*a, *b, w);
    }
}

pub(super) mod lanes;
#[cfg(test)]
mod tests;
