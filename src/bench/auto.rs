//! The measurements behind the `auto` choices (`simulation::setup`, `simulation::stepping`)
//! that the contact and wear benchmarks do not already make: how far the friction coupling
//! term moves the Hertz pressures against `|mu delta-nu|`, the paper scene's answer against
//! its domain at fixed cells, and what leaving out the coupling or the plasticity changes. The
//! wear runs use grid 64 (cells of 2.07 um, 300 cycles) to stay quick; the grid and cycle-step
//! thresholds are read from the wear benchmark's own studies.

use serde::Serialize;

use crate::contact::{
    ContactError, ContactProblem, ContactSolver, CoupledSolver, DcFft, Grid, Kernel, SolverOptions,
    solve,
};
use crate::scene::parse_scene_str;
use crate::simulation::{
    COUPLING_SENSITIVITY, DOMAIN_PER_CONTACT_RADIUS, Model, Setup, SimulationError,
    SimulationResult,
};

use super::contact::paper_hertz;
use super::median_time;
use super::wear::{WearRow, row, simulate};

/// Side of the contact benchmark's domain (`contact::contact_rows`), m.
pub(super) use super::contact::DOMAIN_M as HERTZ_DOMAIN_M;

/// The coupling term's effect on one Hertz contact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CouplingRow {
    /// Cells per side over the contact benchmark's 0.256 mm.
    pub n: usize,
    /// Friction coefficient mu.
    pub friction_coefficient: f64,
    /// `|mu delta-nu|`.
    pub strength: f64,
    /// Largest pressure change from adding the term, relative to Hertz's p0.
    pub change: f64,
    /// `change / strength`: what `COUPLING_SENSITIVITY` bounds from below.
    pub ratio: f64,
    /// Whether `auto` models the term at the default tolerance.
    pub auto_on: bool,
    /// Solve without the term, s (median).
    pub normal_s: f64,
    /// Solve with the term, s (median).
    pub coupled_s: f64,
}

/// The preset's auto grid.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AutoGrid {
    /// Cells per side.
    pub cells: usize,
    /// Cell side, um.
    pub cell_um: f64,
    /// The contact radius the grid is sized to, um.
    pub contact_radius_um: f64,
    /// `contact_radius_um / cell_um` (above the constant: sizes round up to fast FFTs).
    pub cells_per_radius: f64,
}

/// Everything the report's `auto` section needs beyond the contact and wear rows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AutoStudies {
    /// Solver tolerance the decisions are made against.
    pub tolerance: f64,
    /// Coupling sensitivity on the Hertz case.
    pub coupling: Vec<CouplingRow>,
    /// Paper scene studies `domain`, `coupling`, `plasticity`, `elastic_load`.
    pub wear: Vec<WearRow>,
    /// The preset's auto grid.
    pub grid: AutoGrid,
    /// Each domain growth of the auto-domain run, as the run reported it.
    pub domain_growth: Vec<String>,
    /// The plasticity decision for each load studied, as the run reported it.
    pub plasticity: Vec<String>,
}

/// Why an auto study failed.
#[derive(Debug, thiserror::Error)]
pub enum AutoError {
    /// A contact solve.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// A wear run.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
}

/// Friction coefficients of the coupling study: around the threshold at tolerance 1e-8
/// (`|mu delta-nu| = 1e-8 / 1.2` is mu = 2.1e-7) up to mu = 1; 0.45 is the paper's.
const FRICTION: [f64; 6] = [1e-7, 1e-6, 1e-4, 1e-2, 0.45, 1.0];

