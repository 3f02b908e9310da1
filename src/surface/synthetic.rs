//! Synthetic self-affine surfaces by Fourier filtering: each wavevector between the two
//! cut-offs gets the amplitude of a power spectrum C(q) proportional to q^(-2(1+H)) and a
//! random phase; the inverse transform's real part is the surface, scaled to the requested
//! rms height or rms slope. This is the method of Jacobs, Junge & Pastewka, Surf. Topogr.:
//! Metrol. Prop. 5 (2017) 013001, Section 4 (and of Tamaas's and SurfaceTopography's
//! generators); outside the cut-offs the spectrum is zero, so the surface is flat beyond the
//! long cut-off and smooth below the short one. The map is one period of the surface.

use std::f64::consts::TAU;

use rustfft::num_complex::Complex;

use super::spectrum::{fft_2d, wavevector_norms};
use super::statistics::{rms_height, rms_slope};
use super::{HeightMap, SurfaceError};

/// What sets the surface's amplitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Roughness {
    /// Root mean square height about the mean, m.
    RmsHeight(f64),
    /// Root mean square gradient by forward differences on the map's pixels.
    RmsSlope(f64),
}

/// A self-affine surface's description.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAffine {
    /// Its amplitude.
    pub roughness: Roughness,
    /// Hurst exponent H, in (0, 1].
    pub hurst: f64,
    /// Shortest wavelength, m.
    pub short_cutoff_m: f64,
    /// Longest wavelength, m.
    pub long_cutoff_m: f64,
    /// Seed of the random phases: the same seed gives the same surface.
    pub seed: u64,
}

impl SelfAffine {
    /// The surface over `nx` x `ny` pixels of `dx_m` x `dy_m`, periodic over the map.
    pub fn generate(
        &self,
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
    ) -> Result<HeightMap, SurfaceError> {
        self.check()?;
        let mut map = HeightMap::new(nx, ny, dx_m, dy_m, vec![0.0; nx * ny])?;
        let q = wavevector_norms(nx, ny, map.width_m(), map.height_side_m());
        let (q_low, q_high) = (TAU / self.long_cutoff_m, TAU / self.short_cutoff_m);
        let mut random = SplitMix64(self.seed);
        let mut field: Vec<Complex<f64>> = q
            .iter()
            .map(|&qi| {
                // Draw for every entry, so a seed's phases do not depend on the cut-offs.
                let phase = TAU * random.unit();
                if qi > 0.0 && (q_low..=q_high).contains(&qi) {
                    Complex::from_polar(qi.powf(-(1.0 + self.hurst)), phase)
                } else {
                    Complex::default()
                }
            })
            .collect();
        if field.iter().all(|c| c.norm_sqr() == 0.0) {
            return Err(SurfaceError::Invalid(format!(
                "no wavelength of a {:.3} x {:.3} um map with {:.3} um pixels lies between \
                 the cut-offs {:.3} and {:.3} um",
                map.width_m() * 1e6,
                map.height_side_m() * 1e6,
                dx_m.max(dy_m) * 1e6,
                self.long_cutoff_m * 1e6,
                self.short_cutoff_m * 1e6
            )));
        }
        fft_2d(&mut field, nx, ny, true);
        map.heights_m = field.iter().map(|c| c.re).collect();
        map.periodic = true;
        let scale = match self.roughness {
            Roughness::RmsHeight(h) => h / rms_height(&map),
            Roughness::RmsSlope(s) => s / rms_slope(&map),
        };
        map.heights_m.iter_mut().for_each(|h| *h *= scale);
        Ok(map)
    }

    fn check(&self) -> Result<(), SurfaceError> {
        let amplitude = match self.roughness {
            Roughness::RmsHeight(v) | Roughness::RmsSlope(v) => v,
        };
        let problem = if !(amplitude > 0.0 && amplitude.is_finite()) {
            Some(format!(
                "rms height or slope {amplitude}: must be finite and > 0"
            ))
        } else if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            Some(format!("Hurst exponent {}: must be in (0, 1]", self.hurst))
        } else if !(self.short_cutoff_m > 0.0
            && self.short_cutoff_m < self.long_cutoff_m
            && self.long_cutoff_m.is_finite())
        {
            Some(format!(
                "cut-offs {} m (short) and {} m (long): need 0 < short < long",
                self.short_cutoff_m, self.long_cutoff_m
            ))
        } else {
            None
        };
        problem.map_or(Ok(()), |p| Err(SurfaceError::Invalid(p)))
    }
}

/// SplitMix64 (Steele, Lea & Flood, OOPSLA 2014): a seeded generator whose sequence is
/// fixed by this code, so a seed gives the same surface in every version of the crate.
struct SplitMix64(u64);

impl SplitMix64 {
    /// A number uniform in [0, 1), from the top 53 bits.
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}
