//! The settings that take `"auto"` or a number (`numerics.grid`, `numerics.domain_um`,
//! `numerics.tolerance`, `numerics.cycle_step`, `numerics.cycle_step_bound`,
//! `numerics.threads`) and their one JSON shape.

use serde::de::{DeserializeOwned, Error as _};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use thiserror::Error;

/// Cells per side: `"auto"` or a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "AutoOr<usize>", into = "AutoOr<usize>")]
pub enum GridSize {
    /// Sized to the contact by the simulation.
    Auto,
    /// This many cells per side.
    Cells(usize),
}

/// Domain side: `"auto"` or a number of micrometres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "AutoOr<f64>", into = "AutoOr<f64>")]
pub enum DomainSize {
    /// Sized to the contact by the simulation.
    Auto,
    /// This many micrometres per side.
    Micrometres(f64),
}

/// The contact solves' relative residual: `"auto"` or a number.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "AutoOr<f64>", into = "AutoOr<f64>")]
pub enum Tolerance {
    /// Chosen by the disc: smooth or rough (`Numerics::solve_tolerance`).
    Auto,
    /// This relative residual.
    Relative(f64),
}

/// The automatic cycle step's bound: `"auto"` or a number.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "AutoOr<f64>", into = "AutoOr<f64>")]
pub enum StepBound {
    /// Chosen by the scene's rig and disc (`Numerics::step_bound`,
    /// `Numerics::solve_cycle_step`).
    Auto,
    /// This largest relative (L1) change of the per-pass wear profile across one step.
    Share(f64),
}

/// Which cycles are solved: `1` (every one) or `"auto"`.
///
/// Fixed strides n > 1 are rejected rather than supported: `docs/scene.md` names only 1 and
/// `"auto"`, and a stride would silently skip the fast plastic cycles at the start of a run,
/// which `"auto"` resolves under an error bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "AutoOr<u64>", into = "AutoOr<u64>")]
pub enum CycleStep {
    /// Steps chosen by the simulation under an error bound.
    Auto,
    /// Every cycle solved (JSON `1`).
    EveryCycle,
}

/// Threads of each contact solve's FFT passes: `"auto"` or a number. The results do not
/// depend on it (the split apply is bit-identical to the one-thread apply).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "AutoOr<usize>", into = "AutoOr<usize>")]
pub enum SolverThreads {
    /// One thread on grids too small for a split to pay, else the cores the process may use.
    Auto,
    /// This many threads per apply.
    Count(usize),
}

/// The JSON shape shared by the `"auto"`-or-number settings.
#[derive(Debug, Clone, Copy)]
enum AutoOr<T> {
    Auto,
    Value(T),
}

impl<T: Serialize> Serialize for AutoOr<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Auto => serializer.serialize_str("auto"),
            Self::Value(value) => value.serialize(serializer),
        }
    }
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for AutoOr<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        // Buffering through a Value lets one message cover both accepted shapes instead of
        // serde's "did not match any variant".
        let value = serde_json::Value::deserialize(deserializer)?;
        if value.as_str() == Some("auto") {
            return Ok(Self::Auto);
        }
        T::deserialize(&value)
            .map(Self::Value)
            .map_err(|e| D::Error::custom(format!("expected \"auto\" or a number ({e})")))
    }
}

impl From<AutoOr<usize>> for GridSize {
    fn from(value: AutoOr<usize>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(cells) => Self::Cells(cells),
        }
    }
}

impl From<GridSize> for AutoOr<usize> {
    fn from(value: GridSize) -> Self {
        match value {
            GridSize::Auto => Self::Auto,
            GridSize::Cells(cells) => Self::Value(cells),
        }
    }
}

impl From<AutoOr<usize>> for SolverThreads {
    fn from(value: AutoOr<usize>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(threads) => Self::Count(threads),
        }
    }
}

impl From<SolverThreads> for AutoOr<usize> {
    fn from(value: SolverThreads) -> Self {
        match value {
            SolverThreads::Auto => Self::Auto,
            SolverThreads::Count(threads) => Self::Value(threads),
        }
    }
}

impl From<AutoOr<f64>> for Tolerance {
    fn from(value: AutoOr<f64>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(relative) => Self::Relative(relative),
        }
    }
}

impl From<Tolerance> for AutoOr<f64> {
    fn from(value: Tolerance) -> Self {
        match value {
            Tolerance::Auto => Self::Auto,
            Tolerance::Relative(relative) => Self::Value(relative),
        }
    }
}

impl From<AutoOr<f64>> for StepBound {
    fn from(value: AutoOr<f64>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(relative) => Self::Share(relative),
        }
    }
}

impl From<StepBound> for AutoOr<f64> {
    fn from(value: StepBound) -> Self {
        match value {
            StepBound::Auto => Self::Auto,
            StepBound::Share(relative) => Self::Value(relative),
        }
    }
}

impl From<AutoOr<f64>> for DomainSize {
    fn from(value: AutoOr<f64>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(um) => Self::Micrometres(um),
        }
    }
}

impl From<DomainSize> for AutoOr<f64> {
    fn from(value: DomainSize) -> Self {
        match value {
            DomainSize::Auto => Self::Auto,
            DomainSize::Micrometres(um) => Self::Value(um),
        }
    }
}

/// A `numerics.cycle_step` other than 1 or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[error(
    "must be 1 (every cycle solved) or \"auto\" (steps chosen under an error bound); fixed \
     strides are not supported, got {0}"
)]
pub struct FixedStrideError(pub u64);

impl TryFrom<AutoOr<u64>> for CycleStep {
    type Error = FixedStrideError;

    fn try_from(value: AutoOr<u64>) -> Result<Self, Self::Error> {
        match value {
            AutoOr::Auto => Ok(Self::Auto),
            AutoOr::Value(1) => Ok(Self::EveryCycle),
            AutoOr::Value(n) => Err(FixedStrideError(n)),
        }
    }
}

impl From<CycleStep> for AutoOr<u64> {
    fn from(value: CycleStep) -> Self {
        match value {
            CycleStep::Auto => Self::Auto,
            CycleStep::EveryCycle => Self::Value(1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{StepBound, Tolerance};
    use crate::scene::Numerics;

    #[test]
    fn an_auto_tolerance_and_step_bound_read_and_write_auto_and_a_number_is_kept() {
        let auto: Numerics =
            serde_json::from_str(r#"{"tolerance": "auto", "cycle_step_bound": "auto"}"#)
                .expect("auto");
        assert_eq!(auto.tolerance, Tolerance::Auto);
        assert_eq!(auto.cycle_step_bound, StepBound::Auto);
        assert_eq!(auto, Numerics::default());
        let given: Numerics =
            serde_json::from_str(r#"{"tolerance": 1e-7, "cycle_step_bound": 0.05}"#)
                .expect("numbers");
        assert_eq!(given.tolerance, Tolerance::Relative(1e-7));
        assert_eq!(given.cycle_step_bound, StepBound::Share(0.05));
        let written = serde_json::to_value(given).expect("JSON");
        assert_eq!(written["tolerance"], serde_json::json!(1e-7));
        assert_eq!(written["cycle_step_bound"], serde_json::json!(0.05));
        let written = serde_json::to_value(auto).expect("JSON");
        assert_eq!(written["tolerance"], serde_json::json!("auto"));
        assert_eq!(written["cycle_step_bound"], serde_json::json!("auto"));
    }
}
