//! The field references `docs/scene.md` and `docs/result.md` against the code: the scene's
//! tables are the ones the descriptors render, every key the parser accepts has a
//! descriptor, the examples parse, and every field of a real result, of `tribosim contact`
//! and of the job record in the event stream is documented.
//!
//! After changing a scene field, regenerate the tables with
//! `TRIBOSIM_WRITE_DOCS=1 cargo test --release --test docs`.

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use serde_json::{Map, Value, json};
use tribosim::scene::materials::{MATERIALS_BEGIN, MATERIALS_END, materials_table};
use tribosim::scene::{FIELDS, FIELDS_BEGIN, FIELDS_END, Range, field_table, parse_scene};
use tribosim::simulation::{self, first_contact, run};

const REGENERATE: &str = "TRIBOSIM_WRITE_DOCS=1 cargo test --release --test docs";
const PROBE: &str = "__probe__";

fn doc_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("docs")
        .join(name)
}

fn read_doc(name: &str) -> String {
    let path = doc_path(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

#[test]
fn scene_tables_are_the_generated_ones() {
    let text = read_doc("scene.md");
    let (Some(begin), Some(end)) = (text.find(FIELDS_BEGIN), text.find(FIELDS_END)) else {
        panic!("docs/scene.md lacks the generated-table markers; see src/scene/reference.rs");
    };
    let end = end + FIELDS_END.len() + 1;
    let committed = &text[begin..end.min(text.len())];
    let generated = field_table();
    if committed == generated {
        return;
    }
    if std::env::var_os("TRIBOSIM_WRITE_DOCS").is_some() {
        let updated = format!(
            "{}{generated}{}",
            &text[..begin],
            &text[end.min(text.len())..]
        );
        std::fs::write(doc_path("scene.md"), updated).expect("docs/scene.md is writable");
        return;
    }
    panic!(
        "docs/scene.md's field tables differ from src/scene/fields.rs; regenerate them with\n  \
         {REGENERATE}\n--- generated ---\n{generated}"
    );
}

#[test]
fn materials_tables_are_the_generated_ones() {
    let text = read_doc("materials.md");
    let generated = materials_table();
    let committed = match (text.find(MATERIALS_BEGIN), text.find(MATERIALS_END)) {
        (Some(begin), Some(end)) => Some((begin, (end + MATERIALS_END.len() + 1).min(text.len()))),
        _ => None,
    };
    if committed.is_some_and(|(begin, end)| text[begin..end] == generated) {
        return;
    }
    if std::env::var_os("TRIBOSIM_WRITE_DOCS").is_some() {
        let (head, tail) = committed.map_or((text.as_str(), ""), |(b, e)| (&text[..b], &text[e..]));
        std::fs::write(doc_path("materials.md"), format!("{head}{generated}{tail}"))
            .expect("docs/materials.md is writable");
        return;
    }
    panic!(
        "docs/materials.md's tables differ from src/scene/materials; regenerate them with\n  \
         {REGENERATE}\n--- generated ---\n{generated}"
    );
}

#[test]
fn scene_plausibility_table_is_the_generated_one() {
    let text = read_doc("scene.md");
    let begin = text.find(simulation::RULES_BEGIN);
    let end = text.find(simulation::RULES_END);
    let (Some(begin), Some(end)) = (begin, end) else {
        panic!("docs/scene.md lacks the plausibility table's markers");
    };
    let end = (end + simulation::RULES_END.len() + 1).min(text.len());
    let generated = simulation::rules_table();
    if text[begin..end] == generated {
        return;
    }
    if std::env::var_os("TRIBOSIM_WRITE_DOCS").is_some() {
        let updated = format!("{}{generated}{}", &text[..begin], &text[end..]);
        std::fs::write(doc_path("scene.md"), updated).expect("docs/scene.md is writable");
        return;
    }
    panic!(
        "docs/scene.md's plausibility table differs from src/simulation/plausibility.rs; \
         regenerate it with\n  {REGENERATE}\n--- generated ---\n{generated}"
    );
}

/// The document `{a: {b: {...: leaf}}}` for the path `[a, b, ...]`.
fn nested(path: &[String], leaf: Value) -> Value {
    path.iter().rev().fold(leaf, |inner, key| {
        Value::Object(Map::from_iter([(key.clone(), inner)]))
    })
}

/// The names serde lists after "expected" in the error about `PROBE` at `path`, or `None`
/// when the parser does not refuse the probe by name (the value is not an object of fields,
/// or not a choice of names).
fn listed_after_probe(path: &[String], leaf: Value, refusal: &str) -> Option<Vec<String>> {
    let errors = match parse_scene(&nested(path, leaf)) {
        Ok(_) => return None,
        Err(errors) => errors.0,
    };
    let message = errors
        .iter()
        .map(|e| e.message.as_str())
        .find(|m| m.contains(&format!("{refusal} `{PROBE}`")))?;
    let expected = &message[message.find("expected")?..];
    let names = expected
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_owned)
        .collect();
    Some(names)
}

/// Every key path the parser accepts under `path`, found by offering it an unknown key and
/// reading the names it lists, then descending into each.
fn accepted_under(path: &[String], found: &mut BTreeSet<String>) {
    let probe = json!({ PROBE: 0 });
    let Some(keys) = listed_after_probe(path, probe, "unknown field") else {
        return;
    };
    for key in keys {
        let mut child = path.to_vec();
        child.push(key);
        found.insert(child.join("."));
        accepted_under(&child, found);
    }
}

#[test]
fn every_field_the_parser_accepts_has_a_descriptor_and_no_other() {
    let mut accepted = BTreeSet::new();
    accepted_under(&[], &mut accepted);
    assert!(
        accepted.contains("test.load_n"),
        "the probe found {accepted:?}"
    );
    let described: BTreeSet<String> = FIELDS.iter().map(|f| f.path.to_owned()).collect();
    let undocumented: Vec<&String> = accepted.difference(&described).collect();
    let stale: Vec<&String> = described.difference(&accepted).collect();
    assert!(
        undocumented.is_empty() && stale.is_empty(),
        "accepted but without a descriptor in src/scene/fields.rs: {undocumented:?}; \
         described but not accepted: {stale:?}. Edit src/scene/fields.rs, then run {REGENERATE}"
    );
    let text = read_doc("scene.md");
    for path in accepted
        .iter()
        .map(String::as_str)
        .chain(["preset", "overrides"])
    {
        assert!(
            text.contains(&format!("`{path}`")),
            "docs/scene.md lacks `{path}`"
        );
    }
}

#[test]
fn named_choices_are_the_ones_the_parser_accepts() {
    for field in FIELDS {
        let Range::OneOf(names) = field.range else {
            continue;
        };
        let path: Vec<String> = field.path.split('.').map(str::to_owned).collect();
        let listed = listed_after_probe(&path, json!(PROBE), "unknown variant")
            .unwrap_or_else(|| panic!("{} refuses no unknown name", field.path));
        assert_eq!(listed, names, "{}", field.path);
    }
}

/// The bodies of the ```json blocks of a markdown text.
fn json_blocks(text: &str) -> Vec<&str> {
    text.split("```json\n")
        .skip(1)
        .filter_map(|rest| rest.split("```").next())
        .collect()
}

#[test]
fn scene_examples_are_valid_scenes() {
    let text = read_doc("scene.md");
    let blocks = json_blocks(&text);
    assert!(
        blocks.len() >= 3,
        "docs/scene.md has {} examples",
        blocks.len()
    );
    for block in blocks {
        if let Err(errors) = simulation::parse_scene_str(block) {
            panic!("docs/scene.md example refused: {errors}\n{block}");
        }
    }
}

/// Every key path in `value`, arrays as `name[]` (their elements' fields merged), except
/// below the keys in `opaque`.
fn paths_of(value: &Value, prefix: &str, opaque: &[&str], out: &mut BTreeSet<String>) {
    match value {
        Value::Object(map) => {
            for (key, child) in map {
                let path = if prefix.is_empty() {
                    key.clone()
                } else {
                    format!("{prefix}.{key}")
                };
                out.insert(path.clone());
                if !opaque.contains(&path.as_str()) {
                    paths_of(child, &path, opaque, out);
                }
            }
        }
        Value::Array(items) => {
            let path = format!("{prefix}[]");
            for item in items.iter().filter(|item| item.is_object()) {
                paths_of(item, &path, opaque, out);
            }
        }
        _ => {}
    }
}

/// The part of `text` under the `## ` heading starting with `heading`, to the next one.
fn section<'a>(text: &'a str, heading: &str) -> &'a str {
    let start = text
        .find(&format!("\n## {heading}"))
        .unwrap_or_else(|| panic!("docs/result.md has no section `## {heading}`"));
    let rest = &text[start + 1..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |i| i + 3);
    &rest[..end]
}

