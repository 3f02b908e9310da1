//! The discs of the library: each value as read, with its source, or the reason it is
//! missing. Hardness is Vickers in MPa (HV x 9.807, a unit conversion only).

use super::{DiscMaterial, DiscMaterialName, Electrochemistry, Property, missing, read};
use crate::corrosion::ReferenceElectrode;
use crate::corrosion::alloys::{COCRMO, CP_TITANIUM, STAINLESS_304, STAINLESS_316L, TI_6AL_4V};
use crate::scene::PAPER_HARDNESS_TABLE;

/// Newtons per kilogram-force: HV (kgf/mm^2) to MPa.
const MPA_PER_HV: f64 = 9.806_65;

/// A Vickers hardness read as HV, in MPa.
const fn vickers(hv: f64, source: &'static str, note: &'static str) -> Property {
    read(hv * MPA_PER_HV, source, note)
}

/// The paper's disc: every value as the paper measured or fitted it.
const AISI_316L: DiscMaterial = DiscMaterial {
    name: DiscMaterialName::Aisi316l,
    label: "AISI 316L (UNS S31603), annealed: the paper's disc",
    youngs_modulus_gpa: read(205.0, "dalmau2018", "by ultrasound, +- 6"),
    poisson_ratio: read(0.28, "dalmau2018", ""),
    hardness_mpa: read(2473.0, "dalmau2018", "HV1, 30 s, +- 110"),
    hardness_table: Some(&PAPER_HARDNESS_TABLE),
    hardness_law_source: "dalmau2018",
    initial_yield_strength_mpa: read(290.0, "ak-316l", "typical, 42 ksi"),
    alloy: STAINLESS_316L,
    electrochemistry: Some(Electrochemistry {
        medium: "3% NaCl, pH 6, aerated, room temperature",
        reference_electrode: ReferenceElectrode::AgAgCl3MKcl,
        corrosion_potential_v: -0.10,
        tafel_a_c_v: -3.31,
        tafel_b_c_v_per_decade: 0.56,
        anodic_current_density_a_cm2: 0.01,
        source: "dalmau2018",
    }),
};

const AISI_304: DiscMaterial = DiscMaterial {
    name: DiscMaterialName::Aisi304,
    label: "AISI 304 (UNS S30400), annealed",
    youngs_modulus_gpa: read(193.0, "matweb-304", "the low end of 193-200"),
    poisson_ratio: read(0.29, "matweb-304", ""),
    hardness_mpa: vickers(
        129.0,
        "matweb-304",
        "HV 129, converted from HRB 70 by MatWeb",
    ),
    hardness_table: None,
    hardness_law_source: "",
    initial_yield_strength_mpa: read(290.0, "ak-304", "typical, 42 ksi"),
    alloy: STAINLESS_304,
    electrochemistry: None,
};

const TI_6AL_4V_GRADE5: DiscMaterial = DiscMaterial {
    name: DiscMaterialName::Ti6Al4V,
    label: "Ti-6Al-4V (Grade 5, UNS R56400), annealed",
    youngs_modulus_gpa: read(114.0, "matweb-ti64", "mean of tension and compression"),
    poisson_ratio: read(0.33, "matweb-ti64", ""),
    hardness_mpa: vickers(349.0, "materials2021-ti64", "HV1 349 +- 3, measured"),
    hardness_table: None,
    hardness_law_source: "",
    initial_yield_strength_mpa: read(830.0, "matweb-ti64", "typical"),
    alloy: TI_6AL_4V,
    electrochemistry: None,
};

const COCRMO_F75: DiscMaterial = DiscMaterial {
    name: DiscMaterialName::CoCrMo,
    label: "CoCrMo (ASTM F75, UNS R30075), annealed cast",
    youngs_modulus_gpa: read(210.0, "makeitfrom-f75", ""),
    poisson_ratio: read(0.29, "makeitfrom-f75", ""),
    hardness_mpa: missing(
        "no Vickers hardness of F75 was read (MakeItFrom gives HRC 28 for wrought low-carbon \
         F1537); give your disc's HV x 9.807",
    ),
    hardness_table: None,
    hardness_law_source: "",
    initial_yield_strength_mpa: read(480.0, "makeitfrom-f75", ""),
    alloy: COCRMO,
    electrochemistry: None,
};

const CP_TI_GRADE2: DiscMaterial = DiscMaterial {
    name: DiscMaterialName::CpTiGrade2,
    label: "Commercially pure titanium, Grade 2 (UNS R50400), annealed",
    youngs_modulus_gpa: read(105.0, "superior-ti2", ""),
    poisson_ratio: read(0.34, "matweb-ti2", ""),
    hardness_mpa: vickers(145.0, "matweb-ti2-generic", "HV 145, load not stated"),
    hardness_table: None,
    hardness_law_source: "",
    initial_yield_strength_mpa: read(340.0, "matweb-ti2", "typical"),
    alloy: CP_TITANIUM,
    electrochemistry: None,
};

/// Every disc of the library, in the order of `docs/materials.md`.
pub const DISCS: [DiscMaterial; 5] = [
    AISI_316L,
    AISI_304,
    TI_6AL_4V_GRADE5,
    COCRMO_F75,
    CP_TI_GRADE2,
];
