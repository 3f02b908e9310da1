//! A fit's readable summary for `tribosim calibrate`, read from its JSON so that every fit
//! (and any fit added later) gets one: each `{"value", "standard_error"}` as `value +- se`,
//! the other numbers and words as they are, each list of points as a table; the filled-in
//! scene is left to the JSON.

use serde_json::{Map, Value};

/// The summary of the fit `fit` (its JSON), one line per value and a table per list.
pub fn readable(fit: &Value) -> String {
    let mut out = String::new();
    if let Value::Object(map) = fit {
        section(&mut out, "", map);
    }
    out
}

fn section(out: &mut String, prefix: &str, map: &Map<String, Value>) {
    for (key, value) in map {
        let name = format!("{prefix}{key}");
        match value {
            Value::Object(_) if key == "scene" && prefix.is_empty() => {}
            Value::Object(inner) => match (inner.get("value"), inner.get("standard_error")) {
                (Some(v), Some(se)) => {
                    out.push_str(&format!("{name:<28} {} +- {}\n", number(v), number(se)));
                }
                _ => section(out, &format!("{name}."), inner),
            },
            Value::Array(rows) if rows.iter().all(Value::is_object) && !rows.is_empty() => {
                out.push_str(&format!("{name}:\n"));
                out.push_str(&table(rows));
            }
            other => out.push_str(&format!("{name:<28} {}\n", number(other))),
        }
    }
}

/// A number to five significant digits, anything else as JSON.
fn number(value: &Value) -> String {
    match value.as_f64() {
        Some(x) if value.is_f64() => format!("{}", Sig(x)),
        _ => value.to_string(),
    }
}

/// Five significant digits, in exponent form beyond 1e-3..1e6.
struct Sig(f64);

impl std::fmt::Display for Sig {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        if x == 0.0 || (1e-3..1e6).contains(&magnitude) {
            let decimals = (4 - magnitude.log10().floor() as i32).max(0) as usize;
            write!(f, "{x:.decimals$}")
        } else {
            write!(f, "{x:.4e}")
        }
    }
}

/// The objects of `rows` as a table with aligned columns, the first row's keys as heads.
fn table(rows: &[Value]) -> String {
    let heads: Vec<&String> = rows[0]
        .as_object()
        .map(|o| o.keys().collect())
        .unwrap_or_default();
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|row| {
            heads
                .iter()
                .map(|h| row.get(h.as_str()).map_or_else(String::new, number))
                .collect()
        })
        .collect();
    let widths: Vec<usize> = heads
        .iter()
        .enumerate()
        .map(|(i, h)| {
            cells
                .iter()
                .map(|r| r[i].len())
                .chain([h.len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |items: Vec<&str>| {
        let padded: Vec<String> = items
            .iter()
            .zip(&widths)
            .map(|(item, w)| format!("{item:>w$}"))
            .collect();
        format!("  {}\n", padded.join("  "))
    };
    let mut out = line(heads.iter().map(|h| h.as_str()).collect());
    for row in &cells {
        out.push_str(&line(row.iter().map(String::as_str).collect()));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn values_with_errors_scalars_and_residual_tables_read_plainly() {
        let fit = json!({
            "a_mpa": {"value": 2454.9866, "standard_error": 26.9778},
            "bulk_included": true,
            "residuals": [
                {"cycles": 1.0, "residual_mpa": 18.0134},
                {"cycles": 10.0, "residual_mpa": -49.93}
            ],
            "scene": {"name": "left to the JSON"}
        });
        let text = readable(&fit);
        assert!(
            text.contains("a_mpa") && text.contains("2455.0 +- 26.978"),
            "{text}"
        );
        assert!(
            text.contains("bulk_included") && text.contains("true"),
            "{text}"
        );
        assert!(
            text.contains("residuals:\n  cycles  residual_mpa\n"),
            "{text}"
        );
        assert!(text.contains("-49.930"), "{text}");
        assert!(!text.contains("left to the JSON"), "{text}");
    }
}
