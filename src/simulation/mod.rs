//! A simulation run: whether a scene can run (the checked scene, [`Plan`], made by
//! [`Plan::new`] and [`parse_scene`]), its setup and the sizing rules behind it, the
//! per-cycle loop and its result. Plain synchronous code; a caller (the command line, the
//! service) drives it through a callback and a cancel flag.

mod balance;
mod electrochemistry;
mod estimate;
mod feasibility;
mod first;
mod growth;
mod hardening;
mod loaded;
mod ocp_trace;
mod plan;
mod plausibility;
mod provenance;
mod reciprocating;
mod result;
mod roughness;
mod run;
mod score;
mod setup;
mod sizing;
mod stepping;
mod stroke_checks;
mod stroke_report;
mod stroke_run;
mod sweep_wear;
mod warm;

use std::sync::atomic::{AtomicBool, Ordering};

use thiserror::Error;

use crate::contact::ContactError;
use crate::corrosion::CorrosionError;
use crate::scene::SceneErrors;
use crate::surface::SurfaceError;

/// The default cycle-step bound, owned by the scene; here beside [`MAX_STEP`] for the
/// callers that study the stepping (the benchmarks).
pub use crate::scene::STEP_CHANGE_BOUND;
pub use estimate::{RunEstimate, describe_duration, describe_size};
pub use first::{FirstContact, first_contact, first_contact_with};
pub use hardening::FAR_OFF_FRACTION;
pub use loaded::disc_share;
pub use plan::{Plan, parse_scene, parse_scene_str};
pub use plausibility::{RULES_BEGIN, RULES_END, check_map, rules_table};
pub use provenance::{Build, GIT_COMMIT, Provenance, scene_sha256};
pub use reciprocating::{
    RETURN_SOLVED_ABOVE_CUT_SHARE, REUSE_FRACTION_OF_APPROACH, SOLVE_EVERY_POSITIONS, StrokeCycle,
    StrokeEngine, StrokeNumerics, StrokeWear, reciprocate,
};
pub use result::{
    CycleRecord, Model, ModelChoice, OcpPhase, OcpSample, PressureMap, Profile, SimulationResult,
    Summary, SurfaceReport,
};
pub use roughness::{CELLS_PER_SHORT_WAVELENGTH, DiscSurface};
pub use run::{run, run_setup, run_with};
pub use score::{
    Curve, PointScore, VolumeAbscissa, depth_curve, potential_curve, rms_residual, score_points,
    volume_curve,
};
pub use setup::{COUPLING_SENSITIVITY, RunOptions, Setup};
pub use sizing::{CELLS_PER_CONTACT_RADIUS, DOMAIN_PER_CONTACT_RADIUS};
pub use stepping::MAX_STEP;
pub use stroke_report::{
    AXIAL_POINTS, AxialProfile, CycleTrace, MAP_COLUMNS, StrokeReport, TRACE_SAMPLES, WearMapReport,
};

/// Why a run stopped without a result.
#[derive(Debug, Error)]
pub enum SimulationError {
    /// The scene has invalid fields, or describes a contact the simulation cannot run (all
    /// of the problems listed).
    #[error(transparent)]
    Scene(#[from] SceneErrors),
    /// The contact core refused the grid built from a scene that passed its checks: the
    /// scene's checks and the core disagree, a defect rather than bad input.
    #[error("setting up the contact: {0} (the scene passed its checks, so this is a defect)")]
    Setup(#[source] ContactError),
    /// The contact could not be solved at this cycle.
    #[error("cycle {cycle}: {source}")]
    Contact {
        /// The cycle being solved.
        cycle: u64,
        /// What the solver reported.
        #[source]
        source: ContactError,
    },
    /// The corrosion estimate failed (e.g. an anodic area larger than the exposed one).
    #[error("corrosion at cycle {cycle}: {source}")]
    Corrosion {
        /// The cycle being estimated.
        cycle: u64,
        /// What the model reported.
        #[source]
        source: CorrosionError,
    },
    /// The scene names a measured surface the caller did not supply.
    #[error(
        "the measured surface `{id}` was not supplied (`tribosim run --surface FILE` supplies \
         one)"
    )]
    SurfaceNotSupplied {
        /// The scene's `disc.surface.id`.
        id: String,
    },
    /// The disc's surface could not be generated on the grid.
    #[error("disc surface: {0}")]
    Surface(#[from] SurfaceError),
    /// The caller's cancel flag was set.
    #[error("cancelled after {cycles_done} cycles")]
    Cancelled {
        /// Cycles completed before the stop.
        cycles_done: u64,
    },
}

/// The cycle loop of both rigs: `advance(cycle)` from cycle 1 through `total`, each call
/// returning how many cycles its step covered, stopped with [`SimulationError::Cancelled`]
/// once `cancel` is set.
fn each_cycle(
    total: u64,
    cancel: &AtomicBool,
    mut advance: impl FnMut(u64) -> Result<u64, SimulationError>,
) -> Result<(), SimulationError> {
    let mut cycle = 1;
    while cycle <= total {
        if cancel.load(Ordering::Relaxed) {
            return Err(SimulationError::Cancelled {
                cycles_done: cycle - 1,
            });
        }
        cycle += advance(cycle)?;
    }
    Ok(())
}
