//! The pressure cap of the elastic-perfectly-plastic disc (eq. 12) and how it hardens.
//!
//! The paper caps the pressure at `Y = H(n) / 2.8` from the first pass. That is Tabor's
//! relation between a hardness and the flow stress at the indentation's representative
//! strain of about 8% (Tabor, *The Hardness of Metals*, 1951; Johnson, *Contact Mechanics*,
//! 1985, Section 6.2): the flow stress of metal already strained 8%. An annealed 316L
//! surface that no pass has strained yet yields far lower, at its 0.2% proof stress (290 MPa
//! typical, AK Steel's 316/316L product data sheet 316/316L-S-08-01-07, against
//! `H / 2.8 = 883 MPa` for the paper's disc).
//!
//! [`YieldCap::StrainHardening`] starts at that proof stress and rises, linearly in the
//! surface's cumulative plastic strain, to `H(n) / 2.8` at Tabor's 8%; from there on it is
//! the paper's cap: a hardening in strain, as annealed 316L's cyclic hardening is modelled
//! (Chaboche's isotropic hardening, identified on 316L in Lemaitre and Chaboche, *Mechanics
//! of Solid Materials*, 1990). Each pass that yields strains the surface by Tabor's
//! representative strain of a spherical indentation, `0.2 a / R` ([`pass_strain`]). Linear
//! is the simplest law between the two sourced ends; the measured ends, not the shape
//! between them, are what the paper's statements test (`docs/paper.md`).

use super::HardnessLaw;

/// The representative strain at which a hardness is 2.8 times the flow stress (Tabor).
pub const TABOR_REPRESENTATIVE_STRAIN: f64 = 0.08;

/// Tabor's representative strain of a spherical indentation per `a / R` (contact radius
/// over ball radius): `0.2 a / R`.
pub const TABOR_SPHERE_STRAIN_PER_A_OVER_R: f64 = 0.2;

/// How the pressure cap follows the disc's hardening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum YieldCap {
    /// `Y = H(n) / yield_factor` from the first pass (the paper's eq. 12).
    Hardness {
        /// The hardness law H(n).
        law: HardnessLaw,
        /// `H / Y`.
        yield_factor: f64,
    },
    /// From `initial_pa` at no plastic strain, linearly to `H(n) / yield_factor` at
    /// [`TABOR_REPRESENTATIVE_STRAIN`], and the paper's cap beyond.
    StrainHardening {
        /// The hardness law H(n).
        law: HardnessLaw,
        /// `H / Y`.
        yield_factor: f64,
        /// The yield strength of the unstrained disc, Pa.
        initial_pa: f64,
    },
}

impl YieldCap {
    /// The cap at `cycle` after a cumulative plastic strain `plastic_strain`, Pa. Never
    /// above `H(n) / yield_factor`, so an initial yield strength above it changes nothing.
    pub fn pressure_pa(&self, cycle: f64, plastic_strain: f64) -> f64 {
        match *self {
            Self::Hardness { law, yield_factor } => law.yield_pressure_pa(cycle, yield_factor),
            Self::StrainHardening {
                law,
                yield_factor,
                initial_pa,
            } => {
                let hardened = law.yield_pressure_pa(cycle, yield_factor);
                let fraction = (plastic_strain / TABOR_REPRESENTATIVE_STRAIN).clamp(0.0, 1.0);
                let initial = initial_pa.min(hardened);
                initial + (hardened - initial) * fraction
            }
        }
    }

    /// Whether more plastic strain can still raise the cap: never for the paper's, and for
    /// the hardening cap only until Tabor's strain, so a run counts the strain no longer.
    pub fn still_hardens(&self, plastic_strain: f64) -> bool {
        matches!(self, Self::StrainHardening { .. }) && plastic_strain < TABOR_REPRESENTATIVE_STRAIN
    }

