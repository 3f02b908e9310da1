//! Provenance: every result says which build computed it, where, when, and of which scene;
//! and the same scene at the same commit gives the same numbers, run in two processes.

mod common;

use std::path::Path;
use std::process::Command;

use serde_json::Value;
use tribosim::simulation::{GIT_COMMIT, parse_scene, scene_sha256};

use common::TempDir;

/// The paper's preset with corrosion, a change of Archard regime and a synthetic rough disc
/// (a seeded random surface), on a small grid: every part of a result that a run computes.
const SCENE: &str = r#"{"preset": "dalmau2018-316l", "overrides": {
    "numerics": {"grid": 32, "domain_um": 256}, "test": {"cycles": 4},
    "wear": {"archard_regime_change": {"cycle": 2, "archard_k_before": 2e-5}},
    "disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.05,
                         "short_cutoff_um": 64, "long_cutoff_um": 200}}}}"#;

/// `tribosim run scene.json -o name` in `dir`, read back.
fn run_once(dir: &Path, name: &str) -> Value {
    let output = Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["run", "scene.json", "-o", name])
        .current_dir(dir)
        .output()
        .expect("start tribosim");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = std::fs::read_to_string(dir.join(name)).expect("the result is written");
    serde_json::from_str(&text).expect("the result is JSON")
}

/// Every difference between `a` and `b` below `path`, but in the keys that hold the date
/// and the wall-clock time of a run, which no two runs share.
fn differences(a: &Value, b: &Value, path: &str, out: &mut Vec<String>) {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: std::collections::BTreeSet<&String> = x.keys().chain(y.keys()).collect();
            for key in keys {
                if matches!(key.as_str(), "computed_at" | "wall_s") {
                    continue;
                }
                let (Some(u), Some(v)) = (x.get(key), y.get(key)) else {
                    out.push(format!("{path}.{key}: in one result only"));
                    continue;
                };
                differences(u, v, &format!("{path}.{key}"), out);
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                differences(u, v, &format!("{path}[{i}]"), out);
            }
        }
        // Numbers compared as the f64 bits serde_json read back (float_roundtrip): equal
        // text, equal bits.
        _ if a == b => {}
        _ => out.push(format!("{path}: {a} against {b}")),
    }
}

#[test]
fn one_scene_at_one_commit_gives_the_same_numbers_in_two_processes() {
    let dir = TempDir::new("provenance-twice");
    std::fs::write(dir.path().join("scene.json"), SCENE).expect("write the scene");
    let first = run_once(dir.path(), "first.json");
    let second = run_once(dir.path(), "second.json");
    let mut found = Vec::new();
    differences(&first, &second, "", &mut found);
    assert!(found.is_empty(), "the two runs differ: {found:#?}");
    assert!(
        first["cycles"].as_array().is_some_and(|c| c.len() >= 2),
        "the run solved several cycles: {}",
        first["cycles"]
    );
    assert_ne!(
        first["provenance"]["computed_at"],
        Value::Null,
        "the date is there"
    );
}

#[test]
fn the_result_names_its_build_and_the_hash_of_its_scene_as_run() {
    let dir = TempDir::new("provenance-fields");
    std::fs::write(dir.path().join("scene.json"), SCENE).expect("write the scene");
    let result = run_once(dir.path(), "result.json");
    let provenance = &result["provenance"];
    assert_eq!(provenance["tribosim_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(provenance["git_commit"], GIT_COMMIT);
    let commit = GIT_COMMIT;
    assert!(
        commit == "unknown"
            || (commit.len() == 40 && commit.chars().all(|c| c.is_ascii_hexdigit())),
        "{commit}"
    );
    assert!(provenance["cores"].as_u64().is_some_and(|n| n >= 1));
    let at = provenance["computed_at"].as_str().expect("a date");
    time::OffsetDateTime::parse(at, &time::format_description::well_known::Rfc3339)
        .expect("an RFC 3339 date");
    assert!(at.ends_with('Z'), "UTC: {at}");
    // The scene as run, read back from the result, hashes to the recorded hash; so does
    // the scene file it came from.
    let as_run = parse_scene(&result["scene"]).expect("the scene as run is a scene");
    let from_file = parse_scene(&serde_json::from_str(SCENE).expect("JSON")).expect("valid");
    assert_eq!(provenance["scene_sha256"], scene_sha256(as_run.scene()));
    assert_eq!(
        scene_sha256(from_file.scene()),
        scene_sha256(as_run.scene())
    );
}
