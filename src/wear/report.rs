//! What a wear law reports: its entry in the result's `models` and its fields in the
//! result's `summary`, with the line `tribosim run` prints of them.

use std::fmt;

use serde::{Deserialize, Serialize};

use super::regime::ArchardRegimeChange;

/// Whether a law wears at all, and why: the result's `models` entry of the law.
#[derive(Debug, Clone, PartialEq)]
pub struct LawChoice {
    /// Whether it wears anything.
    pub active: bool,
    /// Its coefficients and where they come from, in words.
    pub reason: String,
}

/// The law's fields of the result's `summary`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WearSummary {
    /// The Archard coefficient the run used (dimensionless), given or derived by eq. 14; the
    /// one after the change when the regime changes.
    pub archard_k: f64,
    /// The change of Archard regime: k up to and including its cycle; absent with one k.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_regime_change: Option<ArchardRegimeChange>,
}

/// The summary's line of the law, as `tribosim run` prints it.
impl fmt::Display for WearSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.archard_regime_change {
            None => write!(f, "  Archard k        {:.4e}", self.archard_k),
            Some(change) => write!(
                f,
                "  Archard k        {:.4e} to cycle {}, {:.4e} after",
                change.archard_k_before, change.cycle, self.archard_k
            ),
        }
    }
}
