//! Wear-accelerated corrosion (paper Section 5.1): galvanic coupling between the depassivated
//! anode and the passive cathode (eq. 18), Faraday's law for the dissolved volume, the
//! depassivated area of a sliding contact ([`depassivation`]), what dissolves per coulomb
//! ([`faraday`]) and the reference electrodes potentials are measured against
//! ([`mod@reference`]).
//!
//! Everything here is in SI units (V, A/m^2, m^2, s, kg/mol, kg/m^3, m^3). The one exception is
//! inside the Tafel logarithm: the paper fitted a_c with current densities in A/cm^2, so the
//! argument of log10 is converted to A/cm^2 there and nowhere else. Potentials are against
//! whichever electrode E_corr is given against: eq. 18 only adds differences to it.

pub mod alloys;
pub mod depassivation;
pub mod faraday;
pub mod galvanic;
pub mod kinetics;
pub mod plausible;
pub mod reference;
pub mod spots;
pub mod stroke;

use thiserror::Error;

pub use depassivation::{
    AreaInputs, ContactGeometry, band_area_m2, recovering_area_m2, wake_area_m2,
};
pub use faraday::{Dissolving, FaradayBasis};
pub use reference::ReferenceElectrode;

/// Faraday constant, C/mol (CODATA 2018, exact since the 2019 SI redefinition).
pub const FARADAY_C_PER_MOL: f64 = 96_485.332_12;

/// A/m^2 per A/cm^2.
const A_M2_PER_A_CM2: f64 = 1e4;

/// Why a galvanic-coupling quantity could not be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CorrosionError {
    /// The anodic area is negative or not a number.
    #[error("anodic area must be >= 0 m^2, got {0}")]
    InvalidAnodicArea(f64),
    /// The anode covers the whole exposed surface, leaving no passive cathode.
    #[error("anodic area {anodic_m2} m^2 leaves no cathode on the exposed area {exposed_m2} m^2")]
    NoCathode {
        /// The anodic area, m^2.
        anodic_m2: f64,
        /// The exposed electrode area, m^2.
        exposed_m2: f64,
    },
}

/// Volume of metal dissolved by an anodic charge (Faraday's law), V = Q EW / (F rho), m^3,
/// with EW = M / n the mass dissolved per mole of electrons.
pub fn faraday_volume_m3(charge_c: f64, equivalent_weight_kg_mol: f64, density_kg_m3: f64) -> f64 {
    charge_c * equivalent_weight_kg_mol / (FARADAY_C_PER_MOL * density_kg_m3)
}

/// Real contact area of the plastically deformed asperities, A_r = F / H (paper Section 5.1),
/// m^2.
pub fn real_contact_area_m2(load_n: f64, hardness_pa: f64) -> f64 {
    load_n / hardness_pa
}

/// The electrochemical cell of a tribocorrosion test, in SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorrosionModel {
    /// Free corrosion potential E_corr, V.
    pub corrosion_potential_v: f64,
    /// Cathodic Tafel constant a_c (for current densities in A/cm^2), V.
    pub tafel_a_c_v: f64,
    /// Cathodic Tafel slope b_c, V per decade.
    pub tafel_b_c_v_per_decade: f64,
    /// Anodic current density i_a on depassivated metal, A/m^2.
    pub anodic_current_density_a_m2: f64,
    /// Electrode area exposed to the electrolyte, m^2.
    pub exposed_area_m2: f64,
    /// Mass of metal dissolved per mole of electrons (M / n, or ASTM G102's alloy sum),
    /// kg/mol.
    pub equivalent_weight_kg_mol: f64,
    /// Density of the metal, kg/m^3.
    pub density_kg_m3: f64,
}

impl CorrosionModel {
    /// The cathodic Tafel line E = E_corr + a_c - b_c log10(i_c), V, for a cathodic current
    /// density in A/m^2 (converted to the A/cm^2 that a_c was fitted in).
    pub fn tafel_potential_v(&self, cathodic_current_density_a_m2: f64) -> f64 {
        self.corrosion_potential_v + self.tafel_a_c_v
            - self.tafel_b_c_v_per_decade * (cathodic_current_density_a_m2 / A_M2_PER_A_CM2).log10()
    }

