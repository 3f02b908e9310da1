//! Where a result comes from: the build (tribosim's version and git commit), the machine
//! (its cores), the date, and the scene as run by its SHA-256, so a figure can be traced
//! back to the run that made it.

use serde::{Deserialize, Serialize};
use serde_json::Value;
use sha2::{Digest, Sha256};
use time::OffsetDateTime;

use crate::scene::Scene;

/// The git commit this binary was built from (`build.rs`), "unknown" outside git.
pub const GIT_COMMIT: &str = env!("TRIBOSIM_GIT_COMMIT");

/// The build, the machine and the date of a result or a study summary.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Build {
    /// tribosim's version (`Cargo.toml`).
    pub tribosim_version: String,
    /// The git commit tribosim was built from, or "unknown".
    pub git_commit: String,
    /// When the result was computed, UTC.
    #[serde(with = "time::serde::rfc3339")]
    pub computed_at: OffsetDateTime,
    /// The machine's cores, as the operating system offers them to the process.
    pub cores: usize,
}

impl Build {
    /// This build, on this machine, now.
    pub fn now() -> Self {
        Self {
            tribosim_version: env!("CARGO_PKG_VERSION").to_owned(),
            git_commit: GIT_COMMIT.to_owned(),
            computed_at: OffsetDateTime::now_utc(),
            cores: std::thread::available_parallelism().map_or(1, usize::from),
        }
    }
}

/// The provenance of a result: its [`Build`] and the SHA-256 of the scene as run.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Provenance {
    /// The build, the machine and the date.
    #[serde(flatten)]
    pub build: Build,
    /// [`scene_sha256`] of the scene as run.
    pub scene_sha256: String,
}

impl Provenance {
    /// The provenance of a run of `scene` by this build, now.
    pub fn of(scene: &Scene) -> Self {
        Self {
            build: Build::now(),
            scene_sha256: scene_sha256(scene),
        }
    }
}

/// The SHA-256, as 64 lowercase hex digits, of `scene`'s canonical JSON: every default
/// filled in (the scene as run), object keys sorted, no whitespace, numbers as serde_json
/// writes an f64 (the shortest text that reads back to the same bits). Two texts of one
/// scene (keys in another order, a preset against its fields spelled out) hash alike.
pub fn scene_sha256(scene: &Scene) -> String {
    let value = serde_json::to_value(scene)
        .expect("a scene serialises: its maps have string keys and its numbers are finite");
    let mut canonical = String::new();
    write_canonical(&value, &mut canonical);
    Sha256::digest(canonical.as_bytes())
        .iter()
        .map(|byte| format!("{byte:02x}"))
        .collect()
}

/// `value` as JSON with its objects' keys sorted, whatever order the map keeps.
fn write_canonical(value: &Value, out: &mut String) {
    match value {
        Value::Object(map) => {
            let mut keys: Vec<&String> = map.keys().collect();
            keys.sort();
            out.push('{');
            for (i, key) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::from(key.as_str()).to_string());
                out.push(':');
                write_canonical(&map[key], out);
            }
            out.push('}');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_canonical(item, out);
            }
            out.push(']');
        }
        leaf => out.push_str(&leaf.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::parse_scene_str;

    fn hash(text: &str) -> String {
        scene_sha256(&parse_scene_str(text).expect("valid scene").into_scene())
    }

    #[test]
    fn one_scene_written_two_ways_hashes_alike_and_a_changed_field_does_not() {
        let by_preset = hash(
            r#"{"preset": "dalmau2018-316l", "overrides": {"test": {"cycles": 30, "load_n": 5}}}"#,
        );
        let reordered = hash(
            r#"{"overrides": {"test": {"load_n": 5.0, "cycles": 30}},
                "preset": "dalmau2018-316l"}"#,
        );
        assert_eq!(by_preset, reordered);
        assert_eq!(by_preset.len(), 64);
        assert!(by_preset.chars().all(|c| c.is_ascii_hexdigit()));
        let scene = parse_scene_str(
            r#"{"preset": "dalmau2018-316l", "overrides": {"test": {"cycles": 30, "load_n": 5}}}"#,
        )
        .expect("valid scene")
        .into_scene();
        let spelled_out = serde_json::to_string_pretty(&scene).expect("serialises");
        assert_eq!(hash(&spelled_out), by_preset, "{spelled_out}");
        let heavier = hash(
            r#"{"preset": "dalmau2018-316l", "overrides": {"test": {"cycles": 30, "load_n": 5.5}}}"#,
        );
        assert_ne!(heavier, by_preset);
    }

    #[test]
    fn the_canonical_text_sorts_keys_at_every_level() {
        let value = serde_json::json!({"b": [{"z": 1, "a": 2.5}], "a": "x\"y"});
        let mut text = String::new();
        write_canonical(&value, &mut text);
        assert_eq!(text, r#"{"a":"x\"y","b":[{"a":2.5,"z":1}]}"#);
    }
}
