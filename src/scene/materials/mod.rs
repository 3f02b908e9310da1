//! The materials library: discs and balls with values read from named sources
//! (`docs/materials.md`, rendered from here by [`materials_table`]). A scene names one with
//! `disc.material` or `ball.material`; the values it does not give come from the library
//! (`expand.rs`), and a value the library lacks is refused at its field, never invented.

mod balls;
mod discs;
pub(super) mod expand;
mod provenance;
mod sources;
mod table;

use serde::{Deserialize, Serialize};

use crate::corrosion::ReferenceElectrode;
use crate::corrosion::alloys::Alloy;

pub use balls::BALLS;
pub use discs::DISCS;
pub use provenance::describe;
pub use sources::{REFERENCES, Reference, reference};
pub use table::{MATERIALS_BEGIN, MATERIALS_END, materials_table};

/// One value of a material: as read, or missing with the reason.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Property {
    /// The value in the field's unit; `None` when no source was read.
    pub value: Option<f64>,
    /// The [`Reference`] key it was read from (empty when missing).
    pub source: &'static str,
    /// How it was read (a conversion, a condition), or why it is missing.
    pub note: &'static str,
}

/// A value read from `source`.
pub(crate) const fn read(value: f64, source: &'static str, note: &'static str) -> Property {
    Property {
        value: Some(value),
        source,
        note,
    }
}

/// A value no source gave, and what the user can do.
pub(crate) const fn missing(note: &'static str) -> Property {
    Property {
        value: None,
        source: "",
        note,
    }
}

/// The disc materials a scene can name in `disc.material`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum DiscMaterialName {
    /// AISI 316L, the paper's disc.
    #[serde(rename = "aisi_316l")]
    Aisi316l,
    /// AISI 304.
    #[serde(rename = "aisi_304")]
    Aisi304,
    /// Ti-6Al-4V, Grade 5.
    #[serde(rename = "ti6al4v")]
    Ti6Al4V,
    /// CoCrMo, ASTM F75.
    #[serde(rename = "cocrmo")]
    CoCrMo,
    /// Commercially pure titanium, Grade 2.
    #[serde(rename = "cp_ti_grade2")]
    CpTiGrade2,
}

/// The ball materials a scene can name in `ball.material`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum BallMaterialName {
    /// Sintered alumina.
    #[serde(rename = "alumina")]
    Alumina,
    /// 3Y-TZP zirconia.
    #[serde(rename = "zirconia")]
    Zirconia,
    /// Silicon nitride.
    #[serde(rename = "si3n4")]
    SiliconNitride,
    /// 100Cr6 / 52100 bearing steel.
    #[serde(rename = "100cr6")]
    Steel100Cr6,
    /// WC-Co cemented carbide.
    #[serde(rename = "wc_co")]
    TungstenCarbide,
}

/// The names `disc.material` accepts, in the library's order.
pub const DISC_MATERIAL_NAMES: &[&str] =
    &["aisi_316l", "aisi_304", "ti6al4v", "cocrmo", "cp_ti_grade2"];

/// The names `ball.material` accepts, in the library's order.
pub const BALL_MATERIAL_NAMES: &[&str] = &["alumina", "zirconia", "si3n4", "100cr6", "wc_co"];

/// The electrochemical constants of a disc in one medium, as one source gives them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Electrochemistry {
    /// The electrolyte and conditions they were measured in.
    pub medium: &'static str,
    /// The electrode the potentials are against.
    pub reference_electrode: ReferenceElectrode,
    /// Free corrosion potential, V.
    pub corrosion_potential_v: f64,
    /// Cathodic Tafel constant a_c, V (current densities in A/cm^2).
    pub tafel_a_c_v: f64,
    /// Cathodic Tafel slope b_c, V per decade.
    pub tafel_b_c_v_per_decade: f64,
    /// Anodic current density on depassivated metal, A/cm^2.
    pub anodic_current_density_a_cm2: f64,
    /// The [`Reference`] key.
    pub source: &'static str,
}

/// A disc of the library.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DiscMaterial {
    /// What `disc.material` calls it.
    pub name: DiscMaterialName,
    /// Its name in words, with its condition.
    pub label: &'static str,
    /// Young's modulus, GPa.
    pub youngs_modulus_gpa: Property,
    /// Poisson's ratio.
    pub poisson_ratio: Property,
    /// Vickers hardness, MPa.
    pub hardness_mpa: Property,
    /// A published hardness of the worn surface against the cycle count, `(cycles, MPa)`.
    pub hardness_table: Option<&'static [(f64, f64)]>,
    /// The [`Reference`] key of `hardness_table` (empty without one).
    pub hardness_law_source: &'static str,
    /// 0.2% proof stress, MPa.
    pub initial_yield_strength_mpa: Property,
    /// What Faraday's law dissolves: composition, valences and density.
    #[serde(skip)]
    pub alloy: Alloy,
    /// The constants in chloride; `None` when no source was read.
    pub electrochemistry: Option<Electrochemistry>,
}

