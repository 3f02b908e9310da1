//! The alloys Faraday's law can dissolve by ASTM G102's rule: each one's nominal composition,
//! valences and density, the one home of these numbers (the materials library,
//! [`crate::scene::materials`], reads its densities from here).
//!
//! G102 (Appendix X1) takes the middle of each element's specified range, leaves out the
//! elements at or below 1 wt% and gives the balance to the base metal; each element
//! dissolves as its lowest stable ion. Only 316's line of G102's table was read
//! (`faraday`); the other equivalent weights are the formula's on these compositions, and
//! each alloy says so.

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

/// ASTM G102's equivalent weight of an alloy, 1 / sum(n_i f_i / W_i), g per mole of
/// electrons.
pub fn equivalent_weight_g_per_eq(elements: &[Element]) -> f64 {
    1.0 / elements
        .iter()
        .map(|e| e.valence * e.mass_fraction / e.atomic_mass_g_mol)
        .sum::<f64>()
}

/// An alloy by G102's rule: what `corrosion.faraday` names, its composition and density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Alloy {
    /// What `corrosion.faraday` calls it.
    pub basis: &'static str,
    /// Its name in words.
    pub label: &'static str,
    /// The elements above 1 wt%, the base metal the balance.
    pub elements: &'static [Element],
    /// Density, g/cm^3.
    pub density_g_cm3: f64,
    /// Where the composition and the density come from.
    pub source: &'static str,
}

const fn element(symbol: &'static str, wt_percent: f64, valence: f64, mass: f64) -> Element {
    Element {
        symbol,
        mass_fraction: wt_percent / 100.0,
        valence,
        atomic_mass_g_mol: mass,
    }
}

// Standard atomic weights, g/mol (IUPAC 2013, to the digits G102 uses).
const FE: f64 = 55.845;
const CR: f64 = 51.996;
const NI: f64 = 58.693;
const MO: f64 = 95.95;
const TI: f64 = 47.867;
const AL: f64 = 26.982;
const V: f64 = 50.942;
const CO: f64 = 58.933;

/// Nominal 316L: Cr 17, Ni 12, Mo 2.5 wt%, Fe the balance (68.5); Mn, Si and C, each 2 wt%
/// or less, are left out as G102 leaves out elements at or below 1 wt% of its nominal
/// compositions. The paper's 316L (Section 2.1) is within these grades' ranges.
pub const STAINLESS_316L: Alloy = Alloy {
    basis: "316l_g102",
    label: "AISI 316L",
    elements: &[
        element("Fe", 68.5, 2.0, FE),
        element("Cr", 17.0, 3.0, CR),
        element("Ni", 12.0, 2.0, NI),
        element("Mo", 2.5, 3.0, MO),
    ],
    density_g_cm3: 7.98,
    source: "ASTM G102 Table X1.2 (UNS S31600: Fe 2, Cr 3, Ni 2, Mo 3; EW 25.50 g/eq, \
             7.98 g/cm^3)",
};

/// Nominal 304: the middle of AK Steel's ranges, Cr 18-20 and Ni 8-12 wt% (Mn up to 2 left
/// out as for 316L), Fe the balance.
pub const STAINLESS_304: Alloy = Alloy {
    basis: "304_g102",
    label: "AISI 304",
    elements: &[
        element("Fe", 71.0, 2.0, FE),
        element("Cr", 19.0, 3.0, CR),
        element("Ni", 10.0, 2.0, NI),
    ],
    density_g_cm3: 8.00,
    source: "composition: AK Steel 304/304L data sheet's ranges; density: MatWeb, AISI \
             Type 304; EW by G102's formula",
};

/// Ti-6Al-4V: Al 6, V 4 wt%, Ti the balance; vanadium as V5+, its oxide's state in the
/// passive film (V4+ would give 11.76 g/eq against 11.65).
pub const TI_6AL_4V: Alloy = Alloy {
    basis: "ti6al4v_g102",
    label: "Ti-6Al-4V",
    elements: &[
        element("Ti", 90.0, 4.0, TI),
        element("Al", 6.0, 3.0, AL),
        element("V", 4.0, 5.0, V),
    ],
    density_g_cm3: 4.43,
    source: "composition and density: MatWeb MTP644, Ti-6Al-4V (Grade 5) annealed bar \
             (Allvac); EW by G102's formula",
};

/// Commercially pure titanium, Ti -> Ti4+.
pub const CP_TITANIUM: Alloy = Alloy {
    basis: "cp_ti_g102",
    label: "CP titanium, Grade 2",
    elements: &[element("Ti", 100.0, 4.0, TI)],
    density_g_cm3: 4.51,
    source: "density: MatWeb MTU021, Titanium Grade 2 annealed (Allvac); EW by G102's \
             formula",
};

/// CoCrMo (ASTM F75 / F1537): the middle of Cr 27-30 and Mo 5-7 wt%, Co the balance.
pub const COCRMO: Alloy = Alloy {
    basis: "cocrmo_g102",
    label: "CoCrMo (ASTM F75)",
    elements: &[
        element("Co", 65.5, 2.0, CO),
        element("Cr", 28.5, 3.0, CR),
        element("Mo", 6.0, 3.0, MO),
    ],
    density_g_cm3: 8.4,
    source: "composition ranges and density: MakeItFrom, annealed cast R30075 (ASTM F75); \
             EW by G102's formula",
};

/// Every alloy `corrosion.faraday` can name.
pub const ALLOYS: [Alloy; 5] = [
    STAINLESS_316L,
    STAINLESS_304,
    TI_6AL_4V,
    CP_TITANIUM,
    COCRMO,
];

impl Alloy {
    /// ASTM G102's equivalent weight, 1 / sum(n_i f_i / W_i), g per mole of electrons.
    pub fn equivalent_weight_g_per_eq(&self) -> f64 {
        equivalent_weight_g_per_eq(self.elements)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_composition_is_whole_and_its_equivalent_weight_the_formulas() {
        for alloy in ALLOYS {
            let fractions: f64 = alloy.elements.iter().map(|e| e.mass_fraction).sum();
            // The balance makes the whole, to round-off of a few sums.
            assert!(
                (fractions - 1.0).abs() < 1e-12,
                "{}: {fractions}",
                alloy.label
            );
        }
        // Worked by hand from the compositions above, to the two decimals G102 prints:
        // 304: 1 / (2 x 0.71 / 55.845 + 3 x 0.19 / 51.996 + 2 x 0.10 / 58.693) = 25.13;
        // Ti-6Al-4V: 1 / (4 x 0.9 / 47.867 + 3 x 0.06 / 26.982 + 5 x 0.04 / 50.942) = 11.65;
        // CP Ti: 47.867 / 4 = 11.97; CoCrMo: 1 / (2 x 0.655 / 58.933 + 3 x 0.285 / 51.996 +
        // 3 x 0.06 / 95.95) = 24.66.
        let printed = [25.50, 25.13, 11.65, 11.97, 24.66];
        for (alloy, want) in ALLOYS.iter().zip(printed) {
            let ew = alloy.equivalent_weight_g_per_eq();
            assert!((ew - want).abs() <= 0.005, "{}: {ew}", alloy.label);
        }
    }
}
