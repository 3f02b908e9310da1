//! The descriptors of `corrosion`, the electrochemical cell of Section 5.1 (see
//! [`super::FIELDS`]).

use crate::scene::field::{Field, Range};

const FARADAY_FEEDS: &str = "Faraday's law: V_WAC = i_a A_a t M / (z F rho)";

/// `corrosion.corrosion_potential_v`.
pub(in crate::scene) const CORROSION_POTENTIAL: Field = Field {
    path: "corrosion.corrosion_potential_v",
    unit: "V vs Ag/AgCl",
    range: Range::Finite,
    why: "",
    meaning: "Free corrosion potential E_corr (the open-circuit potential before rubbing, \
              Table 2).",
    feeds: "E_corr in eq. 18",
};

/// `corrosion.tafel_a_c_v`.
pub(in crate::scene) const TAFEL_A: Field = Field {
    path: "corrosion.tafel_a_c_v",
    unit: "V",
    range: Range::Finite,
    why: "",
    meaning: "Cathodic Tafel constant a_c, fitted with current densities in A/cm^2 (Table 2).",
    feeds: "a_c in eq. 18",
};

/// `corrosion.tafel_b_c_v_per_decade`.
pub(in crate::scene) const TAFEL_B: Field = Field {
    path: "corrosion.tafel_b_c_v_per_decade",
    unit: "V/decade",
    range: Range::Positive,
    why: "",
    meaning: "Cathodic Tafel slope b_c (Table 2).",
    feeds: "b_c in eq. 18",
};

/// `corrosion.anodic_current_density_a_cm2`.
pub(in crate::scene) const ANODIC_CURRENT: Field = Field {
    path: "corrosion.anodic_current_density_a_cm2",
    unit: "A/cm^2",
    range: Range::Positive,
    why: "",
    meaning: "Anodic current density i_a on depassivated metal (the paper's typical 10 \
              mA/cm^2).",
    feeds: "i_a in eq. 18 and in Faraday's law",
};

/// `corrosion.exposed_area_cm2`.
pub(in crate::scene) const EXPOSED_AREA: Field = Field {
    path: "corrosion.exposed_area_cm2",
    unit: "cm^2",
    range: Range::Positive,
    why: "",
    meaning: "Electrode area exposed to the electrolyte; the cathodic area A_c is this less \
              the anodic area.",
    feeds: "A_c in eq. 18",
};

/// `corrosion.anodic_area`.
pub(in crate::scene) const ANODIC_AREA: Field = Field {
    path: "corrosion.anodic_area",
    unit: "",
    range: Range::OneOf(&["wear_track", "real_contact", "bem_contact"]),
    why: "",
    meaning: "Which area depassivates: `wear_track` (track width x track length, as in the \
              paper's Fig. 13), `real_contact` (F / H) or `bem_contact` (the solved contact \
              area: on a rough disc, `disc.surface`, the real contact area at the asperity \
              scale, so Fig. 14's depassivated-to-real ratio comes from the model rather \
              than from F / H).",
    feeds: "A_a in eq. 18 and in Faraday's law",
};

/// `corrosion.anodic_area_factor`.
pub(in crate::scene) const ANODIC_AREA_FACTOR: Field = Field {
    path: "corrosion.anodic_area_factor",
    unit: "",
    range: Range::Positive,
    why: "",
    meaning: "Multiplier on the chosen anodic area (the paper finds the depassivated area \
              about 50 times F / H).",
    feeds: "A_a in eq. 18 and in Faraday's law",
};

/// `corrosion.molar_mass_g_mol`.
pub(in crate::scene) const MOLAR_MASS: Field = Field {
    path: "corrosion.molar_mass_g_mol",
    unit: "g/mol",
    range: Range::Positive,
    why: "",
    meaning: "Molar mass M of the dissolving metal (iron).",
    feeds: FARADAY_FEEDS,
};

/// `corrosion.valence`.
pub(in crate::scene) const VALENCE: Field = Field {
    path: "corrosion.valence",
    unit: "",
    range: Range::Positive,
    why: "",
    meaning: "Charge number z of the dissolution reaction (Fe -> Fe2+ + 2e-).",
    feeds: FARADAY_FEEDS,
};

/// `corrosion.density_g_cm3`.
pub(in crate::scene) const DENSITY: Field = Field {
    path: "corrosion.density_g_cm3",
    unit: "g/cm^3",
    range: Range::Positive,
    why: "",
    meaning: "Density rho of the dissolving metal.",
    feeds: FARADAY_FEEDS,
};
