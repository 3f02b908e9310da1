//! What a lab writes on a job besides its scene: the sample it stands for, a note and tags.
//! Set at submit (`POST /api/v1/jobs?sample=...&note=...&tags=a,b`) and changed at any time
//! after (`PATCH /api/v1/jobs/{id}` with JSON), each bounded so that a job record stays
//! small in `status.json` and in every list page.

use std::collections::HashSet;

use serde_json::Value;

use super::job::JobRecord;
use crate::scene::{FieldError, listed};
use crate::service::error::ApiError;
use crate::text::{Lines, check};

/// The longest sample id, in characters: a lab's specimen code, not a text.
pub const SAMPLE_MAX_CHARS: usize = 100;
/// The longest note, in characters: a paragraph.
pub const NOTE_MAX_CHARS: usize = 2000;
/// The most tags on one job.
pub const TAGS_MAX: usize = 20;
/// The longest tag, in characters.
pub const TAG_MAX_CHARS: usize = 40;
/// The most tags one request may give, empty and repeated ones included: counted before any
/// tag is read, so a request of 100,000 tags costs a count, not 100,000 checks. Five times
/// [`TAGS_MAX`] leaves room for a client that repeats or leaves some empty.
pub const TAG_ITEMS_MAX: usize = 5 * TAGS_MAX;

/// A change of a job's labels: `None` leaves a label as it is; `Some(None)` (or no tags)
/// clears it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LabelChange {
    sample: Option<Option<String>>,
    note: Option<Option<String>>,
    tags: Option<Vec<String>>,
}

/// A text label trimmed, `None` when empty; refused past `max` characters or holding a
/// character the text rule refuses ([`crate::text`]; a note may span lines).
fn text(
    field: &str,
    value: &str,
    max: usize,
    lines: Lines,
    errors: &mut Vec<FieldError>,
) -> Option<String> {
    let value = value.trim();
    if let Err(e) = check(value, max, lines) {
        errors.push(FieldError::new(field, e.to_string()));
    }
    (!value.is_empty()).then(|| value.to_owned())
}

/// One line of text: a sample, a tag.
fn line(field: &str, value: &str, max: usize, errors: &mut Vec<FieldError>) -> Option<String> {
    text(field, value, max, Lines::One, errors)
}

/// The refusal of `count` tag items, past [`TAG_ITEMS_MAX`], if it is.
fn too_many_items(count: usize) -> Option<FieldError> {
    (count > TAG_ITEMS_MAX).then(|| {
        FieldError::new(
            "tags",
            format!(
                "{count} tags given; at most {TAGS_MAX} tags ({TAG_ITEMS_MAX} items with \
                 empty and repeated ones)"
            ),
        )
    })
}

/// Tags trimmed, empty ones dropped, each given once (in the order first given); refused
/// past [`TAGS_MAX`] tags, a tag past [`TAG_MAX_CHARS`], holding a comma (the list filter's
/// separator) or a character the text rule refuses. The caller has checked the count of
/// items against [`TAG_ITEMS_MAX`].
fn tags<'a>(values: impl Iterator<Item = &'a str>, errors: &mut Vec<FieldError>) -> Vec<String> {
    let mut tags: Vec<String> = Vec::new();
    let mut seen: HashSet<String> = HashSet::new();
    for (i, value) in values.enumerate() {
        let field = format!("tags[{i}]");
        if value.contains(',') {
            errors.push(FieldError::new(&field, "a tag cannot hold a comma"));
        }
        let tag = line(&field, value, TAG_MAX_CHARS, errors);
        if let Some(tag) = tag.filter(|t| seen.insert(t.clone())) {
            tags.push(tag);
        }
    }
    if tags.len() > TAGS_MAX {
        errors.push(FieldError::new(
            "tags",
            format!("{} tags; at most {TAGS_MAX}", tags.len()),
        ));
    }
    tags
}

/// Labels refused, each field with why.
#[derive(Debug)]
pub struct LabelErrors(pub Vec<FieldError>);

/// 422 naming each field and its limit.
impl From<LabelErrors> for ApiError {
    fn from(LabelErrors(errors): LabelErrors) -> Self {
        let all: Vec<String> = errors
            .iter()
            .map(|e| format!("{}: {}", e.path, e.message))
            .collect();
        Self::unprocessable(format!("invalid job labels: {}", all.join("; ")), errors)
    }
}

/// `change` unless there are `errors`; of those, the ones a refusal lists ([`listed`]), so
/// its message, which names each, stays small however many fields are at fault.
fn checked(change: LabelChange, errors: Vec<FieldError>) -> Result<LabelChange, LabelErrors> {
    if errors.is_empty() {
        return Ok(change);
    }
    Err(LabelErrors(listed(errors)))
}

