//! The elastic half-space under a periodic pressure: each Fourier mode of wavevector q
//! displaces the surface by `2 p(q) / (E* |q|)` (Johnson, Contact Mechanics, Section 13.2;
//! the spectral operator of Stanley & Kato, J. Tribol. 1997, and of Tamaas's Westergaard
//! operator). It is the operator of a rough flat pressed on a rough flat with the map
//! repeating beyond its sides, the setting in which the real contact area of rough surfaces
//! is studied; its exact inverse is the preconditioner. The mean displacement (q = 0) is
//! left at zero: the approach absorbs it.

use super::operator::{Operator, Preconditioner};
use super::precondition::FourierInverse;

/// The periodic half-space operator of an `nx` x `ny` grid.
#[derive(Debug)]
pub struct PeriodicHalfSpace {
    nx: usize,
    ny: usize,
    forward: FourierInverse,
    inverse: FourierInverse,
}

impl PeriodicHalfSpace {
    /// The operator on `nx` x `ny` cells of `dx` x `dy` m, for the reduced modulus
    /// `reduced_modulus_pa` (E*, eq. 6).
    pub fn new(nx: usize, ny: usize, dx: f64, dy: f64, reduced_modulus_pa: f64) -> Self {
        let e = reduced_modulus_pa;
        Self {
            nx,
            ny,
            forward: FourierInverse::multiplier(nx, ny, (dx, dy), |qx, qy| {
                2.0 / (e * qx.hypot(qy))
            }),
            inverse: FourierInverse::multiplier(nx, ny, (dx, dy), |qx, qy| e * qx.hypot(qy) / 2.0),
        }
    }
}

impl Operator for PeriodicHalfSpace {
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    fn apply(&mut self, input: &[f64], output: &mut [f64]) {
        self.forward.apply(input, output);
    }

    fn preconditioner(&mut self) -> Option<&mut dyn Preconditioner> {
        Some(&mut self.inverse)
    }

    fn is_periodic(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cosine_pressure_gives_johnsons_displacement() {
        // p = p0 cos(2 pi x / L) over L = 32 cells: u = 2 p0 cos / (E* 2 pi / L).
        let (n, d, e, p0) = (32, 1e-6, 100e9, 1e6);
        let l = n as f64 * d;
        let q = std::f64::consts::TAU / l;
        let p: Vec<f64> = (0..n * n)
            .map(|i| p0 * (q * (i % n) as f64 * d).cos())
            .collect();
        let mut u = vec![0.0; n * n];
        PeriodicHalfSpace::new(n, n, d, d, e).apply(&p, &mut u);
        for (i, &ui) in u.iter().enumerate() {
            let want = 2.0 * p0 * (q * (i % n) as f64 * d).cos() / (e * q);
            // FFT round-off on 1024 points: a few 1e-16 of the amplitude.
            assert!(
                (ui - want).abs() < 1e-12 * 2.0 * p0 / (e * q),
                "{i}: {ui} {want}"
            );
        }
    }
}
