//! The first cycle's contact alone: what `tribosim contact` prints.

use std::time::Instant;

use serde::Serialize;

use crate::contact::{ContactError, ContactProblem, ContactSolution, Grid, cold_start};
use crate::scene::DomainSize;

use super::growth::widen;
use super::{Model, ModelChoice, Plan, RunOptions, Setup, SimulationError};

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

/// Solves the first cycle of `plan` (unworn surfaces, Y at cycle 1). An auto domain grows
/// when the contact reaches its edge, as the run's first cycle does.
pub fn first_contact(plan: &Plan) -> Result<FirstContact, SimulationError> {
    first_contact_with(plan, &RunOptions::default())
}

/// [`first_contact`] with `options`: a measured map for a scene whose `disc.surface` names
/// one, the FFT plans' sharing.
pub fn first_contact_with(
    plan: &Plan,
    options: &RunOptions,
) -> Result<FirstContact, SimulationError> {
    let started = Instant::now();
    let mut setup = Setup::new(plan, options)?;
    let cap = setup.yield_pressure_pa(1.0, 0.0);
    let (grid, solution) = solve_growing(&mut setup, cap)?;
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
        hertz_peak_pressure_mpa: setup.plan.hertz().peak_pressure_pa() / 1e6,
        hertz_contact_area_mm2: setup.plan.hertz().contact_area_m2() * 1e6,
        models: setup.models,
    })
}

/// The first contact on the setup's grid, or, on an auto domain whose edge it reaches (a
/// rough disc's can, `tests/stability_rough.rs`), on the grid grown along both axes until
/// it fits or reaches the size limit; each growth is recorded in the setup's models.
fn solve_growing(setup: &mut Setup, cap: f64) -> Result<(Grid, ContactSolution), SimulationError> {
    let grows = setup.scene().numerics.domain_um == DomainSize::Auto;
    let mut grid = setup.grid;
    loop {
        let separation = setup.ball_separation(&grid);
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: setup.scene().load_n(),
            yield_pressure_pa: cap,
            pass_wear_per_pa: 0.0,
        };
        let start = cold_start(&problem, setup.plan.pair(), &setup.options);
        let solved = setup
            .solver(&grid)
            .solve(&problem, &setup.options, start.as_deref());
        let wider = match &solved {
            Err(ContactError::ContactAtEdge { .. }) if grows => widen(&grid, (true, true)),
            _ => None,
        };
        let Some(wider) = wider else {
            let solution =
                solved.map_err(|source| SimulationError::Contact { cycle: 1, source })?;
            return Ok((grid, solution));
        };
        setup.models.push(ModelChoice {
            name: Model::DomainGrowth,
            active: true,
            reason: format!(
                "the first contact reached the edge of {} x {} cells: grown to {} x {} cells \
                 ({:.1} um)",
                grid.nx,
                grid.ny,
                wider.nx,
                wider.ny,
                wider.nx as f64 * wider.dx * 1e6
            ),
        });
        grid = wider;
    }
}
