//! A scene that names a material: the library's values fill the fields the user's own
//! object does not give, before it is merged into a preset or deserialised, so that a given
//! value always wins. What the library lacks and the scene needs is refused at its field.

use serde_json::{Map, Value};

use super::{BallMaterialName, DiscMaterial, DiscMaterialName, Property};
use crate::scene::{FieldError, field};

/// The electrochemical fields a scene with a `corrosion` section needs from its disc's
/// material, and `repassivation_time_s`, whose default is fitted to the paper's 316L.
const ELECTROCHEMICAL_FIELDS: [&str; 5] = [
    "corrosion_potential_v",
    "tafel_a_c_v",
    "tafel_b_c_v_per_decade",
    "anodic_current_density_a_cm2",
    "repassivation_time_s",
];

/// Fills `user` (the user's own scene object: the document, or a preset's `overrides`)
/// from the materials it names, where `base` (the preset's scene, or `Value::Null` without
/// one) does not name them; returns what the library lacks and the scene needs, located in
/// `user`.
pub(in crate::scene) fn expand(user: &mut Map<String, Value>, base: &Value) -> Vec<FieldError> {
    let named = |section: &str| -> Option<String> {
        let own = user.get(section).and_then(|s| s.get("material"));
        own.or_else(|| base.get(section).and_then(|s| s.get("material")))
            .and_then(Value::as_str)
            .map(str::to_owned)
    };
    let disc = named("disc").and_then(|n| parse::<DiscMaterialName>(&n));
    let ball = named("ball").and_then(|n| parse::<BallMaterialName>(&n));
    let mut errors = Vec::new();
    if let Some(disc) = disc.map(DiscMaterialName::material) {
        fill_disc(user, disc, &mut errors);
        if corrosion_is_on(user, base) {
            fill_corrosion(user, disc, &mut errors);
        }
    }
    let ball_section = ball.and_then(|b| Some((b.material(), section_mut(user, "ball")?)));
    if let Some((ball, section)) = ball_section {
        for (key, property) in [
            ("youngs_modulus_gpa", ball.youngs_modulus_gpa),
            ("poisson_ratio", ball.poisson_ratio),
        ] {
            fill(section, "ball", key, property, ball.label, &mut errors);
        }
    }
    let papers_pair = disc.is_none_or(|d| d == DiscMaterialName::Aisi316l)
        && ball.is_none_or(|b| b == BallMaterialName::Alumina);
    if !papers_pair && !gives_k(user) {
        errors.push(FieldError::new(
            "wear.archard_k",
            format!(
                "the default k is the paper's calibration for 316L against its alumina ball; \
                 a scene that names another pair ({}; {}) needs its own: give \
                 `archard_k` ({}) or `archard_calibration` from a test of that pair",
                disc.map_or("the paper's 316L", |d| d.material().label),
                ball.map_or("the paper's alumina", |b| b.material().label),
                allowed("wear.archard_k"),
            ),
        ));
    }
    errors
}

fn parse<T: serde::de::DeserializeOwned>(name: &str) -> Option<T> {
    serde_json::from_value(Value::from(name)).ok()
}

fn allowed(path: &str) -> String {
    field(path).map_or_else(String::new, |f| f.allowed())
}

/// The user's object at `key`, made an object if absent; `None` when it is something else,
/// which the deserialiser refuses.
fn section_mut<'a>(
    user: &'a mut Map<String, Value>,
    key: &str,
) -> Option<&'a mut Map<String, Value>> {
    user.entry(key.to_owned())
        .or_insert_with(|| Value::Object(Map::new()))
        .as_object_mut()
}