    /// Passive (cathodic) area A_c for a given anodic area: the exposed area minus the anode,
    /// because the depassivated spots no longer carry the cathodic reaction. (The paper takes
    /// A_c as the whole 2.56 cm^2; for a 3.76 mm^2 wear track that shifts E_c by
    /// 0.56 log10(256 / 252.24) = 3.6 mV.)
    pub fn cathodic_area_m2(&self, anodic_area_m2: f64) -> Result<f64, CorrosionError> {
        if anodic_area_m2.is_nan() || anodic_area_m2 < 0.0 {
            return Err(CorrosionError::InvalidAnodicArea(anodic_area_m2));
        }
        if anodic_area_m2 >= self.exposed_area_m2 {
            return Err(CorrosionError::NoCathode {
                anodic_m2: anodic_area_m2,
                exposed_m2: self.exposed_area_m2,
            });
        }
        Ok(self.exposed_area_m2 - anodic_area_m2)
    }

    /// The cathodic Tafel line's current density at `potential_v`, A/m^2: the inverse of
    /// [`Self::tafel_potential_v`].
    pub fn cathodic_current_density_a_m2(&self, potential_v: f64) -> f64 {
        let decades = (self.corrosion_potential_v + self.tafel_a_c_v - potential_v)
            / self.tafel_b_c_v_per_decade;
        10f64.powf(decades) * A_M2_PER_A_CM2
    }

    /// Eq. 18 as printed, E_c = E_corr + a_c - b_c log10(i_a A_a / A_c), V, for an anodic
    /// area > 0: above E_corr when the coupled current density is below the line's own
    /// current at E_corr (see [`Self::potential_v`]).
    ///
    /// Charge balance puts the anodic current i_a A_a on the cathode, so the cathodic current
    /// density is i_a A_a / A_c.
    pub fn coupled_potential_v(&self, anodic_area_m2: f64) -> Result<f64, CorrosionError> {
        let cathodic_area = self.cathodic_area_m2(anodic_area_m2)?;
        let cathodic_density = self.anodic_current_density_a_m2 * anodic_area_m2 / cathodic_area;
        Ok(self.tafel_potential_v(cathodic_density))
    }

    /// Mixed potential of the coupled electrode, eq. 18, V, capped at E_corr.
    ///
    /// Eq. 18 is a Tafel line, valid only while the coupled current density exceeds the free
    /// corrosion current; below it (including A_a = 0) the electrode stays at E_corr, so the
    /// result is capped there. [`Self::coupled_potential_v`] is the value before the cap.
    pub fn potential_v(&self, anodic_area_m2: f64) -> Result<f64, CorrosionError> {
        if anodic_area_m2 == 0.0 {
            self.cathodic_area_m2(anodic_area_m2)?;
            return Ok(self.corrosion_potential_v);
        }
        Ok(self
            .coupled_potential_v(anodic_area_m2)?
            .min(self.corrosion_potential_v))
    }

    /// The current density at which the Tafel line crosses E_corr, 10^(a_c / b_c) A/cm^2 in
    /// A/m^2 (Table 2's line: 1.23e-6 A/cm^2, against the measured i_corr 1.13e-6).
    pub fn line_corrosion_current_density_a_m2(&self) -> f64 {
        10f64.powf(self.tafel_a_c_v / self.tafel_b_c_v_per_decade) * A_M2_PER_A_CM2
    }

    /// The anodic area below which eq. 18 puts the potential above E_corr, where the coupled
    /// current density equals the line's own current at E_corr, m^2.
    pub fn capping_area_m2(&self) -> f64 {
        let line = self.line_corrosion_current_density_a_m2();
        line * self.exposed_area_m2 / (self.anodic_current_density_a_m2 + line)
    }

