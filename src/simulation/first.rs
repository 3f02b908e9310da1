//! The first cycle's contact alone: what `tribosim contact` prints.

use std::time::Instant;

use serde::Serialize;

use crate::contact::{ContactProblem, coarse_start};
use crate::scene::Scene;

use super::{ModelChoice, Setup, SimulationError};

/// The unworn contact at cycle 1, in the units of its names (`docs/result.md`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FirstContact {
    /// Largest pressure, MPa.
    pub max_pressure_mpa: f64,
    /// Area in contact, mm^2.
    pub contact_area_mm2: f64,
    /// Area at the yield pressure, mm^2.
    pub plastic_area_mm2: f64,
    /// Rigid-body approach, um.
    pub approach_um: f64,
    /// Load carried by the solved pressures, N.
    pub load_n: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Relative residual reached (see `contact::solver`).
    pub residual: f64,
    /// Cells per side.
    pub grid: usize,
    /// Domain side, um.
    pub domain_um: f64,
    /// Wall time of setup and solve, s.
    pub wall_s: f64,
    /// Hertz's peak pressure for the same bodies, MPa, for comparison.
    pub hertz_peak_pressure_mpa: f64,
    /// Hertz's contact area, mm^2.
    pub hertz_contact_area_mm2: f64,
    /// The modelling decisions.
    pub models: Vec<ModelChoice>,
}

/// Solves the first cycle of `scene` (unworn surfaces, Y at cycle 1).
pub fn first_contact(scene: &Scene) -> Result<FirstContact, SimulationError> {
    let started = Instant::now();
    let setup = Setup::new(scene)?;
    let grid = setup.grid;
    let separation = setup.ball_separation(&grid);
    let cap = setup.yield_pressure_pa(1.0);
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: setup.scene.load_n(),
        yield_pressure_pa: cap,
    };
    // A failed coarse solve only loses the starting guess: the solve starts cold then.
    let start = coarse_start(&problem, &setup.pair, &setup.options)
        .ok()
        .flatten();
    let solution = setup
        .solver(&grid)
        .solve(&problem, &setup.options, start.as_deref())
        .map_err(|source| SimulationError::Contact { cycle: 1, source })?;
    Ok(FirstContact {
        max_pressure_mpa: solution.max_pressure_pa() / 1e6,
        contact_area_mm2: solution.contact_area_m2(&grid) * 1e6,
        plastic_area_mm2: solution.plastic_area_m2(&grid, cap) * 1e6,
        approach_um: solution.approach_m * 1e6,
        load_n: solution.load_n(&grid),
        iterations: solution.iterations,
        residual: solution.residual,
        grid: grid.nx,
        domain_um: grid.nx as f64 * grid.dx * 1e6,
        wall_s: started.elapsed().as_secs_f64(),
        hertz_peak_pressure_mpa: setup.hertz.peak_pressure_pa() / 1e6,
        hertz_contact_area_mm2: setup.hertz.contact_area_m2() * 1e6,
        models: setup.models,
    })
}