/// Sets `key` of `section` from `property` unless given; a missing property is an error at
/// `prefix.key`.
fn fill(
    section: &mut Map<String, Value>,
    prefix: &str,
    key: &str,
    property: Property,
    label: &str,
    errors: &mut Vec<FieldError>,
) {
    if section.contains_key(key) {
        return;
    }
    let path = format!("{prefix}.{key}");
    match property.value {
        Some(value) => {
            section.insert(key.to_owned(), Value::from(value));
        }
        None => errors.push(FieldError::new(
            path.as_str(),
            format!(
                "the materials library has no sourced value for {label} ({}); give `{key}` \
                 ({})",
                property.note,
                allowed(&path)
            ),
        )),
    }
}

fn fill_disc(user: &mut Map<String, Value>, disc: &DiscMaterial, errors: &mut Vec<FieldError>) {
    let Some(section) = section_mut(user, "disc") else {
        return;
    };
    for (key, property) in [
        ("youngs_modulus_gpa", disc.youngs_modulus_gpa),
        ("poisson_ratio", disc.poisson_ratio),
        ("hardness_mpa", disc.hardness_mpa),
        (
            "initial_yield_strength_mpa",
            disc.initial_yield_strength_mpa,
        ),
    ] {
        fill(section, "disc", key, property, disc.label, errors);
    }
    if !section.contains_key("hardness_table") {
        let table = disc.hardness_table.map_or(Value::Null, |points| {
            points
                .iter()
                .map(|&(n, h)| Value::from(vec![n, h]))
                .collect()
        });
        section.insert("hardness_table".to_owned(), table);
    }
}

/// Whether the scene the user's object makes has a `corrosion` section: its own, or
/// `base`'s (the default's, which has one, without a preset).
fn corrosion_is_on(user: &Map<String, Value>, base: &Value) -> bool {
    match user.get("corrosion") {
        Some(section) => !section.is_null(),
        None => base.is_null() || base.get("corrosion").is_some_and(|c| !c.is_null()),
    }
}

fn fill_corrosion(
    user: &mut Map<String, Value>,
    disc: &DiscMaterial,
    errors: &mut Vec<FieldError>,
) {
    let Some(section) = section_mut(user, "corrosion") else {
        return;
    };
    let names_metal = ["faraday", "molar_mass_g_mol", "valence", "density_g_cm3"]
        .iter()
        .any(|k| section.contains_key(*k));
    if !names_metal {
        section.insert("faraday".to_owned(), Value::from(disc.alloy.basis));
    }
    let Some(constants) = disc.electrochemistry else {
        for key in ELECTROCHEMICAL_FIELDS {
            if section.contains_key(key) {
                continue;
            }
            let path = format!("corrosion.{key}");
            errors.push(FieldError::new(
                path.as_str(),
                format!(
                    "the materials library has no electrochemical constants in chloride for \
                     {} (docs/materials.md), and the default is the paper's 316L; give \
                     `{key}` ({}), or set `corrosion` to null to predict the wear alone",
                    disc.label,
                    allowed(&path)
                ),
            ));
        }
        return;
    };
    let reference = section
        .get("reference_electrode")
        .and_then(|r| serde_json::from_value(r.clone()).ok())
        .unwrap_or(constants.reference_electrode);
    let corrosion_potential_v = constants
        .reference_electrode
        .convert_v(constants.corrosion_potential_v, reference);
    for (key, value) in [
        ("corrosion_potential_v", corrosion_potential_v),
        ("tafel_a_c_v", constants.tafel_a_c_v),
        ("tafel_b_c_v_per_decade", constants.tafel_b_c_v_per_decade),
        (
            "anodic_current_density_a_cm2",
            constants.anodic_current_density_a_cm2,
        ),
    ] {
        section.entry(key).or_insert_with(|| Value::from(value));
    }
    section
        .entry("reference_electrode")
        .or_insert_with(|| serde_json::to_value(reference).unwrap_or(Value::Null));
}

/// Whether the user's own `wear` gives k or a calibration point.
fn gives_k(user: &Map<String, Value>) -> bool {
    user.get("wear").is_some_and(|wear| {
        ["archard_k", "archard_calibration"]
            .iter()
            .any(|k| wear.get(*k).is_some_and(|v| !v.is_null()))
    })
}
