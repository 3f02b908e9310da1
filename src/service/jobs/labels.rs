//! What a lab writes on a job besides its scene: the sample it stands for, a note and tags.
//! Set at submit (`POST /api/v1/jobs?sample=...&note=...&tags=a,b`) and changed at any time
//! after (`PATCH /api/v1/jobs/{id}` with JSON), each bounded so that a job record stays
//! small in `status.json` and in every list page.

use serde_json::Value;

use super::job::JobRecord;
use crate::scene::FieldError;
use crate::service::error::ApiError;

/// The longest sample id, in characters: a lab's specimen code, not a text.
pub const SAMPLE_MAX_CHARS: usize = 100;
/// The longest note, in characters: a paragraph.
pub const NOTE_MAX_CHARS: usize = 2000;
/// The most tags on one job.
pub const TAGS_MAX: usize = 20;
/// The longest tag, in characters.
pub const TAG_MAX_CHARS: usize = 40;

/// A change of a job's labels: `None` leaves a label as it is; `Some(None)` (or no tags)
/// clears it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LabelChange {
    sample: Option<Option<String>>,
    note: Option<Option<String>>,
    tags: Option<Vec<String>>,
}

/// A text label trimmed, `None` when empty; refused past `max` characters.
fn text(field: &str, value: &str, max: usize, errors: &mut Vec<FieldError>) -> Option<String> {
    let value = value.trim();
    let chars = value.chars().count();
    if chars > max {
        errors.push(FieldError::new(
            field,
            format!("{chars} characters; at most {max}"),
        ));
    }
    (!value.is_empty()).then(|| value.to_owned())
}

/// Tags trimmed, empty ones dropped, each given once; refused past [`TAGS_MAX`] tags, a tag
/// past [`TAG_MAX_CHARS`] or holding a comma (the list filter's separator).
fn tags<'a>(values: impl Iterator<Item = &'a str>, errors: &mut Vec<FieldError>) -> Vec<String> {
    let mut tags: Vec<String> = Vec::new();
    for (i, value) in values.enumerate() {
        let field = format!("tags[{i}]");
        if value.contains(',') {
            errors.push(FieldError::new(&field, "a tag cannot hold a comma"));
        }
        let tag = text(&field, value, TAG_MAX_CHARS, errors);
        if let Some(tag) = tag.filter(|t| !tags.contains(t)) {
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

/// `change` unless there are `errors`.
fn checked(change: LabelChange, errors: Vec<FieldError>) -> Result<LabelChange, LabelErrors> {
    if errors.is_empty() {
        Ok(change)
    } else {
        Err(LabelErrors(errors))
    }
}

impl LabelChange {
    /// The labels of a submit's query: `sample`, `note`, and `tags` separated by commas.
    pub fn from_query(
        sample: Option<&str>,
        note: Option<&str>,
        tag_list: Option<&str>,
    ) -> Result<Self, LabelErrors> {
        let mut errors = Vec::new();
        let change = Self {
            sample: sample.map(|s| text("sample", s, SAMPLE_MAX_CHARS, &mut errors)),
            note: note.map(|n| text("note", n, NOTE_MAX_CHARS, &mut errors)),
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
                    let max = if key == "sample" {
                        SAMPLE_MAX_CHARS
                    } else {
                        NOTE_MAX_CHARS
                    };
                    let label = match value {
                        Value::Null => None,
                        Value::String(s) => text(key, s, max, &mut errors),
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

/// `tags` of a PATCH: an array of strings, or null for none.
fn json_tags(value: &Value, errors: &mut Vec<FieldError>) -> Vec<String> {
    match value {
        Value::Null => Vec::new(),
        Value::Array(items) => {
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
}
