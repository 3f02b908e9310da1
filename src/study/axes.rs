//! An axis of a study: a dotted path into the scene and the values it takes, given as a
//! list or as an evenly spaced range.

use std::fmt;

use serde::de::{Deserialize, Deserializer, MapAccess, Visitor};
use serde_json::{Number, Value};

use super::StudyError;
use crate::text::{Lines, NAME_MAX_CHARS, check, cut};

/// The longest axis path, in characters: the scene's longest field path is under 50.
pub const AXIS_PATH_MAX_CHARS: usize = 100;

/// The longest axis value, in characters: a string's own (a name's bound, since an axis of
/// `name` gives members their names), any other value's as compact JSON (a hardness table
/// of about 15 rows). Every member's name and scene carry their values, so a value is a
/// setting, not a data set.
pub const AXIS_VALUE_MAX_CHARS: usize = NAME_MAX_CHARS;

/// The most intervals a range may have: a study of a million runs is years of a
/// workstation's time. A range's values are not built when the study is read (each is
/// computed when a member needs it), so this bounds no memory; the member limit, checked on
/// the axes' counts, bounds what is built.
pub const MAX_RANGE_STEPS: u64 = 1_000_000;

/// One axis: the path of a scene field and its values, in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted path as in the scene document (`test.load_n`); under a preset, relative
    /// to `overrides`.
    pub path: String,
    /// The values, at least one, as written: a range is kept as its ends and steps.
    pub values: AxisValues,
}

/// How an axis's values are written.
#[derive(Debug, Clone, PartialEq)]
pub enum AxisValues {
    /// The values themselves, any JSON (numbers, strings for a model's name, ...).
    List(Vec<Value>),
    /// `steps` equal intervals from `from` to `to`, both included: `steps + 1` values.
    Range {
        /// The first value.
        from: Number,
        /// The last value.
        to: Number,
        /// How many intervals, at least 1.
        steps: u64,
    },
}

impl AxisValues {
    /// How many values, counted without building them.
    pub fn len(&self) -> usize {
        match self {
            Self::List(values) => values.len(),
            // At most MAX_RANGE_STEPS + 1, which fits any usize.
            Self::Range { steps, .. } => usize::try_from(*steps).map_or(usize::MAX, |s| s + 1),
        }
    }

    /// Whether there are no values (an empty list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The value at `index` (below [`Self::len`]). A range whose ends are both integers
    /// gives integers where the spacing lands on them, so that integer fields
    /// (`test.cycles`) accept them.
    pub fn get(&self, index: usize) -> Value {
        match self {
            Self::List(values) => values[index].clone(),
            Self::Range { from, to, steps } => {
                let integers = from.is_i64() && to.is_i64();
                let (a, b) = (from.as_f64().unwrap_or(0.0), to.as_f64().unwrap_or(0.0));
                let i = index as u64;
                // The ends exactly, not a + (b - a) * 1.0 with its rounding.
                let x = if i == *steps {
                    b
                } else {
                    a + (b - a) * i as f64 / *steps as f64
                };
                number(x, integers)
            }
        }
    }

    /// Every value in order; built only once the member limit has bounded them.
    pub fn to_vec(&self) -> Vec<Value> {
        (0..self.len()).map(|i| self.get(i)).collect()
    }
}

/// `x` as JSON: an integer when asked for and exact, otherwise a float.
fn number(x: f64, integers: bool) -> Value {
    if integers && x.fract() == 0.0 && x.abs() < 2f64.powi(53) {
        Value::from(x as i64)
    } else {
        Number::from_f64(x).map_or(Value::Null, Value::Number)
    }
}

impl Axis {
    /// Reads an axis's values as written, refusing (and naming the axis) a path past
    /// [`AXIS_PATH_MAX_CHARS`] or holding a character the text rule refuses, an empty list,
    /// a value past [`AXIS_VALUE_MAX_CHARS`] (or a string the rule refuses), a malformed
    /// range, or a range with no steps.
    pub fn from_json(path: String, json: &Value) -> Result<Self, StudyError> {
        if let Err(e) = check(&path, AXIS_PATH_MAX_CHARS, Lines::One) {
            return Err(StudyError::Axis {
                axis: cut(&path, AXIS_PATH_MAX_CHARS),
                message: format!("the path: {e}"),
            });
        }
        let fail = |message: String| StudyError::Axis {
            axis: path.clone(),
            message,
        };
        if path.is_empty() || path.split('.').any(str::is_empty) {
            return Err(fail(
                "the path must be dotted field names, as `test.load_n`".into(),
            ));
        }
        let values = match json {
            Value::Array(values) => {
                values.iter().enumerate().try_for_each(|(i, value)| {
                    check_value(value).map_err(|e| fail(format!("value [{i}]: {e}")))
                })?;
                AxisValues::List(values.clone())
            }
            Value::Object(_) => range(json, fail)?,
            other => {
                return Err(fail(format!(
                    "must be a list of values or {{\"from\": A, \"to\": B, \"steps\": N}}, got {other}"
                )));
            }
        };
        if values.is_empty() {
            return Err(fail("has no values; give at least one".into()));
        }
        Ok(Self { path, values })
    }
}

