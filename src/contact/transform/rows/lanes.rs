//! [`Real::untangle`](super::super::Real::untangle) and
//! [`Real::tangle`](super::super::Real::tangle) in single precision, two pairs of bins at a
//! time: bins `k` and `k + 1` in one `f32x4`, `m - k` and `m - k - 1` in another, each
//! lane's arithmetic [`super::untangle_pair`]'s or [`super::tangle_pair`]'s operation for
//! operation. A difference `x - y` stays a difference in the lanes (never `x + (-y)` with
//! the terms swapped), so even the signs of zeros are the same (`tests`).

use rustfft::num_complex::Complex;
use wide::f32x4;

use super::{Pair, each_pair, tangle_pair, untangle_pair};

/// The forward transform's untangling of the pairs `(k, m - k)` of `bins` with `twiddles`.
pub(in crate::contact::transform) fn untangle(
    bins: &mut [Complex<f32>],
    twiddles: &[Complex<f32>],
) {
    two_at_a_time(bins, twiddles, untangle_two, untangle_pair);
}

/// The inverse transform's tangling of the pairs `(k, m - k)` of `bins` with `twiddles`.
pub(in crate::contact::transform) fn tangle(bins: &mut [Complex<f32>], twiddles: &[Complex<f32>]) {
    two_at_a_time(bins, twiddles, tangle_two, tangle_pair);
}

/// Bins `k` and `k + 1` (`a`), and `m - k` and `m - k - 1` (`b`), with their twiddles `w`,
/// through `two`; the last pair, if their number is odd, through `one`.
fn two_at_a_time(
    bins: &mut [Complex<f32>],
    twiddles: &[Complex<f32>],
    two: impl Fn(f32x4, f32x4, f32x4) -> (f32x4, f32x4),
    one: impl Fn(Complex<f32>, Complex<f32>, Complex<f32>) -> Pair<f32>,
) {
    let m = bins.len() - 1;
    let whole = twiddles.len() - twiddles.len() % 2;
    for c in (0..whole).step_by(2) {
        let k = c + 1;
        let a = lanes(bins[k], bins[k + 1]);
        let b = lanes(bins[m - k], bins[m - k - 1]);
        let (low, high) = two(a, b, lanes(twiddles[c], twiddles[c + 1]));
        [bins[k], bins[k + 1]] = unlanes(low);
        [bins[m - k], bins[m - k - 1]] = unlanes(high);
    }
    each_pair(&mut bins[whole..=m - whole], &twiddles[whole..], one);
}

/// Two pairs of [`untangle_pair`].
#[inline(always)]
fn untangle_two(a: f32x4, b: f32x4, w: f32x4) -> (f32x4, f32x4) {
    let (sum, diff) = (a + b, a - b);
    let turned = turned(sum, diff, w);
    let (s, d) = (sum.to_array(), diff.to_array());
    // `half sum.re` and `half diff.im`, one pair's in each half.
    let halves = f32x4::splat(0.5) * f32x4::from([s[0], d[1], s[2], d[3]]);
    let (h, t) = (halves.to_array(), turned.to_array());
    let high = f32x4::from([h[0], t[1], h[2], t[3]]) - f32x4::from([t[0], h[1], t[2], h[3]]);
    (halves + turned, high)
}

/// Two pairs of [`tangle_pair`].
#[inline(always)]
fn tangle_two(a: f32x4, b: f32x4, w: f32x4) -> (f32x4, f32x4) {
    let (sum, diff) = (a + b, a - b);
    let turned = turned(sum, diff, w);
    let (s, d, t) = (sum.to_array(), diff.to_array(), turned.to_array());
    let low = f32x4::from([s[0], d[1], s[2], d[3]]) - turned;
    // `sum.re - (-turned.re)` is `sum.re + turned.re` exactly, and `-turned.im - diff.im`
    // is the pair's own difference.
    let high = f32x4::from([s[0], -t[1], s[2], -t[3]]) - f32x4::from([-t[0], d[1], -t[2], d[3]]);
    (low, high)
}

/// The twiddled part of [`super::sum_diff_turned`] for two pairs: `sum.im w.re +
/// diff.re w.im` in the real lanes and `sum.im w.im + diff.re (-w.re)`, which is
/// `sum.im w.im - diff.re w.re` exactly (a product's sign is its factors'), in the
/// imaginary ones.
#[inline(always)]
fn turned(sum: f32x4, diff: f32x4, w: f32x4) -> f32x4 {
    let (s, d, w) = (sum.to_array(), diff.to_array(), w.to_array());
    let sum_im = f32x4::from([s[1], s[1], s[3], s[3]]);
    let diff_re = f32x4::from([d[0], d[0], d[2], d[2]]);
    let w_turned = f32x4::from([w[1], -w[0], w[3], -w[2]]);
    sum_im * f32x4::from(w) + diff_re * w_turned
}

/// Two bins in one vector: `[x.re, x.im, y.re, y.im]`.
#[inline(always)]
fn lanes(x: Complex<f32>, y: Complex<f32>) -> f32x4 {
    f32x4::from([x.re, x.im, y.re, y.im])
}

/// The two bins of a vector of [`lanes`].
#[inline(always)]
fn unlanes(v: f32x4) -> [Complex<f32>; 2] {
    let v = v.to_array();
    [Complex::new(v[0], v[1]), Complex::new(v[2], v[3])]
}
