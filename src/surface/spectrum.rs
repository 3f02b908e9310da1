//! The 2D discrete Fourier transform of a map (rows, then columns, with rustfft) and the
//! wavevectors of its entries.

use std::f64::consts::PI;

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// The transform of `field` (`nx * ny`, row-major) in place; `inverse` for the inverse,
/// unnormalised both ways.
pub(super) fn fft_2d(field: &mut [Complex<f64>], nx: usize, ny: usize, inverse: bool) {
    let mut planner = FftPlanner::<f64>::new();
    let (rows, cols) = if inverse {
        (planner.plan_fft_inverse(nx), planner.plan_fft_inverse(ny))
    } else {
        (planner.plan_fft_forward(nx), planner.plan_fft_forward(ny))
    };
    for row in field.chunks_exact_mut(nx) {
        rows.process(row);
    }
    let mut column = vec![Complex::default(); ny];
    for ix in 0..nx {
        for (iy, c) in column.iter_mut().enumerate() {
            *c = field[iy * nx + ix];
        }
        cols.process(&mut column);
        for (iy, c) in column.iter().enumerate() {
            field[iy * nx + ix] = *c;
        }
    }
}

/// The signed wavenumber of index `k` of an `n`-point transform over a side `side_m`,
/// rad/m.
pub(super) fn wavenumber(k: usize, n: usize, side_m: f64) -> f64 {
    let signed = if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    };
    2.0 * PI * signed / side_m
}

/// |q| of each entry of an `nx` x `ny` transform over `width_m` x `height_m`, row-major.
pub(super) fn wavevector_norms(nx: usize, ny: usize, width_m: f64, height_m: f64) -> Vec<f64> {
    let mut q = Vec::with_capacity(nx * ny);
    for ky in 0..ny {
        let qy = wavenumber(ky, ny, height_m);
        q.extend((0..nx).map(|kx| wavenumber(kx, nx, width_m).hypot(qy)));
    }
    q
}