    /// The current the depassivated area `anodic_area_m2` passes, i_a A_a, A.
    pub fn anodic_current_a(&self, anodic_area_m2: f64) -> f64 {
        self.anodic_current_density_a_m2 * anodic_area_m2
    }

    /// Volume dissolved by the anodic charge `charge_c` (Faraday's law), m^3.
    pub fn dissolved_volume_m3(&self, charge_c: f64) -> f64 {
        faraday_volume_m3(charge_c, self.equivalent_weight_kg_mol, self.density_kg_m3)
    }

    /// Depassivated (anodic) area implied by a measured potential: eq. 18 solved for A_a with
    /// A_c = exposed - A_a (paper Fig. 14), m^2. Potentials at or above E_corr show no
    /// coupling and give 0; the result is always below the exposed area.
    pub fn anodic_area_m2(&self, potential_v: f64) -> f64 {
        if potential_v >= self.corrosion_potential_v {
            return 0.0;
        }
        let cathodic_density_a_m2 = self.cathodic_current_density_a_m2(potential_v);
        // A_a / A_c = i_c / i_a and A_c = exposed - A_a.
        let ratio = cathodic_density_a_m2 / self.anodic_current_density_a_m2;
        ratio * self.exposed_area_m2 / (1.0 + ratio)
    }

