//! The elastic half-space under a periodic pressure: each Fourier mode of wavevector q
//! displaces the surface by `2 p(q) / (E* |q|)` (Johnson, Contact Mechanics, Section 13.2;
//! the spectral operator of Stanley & Kato, J. Tribol. 1997, and of Tamaas's Westergaard
//! operator). It is the operator of a rough flat pressed on a rough flat with the map
//! repeating beyond its sides, the setting in which the real contact area of rough surfaces
//! is studied; its exact inverse is the preconditioner. The mean displacement (q = 0) is
//! left at zero: the approach absorbs it.

use std::num::NonZeroUsize;

use super::operator::{Operator, Preconditioner};
use super::precondition::FourierInverse;
use super::transform::{periodic_threads, split_threads};

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
    /// `reduced_modulus_pa` (E*, eq. 6), on the automatic thread count of
    /// [`split_threads`] for a transform of its length (`periodic_threads`: from
    /// [`crate::contact::SPLIT_MIN_CELLS`]; no scene chooses one for it) as the only run solving (its callers, the
    /// tests and the benchmark, run one at a time; [`Self::threaded`] chooses another).
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
        .threaded(periodic_threads(
            split_threads(None, nx * ny, NonZeroUsize::MIN),
            nx * ny,
        ))
    }

    /// The same operator, its apply and preconditioner on `threads` threads (1: on the
    /// caller's thread alone); the results are equal to the last bit.
    pub fn threaded(self, threads: usize) -> Self {
        Self {
            forward: self.forward.threaded(threads),
            inverse: self.inverse.threaded(threads),
            ..self
        }
    }

    /// The threads an apply runs on.
    pub fn threads(&self) -> usize {
        self.forward.threads()
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

    fn threads(&self) -> usize {
        PeriodicHalfSpace::threads(self)
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

    #[test]
    fn the_split_operator_equals_the_one_thread_operator() {
        // The split transform is tested against the one-thread one in `precondition`; this
        // checks the operator hands its thread count to both of its transforms.
        let (nx, ny) = (24, 18);
        let p: Vec<f64> = (0..nx * ny).map(|i| ((i * 7) % 11) as f64).collect();
        let mut one = PeriodicHalfSpace::new(nx, ny, 1e-6, 1e-6, 100e9).threaded(1);
        let mut split = PeriodicHalfSpace::new(nx, ny, 1e-6, 1e-6, 100e9).threaded(2);
        assert_eq!((one.threads(), split.threads()), (1, 2));
        let (mut a, mut b) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        one.apply(&p, &mut a);
        split.apply(&p, &mut b);
        assert_eq!(a, b);
        let (one, split) = (one.preconditioner(), split.preconditioner());
        let (mut c, mut d) = (vec![0.0; nx * ny], vec![0.0; nx * ny]);
        one.expect("preconditioned").apply(&a, &mut c);
        split.expect("preconditioned").apply(&a, &mut d);
        assert_eq!(c, d);
    }
}