impl LabelChange {
    /// The labels of a submit's query: `sample`, `note`, and `tags` separated by commas.
    pub fn from_query(
        sample: Option<&str>,
        note: Option<&str>,
        tag_list: Option<&str>,
    ) -> Result<Self, LabelErrors> {
        if let Some(refused) = tag_list.and_then(|t| too_many_items(t.split(',').count())) {
            return Err(LabelErrors(vec![refused]));
        }
        let mut errors = Vec::new();
        let change = Self {
            sample: sample.map(|s| line("sample", s, SAMPLE_MAX_CHARS, &mut errors)),
            note: note.map(|n| text("note", n, NOTE_MAX_CHARS, Lines::Many, &mut errors)),
            tags: tag_list.map(|t| tags(t.split(','), &mut errors)),
        };
        checked(change, errors)
    }

    /// The labels of a PATCH's JSON object: `sample` and `note` a string or null, `tags` an
    /// array of strings or null; a key left out is left as it is; any other key refused.
    pub fn from_json(document: &Value) -> Result<Self, LabelErrors> {
        let Some(object) = document.as_object() else {
            let message = "the labels must be a JSON object of `sample`, `note` and `tags`";
            return Err(LabelErrors(vec![FieldError::new("", message)]));
        };
        let mut errors = Vec::new();
        let mut change = Self::default();
        for (key, value) in object {
            match key.as_str() {
                "sample" | "note" => {
                    let (max, lines) = if key == "sample" {
                        (SAMPLE_MAX_CHARS, Lines::One)
                    } else {
                        (NOTE_MAX_CHARS, Lines::Many)
                    };
                    let label = match value {
                        Value::Null => None,
                        Value::String(s) => text(key, s, max, lines, &mut errors),
                        _ => {
                            errors.push(FieldError::new(key, "a string or null"));
                            None
                        }
                    };
                    *change.slot(key) = Some(label);
                }
                "tags" => change.tags = Some(json_tags(value, &mut errors)),
                other => errors.push(FieldError::new(
                    other,
                    "unknown field; a job's labels are `sample`, `note` and `tags`",
                )),
            }
        }
        checked(change, errors)
    }

    fn slot(&mut self, key: &str) -> &mut Option<Option<String>> {
        if key == "sample" {
            &mut self.sample
        } else {
            &mut self.note
        }
    }

    /// `record` with the change made.
    pub fn apply(self, record: &mut JobRecord) {
        if let Some(sample) = self.sample {
            record.sample = sample;
        }
        if let Some(note) = self.note {
            record.note = note;
        }
        if let Some(tags) = self.tags {
            record.tags = tags;
        }
    }
}