    /// The lowest cap over `cycles` cycles, Pa, and the cycle and hardness where it lies:
    /// the initial yield strength at cycle 1 when the cap hardens from it, else `H / factor`
    /// at the first or last cycle (`A + B ln n` is monotone).
    pub fn lowest(&self, cycles: u64) -> (u64, f64, f64) {
        let (law, factor) = self.hardness();
        let last = cycles as f64;
        let (cycle, hardness_pa) = if law.hardness_pa(last) < law.hardness_pa(1.0) {
            (cycles, law.hardness_pa(last))
        } else {
            (1, law.hardness_pa(1.0))
        };
        let lowest_pa = hardness_pa / factor;
        match *self {
            Self::StrainHardening { initial_pa, .. } if initial_pa < lowest_pa => {
                (1, law.hardness_pa(1.0), initial_pa)
            }
            _ => (cycle, hardness_pa, lowest_pa),
        }
    }

    /// The hardness law and the factor `H / Y` the cap hardens to.
    pub fn hardness(&self) -> (&HardnessLaw, f64) {
        match self {
            Self::Hardness { law, yield_factor }
            | Self::StrainHardening {
                law, yield_factor, ..
            } => (law, *yield_factor),
        }
    }
}

/// The plastic strain one yielding pass gives the surface: Tabor's representative strain of
/// a spherical indentation, `0.2 a / R`, with `a` the half-width across the track of the
/// zone at the cap
/// and `R` the ball's radius.
pub fn pass_strain(contact_half_width_m: f64, ball_radius_m: f64) -> f64 {
    TABOR_SPHERE_STRAIN_PER_A_OVER_R * contact_half_width_m / ball_radius_m
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAW: HardnessLaw = HardnessLaw::Logarithmic {
        a_pa: 2455e6,
        b_pa: 63.4e6,
    };

    #[test]
    fn the_hardening_cap_runs_from_the_proof_stress_to_the_papers() {
        let cap = YieldCap::StrainHardening {
            law: LAW,
            yield_factor: 2.8,
            initial_pa: 290e6,
        };
        let paper = |n: f64| LAW.yield_pressure_pa(n, 2.8);
        // The ends are the two sourced values, bit for bit.
        assert_eq!(cap.pressure_pa(1.0, 0.0).to_bits(), 290e6_f64.to_bits());
        assert_eq!(cap.pressure_pa(10.0, 0.08).to_bits(), paper(10.0).to_bits());
        assert_eq!(cap.pressure_pa(10.0, 0.5).to_bits(), paper(10.0).to_bits());
        // Half way in strain is half way in stress (linear): one rounding of each operand.
        let half = cap.pressure_pa(1.0, 0.04);
        assert!((half - (290e6 + paper(1.0)) / 2.0).abs() < 1e-6, "{half}");
        assert_eq!(cap.lowest(3600), (1, 2455e6, 290e6));
        assert!(cap.still_hardens(0.079));
        assert!(!cap.still_hardens(0.08));
    }

    #[test]
    fn a_proof_stress_above_the_papers_cap_changes_nothing() {
        let paper = YieldCap::Hardness {
            law: LAW,
            yield_factor: 2.8,
        };
        let strong = YieldCap::StrainHardening {
            law: LAW,
            yield_factor: 2.8,
            initial_pa: 2e9,
        };
        for strain in [0.0, 0.01, 0.2] {
            assert_eq!(
                strong.pressure_pa(5.0, strain).to_bits(),
                paper.pressure_pa(5.0, strain).to_bits()
            );
        }
        assert_eq!(strong.lowest(300), paper.lowest(300));
        assert!(!paper.still_hardens(0.0));
    }

    #[test]
    fn a_pass_strains_the_surface_by_taber_s_sphere_rule() {
        // The paper's Hertz contact, a = 44.2 um under R = 3 mm: 0.29% a pass, so 27 yielding
        // passes reach Tabor's 8%.
        let strain = pass_strain(44.2e-6, 3e-3);
        assert!((strain - 0.002_946_7).abs() < 1e-6, "{strain}");
    }
}
