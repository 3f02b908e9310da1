//! The descriptors of `corrosion`, the electrochemical cell of Section 5.1, and of the
//! open-circuit times of `test` around the rubbing (see [`super::FIELDS`]).

use crate::scene::TAFEL_OVERPOTENTIAL_RANGE_V;
use crate::scene::field::{Field, Range};

const FARADAY_FEEDS: &str = "Faraday's law: V_WAC = i_a A_a t M / (z F rho)";

/// `test.ocp_before_s`.
pub(in crate::scene) const OCP_BEFORE: Field = Field {
    path: "test.ocp_before_s",
    unit: "s",
    range: Range::AtLeast(0.0),
    why: "",
    meaning: "Open-circuit time recorded before the rubbing starts: the result's `ocp_trace` \
              starts this long before the ball moves, at E_corr. The paper's protocol holds \
              the OCP 3600 s before sliding (Section 2.3); 0 starts the trace at the \
              rubbing's start.",
    feeds: "the OCP trace of Fig. 6",
};

/// `test.ocp_after_s`.
pub(in crate::scene) const OCP_AFTER: Field = Field {
    path: "test.ocp_after_s",
    unit: "s",
    range: Range::AtLeast(0.0),
    why: "",
    meaning: "Open-circuit time recorded after the rubbing stops, while the bare area \
              repassivates (the paper's protocol: 1200 s, Section 2.3); 0 ends the trace at \
              the stop.",
    feeds: "the OCP trace of Fig. 6",
};

/// `corrosion.corrosion_potential_v`.
pub(in crate::scene) const CORROSION_POTENTIAL: Field = Field {
    path: "corrosion.corrosion_potential_v",
    unit: "V",
    range: Range::Finite,
    why: "",
    meaning: "Free corrosion potential E_corr (the open-circuit potential before rubbing, \
              Table 2), against `corrosion.reference_electrode`. Left out while \
              `reference_electrode` is given, it is the paper's -0.10 V vs Ag/AgCl in that \
              electrode (-0.136 V vs SCE, +0.105 V vs SHE).",
    feeds: "E_corr in eq. 18",
};

