//! Physics helpers shared by the contact, wear and stability tests: the paper's pair and
//! Hertz case, the tolerances of the independent solution check, relative errors, and
//! scenes run through the library.

// Each test crate compiles this module on its own and uses a part of it.
#![allow(dead_code)]

use std::sync::atomic::AtomicBool;

use tribosim::contact::{ElasticPair, Hertz, Material, SolverOptions};
use tribosim::scene::Scene;
use tribosim::simulation::{Plan, SimulationError, SimulationResult, parse_scene_str, run};

/// The paper's ball radius, m.
pub const RADIUS_M: f64 = 3e-3;
/// The paper's load, N.
pub const LOAD_N: f64 = 5.0;
/// The paper's domain side (0.256 mm), m.
pub const DOMAIN_M: f64 = 0.256e-3;

/// What recomputing the displacement by another operator (the direct sum, or the FFT of
/// another grouping) may add to the solver's own residual: above the 3.7e-15 the FFT and the
/// direct sum disagree by on grids up to 32 x 32 (`contact::fft` unit tests).
pub const OTHER_OPERATOR: f64 = 1e-12;

/// The carried load must equal F to this, relative: the solver's own load tolerance (1e-11)
/// plus the worst round-off of summing 1024^2 pressures in another order (1.2e-10).
pub const LOAD_CHECK: f64 = 1e-9;

/// The independent check's tolerance for a solve at `options`: the solver promises every
/// cell within its tolerance on its own displacement.
pub fn check_tolerance(options: &SolverOptions) -> f64 {
    options.tolerance + OTHER_OPERATOR
}

/// Alumina (E 300 GPa, nu 0.21) on AISI 316L (205 GPa, 0.28), the paper's Table 2.
pub fn paper_pair() -> ElasticPair {
    ElasticPair::new(
        Material::new(300e9, 0.21).expect("valid"),
        Material::new(205e9, 0.28).expect("valid"),
    )
}

/// Hertz's contact of the paper's 3 mm ball on `pair` at `load_n`.
pub fn paper_hertz(pair: &ElasticPair, load_n: f64) -> Hertz {
    Hertz {
        radius_m: RADIUS_M,
        load_n,
        reduced_modulus_pa: pair.reduced_modulus_pa,
    }
}

/// `|got / want - 1|`.
pub fn relative_error(got: f64, want: f64) -> f64 {
    (got / want - 1.0).abs()
}

/// A scene the simulation accepts, from JSON.
pub fn scene(json: &str) -> Scene {
    parse_scene_str(json).expect("valid scene").into_scene()
}

/// `scene`, checked (a changed scene may be refused).
pub fn plan(scene: &Scene) -> Result<Plan, SimulationError> {
    Ok(Plan::new(scene.clone())?)
}

/// `scene` checked and run to the end, with no callback and no cancel.
pub fn simulate(scene: &Scene) -> Result<SimulationResult, SimulationError> {
    run(&plan(scene)?, &mut |_| {}, &AtomicBool::new(false))
}