fn assert_documented(paths: &BTreeSet<String>, part: &str, what: &str) {
    let missing: Vec<&String> = paths
        .iter()
        .filter(|path| !part.contains(&format!("`{path}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/result.md ({what}) does not document {missing:?}"
    );
}

/// The paper's preset on a small grid with corrosion, a change of Archard regime and a rough
/// disc, so that every optional field appears.
fn tiny_scene() -> simulation::Plan {
    let scene = json!({"preset": "dalmau2018-316l", "overrides": {
        "numerics": {"grid": 32, "domain_um": 256}, "test": {"cycles": 3},
        "wear": {"archard_regime_change": {"cycle": 1, "archard_k_before": 2e-5}},
        "disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.05,
                             "short_cutoff_um": 64, "long_cutoff_um": 200}}
    }});
    simulation::parse_scene(&scene).expect("the tiny scene is valid")
}

#[test]
fn every_result_field_is_documented() {
    let scene = tiny_scene();
    let result = run(&scene, &mut |_| {}, &AtomicBool::new(false)).expect("the tiny run runs");
    let json = serde_json::to_value(&result).expect("results serialise");
    let mut paths = BTreeSet::new();
    paths_of(&json, "", &["scene"], &mut paths);
    assert!(paths.contains("cycles[].potential_v"), "{paths:?}");
    let text = read_doc("result.md");
    assert_documented(&paths, section(&text, "The result"), "the result");
    for model in &result.models {
        let name = serde_json::to_value(model.name).expect("model names serialise");
        let name = name.as_str().expect("a model name is a string");
        assert!(
            text.contains(&format!("`{name}`")),
            "docs/result.md does not name the model `{name}`"
        );
    }

    let contact = serde_json::to_value(first_contact(&scene).expect("the first contact solves"))
        .expect("the first contact serialises");
    let mut paths = BTreeSet::new();
    paths_of(&contact, "", &["models"], &mut paths);
    let part = section(&text, "`tribosim contact`");
    assert_documented(&paths, part, "tribosim contact");
}

#[test]
fn every_job_field_of_the_event_stream_is_documented() {
    // The job record's fields as the API declares them; CI's schemathesis run holds the
    // server's responses to `openapi.yaml`.
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("openapi.yaml");
    let text = std::fs::read_to_string(path).expect("openapi.yaml is readable");
    let spec: Value = serde_norway::from_str(&text).expect("openapi.yaml parses");
    let job = &spec["components"]["schemas"]["Job"]["properties"];
    let names: BTreeSet<String> = job
        .as_object()
        .expect("the Job schema has properties")
        .keys()
        .cloned()
        .collect();
    assert!(names.contains("cycles_done"), "{names:?}");
    let doc = read_doc("result.md");
    let part = section(&doc, "The event stream");
    assert_documented(&names, part, "the event stream's job record");
    for event in ["event: cycle", "event: status"] {
        assert!(part.contains(event), "docs/result.md lacks `{event}`");
    }
}