/// `corrosion.reference_electrode`.
pub(in crate::scene) const REFERENCE: Field = Field {
    path: "corrosion.reference_electrode",
    unit: "",
    range: Range::OneOf(&["ag_agcl_3m_kcl", "ag_agcl_sat_kcl", "sce", "she"]),
    why: "",
    meaning: "The electrode every potential is against: E_corr here, the potentials of \
              `tribosim calibrate tafel` and `ocp` tables, and every potential of the result \
              (`summary.potential_reference` names it). `ag_agcl_3m_kcl`: +0.205 V vs SHE, \
              the paper's (Section 2.2); `ag_agcl_sat_kcl`: Ag/AgCl in saturated KCl, \
              +0.197 V vs SHE; `sce`: +0.241 V vs SHE; `she`: 0.",
    feeds: "the reference of every potential",
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

/// `corrosion.tafel_overpotential_min_v`.
pub(in crate::scene) const TAFEL_ETA_MIN: Field = Field {
    path: "corrosion.tafel_overpotential_min_v",
    unit: "V",
    range: Range::Closed(TAFEL_OVERPOTENTIAL_RANGE_V.0, TAFEL_OVERPOTENTIAL_RANGE_V.1),
    why: "below E_corr, within the few volts an aqueous scan covers",
    meaning: "The most cathodic potential of the Tafel line's fitted domain, as E - E_corr \
              (the paper's scan ends at -1.1 V: -1.0). A potential during rubbing below it \
              is outside what a_c and b_c were fitted on: the result warns.",
    feeds: "the domain of eq. 18",
};

/// `corrosion.tafel_overpotential_max_v`.
pub(in crate::scene) const TAFEL_ETA_MAX: Field = Field {
    path: "corrosion.tafel_overpotential_max_v",
    unit: "V",
    range: Range::Closed(TAFEL_OVERPOTENTIAL_RANGE_V.0, TAFEL_OVERPOTENTIAL_RANGE_V.1),
    why: "below E_corr, within the few volts an aqueous scan covers, and above \
          `tafel_overpotential_min_v`",
    meaning: "The least cathodic potential of the Tafel line's fitted domain, as E - E_corr \
              (the paper's Tafel domain lies below -0.15 V: -0.05). A potential during \
              rubbing above it is outside what a_c and b_c were fitted on: the result warns.",
    feeds: "the domain of eq. 18",
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
    range: Range::OneOf(&[
        "depassivated_wake",
        "hertz_band",
        "wear_track",
        "real_contact",
        "bem_contact",
        "asperity_spots",
        "contact_spots",
    ]),
    why: "",
    meaning: "Which area depassivates (`docs/corrosion.md`). `depassivated_wake`: the real \
              contact F / H, stripped as it crosses the solved contact and bare for \
              `repassivation_time_s` after it, F / H (1 + v tau / L) with L the solved \
              contact's mean chord along the sliding (each island's chords counted on a \
              rough disc); `hertz_band`: F / H plus a band as wide as the unworn Hertz \
              contact, bare for tau, F / H + 2a v tau; `wear_track` (track width x track \
              length, as in the paper's Fig. 13); `real_contact` (F / H) or `bem_contact` \
              (the solved contact area: on a rough disc, `disc.surface`, the real contact \
              area at the asperity scale); `asperity_spots`: the plastically deformed spots \
              of the solved contact (cells at the cap), island by island, each stripped as it \
              enters the contact and repassivating by `repassivation_kinetics` until the next \
              spot of its row strips it again, every row of the track carrying its own age \
              (no fitted constant: tau defaults to 0.01 s with these models); \
              `contact_spots`: the same with every cell in contact a spot.",
    feeds: "A_a in eq. 18 and in Faraday's law",
};

/// `corrosion.repassivation_time_s`.
pub(in crate::scene) const REPASSIVATION_TIME: Field = Field {
    path: "corrosion.repassivation_time_s",
    unit: "s",
    range: Range::AtLeast(0.0),
    why: "and, with `depassivated_wake` or `hertz_band`, short enough that the wake v tau \
          stays shorter than the track",
    meaning: "How long a stripped spot stays bare after the contact leaves it, tau, at the \
              anodic current density i_a. During rubbing tau enters the potential and the WAC \
              volume only as Q_p = i_a tau, the charge that repassivates a unit of bare area \
              (default: 1.48 mC/cm^2); after the stop the bare area decays as exp(-t / tau). \
              The default is the fit to the paper's A_a = 50 F / H on the default run; a \
              section that names `asperity_spots` or `contact_spots` without this field gets \
              0.01 s instead, not fitted (`docs/corrosion.md`). With the power law it is t0, \
              how long a spot passes the full i_a.",
    feeds: "A_a in eq. 18 and in Faraday's law (Section 5.1's repassivation)",
};

/// `corrosion.repassivation_kinetics`.
pub(in crate::scene) const REPASSIVATION_KINETICS: Field = Field {
    path: "corrosion.repassivation_kinetics",
    unit: "",
    range: Range::OneOf(&["exponential", "power_law"]),
    why: "",
    meaning: "The current transient of a stripped spot, as a fraction of i_a: `exponential`, \
              exp(-t / tau); `power_law`, 1 up to t0 = `repassivation_time_s`, then (t / \
              t0)^-n with n = `repassivation_exponent` (film-growth laws: n = 1/2 limited by \
              transport through the film, near 1 for high-field growth). Used by the spot \
              models, during the rubbing and after the stop (the wake and the band decay \
              as exp(-t / tau) after it).",
    feeds: "A_a of `asperity_spots` and `contact_spots`; the OCP after the stop",
};

/// `corrosion.repassivation_exponent`.
pub(in crate::scene) const REPASSIVATION_EXPONENT: Field = Field {
    path: "corrosion.repassivation_exponent",
    unit: "1",
    range: Range::Open(0.0, 3.0),
    why: " (film-growth transients fall as t^-1/2 to t^-1; above 3 the tail is gone within \
          a few t0, an exponential's job)",
    meaning: "The power law's exponent n (`repassivation_kinetics: \"power_law\"`).",
    feeds: "the power-law transient",
};

/// `corrosion.galvanic_cell`.
pub(in crate::scene) const GALVANIC_CELL: Field = Field {
    path: "corrosion.galvanic_cell",
    unit: "",
    range: Range::OneOf(&["eq18", "balanced"]),
    why: "",
    meaning: "How the potential follows from the anodic area. `eq18`: eq. 18 as printed, \
              capped at E_corr where it would rise above it. `balanced`: the charge balance \
              at open circuit, with the passive area's own current 10^(a_c / b_c) kept (which \
              eq. 18 drops: at the paper's A_a of 0.1 mm^2 that lowers E by 66 mV), the \
              anode at E - I R (`ohmic_resistance_ohm`) and the bare metal's net current \
              falling to 0 at `bare_corrosion_potential_v`, which bounds the potential.",
    feeds: "the potential during rubbing and after; the anodic current and the WAC",
};

/// `corrosion.bare_corrosion_potential_v`.
pub(in crate::scene) const BARE_CORROSION_POTENTIAL: Field = Field {
    path: "corrosion.bare_corrosion_potential_v",
    unit: "V",
    range: Range::Finite,
    why: " and below `corrosion_potential_v`, or null for none",
    meaning: "The bare metal's own corrosion potential, against `reference_electrode`: the \
              floor of the `balanced` cell. No value for 316L in NaCl was found in the \
              literature this project could reach, so the default is null (no floor, the \
              bare metal passes i_a at any potential, as eq. 18 assumes).",
    feeds: "the `balanced` cell",
};

/// `corrosion.ohmic_resistance_ohm`.
pub(in crate::scene) const OHMIC_RESISTANCE: Field = Field {
    path: "corrosion.ohmic_resistance_ohm",
    unit: "ohm",
    range: Range::AtLeast(0.0),
    why: "",
    meaning: "Electrolyte resistance between the bare spots and the passive area (the \
              `balanced` cell). 0 by default: Newman's disc resistance 1 / (4 kappa r) for \
              0.1 mm^2 of anode in seawater-like 3% NaCl (kappa about 5 S/m) is about 280 \
              ohm, a drop of about 3 mV at the paper's current.",
    feeds: "the `balanced` cell",
};

/// `corrosion.control`.
pub(in crate::scene) const CONTROL: Field = Field {
    path: "corrosion.control",
    unit: "",
    range: Range::OneOf(&["open_circuit", "potentiostatic"]),
    why: "",
    meaning: "What sets the disc's potential. `open_circuit`: the galvanic cell (the paper's \
              test). `potentiostatic`: a potentiostat holds it at `applied_potential_v`; the \
              bare spots then dissolve at the bare metal's net current there, which needs \
              `bare_corrosion_potential_v` (below it nothing dissolves: cathodic protection, \
              ASTM G119's run for the mechanical loss alone). Each record's \
              `anodic_current_ma` is then the potentiostat's current less the passive \
              area's constant share, which the `corrosion` model gives; there is no OCP trace.",
    feeds: "the potential, the anodic current and the WAC",
};

/// `corrosion.applied_potential_v`.
pub(in crate::scene) const APPLIED_POTENTIAL: Field = Field {
    path: "corrosion.applied_potential_v",
    unit: "V",
    range: Range::Finite,
    why: ", within 3 V below and 1 V above `corrosion_potential_v` (what an aqueous cell \
          holds without decomposing the water), with `control: \"potentiostatic\"`",
    meaning: "The potential the potentiostat holds, against `reference_electrode`; null at \
              open circuit.",
    feeds: "the potentiostatic cell",
};

/// `corrosion.anodic_area_factor`.
pub(in crate::scene) const ANODIC_AREA_FACTOR: Field = Field {
    path: "corrosion.anodic_area_factor",
    unit: "",
    range: Range::Positive,
    why: "",
    meaning: "Multiplier on the chosen anodic area: 1 for the depassivation models, whose \
              parameter is `repassivation_time_s`; the paper finds the depassivated area \
              about 50 times F / H, so 50 with `real_contact` is its reading of Fig. 14.",
    feeds: "A_a in eq. 18 and in Faraday's law",
};

/// `corrosion.faraday`.
pub(in crate::scene) const FARADAY: Field = Field {
    path: "corrosion.faraday",
    unit: "",
    range: Range::OneOf(&[
        "316l_g102",
        "304_g102",
        "ti6al4v_g102",
        "cp_ti_g102",
        "cocrmo_g102",
        "pure_iron",
        "given",
    ]),
    why: "",
    meaning: "What Faraday's law dissolves, as its equivalent weight EW = M / z and density \
              (V_WAC = Q EW / (F rho)). `316l_g102` (the default): 316L dissolving \
              congruently, ASTM G102's EW = 1 / sum(n_i f_i / W_i) over Fe 68.5, Cr 17, Ni \
              12, Mo 2.5 wt% at valences 2, 3, 2, 3, 25.50 g/eq, at 7.98 g/cm^3; \
              `304_g102`, `ti6al4v_g102`, `cp_ti_g102`, `cocrmo_g102`: the library's discs by \
              the same rule (`docs/materials.md`), which `disc.material` sets; \
              `pure_iron`: Fe -> Fe2+, 27.92 g/eq at 7.874 g/cm^3, 11% more volume per \
              coulomb; `given`: `molar_mass_g_mol / valence` at `density_g_cm3`. Before \
              this field, every run dissolved iron (55.85 g/mol, z 2, 7.9 g/cm^3): the \
              default WAC is 9.6% below those runs'. A section that gives `molar_mass_g_mol`, \
              `valence` or `density_g_cm3` without `faraday` is `given`. The result's \
              `models` name the choice (`faraday`).",
    feeds: FARADAY_FEEDS,
};

/// `corrosion.molar_mass_g_mol`.
pub(in crate::scene) const MOLAR_MASS: Field = Field {
    path: "corrosion.molar_mass_g_mol",
    unit: "g/mol",
    range: Range::Positive,
    why: "",
    meaning: "Molar mass M of the dissolving metal, read with `faraday` `given` (default: \
              iron's).",
    feeds: FARADAY_FEEDS,
};

/// `corrosion.valence`.
pub(in crate::scene) const VALENCE: Field = Field {
    path: "corrosion.valence",
    unit: "",
    range: Range::Positive,
    why: "",
    meaning: "Charge number z of the dissolution reaction, read with `faraday` `given` \
              (default: Fe -> Fe2+ + 2e-).",
    feeds: FARADAY_FEEDS,
};

/// `corrosion.density_g_cm3`.
pub(in crate::scene) const DENSITY: Field = Field {
    path: "corrosion.density_g_cm3",
    unit: "g/cm^3",
    range: Range::Positive,
    why: "",
    meaning: "Density rho of the dissolving metal, read with `faraday` `given`.",
    feeds: FARADAY_FEEDS,
};
