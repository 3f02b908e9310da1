use rand::{Rng, SeedableRng};
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

use super::{
    Pair, RealRows, each_pair, each_value, lanes, pack, packed_len, tangle_pair, untangle_pair,
};
use crate::contact::transform::Real;

/// Even lengths whose half is even and odd (the middle bin alone, or none), a half with
/// an odd number of pairs (the lanes' last pair one at a time), odd lengths, a rough
/// window's padded rows (576) and the smallest rows.
const LENGTHS: [usize; 17] = [
    2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 18, 22, 26, 575, 576, 578,
];

/// Values in `T`'s precision (so a row narrows to them exactly), with exact zeros, equal
/// neighbours and opposite values, whose sums and differences in the untangling are zeros
/// of either sign.
fn values<T: Real>(rng: &mut rand::rngs::StdRng, len: usize) -> Vec<f64> {
    (0..len)
        .map(|i| match i % 7 {
            0 => 0.0,
            1 => -0.0,
            2 => 1.5,
            3 => -1.5,
            _ => T::narrow(rng.random_range(-1.0..1.0)).widen(),
        })
        .collect()
}

fn bits<T: Real>(z: &[Complex<T>]) -> Vec<(u64, u64)> {
    z.iter()
        .map(|c| (c.re.widen().to_bits(), c.im.widen().to_bits()))
        .collect()
}

/// The forward and the inverse transform of each length, against realfft's on the same
/// values, compared by their bits (the signs of zeros included).
fn as_realfft<T: Real>() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let mut real_planner = RealFftPlanner::<T>::new();
    for len in LENGTHS {
        let rows = RealRows::<T>::new(len, &mut FftPlanner::new());
        let mut scratch = vec![Complex::default(); rows.scratch_len()];
        let mut packed = vec![Complex::default(); packed_len(len)];
        let row = values::<T>(&mut rng, len);

        let r2c = real_planner.plan_fft_forward(len);
        let mut theirs = r2c.make_output_vec();
        let mut input: Vec<T> = row.iter().map(|&v| T::narrow(v)).collect();
        r2c.process(&mut input, &mut theirs).expect("lengths match");
        let mut ours = vec![Complex::default(); len / 2 + 1];
        pack(&row, &mut packed);
        rows.forward(&mut packed, &mut ours, &mut scratch);
        assert_eq!(bits(&ours), bits(&theirs), "forward, length {len}");

        // A spectrum with imaginary parts where a real row has none: realfft zeroes them
        // (and says so), the inverse here takes them as zero.
        let mut spectrum = theirs;
        spectrum.iter_mut().for_each(|z| z.im += T::narrow(0.25));
        let mut theirs_in = spectrum.clone();
        let c2r = real_planner.plan_fft_inverse(len);
        let mut theirs_out = c2r.make_output_vec();
        assert!(c2r.process(&mut theirs_in, &mut theirs_out).is_err());
        rows.inverse(&mut spectrum, &mut packed, &mut scratch);
        let mut ours = vec![0.0; len];
        each_value(&mut ours, &packed, |o, v| *o = v.widen());
        let ours: Vec<u64> = ours.iter().map(|v| v.to_bits()).collect();
        let theirs: Vec<u64> = theirs_out.iter().map(|v| v.widen().to_bits()).collect();
        assert_eq!(ours, theirs, "inverse, length {len}");
    }
}

#[test]
fn the_rows_transform_as_realfft_does_to_the_bit_in_double_precision() {
    as_realfft::<f64>();
}

#[test]
fn the_rows_transform_as_realfft_does_to_the_bit_in_single_precision() {
    as_realfft::<f32>();
}

