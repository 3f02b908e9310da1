//! The scene as run, field by field, and how it differs from the preset it is closest to.

use std::collections::BTreeMap;

use serde_json::Value;

use crate::scene::{Scene, presets};

/// Every leaf of `value` by its dotted path (array elements as `path[i]`).
pub fn flatten(value: &Value) -> BTreeMap<String, Value> {
    let mut out = BTreeMap::new();
    walk(value, "", &mut out);
    out
}

fn walk(value: &Value, path: &str, out: &mut BTreeMap<String, Value>) {
    let join = |key: &str| {
        if path.is_empty() {
            key.to_owned()
        } else {
            format!("{path}.{key}")
        }
    };
    match value {
        Value::Object(map) if !map.is_empty() => {
            for (key, child) in map {
                walk(child, &join(key), out);
            }
        }
        Value::Array(items) if !items.is_empty() => {
            for (i, child) in items.iter().enumerate() {
                walk(child, &format!("{path}[{i}]"), out);
            }
        }
        leaf => {
            out.insert(path.to_owned(), leaf.clone());
        }
    }
}

/// One field that differs from the preset.
#[derive(Debug, Clone, PartialEq)]
pub struct Difference {
    /// The field's dotted path.
    pub path: String,
    /// The preset's value; `None` where the preset has no such field.
    pub preset: Option<Value>,
    /// The run's value; `None` where the run has no such field (a section left out).
    pub run: Option<Value>,
}

/// The scene's differences from the built-in preset with the fewest, and that preset's
/// name: a scene as run keeps no record of the preset it started from, so the closest one
/// stands for it.
pub fn closest_preset(scene: &Scene) -> Option<(&'static str, Vec<Difference>)> {
    let run = flatten(&serde_json::to_value(scene).ok()?);
    presets()
        .into_iter()
        .filter_map(|preset| {
            let base = flatten(&serde_json::to_value(&preset.scene).ok()?);
            Some((preset.name, differences(&base, &run)))
        })
        .min_by_key(|(_, differences)| differences.len())
}

/// The fields where `run` differs from `base`, in path order.
pub fn differences(
    base: &BTreeMap<String, Value>,
    run: &BTreeMap<String, Value>,
) -> Vec<Difference> {
    let paths: std::collections::BTreeSet<&String> = base.keys().chain(run.keys()).collect();
    paths
        .into_iter()
        .filter(|path| base.get(*path) != run.get(*path))
        .map(|path| Difference {
            path: path.clone(),
            preset: base.get(path).cloned(),
            run: run.get(path).cloned(),
        })
        .collect()
}

/// A value as a table shows it: strings without their quotes, absent as a dash.
pub fn shown(value: Option<&Value>) -> String {
    match value {
        None => "(absent)".to_owned(),
        Some(Value::String(text)) => text.clone(),
        Some(other) => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::parse_scene_str;

    #[test]
    fn a_changed_field_and_a_removed_section_are_the_differences() {
        let scene = parse_scene_str(
            r#"{"preset": "dalmau2018-316l", "overrides": {"test": {"load_n": 7}, "corrosion": null}}"#,
        )
        .expect("valid")
        .into_scene();
        let (name, found) = closest_preset(&scene).expect("a preset");
        assert_eq!(name, "dalmau2018-316l");
        let load = found
            .iter()
            .find(|d| d.path == "test.load_n")
            .expect("load differs");
        assert_eq!(shown(load.preset.as_ref()), "5.0");
        assert_eq!(shown(load.run.as_ref()), "7.0");
        let corrosion: Vec<&Difference> = found
            .iter()
            .filter(|d| d.path.starts_with("corrosion."))
            .collect();
        assert!(!corrosion.is_empty() && corrosion.iter().all(|d| d.run.is_none()));
        // The run writes the removed section as `null`, which the preset has not.
        let section = found.iter().find(|d| d.path == "corrosion").expect("null");
        assert_eq!(
            (section.preset.as_ref(), section.run.as_ref()),
            (None, Some(&Value::Null))
        );
        assert!(found.iter().all(|d| d.path == "test.load_n"
            || d.path == "corrosion"
            || d.path.starts_with("corrosion.")));
    }

    #[test]
    fn the_preset_itself_differs_in_nothing() {
        let scene = parse_scene_str(r#"{"preset": "dalmau2018-316l"}"#)
            .expect("valid")
            .into_scene();
        let (_, found) = closest_preset(&scene).expect("a preset");
        assert!(found.is_empty(), "{found:?}");
    }
}
