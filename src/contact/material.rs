//! Elastic constants of the two bodies and their combinations (paper eqs. 6 and 8).

use super::error::{ContactError, ElasticConstant};

/// An isotropic linear-elastic material, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
}

impl Material {
    /// A material, checked: E finite and > 0, nu in the open interval (-1, 0.5). The error
    /// names the constant; which body and which input field it came from is the caller's to
    /// say.
    pub fn new(youngs_modulus_pa: f64, poisson_ratio: f64) -> Result<Self, ContactError> {
        if !(youngs_modulus_pa.is_finite() && youngs_modulus_pa > 0.0) {
            return Err(ContactError::InvalidMaterial {
                constant: ElasticConstant::YoungsModulus,
                value: youngs_modulus_pa,
                allowed: "finite and > 0",
            });
        }
        if !(poisson_ratio > -1.0 && poisson_ratio < 0.5) {
            return Err(ContactError::InvalidMaterial {
                constant: ElasticConstant::PoissonRatio,
                value: poisson_ratio,
                allowed: "-1 < nu < 0.5",
            });
        }
        Ok(Self {
            youngs_modulus_pa,
            poisson_ratio,
        })
    }

    /// Normal compliance of the half-space, (1 - nu^2) / E, 1/Pa: this body's term of 1/E*
    /// (eq. 6), so times E* its share of the elastic approach under the same pressure.
    pub fn compliance_per_pa(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus_pa
    }

    /// Shear modulus G = E / (2 (1 + nu)), Pa.
    pub fn shear_modulus_pa(&self) -> f64 {
        self.youngs_modulus_pa / (2.0 * (1.0 + self.poisson_ratio))
    }
}

/// The combined elastic constants of a ball (body 1) pressed on a disc (body 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticPair {
    /// Reduced modulus E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (eq. 6), Pa.
    pub reduced_modulus_pa: f64,
    /// Reduced shear modulus G*, 1/G* = 1/G1 + 1/G2 (eq. 6), Pa.
    pub reduced_shear_modulus_pa: f64,
    /// nu* = (nu1 G2 + nu2 G1) / (G1 + G2) (eq. 8).
    pub nu_star: f64,
    /// Delta-nu = ((1 - 2 nu1) G2 - (1 - 2 nu2) G1) / (G1 + G2) (eq. 8): the dissimilarity
    /// that couples friction to normal displacement. Zero for identical materials.
    pub delta_nu: f64,
}

impl ElasticPair {
    /// Combines ball and disc.
    pub fn new(ball: Material, disc: Material) -> Self {
        let (g1, g2) = (ball.shear_modulus_pa(), disc.shear_modulus_pa());
        let (nu1, nu2) = (ball.poisson_ratio, disc.poisson_ratio);
        let compliance = ball.compliance_per_pa() + disc.compliance_per_pa();
        Self {
            reduced_modulus_pa: 1.0 / compliance,
            reduced_shear_modulus_pa: g1 * g2 / (g1 + g2),
            nu_star: (nu1 * g2 + nu2 * g1) / (g1 + g2),
            delta_nu: ((1.0 - 2.0 * nu1) * g2 - (1.0 - 2.0 * nu2) * g1) / (g1 + g2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_pair() -> ElasticPair {
        let ball = Material::new(300e9, 0.21).expect("valid");
        let disc = Material::new(205e9, 0.28).expect("valid");
        ElasticPair::new(ball, disc)
    }

    #[test]
    fn reduced_modulus_matches_hand_value() {
        // 1/E* = 0.9559/300 + 0.9216/205 GPa^-1 -> 130.17 GPa (numerics notes).
        let pair = paper_pair();
        assert!((pair.reduced_modulus_pa / 1e9 - 130.17).abs() < 0.01);
    }

    #[test]
    fn shear_form_of_eq7_equals_reduced_modulus() {
        // Eq. 7 scales the normal term by (1 - nu*) / (2 pi G*); it must equal 1 / (pi E*),
        // since (1 - nu*) / G* = (1 - nu1)/G1 + (1 - nu2)/G2 = 2/E*. Exact up to rounding.
        let pair = paper_pair();
        let lhs = (1.0 - pair.nu_star) / (2.0 * pair.reduced_shear_modulus_pa);
        let rhs = 1.0 / pair.reduced_modulus_pa;
        assert!((lhs / rhs - 1.0).abs() < 1e-14);
    }

    #[test]
    fn delta_nu_vanishes_for_identical_bodies_and_has_paper_sign() {
        let steel = Material::new(205e9, 0.28).expect("valid");
        assert!(ElasticPair::new(steel, steel).delta_nu.abs() < 1e-16);
        // Alumina on 316L: (0.58 * 80.08 - 0.44 * 123.97) / 204.05 = -0.0397.
        assert!((paper_pair().delta_nu + 0.0397).abs() < 5e-5);
    }

    #[test]
    fn rejects_unphysical_constants() {
        assert!(Material::new(-1.0, 0.3).is_err());
        assert!(Material::new(f64::NAN, 0.3).is_err());
        assert!(Material::new(200e9, 0.5).is_err());
        assert!(Material::new(200e9, -1.0).is_err());
        assert!(Material::new(200e9, f64::NAN).is_err());
    }
}
