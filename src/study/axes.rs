//! An axis of a study: a dotted path into the scene and the values it takes, given as a
//! list or as an evenly spaced range.

use std::fmt;

use serde::de::{Deserialize, Deserializer, MapAccess, Visitor};
use serde_json::{Number, Value};

use super::StudyError;

/// The most intervals a range may have. A range's values are built when the study is read,
/// before the member limit is checked, so this bounds the memory a study file can ask for
/// (a million values, 32 MB) whatever the member limit; a study of a million runs is years
/// of a workstation's time.
pub const MAX_RANGE_STEPS: u64 = 1_000_000;

/// One axis: the path of a scene field and its values, in the order given.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The dotted path as in the scene document (`test.load_n`); under a preset, relative
    /// to `overrides`.
    pub path: String,
    /// The values, at least one.
    pub values: Vec<Value>,
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
    /// The values in order. A range whose ends are both integers gives integers where the
    /// spacing lands on them, so that integer fields (`test.cycles`) accept them.
    pub fn values(&self) -> Vec<Value> {
        match self {
            Self::List(values) => values.clone(),
            Self::Range { from, to, steps } => {
                let integers = from.is_i64() && to.is_i64();
                let (a, b) = (from.as_f64().unwrap_or(0.0), to.as_f64().unwrap_or(0.0));
                (0..=*steps)
                    .map(|i| {
                        // The ends exactly, not a + (b - a) * 1.0 with its rounding.
                        let x = if i == *steps {
                            b
                        } else {
                            a + (b - a) * i as f64 / *steps as f64
                        };
                        number(x, integers)
                    })
                    .collect()
            }
        }
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
    /// Reads an axis's values as written, refusing (and naming the axis) an empty list, a
    /// malformed range, or a range with no steps.
    pub fn from_json(path: String, json: &Value) -> Result<Self, StudyError> {
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
            Value::Array(values) => AxisValues::List(values.clone()),
            Value::Object(_) => range(json).map_err(fail)?,
            other => {
                return Err(fail(format!(
                    "must be a list of values or {{\"from\": A, \"to\": B, \"steps\": N}}, got {other}"
                )));
            }
        };
        let values = values.values();
        if values.is_empty() {
            return Err(fail("has no values; give at least one".into()));
        }
        Ok(Self { path, values })
    }
}

/// `{"from": A, "to": B, "steps": N}` with finite numeric ends and at least one step.
fn range(json: &Value) -> Result<AxisValues, String> {
    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Range {
        from: Number,
        to: Number,
        steps: u64,
    }
    let Range { from, to, steps } = serde_json::from_value(json.clone())
        .map_err(|e| format!("a range is {{\"from\": A, \"to\": B, \"steps\": N}}: {e}"))?;
    if steps == 0 {
        return Err("a range needs at least 1 step (steps + 1 values, both ends included); for one value give a list".into());
    }
    if steps > MAX_RANGE_STEPS {
        return Err(format!(
            "a range has at most {MAX_RANGE_STEPS} steps, got {steps}"
        ));
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
}
