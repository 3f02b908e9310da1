//! Built-in scenes, and the `{"preset": ..., "overrides": {...}}` form that starts from one.

use serde::Serialize;
use serde_json::{Map, Value};

use super::corrosion::follow_corrosion;
use super::materials::expand::expand;
use super::surface::{SurfaceKind, SurfaceSpec};
use super::{
    AnodicArea, Corrosion, FieldError, GalvanicCell, PAPER_TABLE3, SPOT_REPASSIVATION_TIME_S,
    Scene, SceneErrors, Table3Row,
};

/// Name of the paper's scene: AISI 316L against alumina, 5 N, 60 rpm, 3600 cycles.
pub const DALMAU2018_316L: &str = "dalmau2018-316l";

/// Name of the paper's test on the paper's polished surface, with the depassivated area
/// predicted from the plastically deformed asperities (`docs/corrosion.md`).
pub const DALMAU2018_316L_ASPERITIES: &str = "dalmau2018-316l-asperities";

/// A named built-in scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Preset {
    /// What `"preset"` refers to.
    pub name: &'static str,
    /// One line on where the scene comes from.
    pub description: &'static str,
    /// The full scene.
    pub scene: Scene,
    /// What was measured on the test the scene describes (empty when nothing was), for a
    /// client to draw beside a run of it: the paper's Table 3 for [`DALMAU2018_316L`].
    pub measured: &'static [Table3Row],
}

/// Every built-in scene, for `tribosim presets` and `GET /presets`.
pub fn presets() -> Vec<Preset> {
    vec![
        Preset {
            name: DALMAU2018_316L,
            description: "Dalmau et al., Wear 394-395 (2018): AISI 316L against an alumina ball \
                      in 3% NaCl, Tables 2 and 3",
            scene: dalmau2018_316l(),
            measured: &PAPER_TABLE3,
        },
        Preset {
            name: DALMAU2018_316L_ASPERITIES,
            description: "The paper's test on its polished surface (Ra 0.1 um, Section 2.1), the \
                      depassivated area predicted from the plastically deformed asperities \
                      with a 10 ms repassivation and the balanced galvanic cell, nothing \
                      fitted to the potential (about 2.5 minutes on 2 cores)",
            scene: dalmau2018_316l_asperities(),
            measured: &PAPER_TABLE3,
        },
    ]
}

/// The paper's polished surface: Ra 0.1 um (Section 2.1) is rms 0.125 um for Gaussian
/// heights (Rq = 1.25 Ra); Hurst 0.85 is Persson's D_f = 2.15 for polished surfaces
/// (Tribol. Lett. 54 (2014) 99); the long cut-off, 50 um, is the contact's size; the short
/// one, 4 um (cells of 0.5 um), is the finest that 3600 cycles allow on 2 cores in minutes
/// (`docs/corrosion.md`).
pub fn paper_surface() -> SurfaceSpec {
    SurfaceSpec {
        kind: SurfaceKind::Synthetic,
        rms_height_um: Some(0.125),
        rms_slope: None,
        hurst: Some(0.85),
        short_cutoff_um: Some(4.0),
        long_cutoff_um: Some(50.0),
        seed: Some(1),
        id: None,
        remove_tilt: false,
    }
}

/// The [`DALMAU2018_316L_ASPERITIES`] preset: the paper's test on [`paper_surface`], with
/// `asperity_spots` at tau 10 ms and the balanced cell (eq. 18 as printed puts these
/// spots' potential above E_corr).
pub fn dalmau2018_316l_asperities() -> Scene {
    let mut scene = dalmau2018_316l();
    scene.name = "316L vs alumina, 5 N, 60 rpm, polished surface, asperity spots".to_owned();
    scene.disc.surface = Some(paper_surface());
    scene.corrosion = Some(Corrosion {
        anodic_area: AnodicArea::AsperitySpots,
        repassivation_time_s: SPOT_REPASSIVATION_TIME_S,
        galvanic_cell: GalvanicCell::Balanced,
        ..Corrosion::default()
    });
    scene
}

/// The paper's test, the [`DALMAU2018_316L`] preset: the defaults under the paper's name.
pub fn dalmau2018_316l() -> Scene {
    Scene {
        name: "316L vs alumina, 5 N, 60 rpm".to_owned(),
        ..Scene::default()
    }
}

/// The document to parse, and where the user's text is in it.
pub(super) struct Resolved {
    /// `json` itself, or a preset's scene with the overrides merged in, with the named
    /// materials' values filled in.
    pub document: Value,
    /// The path prefix that locates errors in the user's document.
    pub prefix: &'static str,
    /// What the named materials lack and the scene needs, located in the user's text.
    pub errors: Vec<FieldError>,
}

