//! Where a run's material values came from, for the result's `models` entry `materials`:
//! each value the library gave with its source, and each one the scene gave instead.

use super::{BallMaterial, DiscMaterial, Property};
use crate::scene::Scene;

/// `label: E 114 GPa [matweb-ti64], ...; the scene's own: hardness_mpa 3300`.
fn entries(label: &str, rows: &[(&str, &str, Property, f64)]) -> String {
    let mut library = Vec::new();
    let mut own = Vec::new();
    for &(key, unit, property, used) in rows {
        match property.value {
            Some(value) if value.to_bits() == used.to_bits() => {
                library.push(format!("{key} {value}{unit} [{}]", property.source));
            }
            _ => own.push(format!("{key} {used}{unit}")),
        }
    }
    let mut text = format!("{label}: {}", library.join(", "));
    if !own.is_empty() {
        text.push_str(&format!("; the scene's own: {}", own.join(", ")));
    }
    text
}

fn disc(material: &DiscMaterial, scene: &Scene) -> String {
    let d = &scene.disc;
    let mut text = entries(
        material.label,
        &[
            (
                "E",
                " GPa",
                material.youngs_modulus_gpa,
                d.youngs_modulus_gpa,
            ),
            ("nu", "", material.poisson_ratio, d.poisson_ratio),
            ("H", " MPa", material.hardness_mpa, d.hardness_mpa),
            (
                "yield",
                " MPa",
                material.initial_yield_strength_mpa,
                d.initial_yield_strength_mpa,
            ),
        ],
    );
    let law = match (&d.hardness_table, material.hardness_table) {
        (None, _) => "constant hardness".to_owned(),
        (Some(table), Some(points)) if table.as_slice() == points => {
            format!("hardness law [{}]", material.hardness_law_source)
        }
        (Some(_), _) => "the scene's hardness table".to_owned(),
    };
    text.push_str(&format!("; {law}"));
    if scene.corrosion.is_some() {
        text.push_str(&match material.electrochemistry {
            Some(e) => format!("; electrochemistry in {} [{}]", e.medium, e.source),
            None => "; the scene's own electrochemical constants".to_owned(),
        });
    }
    text
}

fn ball(material: &BallMaterial, scene: &Scene) -> String {
    let b = &scene.ball;
    entries(
        material.label,
        &[
            (
                "E",
                " GPa",
                material.youngs_modulus_gpa,
                b.youngs_modulus_gpa,
            ),
            ("nu", "", material.poisson_ratio, b.poisson_ratio),
        ],
    )
}

/// The `materials` entry's reason, or `None` when the scene names no material.
pub fn describe(scene: &Scene) -> Option<String> {
    let parts: Vec<String> = [
        scene.disc.material.map(|m| disc(m.material(), scene)),
        scene.ball.material.map(|m| ball(m.material(), scene)),
    ]
    .into_iter()
    .flatten()
    .collect();
    (!parts.is_empty()).then(|| format!("{} (docs/materials.md)", parts.join(". ")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse_scene;
    use serde_json::json;

    #[test]
    fn a_given_value_is_named_as_the_scenes_and_the_rest_by_source() {
        let scene = parse_scene(&json!({
            "disc": {"material": "ti6al4v", "hardness_mpa": 3300}, "corrosion": null,
            "wear": {"archard_k": 1e-4}
        }))
        .expect("valid");
        let text = describe(&scene).expect("a material");
        assert!(text.contains("E 114 GPa [matweb-ti64]"), "{text}");
        assert!(text.contains("the scene's own: H 3300 MPa"), "{text}");
        assert!(text.contains("constant hardness"), "{text}");
        assert_eq!(describe(&Scene::default()), None);
    }
}
