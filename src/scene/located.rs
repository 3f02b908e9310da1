//! Deserialising a scene with every problem located by path.
//!
//! Why the field-by-field retry: serde stops at the first error, and errors from deserialising
//! a `serde_json::Value` carry no location at all (`serde_path_to_error` is not a dependency).
//! So when the whole document fails, each section field is deserialised alone. Every section
//! field has a default, so a one-field object deserialises exactly when that field is
//! well-formed; its failure is reported at its dotted path with serde's own message ("invalid
//! type: string \"5\", expected f64", "unknown field `lod_n`, expected one of `load_n`, ..."),
//! which names the expected type and, for typos, the valid names. The well-formed fields are
//! then deserialised and range-checked, so type and range problems come back together.

use serde::Deserialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

use super::fields::{CYCLES, GRID};
use super::suggest::did_you_mean_field;
use super::{
    Ball, Corrosion, Disc, FieldError, MAX_LISTED_PROBLEMS, Numerics, Reciprocating, Scene,
    TestConditions, Wear,
};

/// The top-level fields of a scene, in the order of `docs/scene.md`.
pub(super) const SECTIONS: [&str; 7] = [
    "name",
    "ball",
    "disc",
    "test",
    "wear",
    "corrosion",
    "numerics",
];

/// Deserialises `document`; on failure records each ill-formed field and returns the scene
/// built from the well-formed ones (or `None` if not even that is possible).
pub(super) fn deserialize_located(document: &Value, errors: &mut Vec<FieldError>) -> Option<Scene> {
    let Some(top) = document.as_object() else {
        errors.push(FieldError::new(
            "",
            format!("a scene must be a JSON object, got {document}"),
        ));
        return None;
    };
    let top = drop_non_objects(top, errors);
    if errors.is_empty() {
        if let Ok(scene) = Scene::deserialize(&Value::Object(top.clone())) {
            return Some(scene);
        }
    }
    let mut kept = Map::new();
    let mut unchecked = 0;
    for (i, (key, value)) in top.iter().enumerate() {
        if errors.len() >= MAX_LISTED_PROBLEMS {
            unchecked += top.len() - i;
            break;
        }
        let field = match key.as_str() {
            "name" => whole::<String>(key, value, errors),
            "ball" => by_field::<Ball>(key, value, errors, &mut unchecked),
            "disc" => by_field::<Disc>(key, value, errors, &mut unchecked),
            "test" => by_field::<TestConditions>(key, value, errors, &mut unchecked),
            "wear" => by_field::<Wear>(key, value, errors, &mut unchecked),
            "corrosion" => by_field::<Option<Corrosion>>(key, value, errors, &mut unchecked),
            "numerics" => by_field::<Numerics>(key, value, errors, &mut unchecked),
            _ => {
                let expected: Vec<String> = SECTIONS.iter().map(|s| format!("`{s}`")).collect();
                errors.push(FieldError::new(
                    key.as_str(),
                    format!(
                        "unknown field `{key}`, expected one of {}{}",
                        expected.join(", "),
                        did_you_mean_field(key)
                    ),
                ));
                None
            }
        };
        if let Some(field) = field {
            kept.insert(key.clone(), field);
        }
    }
    if unchecked > 0 {
        errors.push(FieldError::new(
            "",
            format!(
                "{unchecked} more fields were not checked: a refusal lists at most \
                 {MAX_LISTED_PROBLEMS} problems; mend these and send the scene again"
            ),
        ));
        return None;
    }
    match Scene::deserialize(&Value::Object(kept)) {
        Ok(scene) => Some(scene),
        Err(e) => {
            errors.push(FieldError::new("", e.to_string()));
            None
        }
    }
}

/// `top` without the sections (and `wear.archard_calibration`, `wear.archard_regime_change`)
/// that are not objects, each recorded as an error. Serde's derived structs also accept a JSON array of the fields in
/// declaration order, so `"ball": [3]` would silently set the radius; the documented shape
/// is an object, and this keeps it so.
fn drop_non_objects(top: &Map<String, Value>, errors: &mut Vec<FieldError>) -> Map<String, Value> {
    let mut kept = top.clone();
    for (key, value) in top {
        let optional = key == "corrosion";
        let is_section = SECTIONS.contains(&key.as_str()) && key != "name";
        if is_section && !(value.is_object() || (optional && value.is_null())) {
            errors.push(FieldError::new(
                key.as_str(),
                format!("must be an object of `{key}` fields, got {value}"),
            ));
            kept.remove(key);
        }
    }
    if let Some(Value::Object(wear)) = kept.get_mut("wear") {
        let shapes = [
            (
                "archard_calibration",
                "{\"time_s\": ..., \"wear_volume_mm3\": ...}",
            ),
            (
                "archard_regime_change",
                "{\"cycle\": ..., \"archard_k_before\": ...}",
            ),
        ];
        for (key, shape) in shapes {
            if let Some(value) = wear.get(key) {
                if !(value.is_object() || value.is_null()) {
                    errors.push(FieldError::new(
                        format!("wear.{key}"),
                        format!("must be an object {shape}, got {value}"),
                    ));
                    wear.remove(key);
                }
            }
        }
    }
    kept
}