    /// Volume dissolved from an anodic area over a duration (one time step, e.g. one cycle
    /// period, gives the per-step increment): V_WAC = i_a A_a t M / (n F rho), m^3.
    pub fn wac_volume_m3(&self, anodic_area_m2: f64, duration_s: f64) -> f64 {
        self.dissolved_volume_m3(self.anodic_current_a(anodic_area_m2) * duration_s)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The paper's 316L cell (Table 2 and Section 2.2) with i_a = 10 mA/cm^2 (Section 5.1).
    pub(crate) fn paper_cell() -> CorrosionModel {
        CorrosionModel {
            corrosion_potential_v: -0.10,
            tafel_a_c_v: -3.31,
            tafel_b_c_v_per_decade: 0.56,
            anodic_current_density_a_m2: 0.01 * 1e4,
            exposed_area_m2: 2.56e-4,
            equivalent_weight_kg_mol: 55.85e-3 / 2.0,
            density_kg_m3: 7900.0,
        }
    }

    #[test]
    fn tafel_line_passes_through_e_corr_at_i_corr() {
        let cell = paper_cell();
        let i_corr_a_m2 = 1.13e-6 * 1e4;
        let offset = cell.tafel_potential_v(i_corr_a_m2) - cell.corrosion_potential_v;
        // a_c and b_c are printed to 0.01, so each may be off by 0.005: the line can be off by
        // 0.005 + 0.005 |log10(1.13e-6)| = 0.005 + 0.005 x 5.95 = 0.0347 V. Measured: 0.0203 V.
        let rounding = 0.005 + 0.005 * 1.13e-6_f64.log10().abs();
        assert!(offset.abs() < rounding, "offset {offset} V > {rounding} V");
    }

    #[test]
    fn potential_and_anodic_area_invert_each_other() {
        let cell = paper_cell();
        // Fig. 14's depassivated areas (about 0.1 mm^2), 1 mm^2 and a wear track
        // (0.2 mm x 18.8 mm): all above the cap (see below) and far below the exposed 256 mm^2.
        for area_mm2 in [0.1, 1.0, 3.76] {
            let area = area_mm2 * 1e-6;
            let potential = cell
                .potential_v(area)
                .expect("anode smaller than the electrode");
            assert!(potential < cell.corrosion_potential_v);
            let back = cell.anodic_area_m2(potential);
            // powf(log10(x)) round trips to about 1e-15 relative times the exponent (~5).
            assert!(((back - area) / area).abs() < 1e-12, "{back} vs {area}");
        }
    }

    #[test]
    fn larger_anode_lowers_the_potential_by_b_c_per_decade() {
        let cell = paper_cell();
        let small = cell.potential_v(1e-7).expect("valid area");
        let large = cell.potential_v(1e-6).expect("valid area");
        // Tenfold A_a changes A_a / A_c by 10 (A_exp - 1e-7) / (A_exp - 1e-6) = 10 (1 + 3.5e-3),
        // so the drop exceeds b_c by 0.56 log10(1 + 3.5e-3) = 8.5e-4 V.
        let excess = (small - large) - 0.56;
        assert!((0.0..9e-4).contains(&excess), "drop {}", small - large);
    }

    #[test]
    fn small_anodes_sit_on_the_e_corr_cap() {
        let cell = paper_cell();
        // The cap engages below i_a A_a / A_c = 10^(a_c / b_c) A/cm^2 = 1.23e-6 A/cm^2, i.e.
        // A_a < 1.23e-6 x 2.56 / 0.01 = 3.1e-4 cm^2 = 0.031 mm^2. The Hertzian area
        // (6e-3 mm^2) lies below it: eq. 18 would put E above E_corr there.
        let hertz = cell.potential_v(6e-3 * 1e-6).expect("valid area");
        assert!((hertz - cell.corrosion_potential_v).abs() < f64::EPSILON);
        let uncapped = cell.coupled_potential_v(6e-3 * 1e-6).expect("valid area");
        assert!(uncapped > cell.corrosion_potential_v, "{uncapped}");
        let above = cell.potential_v(0.05e-6).expect("valid area");
        assert!(above < cell.corrosion_potential_v);
        // The cap sits where the coupled density is the line's own current at E_corr.
        let there = cell
            .coupled_potential_v(cell.capping_area_m2())
            .expect("valid area");
        // powf and log10 of the same number: 1e-15 relative of a_c (3.31 V).
        assert!(
            (there - cell.corrosion_potential_v).abs() < 1e-13,
            "{there}"
        );
    }

    #[test]
    fn no_anode_stays_at_e_corr_and_a_full_anode_is_an_error() {
        let cell = paper_cell();
        let at_zero = cell.potential_v(0.0).expect("zero area is valid");
        assert!((at_zero - cell.corrosion_potential_v).abs() < f64::EPSILON);
        assert!(cell.anodic_area_m2(-0.05).abs() < f64::MIN_POSITIVE);
        assert!(matches!(
            cell.potential_v(2.56e-4),
            Err(CorrosionError::NoCathode { .. })
        ));
        assert!(matches!(
            cell.potential_v(-1e-9),
            Err(CorrosionError::InvalidAnodicArea(_))
        ));
        assert!(matches!(
            cell.potential_v(f64::NAN),
            Err(CorrosionError::InvalidAnodicArea(_))
        ));
    }

    #[test]
    fn faraday_volume_by_hand() {
        // 10 mA/cm^2 on 1 mm^2 for 1 s is 1e-4 C; 1e-4 C / (2 x 96485.33212 C/mol)
        // = 5.18213e-10 mol of Fe; x 55.85 g/mol = 2.89422e-8 g; / 7.9 g/cm^3
        // = 3.66357e-9 cm^3 = 3.66357e-15 m^3.
        let cell = paper_cell();
        let volume = cell.wac_volume_m3(1e-6, 1.0);
        // Hand value carried to 6 digits: 1e-5 relative.
        assert!(
            ((volume - 3.66357e-15) / 3.66357e-15).abs() < 1e-5,
            "{volume}"
        );
        // Linear in time: one 1 s cycle of a 300-cycle run is 1/300 of the total.
        let total = cell.wac_volume_m3(1e-6, 300.0);
        assert!(((total / 300.0 - volume) / volume).abs() < 1e-14);
    }

    #[test]
    fn real_contact_area_is_load_over_hardness() {
        // 5 N / 2473 MPa = 2.0218e-9 m^2 = 2.02e-3 mm^2 (paper Fig. 14 starts near 2e-3 mm^2).
        let area = real_contact_area_m2(5.0, 2473e6);
        assert!(((area - 2.0218e-9) / 2.0218e-9).abs() < 1e-4, "{area}");
    }
}
