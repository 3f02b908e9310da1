//! From a study to its members: every combination of the axes' values, each set at its
//! path in the base scene and parsed as any scene is.

use serde_json::{Map, Value};

use crate::simulation::parse_scene;
use crate::text::NAME_MAX_CHARS;

use super::{Member, Study, StudyError, describe_values};

impl Study {
    /// Every member, the first axis varying slowest (as nested loops written in the axes'
    /// order). Refuses a study with no axes or more than `max_members` members before
    /// building any, and a member whose scene the scene parser refuses, naming the field.
    pub fn members(&self, max_members: usize) -> Result<Vec<Member>, StudyError> {
        if self.axes.is_empty() {
            return Err(StudyError::NoAxes);
        }
        let count = self.member_count();
        if count > max_members {
            let sizes = self
                .axes
                .iter()
                .map(|axis| format!("{}: {}", axis.path, axis.values.len()))
                .collect::<Vec<_>>()
                .join(" x ");
            return Err(StudyError::TooManyMembers {
                members: count,
                sizes,
                limit: max_members,
            });
        }
        let name = self.name();
        (0..count).map(|index| self.member(index, &name)).collect()
    }

    /// The member at `index` of the expansion order (mixed-radix digits, last axis fastest),
    /// named after the study's `name` and its own values.
    fn member(&self, index: usize, name: &str) -> Result<Member, StudyError> {
        let mut rest = index;
        let mut values = vec![(String::new(), Value::Null); self.axes.len()];
        for (slot, axis) in values.iter_mut().zip(&self.axes).rev() {
            let n = axis.values.len();
            *slot = (axis.path.clone(), axis.values.get(rest % n));
            rest /= n;
        }
        let mut document = self.base.clone();
        for (path, value) in &values {
            set(&mut document, path, value.clone())?;
        }
        let described = describe_values(&values);
        let mut scene = parse_scene(&document)
            .map_err(|source| StudyError::Member {
                index,
                values: described.clone(),
                source,
            })?
            .into_scene();
        // The base's name (a preset's "316L vs alumina, 5 N, 60 rpm") would name the wrong
        // test in a job list or a result file for a member at another load.
        scene.name = member_name(name, &described);
        Ok(Member {
            index,
            values,
            scene,
        })
    }
}

/// A member's name: its study's name and its values, `study [a = 1, b = 2]`, within the
/// scene's bound on names ([`NAME_MAX_CHARS`]), which the member's scene is held to when it
/// runs as every scene is. Past the bound the study's name is cut first, being the same in
/// every member, where the values tell the members apart; values longer than the whole
/// bound are cut at their end. A cut is marked `…`.
fn member_name(study: &str, described: &str) -> String {
    let values = format!("[{described}]");
    let whole = format!("{study} {values}");
    if whole.chars().count() <= NAME_MAX_CHARS {
        return whole;
    }
    let value_chars = values.chars().count();
    // The study's name keeps what the values and "… " leave.
    match NAME_MAX_CHARS.checked_sub(value_chars + 2) {
        Some(keep) => {
            let head: String = study.chars().take(keep).collect();
            format!("{head}… {values}")
        }
        None => {
            let head: String = values.chars().take(NAME_MAX_CHARS - 2).collect();
            format!("{head}…]")
        }
    }
}

/// Sets `value` at the dotted `path` of a scene document, under `overrides` when the
/// document starts from a preset, creating the objects on the way. Whether the field exists
/// is the scene parser's to say.
fn set(document: &mut Value, path: &str, value: Value) -> Result<(), StudyError> {
    let fail = |message: &str| StudyError::Axis {
        axis: path.to_owned(),
        message: message.to_owned(),
    };
    let Some(root) = document.as_object_mut() else {
        return Err(StudyError::BaseNotObject);
    };
    let mut at = if root.contains_key("preset") {
        root.entry("overrides")
            .or_insert_with(|| Value::Object(Map::new()))
    } else {
        document
    };
    let keys: Vec<&str> = path.split('.').collect();
    for (depth, key) in keys.iter().enumerate() {
        let Some(object) = at.as_object_mut() else {
            return Err(fail(&format!(
                "`{}` is not an object in the base scene, so nothing can be set under it",
                keys[..depth].join(".")
            )));
        };
        if depth + 1 == keys.len() {
            object.insert((*key).to_owned(), value);
            return Ok(());
        }
        at = object
            .entry(*key)
            .or_insert_with(|| Value::Object(Map::new()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn many_large_ranges_are_refused_on_their_counts_alone() {
        // The most axes, each of a million steps: built in full, each would take 32 MB
        // (half a GB in all); counted, the study is refused at once.
        let axes: Map<String, Value> = (0..crate::study::MAX_AXES)
            .map(|i| {
                let range = serde_json::json!({"from": 0, "to": 1, "steps": 1_000_000});
                (format!("test.a{i}"), range)
            })
            .collect();
        let text = serde_json::json!({"base": {}, "axes": axes}).to_string();
        let study = Study::parse(&text).expect("a well-formed study");
        assert_eq!(study.member_count(), usize::MAX);
        let err = study.members(1000).expect_err("over the member limit");
        assert!(
            matches!(err, StudyError::TooManyMembers { limit: 1000, .. }),
            "{err}"
        );
    }

    /// A member's name once grew with its base's name and values without bound (a study
    /// of 900 KB added 158 MB to the store); it now stays within the scene's bound on names,
    /// its values kept whole where they fit.
    #[test]
    fn a_member_name_stays_within_the_bound_and_keeps_its_values() {
        assert_eq!(member_name("run", "a = 1"), "run [a = 1]");
        let long_base = "b".repeat(NAME_MAX_CHARS);
        let name = member_name(&long_base, "test.load_n = 2");
        assert_eq!(name.chars().count(), NAME_MAX_CHARS);
        assert!(name.ends_with("b… [test.load_n = 2]"), "{name}");
        let long_values = "v".repeat(3 * NAME_MAX_CHARS);
        let name = member_name("run", &long_values);
        assert_eq!(name.chars().count(), NAME_MAX_CHARS);
        assert!(name.starts_with("[vvv") && name.ends_with("v…]"), "{name}");
        // Every member of a study passes the scene's own check of its name.
        let text = serde_json::json!({
            "base": {"name": long_base, "test": {"cycles": 20}, "numerics": {"grid": 32}},
            "axes": {"test.load_n": [2, 5]}
        })
        .to_string();
        let members = Study::parse(&text)
            .and_then(|s| s.members(10))
            .expect("valid");
        for member in members {
            assert_eq!(member.scene.validate(), Ok(()), "{}", member.scene.name);
        }
    }
}