/// `value` if it deserialises as a `T`, else an error at `path`.
fn whole<T: DeserializeOwned>(
    path: &str,
    value: &Value,
    errors: &mut Vec<FieldError>,
) -> Option<Value> {
    match T::deserialize(value) {
        Ok(_) => Some(value.clone()),
        Err(e) => {
            errors.push(FieldError::new(path, e.to_string()));
            None
        }
    }
}

/// The fields of the section object `value` that deserialise alone as a `T`; an error at
/// `path.field` for each one that does not. Once [`MAX_LISTED_PROBLEMS`] are found, the
/// fields left are counted in `unchecked` instead: each check may look for a near name
/// among every field of the scene, which a megabyte of keys makes seconds of work.
fn by_field<T: DeserializeOwned>(
    path: &str,
    value: &Value,
    errors: &mut Vec<FieldError>,
    unchecked: &mut usize,
) -> Option<Value> {
    let Value::Object(object) = value else {
        return whole::<T>(path, value, errors);
    };
    let mut kept = Map::new();
    for (i, (key, field)) in object.iter().enumerate() {
        if errors.len() >= MAX_LISTED_PROBLEMS {
            *unchecked += object.len() - i;
            break;
        }
        let alone = Value::Object(Map::from_iter([(key.clone(), field.clone())]));
        match T::deserialize(&alone) {
            Ok(_) => {
                kept.insert(key.clone(), field.clone());
            }
            Err(e) => {
                let field_path = format!("{path}.{key}");
                let refined = match field_path.as_str() {
                    "disc.hardness_table" => table_errors(&field_path, field),
                    // A section within a section: each of its fields located in turn.
                    "test.reciprocating" if field.is_object() => {
                        let mut inner = Vec::new();
                        by_field::<Reciprocating>(&field_path, field, &mut inner, unchecked);
                        inner
                    }
                    _ => Vec::new(),
                };
                if refined.is_empty() {
                    let message = e.to_string();
                    let hint = hint(&field_path)
                        .or_else(|| unknown_hint(&field_path, key, &message))
                        .unwrap_or_default();
                    errors.push(FieldError::new(field_path, format!("{message}{hint}")));
                } else {
                    errors.extend(refined);
                }
            }
        }
    }
    Some(Value::Object(kept))
}

/// Element-level type errors in a hardness table, so a bad cell is named by its indices
/// rather than the whole table. Empty when the problem is not in an element.
fn table_errors(path: &str, value: &Value) -> Vec<FieldError> {
    let Some(rows) = value.as_array() else {
        return Vec::new();
    };
    let mut errors = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        match row.as_array() {
            Some(pair) if pair.len() == 2 => {
                for (j, cell) in pair.iter().enumerate() {
                    if !cell.is_number() {
                        errors.push(FieldError::new(
                            format!("{path}[{i}][{j}]"),
                            format!("must be a number, got {cell}"),
                        ));
                    }
                }
            }
            _ => errors.push(FieldError::new(
                format!("{path}[{i}]"),
                format!("must be a [cycles, hardness_mpa] pair, got {row}"),
            )),
        }
    }
    errors
}

/// The field meant, for serde's "unknown field `name`" at `path` (the section's field
/// `key`, or a field of the object under it).
fn unknown_hint(path: &str, key: &str, message: &str) -> Option<String> {
    let name = message.strip_prefix("unknown field `")?.split('`').next()?;
    let typed = if name == key {
        path.to_owned()
    } else {
        format!("{path}.{name}")
    };
    Some(did_you_mean_field(&typed)).filter(|hint| !hint.is_empty())
}

/// The allowed range, for fields whose serde type error would not say it.
fn hint(path: &str) -> Option<String> {
    [CYCLES, GRID]
        .iter()
        .find(|field| field.path == path)
        .map(|field| format!("; must be {}", field.range.describe(field.unit)))
}