/// A listed value within [`AXIS_VALUE_MAX_CHARS`]: a string as a name is checked
/// ([`crate::text`]), any other value by the length of its compact JSON.
fn check_value(value: &Value) -> Result<(), crate::text::TextError> {
    match value {
        Value::String(text) => check(text, AXIS_VALUE_MAX_CHARS, Lines::One),
        other => {
            let chars = other.to_string().chars().count();
            if chars > AXIS_VALUE_MAX_CHARS {
                Err(crate::text::TextError::TooLong {
                    chars,
                    max: AXIS_VALUE_MAX_CHARS,
                })
            } else {
                Ok(())
            }
        }
    }
}

/// `{"from": A, "to": B, "steps": N}` with finite numeric ends and at least one step;
/// `fail` names the axis in the refusal.
fn range(json: &Value, fail: impl Fn(String) -> StudyError) -> Result<AxisValues, StudyError> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Range {
        from: Number,
        to: Number,
        steps: u64,
    }
    let Range { from, to, steps } = serde_json::from_value(json.clone()).map_err(|e| {
        fail(format!(
            "a range is {{\"from\": A, \"to\": B, \"steps\": N}}: {e}"
        ))
    })?;
    if steps == 0 {
        return Err(fail("a range needs at least 1 step (steps + 1 values, both ends included); for one value give a list".into()));
    }
    if steps > MAX_RANGE_STEPS {
        return Err(fail(format!(
            "a range has at most {MAX_RANGE_STEPS} steps, got {steps}"
        )));
    }
    Ok(AxisValues::Range { from, to, steps })
}

/// The `axes` object with its keys in the file's order.
pub(super) struct OrderedAxes(pub Vec<(String, Value)>);

impl<'de> Deserialize<'de> for OrderedAxes {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct InOrder;
        impl<'de> Visitor<'de> for InOrder {
            type Value = OrderedAxes;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object of axes, as {\"test.load_n\": [2, 5, 10]}")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<OrderedAxes, A::Error> {
                let mut axes = Vec::new();
                while let Some(entry) = map.next_entry::<String, Value>()? {
                    axes.push(entry);
                }
                Ok(OrderedAxes(axes))
            }
        }
        deserializer.deserialize_map(InOrder)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_range_with_too_many_steps_is_refused_before_its_values_are_built() {
        let huge = serde_json::json!({"from": 2, "to": 4, "steps": 331_526_042_580_u64});
        let err = Axis::from_json("test.load_n".into(), &huge).expect_err("too many steps");
        assert!(err.to_string().contains("test.load_n"), "{err}");
        assert!(err.to_string().contains("at most 1000000 steps"), "{err}");
        let most = serde_json::json!({"from": 0, "to": 1, "steps": MAX_RANGE_STEPS});
        let axis = Axis::from_json("test.load_n".into(), &most).expect("the largest range");
        assert_eq!(axis.values.len() as u64, MAX_RANGE_STEPS + 1);
    }

    #[test]
    fn a_range_is_counted_and_its_values_computed_one_at_a_time() {
        let range = serde_json::json!({"from": 2, "to": 4, "steps": 4});
        let axis = Axis::from_json("test.load_n".into(), &range).expect("a range");
        assert_eq!(axis.values.len(), 5);
        let built = axis.values.to_vec();
        assert_eq!(
            built,
            serde_json::json!([2, 2.5, 3, 3.5, 4])
                .as_array()
                .cloned()
                .unwrap_or_default()
        );
        let thirds = serde_json::json!({"from": 0.1, "to": 0.7, "steps": 3});
        let axis = Axis::from_json("test.x".into(), &thirds).expect("a range");
        // The last value is the end as written, not 0.1 + 0.6 * 1.0 with its rounding.
        assert_eq!(axis.values.get(3), serde_json::json!(0.7));
    }
}
