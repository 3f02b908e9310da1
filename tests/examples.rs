//! Every documented example scene runs. The examples are read at test time, so a new one is
//! covered without touching this file:
//!
//! - each ` ```json ` block of `README.md` and of `docs/*.md` that is a JSON object of scene
//!   sections (`preset`, `overrides`, `ball`, `disc`, `test`, `wear`, `corrosion`,
//!   `numerics`, `name`) is a scene; one with `base` and `axes` is a study, whose members
//!   are scenes. Blocks that are not JSON (snippets with `...`) or are other objects (a
//!   result, a request) are not scenes, and a scene-like block that is not JSON fails the
//!   test rather than being skipped;
//! - each `scenes/*.json` is a scene or a study, by the same rule.
//!
//! Inline code in the prose (`` `{"test": {"cycles": 300}}` ``) is a fragment of a sentence,
//! not an example to run. Each scene runs for [`FEW_CYCLES`] cycles where it allows (a scene
//! whose other fields need more, a change of wear regime at cycle 300, runs its own count):
//! the test is that the documented scene is accepted and simulated, not its long-run numbers.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use serde_json::{Value, json};
use tribosim::simulation::{Plan, parse_scene, run};
use tribosim::study::{MAX_MEMBERS, Study};

/// Cycles each example runs when it allows: the first, cold solve and two warm ones.
const FEW_CYCLES: u64 = 3;

/// The top-level keys of a scene document.
const SCENE_KEYS: [&str; 9] = [
    "preset",
    "overrides",
    "name",
    "ball",
    "disc",
    "test",
    "wear",
    "corrosion",
    "numerics",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// `path` from the repository's root, for messages.
fn relative(path: &Path) -> String {
    path.strip_prefix(root())
        .unwrap_or(path)
        .display()
        .to_string()
}

/// The bodies of the ```json blocks of a markdown text.
fn json_blocks(text: &str) -> Vec<&str> {
    text.split("```json\n")
        .skip(1)
        .filter_map(|rest| rest.split("```").next())
        .collect()
}

/// What a documented JSON text is.
enum Example {
    Scene(Value),
    Study(Value),
    Other,
}

/// Classifies `text` from `origin` by its keys. A text that is not JSON but names a scene
/// section at its top level is a broken scene example, and fails.
fn classify(text: &str, origin: &str) -> Example {
    let Ok(value) = serde_json::from_str::<Value>(text) else {
        let scene_like = SCENE_KEYS
            .iter()
            .any(|key| text.trim_start().starts_with(&format!("{{\"{key}\"")));
        assert!(
            !scene_like,
            "{origin}: a scene example that is not JSON:\n{text}"
        );
        return Example::Other;
    };
    let Some(object) = value.as_object() else {
        return Example::Other;
    };
    if object.contains_key("base") && object.contains_key("axes") {
        return Example::Study(value);
    }
    if !object.is_empty() && object.keys().all(|k| SCENE_KEYS.contains(&k.as_str())) {
        return Example::Scene(value);
    }
    Example::Other
}

/// `document` (either scene form) with its cycles set to `cycles`.
fn with_cycles(document: &Value, cycles: u64) -> Value {
    let mut document = document.clone();
    let sections = if document.get("preset").is_some() {
        document
            .as_object_mut()
            .expect("an object")
            .entry("overrides")
            .or_insert_with(|| json!({}))
    } else {
        &mut document
    };
    let test = sections
        .as_object_mut()
        .expect("scene sections are an object")
        .entry("test")
        .or_insert_with(|| json!({}));
    test.as_object_mut()
        .expect("`test` is an object")
        .insert("cycles".into(), json!(cycles));
    document
}

/// The scene of `document` cut to [`FEW_CYCLES`] where the scene allows it, else as given.
fn few_cycles(document: &Value, origin: &str) -> Plan {
    let given = parse_scene(document)
        .unwrap_or_else(|e| panic!("{origin}: the example is refused: {e}\n{document}"));
    if given.scene().test.cycles <= FEW_CYCLES {
        return given;
    }
    parse_scene(&with_cycles(document, FEW_CYCLES)).unwrap_or(given)
}

/// Runs `scene` to its last cycle.
fn run_scene(plan: &Plan, origin: &str) {
    let started = std::time::Instant::now();
    let result =
        run(plan, &mut |_| {}, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{origin}: {e}"));
    let last = result.cycles.last().map(|c| c.cycle);
    assert_eq!(last, Some(plan.scene().test.cycles), "{origin}");
    println!(
        "{origin}: {} cycles in {:.1} s",
        plan.scene().test.cycles,
        started.elapsed().as_secs_f64()
    );
}

/// Runs the example `text` from `origin` if it is a scene or a study; returns the runs.
fn run_example(text: &str, origin: &str) -> usize {
    match classify(text, origin) {
        Example::Scene(document) => {
            run_scene(&few_cycles(&document, origin), origin);
            1
        }
        Example::Study(mut study) => {
            let base = few_cycles(&study["base"], origin);
            study["base"] = with_cycles(&study["base"], base.scene().test.cycles);
            let members = Study::parse(&study.to_string())
                .and_then(|s| s.members(MAX_MEMBERS))
                .unwrap_or_else(|e| panic!("{origin}: the study is refused: {e}"));
            for member in &members {
                let origin = format!("{origin}, member {}", member.index);
                let plan = Plan::new(member.scene.clone())
                    .unwrap_or_else(|e| panic!("{origin}: the member is refused: {e}"));
                run_scene(&plan, &origin);
            }
            members.len()
        }
        Example::Other => 0,
    }
}

#[test]
fn every_json_example_of_the_docs_and_the_readme_runs() {
    let mut pages: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/ is readable")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.push(root().join("README.md"));
    pages.sort();
    let mut runs = 0;
    for page in &pages {
        let text = read(page);
        for (k, block) in json_blocks(&text).into_iter().enumerate() {
            let origin = format!("{} example {}", relative(page), k + 1);
            runs += run_example(block, &origin);
        }
    }
    // docs/scene.md alone documents seven scenes.
    assert!(runs >= 7, "only {runs} documented scenes found");
}

#[test]
fn every_scene_file_runs() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/ is readable")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "json"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no scenes/*.json");
    for file in &files {
        let origin = relative(file);
        let runs = run_example(&read(file), &origin);
        assert!(runs > 0, "{origin} is neither a scene nor a study");
    }
}