/// Runs every study (about half a minute).
pub fn auto_studies() -> Result<AutoStudies, AutoError> {
    let tolerance = SolverOptions::default().tolerance;
    let coupling = [64, 128, 256]
        .into_iter()
        .flat_map(|n| FRICTION.map(|mu| coupling_row(n, mu)))
        .collect::<Result<_, _>>()?;

    let mut wear = Vec::new();
    let base = simulate(r#"{"numerics": {"grid": 64}}"#)?;

    // Domain at the cells of grid 64: auto (3 radii, grown near the edge) against fixed sides.
    let cell_um = setup(r#"{"numerics": {"grid": 64}}"#)?.grid.dx * 1e6;
    let fixed = |n: usize| {
        simulate(&format!(
            r#"{{"numerics": {{"grid": {n}, "domain_um": {:.6}}}}}"#,
            n as f64 * cell_um
        ))
    };
    let (wide, widest) = (fixed(96)?, fixed(128)?);
    let radii = |n: usize| n as f64 / 64.0 * DOMAIN_PER_CONTACT_RADIUS;
    for (setting, result) in [
        (
            format!("auto: {DOMAIN_PER_CONTACT_RADIUS} radii, grown near the edge"),
            &base,
        ),
        (format!("fixed {:.1} radii (96 cells)", radii(96)), &wide),
        (
            format!("fixed {:.1} radii (128 cells, reference)", radii(128)),
            &widest,
        ),
    ] {
        wear.push(row("domain", setting, result, &widest));
    }
    let domain_growth = reasons(&base, Model::DomainGrowth);

    // Coupling: the paper's mu delta-nu, modelled (auto) or left out.
    let uncoupled = simulate(r#"{"numerics": {"grid": 64, "coupling": "off"}}"#)?;
    wear.push(row("coupling", "auto (on), reference".into(), &base, &base));
    wear.push(row("coupling", "off".into(), &uncoupled, &base));

    // Plasticity at the paper's load (p0 above Y) and at a load where p0 stays below Y.
    let elastic = simulate(r#"{"numerics": {"grid": 64}, "wear": {"plasticity": "off"}}"#)?;
    wear.push(row(
        "plasticity",
        "auto (on) at 5 N, reference".into(),
        &base,
        &base,
    ));
    wear.push(row("plasticity", "off at 5 N".into(), &elastic, &base));
    let light = r#""test": {"load_n": 1.5}, "numerics": {"grid": 64}"#;
    let light_auto = simulate(&format!("{{{light}}}"))?;
    let light_on = simulate(&format!(r#"{{{light}, "wear": {{"plasticity": "on"}}}}"#))?;
    wear.push(row(
        "elastic_load",
        "auto (off) at 1.5 N, reference".into(),
        &light_auto,
        &light_auto,
    ));
    wear.push(row(
        "elastic_load",
        "on at 1.5 N".into(),
        &light_on,
        &light_auto,
    ));
    let plasticity = [&base, &light_auto]
        .into_iter()
        .flat_map(|r| reasons(r, Model::Plasticity))
        .collect();

    Ok(AutoStudies {
        tolerance,
        coupling,
        wear,
        grid: auto_grid()?,
        domain_growth,
        plasticity,
    })
}

fn setup(overrides: &str) -> Result<Setup, SimulationError> {
    let json = format!(r#"{{"preset": "dalmau2018-316l", "overrides": {overrides}}}"#);
    Setup::new(&parse_scene_str(&json)?)
}

/// The preset's grid, and the contact radius it is sized to: a requested cell count with an
/// auto domain spans exactly `DOMAIN_PER_CONTACT_RADIUS` radii, so that grid gives the radius.
fn auto_grid() -> Result<AutoGrid, SimulationError> {
    let sized = setup(r#"{"numerics": {"grid": 64}}"#)?.grid;
    let radius = sized.nx as f64 * sized.dx / DOMAIN_PER_CONTACT_RADIUS;
    let grid = setup("{}")?.grid;
    Ok(AutoGrid {
        cells: grid.nx,
        cell_um: grid.dx * 1e6,
        contact_radius_um: radius * 1e6,
        cells_per_radius: radius / grid.dx,
    })
}

fn reasons(result: &SimulationResult, name: Model) -> Vec<String> {
    result
        .models
        .iter()
        .filter(|m| m.name == name)
        .map(|m| m.reason.clone())
        .collect()
}

/// The paper's Hertz case on `n` cells, solved without and with the coupling term at `mu`.
fn coupling_row(n: usize, mu: f64) -> Result<CouplingRow, ContactError> {
    let (pair, hertz) = paper_hertz();
    let options = SolverOptions::default();
    let grid = Grid::square(n, HERTZ_DOMAIN_M)?;
    let separation = grid.sample(|x, y| hertz.separation_m(x, y));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: hertz.load_n,
        yield_pressure_pa: f64::INFINITY,
    };
    let normal = Kernel::normal(&grid, &pair);
    let mut plain = DcFft::new(&normal);
    let mut coupled = CoupledSolver::new(&normal, &Kernel::coupling(&grid, &pair, mu));
    let without = solve(&mut plain, &problem, &options, None)?;
    let with = coupled.solve(&problem, &options, None)?;
    let reps = if n >= 256 { 3 } else { 5 };
    let normal_s = median_time(reps, || {
        std::hint::black_box(solve(&mut plain, &problem, &options, None).ok());
    });
    let coupled_s = median_time(reps, || {
        std::hint::black_box(coupled.solve(&problem, &options, None).ok());
    });
    let change = with
        .pressure
        .iter()
        .zip(&without.pressure)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / hertz.peak_pressure_pa();
    let strength = (mu * pair.delta_nu).abs();
    Ok(CouplingRow {
        n,
        friction_coefficient: mu,
        strength,
        change,
        ratio: change / strength,
        auto_on: COUPLING_SENSITIVITY * strength >= options.tolerance,
        normal_s,
        coupled_s,
    })
}

/// The coupling rows as a fixed-width table.
pub fn coupling_table(rows: &[CouplingRow]) -> String {
    let mut out = format!(
        "Coupling term on the Hertz case: max |p_coupled - p| / p0 against |mu delta-nu| (auto models it when {COUPLING_SENSITIVITY} |mu delta-nu| >= tolerance)\n\
         \x20    N       mu  |mu dnu|     change   ratio  auto  solve s  coupled s\n"
    );
    for r in rows {
        out += &format!(
            "{:>6} {:>8.0e} {:>9.2e} {:>10.2e} {:>7.3} {:>5} {:>8.4} {:>10.4}\n",
            r.n,
            r.friction_coefficient,
            r.strength,
            r.change,
            r.ratio,
            if r.auto_on { "on" } else { "off" },
            r.normal_s,
            r.coupled_s
        );
    }
    out
}

/// The facts that are not rows, one per line.
pub fn facts(studies: &AutoStudies) -> String {
    let g = &studies.grid;
    let mut out = format!(
        "Auto grid of the paper scene: {} cells of {:.3} um, {:.1} cells per contact radius of {:.1} um\n",
        g.cells, g.cell_um, g.cells_per_radius, g.contact_radius_um
    );
    for reason in &studies.domain_growth {
        out += &format!("Domain growth (grid 64, auto domain): {reason}\n");
    }
    for reason in &studies.plasticity {
        out += &format!("Plasticity: {reason}\n");
    }
    out
}
