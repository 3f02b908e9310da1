//! What Faraday's law dissolves per coulomb: the equivalent weight and density of the metal.
//!
//! An alloy dissolves its elements in proportion (congruent dissolution), so its equivalent
//! weight is ASTM G102's, EW = 1 / sum(n_i f_i / W_i), over the elements above 1 wt% with
//! f_i the mass fraction, n_i the valence and W_i the atomic mass (ASTM G102-89 (2015),
//! "Calculation of Corrosion Rates and Related Information from Electrochemical
//! Measurements", Section 7 and Appendix X1, whose Table X1.2 lists UNS S31600 with Fe 2,
//! Cr 3, Ni 2, Mo 3 and EW 25.50 g/eq, density 7.98 g/cm^3).

use serde::{Deserialize, Serialize};

use super::alloys::{self, Alloy, STAINLESS_316L};

/// Iron's standard atomic weight, g/mol (IUPAC 2013).
pub const IRON_ATOMIC_MASS_G_MOL: f64 = 55.845;

/// Iron's density at 20 C, g/cm^3 (CRC Handbook of Chemistry and Physics: 7.874).
pub const IRON_DENSITY_G_CM3: f64 = 7.874;

/// What dissolves, named in the scene as `corrosion.faraday`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum FaradayBasis {
    /// 316L dissolving congruently: its Fe, Cr, Ni and Mo at their G102 valences.
    #[default]
    #[serde(rename = "316l_g102")]
    Stainless316lG102,
    /// 304 by G102's rule ([`alloys::STAINLESS_304`]).
    #[serde(rename = "304_g102")]
    Stainless304G102,
    /// Ti-6Al-4V by G102's rule ([`alloys::TI_6AL_4V`]).
    #[serde(rename = "ti6al4v_g102")]
    Ti6Al4VG102,
    /// Commercially pure titanium ([`alloys::CP_TITANIUM`]).
    #[serde(rename = "cp_ti_g102")]
    CpTitaniumG102,
    /// CoCrMo by G102's rule ([`alloys::COCRMO`]).
    #[serde(rename = "cocrmo_g102")]
    CoCrMoG102,
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
                let ew = STAINLESS_316L.equivalent_weight_g_per_eq();
                let density = STAINLESS_316L.density_g_cm3;
                Dissolving {
                    equivalent_weight_g_per_eq: ew,
                    density_g_cm3: density,
                    reason: format!(
                        "316l_g102: 316L dissolving congruently, Fe 68.5 / Cr 17 / Ni 12 / Mo \
                         2.5 wt% at valences 2 / 3 / 2 / 3, EW {ew:.2} g/eq (ASTM G102 Table \
                         X1.2: 25.50), density {density} g/cm^3; the paper's disc is 316L, \
                         and pure iron's 27.92 g/eq at 7.874 g/cm^3 would dissolve 11% more \
                         volume per coulomb"
                    ),
                }
            }
            Self::Stainless304G102 => alloy_dissolving(&alloys::STAINLESS_304),
            Self::Ti6Al4VG102 => alloy_dissolving(&alloys::TI_6AL_4V),
            Self::CpTitaniumG102 => alloy_dissolving(&alloys::CP_TITANIUM),
            Self::CoCrMoG102 => alloy_dissolving(&alloys::COCRMO),
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

/// What `alloy` dissolves by G102's rule, with its composition in the words.
fn alloy_dissolving(alloy: &Alloy) -> Dissolving {
    let ew = alloy.equivalent_weight_g_per_eq();
    let composition = alloy
        .elements
        .iter()
        .map(|e| {
            format!(
                "{} {} wt% as {}+",
                e.symbol,
                e.mass_fraction * 100.0,
                e.valence
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    Dissolving {
        equivalent_weight_g_per_eq: ew,
        density_g_cm3: alloy.density_g_cm3,
        reason: format!(
            "{}: {} dissolving congruently, {composition}, EW {ew:.2} g/eq by ASTM G102's \
             formula, density {} g/cm^3 ({})",
            alloy.basis, alloy.label, alloy.density_g_cm3, alloy.source
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_316l_equivalent_weight_is_astm_g102s() {
        let ew = STAINLESS_316L.equivalent_weight_g_per_eq();
        // G102 prints 25.50 to two decimals: within half a unit of the last digit.
        assert!((ew - 25.50).abs() <= 0.005, "{ew}");
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