/// The document to parse ([`Resolved`]).
pub(super) fn resolve(json: &Value) -> Result<Resolved, SceneErrors> {
    let Some(object) = json.as_object().filter(|o| o.contains_key("preset")) else {
        let mut document = json.clone();
        let errors = match document.as_object_mut() {
            Some(user) => expand(user, &Value::Null),
            None => Vec::new(),
        };
        let given = document.get("corrosion").cloned();
        follow_corrosion(&mut document, given.as_ref(), &Corrosion::default());
        return Ok(Resolved {
            document,
            prefix: "",
            errors,
        });
    };
    let mut errors: Vec<FieldError> = object
        .keys()
        .filter(|key| !matches!(key.as_str(), "preset" | "overrides"))
        .map(|key| {
            FieldError::new(
                key.as_str(),
                "not allowed next to `preset`; put changes to the preset under `overrides`",
            )
        })
        .collect();
    let known: Vec<Preset> = presets();
    let preset = named_preset(&object["preset"], &known, &mut errors);
    let overrides = overrides_of(object.get("overrides"), &mut errors);
    match (preset, overrides) {
        (Some(preset), Some(mut overrides)) if errors.is_empty() => {
            let mut document = serde_json::to_value(&preset.scene).map_err(|e| {
                SceneErrors(vec![FieldError::new(
                    "preset",
                    format!("internal error serialising the preset: {e}"),
                )])
            })?;
            let errors = expand(&mut overrides, &document);
            merge(&mut document, &Value::Object(overrides.clone()));
            keep_one_archard_setting(&mut document, &overrides);
            let base = preset.scene.corrosion.clone().unwrap_or_default();
            follow_corrosion(&mut document, overrides.get("corrosion"), &base);
            Ok(Resolved {
                document,
                prefix: "overrides",
                errors,
            })
        }
        _ => Err(SceneErrors(errors)),
    }
}

/// The preset `value` names among `known`; `None`, with the error said, for an unknown
/// name (and the nearest known one) or a value that is not a name.
fn named_preset<'a>(
    value: &Value,
    known: &'a [Preset],
    errors: &mut Vec<FieldError>,
) -> Option<&'a Preset> {
    let names = || {
        known
            .iter()
            .map(|p| format!("`{}`", p.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Value::String(name) = value else {
        errors.push(FieldError::new(
            "preset",
            format!("must be a preset name ({}), got {value}", names()),
        ));
        return None;
    };
    let found = known.iter().find(|p| p.name == name);
    if found.is_none() {
        let meant = super::suggest::nearest(name, known.iter().map(|p| p.name))
            .map_or_else(String::new, |p| format!("; did you mean `{p}`?"));
        errors.push(FieldError::new(
            "preset",
            format!("unknown preset `{name}`; known presets: {}{meant}", names()),
        ));
    }
    found
}

/// The scene fields `overrides` changes (none when absent or null); `None`, with the error
/// said, when it is not an object.
fn overrides_of(
    overrides: Option<&Value>,
    errors: &mut Vec<FieldError>,
) -> Option<Map<String, Value>> {
    match overrides {
        None | Some(Value::Null) => Some(Map::new()),
        Some(Value::Object(map)) => Some(map.clone()),
        Some(other) => {
            errors.push(FieldError::new(
                "overrides",
                format!("must be an object of scene fields, got {other}"),
            ));
            None
        }
    }
}

/// `wear.archard_k` and `wear.archard_calibration` are one setting given two ways: the one
/// the overrides give replaces the preset's other. A calibration point is one measurement,
/// so it replaces the preset's point whole rather than merging with it.
fn keep_one_archard_setting(document: &mut Value, overrides: &Map<String, Value>) {
    let Some(given) = overrides.get("wear").and_then(Value::as_object) else {
        return;
    };
    let Some(Value::Object(wear)) = document.get_mut("wear") else {
        return;
    };
    let set = |key: &str| given.get(key).filter(|value| !value.is_null());
    match (set("archard_k"), set("archard_calibration")) {
        (Some(_), None) => {
            wear.remove("archard_calibration");
        }
        (None, Some(point)) => {
            wear.remove("archard_k");
            wear.insert("archard_calibration".to_owned(), point.clone());
        }
        _ => {}
    }
}

/// Deep merge: objects merge key by key; anything else (including `null`, which removes an
/// optional section such as `corrosion`) replaces.
fn merge(base: &mut Value, patch: &Value) {
    match (base, patch) {
        (Value::Object(base), Value::Object(patch)) => {
            for (key, value) in patch {
                match base.get_mut(key) {
                    Some(slot) => merge(slot, value),
                    None => {
                        base.insert(key.clone(), value.clone());
                    }
                }
            }
        }
        (slot, patch) => *slot = patch.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn merge_is_deep_for_objects_and_replaces_everything_else() {
        let mut base = json!({"a": {"x": 1, "y": [1, 2]}, "b": 2, "c": {"z": 3}});
        merge(
            &mut base,
            &json!({"a": {"y": [9], "w": 4}, "b": {"new": true}, "c": null}),
        );
        assert_eq!(
            base,
            json!({"a": {"x": 1, "y": [9], "w": 4}, "b": {"new": true}, "c": null})
        );
    }
}