/// `tags` of a PATCH: an array of strings, or null for none; an array past
/// [`TAG_ITEMS_MAX`] refused on its length alone.
fn json_tags(value: &Value, errors: &mut Vec<FieldError>) -> Vec<String> {
    match value {
        Value::Null => Vec::new(),
        Value::Array(items) => {
            if let Some(refused) = too_many_items(items.len()) {
                errors.push(refused);
                return Vec::new();
            }
            let mut strings = Vec::new();
            for (i, item) in items.iter().enumerate() {
                match item.as_str() {
                    Some(s) => strings.push(s),
                    None => errors.push(FieldError::new(format!("tags[{i}]"), "a string")),
                }
            }
            tags(strings.into_iter(), errors)
        }
        _ => {
            errors.push(FieldError::new("tags", "an array of strings or null"));
            Vec::new()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::MAX_LISTED_PROBLEMS;
    use serde_json::json;

    fn fields(LabelErrors(errors): LabelErrors) -> Vec<String> {
        errors.into_iter().map(|f| f.path).collect()
    }

    #[test]
    fn labels_are_trimmed_bounded_and_named_when_refused() {
        let change =
            LabelChange::from_query(Some(" S-12 "), Some(""), Some("a, b,,a")).expect("valid");
        assert_eq!(change.sample, Some(Some("S-12".to_owned())));
        assert_eq!(change.note, Some(None));
        assert_eq!(change.tags, Some(vec!["a".to_owned(), "b".to_owned()]));

        let long = "x".repeat(SAMPLE_MAX_CHARS + 1);
        let error = LabelChange::from_query(Some(&long), None, None).expect_err("too long");
        assert_eq!(fields(error), ["sample"]);
        let many: Vec<String> = (0..=TAGS_MAX).map(|i| i.to_string()).collect();
        let error = LabelChange::from_query(None, None, Some(&many.join(","))).expect_err("many");
        assert_eq!(fields(error), ["tags"]);

        let document = json!({"note": null, "tags": ["ok", "a,b", 3], "colour": "red"});
        let error = LabelChange::from_json(&document).expect_err("refused");
        // serde_json's map is ordered by key.
        assert_eq!(fields(error), ["colour", "tags[2]", "tags[1]"]);
        let error = LabelChange::from_json(&json!([])).expect_err("not an object");
        assert_eq!(fields(error), [""]);

        let mut record: JobRecord = serde_json::from_value(json!({
            "id": "00000000-0000-0000-0000-000000000000", "name": "n", "status": "queued",
            "cycles_done": 0, "cycles_total": 1, "eta_s": null, "error": null,
            "created_at": "2026-01-01T00:00:00Z", "started_at": null, "finished_at": null,
            "sample": "old", "note": "kept"
        }))
        .expect("a stored record");
        assert!(
            record.tags.is_empty(),
            "records stored without labels read with none"
        );
        let change =
            LabelChange::from_json(&json!({"sample": null, "tags": ["x"]})).expect("valid");
        change.apply(&mut record);
        assert_eq!(record.sample, None);
        assert_eq!(record.note.as_deref(), Some("kept"));
        assert_eq!(record.tags, ["x"]);
    }
    #[test]
    fn hidden_characters_are_refused_naming_the_field_the_character_and_its_place() {
        let error = LabelChange::from_json(&json!({"tags": ["ok", "\u{202e}gpj.exe"]}))
            .expect_err("a right-to-left override");
        let LabelErrors(errors) = error;
        assert_eq!(errors.len(), 1, "{errors:?}");
        assert_eq!(errors[0].path, "tags[1]");
        assert!(
            errors[0]
                .message
                .starts_with("holds U+202E (a bidirectional control) at character 1"),
            "{}",
            errors[0].message
        );
        for (sample, what) in [
            ("a\0b", "U+0000"),
            ("x\u{200b}y", "U+200B"),
            ("S\tT", "U+0009"),
        ] {
            let error = LabelChange::from_query(Some(sample), None, None).expect_err(what);
            let LabelErrors(errors) = error;
            assert_eq!(errors[0].path, "sample");
            assert!(errors[0].message.contains(what), "{}", errors[0].message);
        }
        // A note is a paragraph: line feeds and tabs are its text.
        let change = LabelChange::from_json(&json!({"note": "one\n\ttwo"})).expect("a paragraph");
        assert_eq!(change.note, Some(Some("one\n\ttwo".to_owned())));
        let error = LabelChange::from_json(&json!({"note": "a\u{2066}b"})).expect_err("an isolate");
        assert_eq!(fields(error), ["note"]);
    }

    /// Two PATCHes of 100,000 distinct tags each once held the server for 43 s (a quadratic
    /// de-duplication of every tag before the count). They are refused on their count, with
    /// one problem named; speed is not asserted, the shape of the refusal is.
    #[test]
    fn a_hundred_thousand_tags_are_refused_on_their_count_in_one_problem() {
        let many: Vec<String> = (0..100_000).map(|i| format!("t{i}")).collect();
        let error = LabelChange::from_json(&json!({"tags": many})).expect_err("too many");
        let LabelErrors(errors) = error;
        assert_eq!(errors.len(), 1, "{errors:?}");
        assert_eq!(errors[0].path, "tags");
        assert!(
            errors[0]
                .message
                .starts_with("100000 tags given; at most 20"),
            "{}",
            errors[0].message
        );
        let error = LabelChange::from_query(None, None, Some(&many.join(","))).expect_err("many");
        assert_eq!(fields(error), ["tags"]);

        // At the item bound, every tag is read (in linear time) and the distinct ones counted.
        let most: Vec<String> = (0..TAG_ITEMS_MAX).map(|i| format!("t{}", i % 30)).collect();
        let error = LabelChange::from_json(&json!({"tags": most})).expect_err("30 distinct");
        let LabelErrors(errors) = error;
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].message, "30 tags; at most 20");
    }

    #[test]
    fn a_refusal_names_the_first_problems_and_counts_the_rest() {
        let bad: Vec<Value> = (0..TAG_ITEMS_MAX).map(|_| Value::from(1)).collect();
        let error = LabelChange::from_json(&json!({"tags": bad})).expect_err("not strings");
        let LabelErrors(errors) = error;
        assert_eq!(errors.len(), MAX_LISTED_PROBLEMS + 1);
        assert_eq!(errors[MAX_LISTED_PROBLEMS].path, "");
        assert_eq!(errors[MAX_LISTED_PROBLEMS].message, "and 80 more problems");
        let keys: serde_json::Map<String, Value> = (0..100_000)
            .map(|i| (format!("k{i}"), Value::Null))
            .collect();
        let error = LabelChange::from_json(&Value::Object(keys)).expect_err("unknown keys");
        let LabelErrors(errors) = error;
        assert_eq!(errors.len(), MAX_LISTED_PROBLEMS + 1);
        assert_eq!(
            errors[MAX_LISTED_PROBLEMS].message,
            "and 99980 more problems"
        );
    }
}
