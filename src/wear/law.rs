//! The wear law of a run, the one place that knows its coefficient: the depth a pass wears
//! at a cycle, the cycle at which its rate changes, its words in the result's `models` and
//! its fields in the result's `summary` ([`super::report`]).

use std::ops::Range;

use crate::contact::Grid;
use crate::hardness::HardnessLaw;

use super::archard::{Archard, pass_pressure_integral};
use super::report::{LawChoice, WearSummary};

/// How a pass of the ball wears the disc. A pass at cycle `n` deepens each row of the track
/// by [`WearLaw::depth_scale`] of `n..n + 1` times its [`WearLaw::pass_profile`].
#[derive(Debug, Clone, PartialEq)]
pub enum WearLaw {
    /// Archard's law (eqs. 14-16), with its optional change of regime.
    Archard(Archard),
}

impl WearLaw {
    /// The depth profile of one pass, per grid row, up to the factor
    /// [`WearLaw::depth_scale`]: the part the contact's `pressure` decides, which the cycle
    /// stepping compares between solves. Archard's: the pressure integrated along the
    /// sliding direction (eqs. 15-16), Pa m.
    pub fn pass_profile(&self, grid: &Grid, pressure: &[f64]) -> Vec<f64> {
        match self {
            Self::Archard(_) => pass_pressure_integral(grid, pressure),
        }
    }

    /// The depth per unit of [`WearLaw::pass_profile`] the passes of `cycles` wear together,
    /// each at its own hardness from `hardness`. Archard's: `sum k(n) / H(n)`, 1/Pa.
    pub fn depth_scale(&self, cycles: Range<u64>, hardness: &HardnessLaw) -> f64 {
        match self {
            Self::Archard(law) => law.depth_scale(cycles, hardness),
        }
    }

    /// The first cycle worn at a rate the last solve's cannot stand for, other than by the
    /// hardness (the first of a new Archard regime): a cycle step stops before it, and the
    /// stepping starts afresh there.
    pub fn rate_change_cycle(&self) -> Option<u64> {
        match self {
            Self::Archard(law) => law.rate_change_cycle(),
        }
    }

    /// Whether the law wears, and why.
    pub fn choice(&self) -> LawChoice {
        match self {
            Self::Archard(law) => law.choice(),
        }
    }

    /// The law's fields of the result's `summary`.
    pub fn summary(&self) -> WearSummary {
        match self {
            Self::Archard(law) => law.summary(),
        }
    }
}