/// A ball of the library.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BallMaterial {
    /// What `ball.material` calls it.
    pub name: BallMaterialName,
    /// Its name in words, with its grade.
    pub label: &'static str,
    /// Young's modulus, GPa.
    pub youngs_modulus_gpa: Property,
    /// Poisson's ratio.
    pub poisson_ratio: Property,
    /// Density, g/cm^3.
    pub density_g_cm3: Property,
    /// Hardness in the scale the source gives, and the source's key.
    pub hardness: (&'static str, &'static str),
}

impl DiscMaterialName {
    /// The library's entry.
    pub fn material(self) -> &'static DiscMaterial {
        DISCS.iter().find(|d| d.name == self).unwrap_or(&DISCS[0])
    }
}

impl BallMaterialName {
    /// The library's entry.
    pub fn material(self) -> &'static BallMaterial {
        BALLS.iter().find(|b| b.name == self).unwrap_or(&BALLS[0])
    }
}

/// The library as `GET /api/v1/materials` and `tribosim presets --materials` list it.
#[derive(Debug, Clone, Serialize)]
pub struct Library {
    /// The discs.
    pub discs: Vec<DiscListing>,
    /// The balls.
    pub balls: &'static [BallMaterial],
    /// The documents the values cite.
    pub references: &'static [Reference],
}

/// A disc as listed: its entry with its density and equivalent weight spelled out.
#[derive(Debug, Clone, Serialize)]
pub struct DiscListing {
    /// The entry.
    #[serde(flatten)]
    pub material: DiscMaterial,
    /// Density, g/cm^3.
    pub density_g_cm3: f64,
    /// ASTM G102's equivalent weight, g/eq.
    pub equivalent_weight_g_per_eq: f64,
    /// What `corrosion.faraday` the disc dissolves by, and where its numbers come from.
    pub faraday: &'static str,
    /// Where the composition and density come from.
    pub composition_source: &'static str,
    /// The [`Reference`] key of the equivalent weight's rule.
    pub equivalent_weight_source: &'static str,
}

/// The whole library.
pub fn library() -> Library {
    Library {
        discs: DISCS
            .iter()
            .map(|d| DiscListing {
                material: *d,
                density_g_cm3: d.alloy.density_g_cm3,
                equivalent_weight_g_per_eq: d.alloy.equivalent_weight_g_per_eq(),
                faraday: d.alloy.basis,
                composition_source: d.alloy.source,
                equivalent_weight_source: "astm-g102",
            })
            .collect(),
        balls: &BALLS,
        references: REFERENCES,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_names_lists_are_the_entries_names_in_order() {
        let discs: Vec<String> = DISCS
            .iter()
            .map(|d| crate::json::variant_name(d.name))
            .collect();
        assert_eq!(discs, DISC_MATERIAL_NAMES);
        let balls: Vec<String> = BALLS
            .iter()
            .map(|b| crate::json::variant_name(b.name))
            .collect();
        assert_eq!(balls, BALL_MATERIAL_NAMES);
    }

    #[test]
    fn every_value_cites_a_listed_reference_or_says_why_it_is_missing() {
        let properties = DISCS
            .iter()
            .flat_map(|d| {
                [
                    d.youngs_modulus_gpa,
                    d.poisson_ratio,
                    d.hardness_mpa,
                    d.initial_yield_strength_mpa,
                ]
            })
            .chain(
                BALLS
                    .iter()
                    .flat_map(|b| [b.youngs_modulus_gpa, b.poisson_ratio, b.density_g_cm3]),
            );
        for p in properties {
            match p.value {
                Some(_) => assert!(reference(p.source).is_some(), "{p:?}"),
                None => assert!(p.source.is_empty() && !p.note.is_empty(), "{p:?}"),
            }
        }
        let other_keys = DISCS
            .iter()
            .filter_map(|d| d.electrochemistry.map(|e| e.source))
            .chain(
                DISCS
                    .iter()
                    .map(|d| d.hardness_law_source)
                    .filter(|k| !k.is_empty()),
            )
            .chain(BALLS.iter().map(|b| b.hardness.1));
        for key in other_keys {
            assert!(reference(key).is_some(), "{key}");
        }
        // Each reference is cited: none is listed for nothing.
        let listing = serde_json::to_string(&library()).expect("serialises");
        for r in REFERENCES {
            let cited = listing.matches(&format!("\"{}\"", r.key)).count();
            assert!(cited >= 2, "{} is not cited", r.key);
        }
    }
}
