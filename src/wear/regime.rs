//! A change of Archard regime: the scene's `wear.archard_regime_change`, which the result's
//! `summary.archard_regime_change` repeats.

use serde::{Deserialize, Serialize};

/// A change of Archard regime (the paper's Section 5.2: a low-wear period before about 300
/// cycles, Archard wear after it): cycles up to and including `cycle` wear with
/// `archard_k_before`, the later ones with the law's k. The scene's
/// `wear.archard_regime_change` and the result's `summary.archard_regime_change`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArchardRegimeChange {
    /// The last cycle of the first regime.
    pub cycle: u64,
    /// k of the cycles up to and including `cycle`, dimensionless.
    pub archard_k_before: f64,
}

impl ArchardRegimeChange {
    /// k of `cycle` when `k_after` applies after the change.
    pub fn k_at(&self, cycle: u64, k_after: f64) -> f64 {
        if cycle <= self.cycle {
            self.archard_k_before
        } else {
            k_after
        }
    }
}
