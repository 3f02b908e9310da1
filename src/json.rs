//! JSON text to [`Value`], refusing an object that gives a key twice. serde_json keeps the
//! last of duplicate keys silently, so `{"load_n": 5, "load_n": 50}` would run at 50 N while
//! the reader of the file sees 5 N first; a scene must say each thing once. Also the name
//! serde writes for an enum's unit variant ([`variant_name`]).

use std::cell::RefCell;
use std::fmt;

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};
use thiserror::Error;

/// Why JSON text was not turned into a [`Value`].
#[derive(Debug, Error)]
pub enum JsonError {
    /// Not JSON (syntax, truncation, a number out of range, nesting too deep).
    #[error("not valid JSON: {0}")]
    Syntax(serde_json::Error),
    /// An object gives the same key twice.
    #[error("the key {path:?} is given more than once (line {line}, column {column})")]
    DuplicateKey {
        /// The repeated key with the path of its object, as scene paths are written
        /// (`test.load_n`, `disc.hardness_table[2].x`).
        path: String,
        /// Line of the second occurrence (1-based).
        line: usize,
        /// Column just after the second occurrence's value.
        column: usize,
    },
}

/// The name serde writes for `value`, a unit variant (`"aisi_316l"`, `"plasticity"`); empty
/// for anything that does not serialise to a string.
pub fn variant_name<T: serde::Serialize>(value: T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_owned))
        .unwrap_or_default()
}

/// Parses JSON text to a [`Value`], refusing duplicate keys at any depth.
pub fn from_str(text: &str) -> Result<Value, JsonError> {
    from_slice(text.as_bytes())
}

/// [`from_str`] on bytes (which must be UTF-8, as JSON is).
pub fn from_slice(bytes: &[u8]) -> Result<Value, JsonError> {
    let found = RefCell::new(None);
    let mut deserializer = serde_json::Deserializer::from_slice(bytes);
    let parsed = UniqueSeed {
        at: None,
        found: &found,
    }
    .deserialize(&mut deserializer)
    .and_then(|value| deserializer.end().map(|()| value));
    parsed.map_err(|error| match found.into_inner() {
        Some(path) => JsonError::DuplicateKey {
            path,
            line: error.line(),
            column: error.column(),
        },
        None => JsonError::Syntax(error),
    })
}

/// One step from the document's root: an object key or an array index.
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

/// Where a value is: its step and its parent's place, a list living on the stack.
struct At<'a> {
    parent: Option<&'a At<'a>>,
    step: Step<'a>,
}

impl At<'_> {
    fn path(at: Option<&Self>) -> String {
        let Some(at) = at else {
            return String::new();
        };
        let parent = Self::path(at.parent);
        match at.step {
            Step::Key(key) if parent.is_empty() => key.to_owned(),
            Step::Key(key) => format!("{parent}.{key}"),
            Step::Index(i) => format!("{parent}[{i}]"),
        }
    }
}

/// Deserialises one value at `at`, recording in `found` the first duplicate key met.
#[derive(Clone, Copy)]
struct UniqueSeed<'a, 'f> {
    at: Option<&'a At<'a>>,
    found: &'f RefCell<Option<String>>,
}

impl<'de> DeserializeSeed<'de> for UniqueSeed<'_, '_> {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for UniqueSeed<'_, '_> {
    type Value = Value;

    fn expecting(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str("any JSON value")
    }

    fn visit_bool<E>(self, value: bool) -> Result<Value, E> {
        Ok(Value::Bool(value))
    }

    fn visit_i64<E>(self, value: i64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_u64<E>(self, value: u64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_f64<E>(self, value: f64) -> Result<Value, E> {
        // As serde_json's own Value: a float JSON cannot hold becomes null.
        Ok(Number::from_f64(value).map_or(Value::Null, Value::Number))
    }

    fn visit_str<E>(self, value: &str) -> Result<Value, E> {
        Ok(Value::String(value.to_owned()))
    }

    fn visit_string<E>(self, value: String) -> Result<Value, E> {
        Ok(Value::String(value))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        loop {
            let at = At {
                parent: self.at,
                step: Step::Index(items.len()),
            };
            let seed = UniqueSeed {
                at: Some(&at),
                found: self.found,
            };
            match seq.next_element_seed(seed)? {
                Some(item) => items.push(item),
                None => return Ok(Value::Array(items)),
            }
        }
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            let at = At {
                parent: self.at,
                step: Step::Key(&key),
            };
            let value = map.next_value_seed(UniqueSeed {
                at: Some(&at),
                found: self.found,
            })?;
            if object.contains_key(&key) {
                let path = At::path(Some(&at));
                let message = format!("duplicate key {path:?}");
                *self.found.borrow_mut() = Some(path);
                return Err(de::Error::custom(message));
            }
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn unique_keys_parse_as_serde_json_parses_them() {
        let text = r#"{"a": [1, -2, 2.5, "x", null, true, {"b": {}}], "c": {"d": 1e300}}"#;
        let expected: Value = serde_json::from_str(text).expect("valid JSON");
        assert_eq!(from_str(text).expect("no duplicates"), expected);
        assert_eq!(from_str("3").expect("a scalar"), json!(3));
    }

    #[test]
    fn a_duplicate_is_named_with_its_path_at_any_depth() {
        let cases = [
            (r#"{"name": "a", "name": "b"}"#, "name"),
            (r#"{"test": {"load_n": 5, "load_n": 50}}"#, "test.load_n"),
            (r#"{"t": [{"k": 1}, {"k": 1, "k": 2}]}"#, "t[1].k"),
        ];
        for (text, expected) in cases {
            match from_str(text) {
                Err(JsonError::DuplicateKey { path, .. }) => assert_eq!(path, expected),
                other => panic!("{text}: {other:?}"),
            }
        }
    }

    #[test]
    fn syntax_errors_stay_syntax_errors() {
        for text in ["{\"a\": ", "{\"a\": 1} x", "{\"a\": 1e400}", ""] {
            assert!(
                matches!(from_str(text), Err(JsonError::Syntax(_))),
                "{text}"
            );
        }
    }
}
