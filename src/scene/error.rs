//! Problems found in a scene, each located by the dotted path of its field.

use std::fmt;

use serde::{Deserialize, Serialize};

/// The most problems one refusal lists. A document with more (a megabyte of unknown keys)
/// is refused with these and the count of the fields left unchecked: finding a near name
/// for each of 110,000 unknown keys took 5.6 s and gave a 14 MB answer, and nobody reads
/// past the first screenful anyway.
pub const MAX_LISTED_PROBLEMS: usize = 20;

/// `errors` as a refusal lists them: the first [`MAX_LISTED_PROBLEMS`], and one more entry
/// counting the rest when there are more.
pub fn listed(mut errors: Vec<FieldError>) -> Vec<FieldError> {
    if errors.len() > MAX_LISTED_PROBLEMS {
        let more = errors.len() - MAX_LISTED_PROBLEMS;
        errors.truncate(MAX_LISTED_PROBLEMS);
        errors.push(FieldError::new("", format!("and {more} more problems")));
    }
    errors
}

/// One problem in a scene, located by a dotted path such as `test.load_n` or
/// `disc.hardness_table[2][0]` (empty for the document as a whole).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct FieldError {
    /// Where the problem is.
    pub path: String,
    /// What is wrong, with the allowed range.
    pub message: String,
}

impl FieldError {
    /// A problem at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.path, self.message)
        }
    }
}

/// Something in a scene that looks wrong without being invalid (a value far from any
/// real test, as a unit slip gives), located as a [`FieldError`] is. It displays as the
/// result's `warnings` carry it, `path: message`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FieldWarning {
    /// The field it is about (empty for the scene as a whole).
    pub path: String,
    /// What looks wrong, with the numbers and the likely slip.
    pub message: String,
}

impl FieldWarning {
    /// A warning about the field at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl FieldWarning {
    /// The warning in a line a table cell holds: its path and its first clause (up to the
    /// first ": " or "; " of its message, where the explanation starts).
    pub fn headline(&self) -> String {
        let end = ["; ", ": "]
            .iter()
            .filter_map(|mark| self.message.find(mark))
            .min()
            .unwrap_or(self.message.len());
        let clause = &self.message[..end];
        if self.path.is_empty() {
            clause.to_owned()
        } else {
            format!("{}: {clause}", self.path)
        }
    }
}

impl fmt::Display for FieldWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.path, self.message)
        }
    }
}

/// Every problem found in a scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct SceneErrors(pub Vec<FieldError>);

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0.as_slice() {
            [single] => write!(f, "invalid scene: {single}"),
            errors => {
                write!(f, "invalid scene, {} problems:", errors.len())?;
                for error in errors {
                    write!(f, "\n  {error}")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for SceneErrors {}