#[test]
fn the_lanes_untangle_and_tangle_as_one_pair_at_a_time_to_the_bit() {
    // Bins of every kind of pair the lanes can meet: equal and opposite bins (zero sums
    // and differences of either sign), zeros of both signs, and random values, with an
    // even and an odd number of pairs. A lane that computed `-(x + y)` for `-x - y`, which
    // differs in the sign of a zero alone, failed here.
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let special = [0.0f32, -0.0, 1.0, -1.0, 0.5];
    for m in [8usize, 9, 10, 64, 65] {
        let pairs = m.div_ceil(2) - 1;
        let mut random =
            || Complex::new(rng.random_range(-2.0f32..2.0), rng.random_range(-2.0..2.0));
        // Zero twiddles, which no transform has, make zero terms the bins alone do not.
        let twiddles: Vec<Complex<f32>> = (0..pairs)
            .map(|c| match c % 3 {
                0 => Complex::new(special[c % 5], special[(c + 1) % 5]),
                _ => random(),
            })
            .collect();
        // Each pair (k, m - k) equal, opposite, conjugate or unrelated, in turn.
        let mut bins: Vec<Complex<f32>> = (0..=m).map(|_| random()).collect();
        for k in 1..=pairs {
            let a = match k % 3 {
                0 => Complex::new(special[k % 5], special[(k + 1) % 5]),
                _ => bins[k],
            };
            bins[k] = a;
            bins[m - k] = match k % 4 {
                0 => a,
                1 => -a,
                2 => a.conj(),
                _ => bins[m - k],
            };
        }
        type Lanes = fn(&mut [Complex<f32>], &[Complex<f32>]);
        type One = fn(Complex<f32>, Complex<f32>, Complex<f32>) -> Pair<f32>;
        let both: [(Lanes, One); 2] = [
            (lanes::untangle, untangle_pair),
            (lanes::tangle, tangle_pair),
        ];
        for (two, one) in both {
            let (mut two_at_a_time, mut one_at_a_time) = (bins.clone(), bins.clone());
            two(&mut two_at_a_time, &twiddles);
            each_pair(&mut one_at_a_time, &twiddles, one);
            assert_eq!(bits(&two_at_a_time), bits(&one_at_a_time), "m = {m}");
        }
    }
}

#[test]
fn a_row_transforms_to_its_discrete_fourier_transform_and_back() {
    // The definition summed term by term in f64. Both sides err by round-off bounded by the
    // row's absolute sum times the terms' count times the unit round-off (the direct sum's
    // bound, the larger; the FFT's grows as the logarithm of the length), so the tolerance
    // is `len` ulps of that sum.
    let mut rng = rand::rngs::StdRng::seed_from_u64(3);
    for len in LENGTHS {
        let rows = RealRows::<f64>::new(len, &mut FftPlanner::new());
        let mut scratch = vec![Complex::default(); rows.scratch_len()];
        let mut packed = vec![Complex::default(); packed_len(len)];
        let row: Vec<f64> = (0..len).map(|_| rng.random_range(-1.0..1.0)).collect();
        let tolerance = len as f64 * f64::EPSILON * row.iter().map(|v| v.abs()).sum::<f64>();
        let mut bins = vec![Complex::default(); len / 2 + 1];
        pack(&row, &mut packed);
        rows.forward(&mut packed, &mut bins, &mut scratch);
        for (k, bin) in bins.iter().enumerate() {
            let dft: Complex<f64> = row
                .iter()
                .enumerate()
                .map(|(j, &v)| {
                    let angle = -2.0 * std::f64::consts::PI * (j * k) as f64 / len as f64;
                    Complex::new(v * angle.cos(), v * angle.sin())
                })
                .sum();
            assert!((bin - dft).norm() <= tolerance, "length {len}, bin {k}");
        }
        rows.inverse(&mut bins, &mut packed, &mut scratch);
        let mut back = vec![0.0; len];
        each_value(&mut back, &packed, |o, v| *o = v);
        for (back, &v) in back.iter().zip(&row) {
            assert!((back / len as f64 - v).abs() <= tolerance, "length {len}");
        }
    }
}
