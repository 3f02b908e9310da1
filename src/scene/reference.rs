//! The field table of `docs/scene.md`, rendered from the descriptors in [`super::FIELDS`]
//! and from the defaults the parser fills in, so the reference cannot drift from the code.

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::field::{Field, Range};
use super::fields::FIELDS;
use super::parse_scene;

/// The line before the generated table in `docs/scene.md`.
pub const FIELDS_BEGIN: &str = "<!-- The tables below are generated from src/scene/fields.rs: \
                                edit there, then run TRIBOSIM_WRITE_DOCS=1 cargo test \
                                --release --test docs -->";
/// The line after the generated table in `docs/scene.md`.
pub const FIELDS_END: &str = "<!-- End of the generated tables. -->";

/// The markdown tables of every scene field, one per section, between [`FIELDS_BEGIN`] and
/// [`FIELDS_END`] (both included).
pub fn field_table() -> String {
    // `{}` gives the defaults of every field but those of the optional corrosion section,
    // which `{"corrosion": {}}` fills in.
    let bare = defaults(&json!({}));
    let with_corrosion = defaults(&json!({"corrosion": {}}));
    let mut out = format!("{FIELDS_BEGIN}\n");
    for field in FIELDS {
        let is_section = !field.path.contains('.')
            && matches!(field.range, Range::Object | Range::OptionalObject);
        if is_section || field.path == "name" {
            let title = if is_section {
                format!("`{}`", field.path)
            } else {
                "Top level".to_owned()
            };
            let _ = write!(out, "\n### {title}\n\n");
            if is_section {
                let _ = write!(out, "{}\n\n", escape(field.meaning));
            }
            out.push_str("| field | meaning | unit | default in `{}` | allowed | paper |\n");
            out.push_str("|---|---|---|---|---|---|\n");
            if is_section {
                continue;
            }
        }
        let source = if field.path.starts_with("corrosion.") {
            &with_corrosion
        } else {
            &bare
        };
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} | {} |",
            field.path,
            escape(field.meaning),
            unit(field),
            default_of(source, field),
            escape(&field.allowed()),
            escape(field.feeds),
        );
    }
    let _ = write!(out, "\n{FIELDS_END}\n");
    out
}

/// The scene `document` parses to, as JSON (null if it does not parse: the defaults column
/// then reads "absent", which the docs test would show as a difference).
fn defaults(document: &Value) -> Value {
    parse_scene(document)
        .ok()
        .and_then(|scene| serde_json::to_value(scene).ok())
        .unwrap_or(Value::Null)
}

fn default_of(scene: &Value, field: &Field) -> String {
    if matches!(field.range, Range::Object) {
        return String::new();
    }
    let value = field
        .path
        .split('.')
        .try_fold(scene, |value, key| value.get(key));
    match value {
        Some(Value::Object(_)) => "given".to_owned(),
        Some(value) => format!("`{value}`"),
        None => "absent".to_owned(),
    }
}

fn unit(field: &Field) -> String {
    if !field.unit.is_empty() {
        field.unit.to_owned()
    } else if field.range.is_number() {
        "1 (dimensionless)".to_owned()
    } else {
        String::new()
    }
}

/// `text` safe inside a table cell: `*` would start emphasis (E*, G*), `|` a new cell.
fn escape(text: &str) -> String {
    text.replace('*', "\\*").replace('|', "\\|")
}
