//! What Faraday's law dissolves per coulomb: the equivalent weight and density of the metal.
//!
//! An alloy dissolves its elements in proportion (congruent dissolution), so its equivalent
//! weight is ASTM G102's, EW = 1 / sum(n_i f_i / W_i), over the elements above 1 wt% with
//! f_i the mass fraction, n_i the valence and W_i the atomic mass (ASTM G102-89 (2015),
//! "Calculation of Corrosion Rates and Related Information from Electrochemical
//! Measurements", Section 7 and Appendix X1, whose Table X1.2 lists UNS S31600 with Fe 2,
//! Cr 3, Ni 2, Mo 3 and EW 25.50 g/eq, density 7.98 g/cm^3).

use serde::{Deserialize, Serialize};

/// One element of an alloy, as ASTM G102 counts it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Element {
    /// Chemical symbol.
    pub symbol: &'static str,
    /// Mass fraction, 0 to 1.
    pub mass_fraction: f64,
    /// Charge number of its dissolution (the lowest stable ion, as G102 takes it).
    pub valence: f64,
    /// Standard atomic weight, g/mol (IUPAC 2013, to the digits G102 uses).
    pub atomic_mass_g_mol: f64,
}

/// Nominal 316L: Cr 17, Ni 12, Mo 2.5 wt%, Fe the balance (68.5); Mn, Si and C, each 2 wt%
/// or less, are left out as G102 leaves out elements at or below 1 wt% of its nominal
/// compositions. The paper's 316L (Section 2.1) is within these grades' ranges.
pub const STAINLESS_316L: [Element; 4] = [
    Element {
        symbol: "Fe",
        mass_fraction: 0.685,
        valence: 2.0,
        atomic_mass_g_mol: 55.845,
    },
    Element {
        symbol: "Cr",
        mass_fraction: 0.17,
        valence: 3.0,
        atomic_mass_g_mol: 51.996,
    },
    Element {
        symbol: "Ni",
        mass_fraction: 0.12,
        valence: 2.0,
        atomic_mass_g_mol: 58.693,
    },
    Element {
        symbol: "Mo",
        mass_fraction: 0.025,
        valence: 3.0,
        atomic_mass_g_mol: 95.95,
    },
];

/// 316's density, g/cm^3 (ASTM G102 Table X1.2; 7.98 in steel makers' sheets too).
pub const STAINLESS_316L_DENSITY_G_CM3: f64 = 7.98;

/// Iron's standard atomic weight, g/mol (IUPAC 2013).
pub const IRON_ATOMIC_MASS_G_MOL: f64 = 55.845;

/// Iron's density at 20 C, g/cm^3 (CRC Handbook of Chemistry and Physics: 7.874).
pub const IRON_DENSITY_G_CM3: f64 = 7.874;

/// ASTM G102's equivalent weight of an alloy, 1 / sum(n_i f_i / W_i), g per mole of
/// electrons.
pub fn equivalent_weight_g_per_eq(elements: &[Element]) -> f64 {
    1.0 / elements
        .iter()
        .map(|e| e.valence * e.mass_fraction / e.atomic_mass_g_mol)
        .sum::<f64>()
}

/// What dissolves, named in the scene as `corrosion.faraday`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum FaradayBasis {
    /// 316L dissolving congruently: its Fe, Cr, Ni and Mo at their G102 valences.
    #[default]
    #[serde(rename = "316l_g102")]
    Stainless316lG102,
    /// Pure iron, Fe -> Fe2+.
    #[serde(rename = "pure_iron")]
    PureIron,
    /// The scene's `molar_mass_g_mol`, `valence` and `density_g_cm3`.
    #[serde(rename = "given")]
    Given,
}

/// The equivalent weight and density Faraday's law uses, with its words.
#[derive(Debug, Clone, PartialEq)]
pub struct Dissolving {
    /// Grams dissolved per mole of electrons, g/eq.
    pub equivalent_weight_g_per_eq: f64,
    /// Density, g/cm^3.
    pub density_g_cm3: f64,
    /// What it is and where the numbers come from.
    pub reason: String,
}

impl FaradayBasis {
    /// What dissolves under this basis; `given` takes the scene's molar mass (g/mol),
    /// valence and density (g/cm^3).
    pub fn dissolving(self, molar_mass_g_mol: f64, valence: f64, density_g_cm3: f64) -> Dissolving {
        match self {
            Self::Stainless316lG102 => {
                let ew = equivalent_weight_g_per_eq(&STAINLESS_316L);
                Dissolving {
                    equivalent_weight_g_per_eq: ew,
                    density_g_cm3: STAINLESS_316L_DENSITY_G_CM3,
                    reason: format!(
                        "316l_g102: 316L dissolving congruently, Fe 68.5 / Cr 17 / Ni 12 / Mo \
                         2.5 wt% at valences 2 / 3 / 2 / 3, EW {ew:.2} g/eq (ASTM G102 Table \
                         X1.2: 25.50), density {STAINLESS_316L_DENSITY_G_CM3} g/cm^3; the \
                         paper's disc is 316L, and pure iron's 27.92 g/eq at 7.874 g/cm^3 \
                         would dissolve 11% more volume per coulomb"
                    ),
                }
            }
            Self::PureIron => Dissolving {
                equivalent_weight_g_per_eq: IRON_ATOMIC_MASS_G_MOL / 2.0,
                density_g_cm3: IRON_DENSITY_G_CM3,
                reason: format!(
                    "pure_iron: Fe -> Fe2+, EW {:.2} g/eq, density {IRON_DENSITY_G_CM3} g/cm^3 \
                     (as chosen; 316L's own is `316l_g102`)",
                    IRON_ATOMIC_MASS_G_MOL / 2.0
                ),
            },
            Self::Given => Dissolving {
                equivalent_weight_g_per_eq: molar_mass_g_mol / valence,
                density_g_cm3,
                reason: format!(
                    "given: M {molar_mass_g_mol} g/mol, z {valence}, EW {:.2} g/eq, density \
                     {density_g_cm3} g/cm^3 (`corrosion.molar_mass_g_mol`, `valence`, \
                     `density_g_cm3`)",
                    molar_mass_g_mol / valence
                ),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_316l_equivalent_weight_is_astm_g102s() {
        let ew = equivalent_weight_g_per_eq(&STAINLESS_316L);
        // G102 prints 25.50 to two decimals: within half a unit of the last digit.
        assert!((ew - 25.50).abs() <= 0.005, "{ew}");
        let fractions: f64 = STAINLESS_316L.iter().map(|e| e.mass_fraction).sum();
        // The four fractions add up to the whole (Fe is the balance), to round-off.
        assert!((fractions - 1.0).abs() < 1e-12, "{fractions}");
    }

    #[test]
    fn pure_iron_dissolves_more_volume_per_coulomb_than_316l() {
        let volume = |d: Dissolving| d.equivalent_weight_g_per_eq / d.density_g_cm3;
        let steel = volume(FaradayBasis::Stainless316lG102.dissolving(0.0, 1.0, 0.0));
        let iron = volume(FaradayBasis::PureIron.dissolving(0.0, 1.0, 0.0));
        // (27.9225 / 7.874) / (25.503 / 7.98) = 3.5461 / 3.1959 = 1.1096.
        let ratio = iron / steel;
        assert!((ratio - 1.1096).abs() < 1e-4, "{ratio}");
        let given = FaradayBasis::Given.dissolving(55.85, 2.0, 7.9);
        assert!((given.equivalent_weight_g_per_eq - 27.925).abs() < 1e-12);
    }
}
