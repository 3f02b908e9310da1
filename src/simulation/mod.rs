//! A simulation run: the scene's setup, the per-cycle loop and its result. Plain
//! synchronous code; a caller (the command line, the service) drives it through a callback
//! and a cancel flag.

mod first;
mod result;
mod run;
mod setup;
mod stepping;

use thiserror::Error;

use crate::contact::ContactError;
use crate::corrosion::CorrosionError;
use crate::hardness::HardnessError;
use crate::scene::SceneErrors;

pub use first::{FirstContact, first_contact};
pub use result::{CycleRecord, ModelChoice, PressureMap, Profile, SimulationResult, Summary};
pub use run::run;
pub use setup::{CELLS_PER_CONTACT_RADIUS, COUPLING_SENSITIVITY, DOMAIN_PER_CONTACT_RADIUS, Setup};
pub use stepping::{MAX_STEP, STEP_CHANGE_BOUND};

/// Why a run stopped without a result.
#[derive(Debug, Error)]
pub enum SimulationError {
    /// The scene has invalid fields (all of them listed).
    #[error("invalid scene: {0}")]
    Scene(#[from] SceneErrors),
    /// The contact could not be solved at this cycle (0: while setting up).
    #[error("cycle {cycle}: {source}")]
    Contact {
        /// The cycle being solved.
        cycle: u64,
        /// What the solver reported.
        #[source]
        source: ContactError,
    },
    /// The hardness law could not be built.
    #[error("hardness: {0}")]
    Hardness(#[from] HardnessError),
    /// The corrosion estimate failed (e.g. an anodic area larger than the exposed one).
    #[error("corrosion at cycle {cycle}: {source}")]
    Corrosion {
        /// The cycle being estimated.
        cycle: u64,
        /// What the model reported.
        #[source]
        source: CorrosionError,
    },
    /// The caller's cancel flag was set.
    #[error("cancelled after {cycles_done} cycles")]
    Cancelled {
        /// Cycles completed before the stop.
        cycles_done: u64,
    },
}
