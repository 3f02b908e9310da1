//! The measurements behind the `auto` choices (`simulation::setup`, `simulation::stepping`)
//! that the contact and wear benchmarks do not already make: how far the friction coupling
//! term moves the Hertz pressures against `|mu delta-nu|`, the paper scene's answer against
//! its domain at fixed cells, and what leaving out the coupling or the plasticity changes. The
//! wear runs use the quick grid ([`QUICK_GRID`]) and the preset's cycles to stay quick; the
//! grid and cycle-step thresholds are read from the wear benchmark's own studies.

use serde::Serialize;

use crate::contact::{
    ContactError, ContactProblem, ContactSolver, CoupledSolver, DcFft, Grid, Kernel, SolverOptions,
    solve,
};
use crate::scene::{DEFAULT_TOLERANCE, DomainSize, GridSize, Switch};
use crate::simulation::{
    COUPLING_SENSITIVITY, DOMAIN_PER_CONTACT_RADIUS, Model, SimulationError, SimulationResult,
};

use super::contact::{DOMAIN_M, paper_hertz};
use super::wear::{
    QUICK_GRID, WearRow, WearStudy, first_grid, paper_scene_with, row, simulate_with,
};
use super::{BenchError, median_time};

/// Cells per side of the coupling study on the contact benchmark's domain: the ratio of
/// pressure change to `|mu delta-nu|` grows with the grid, so the coarsest sets the bound.
pub const COUPLING_STUDY_SIZES: [usize; 3] = [64, 128, 256];

/// Cells per side of the fixed domains at the quick grid's cells: 1.5 and 2 times the auto
/// domain, the larger the reference.
pub const FIXED_DOMAIN_CELLS: [usize; 2] = [96, 128];

/// A load whose Hertz peak pressure stays below the lowest yield pressure of the paper
/// scene (818 MPa against 877 MPa), N: where `auto` leaves plasticity out.
pub const ELASTIC_LOAD_N: f64 = 1.5;

/// The coupling term's effect on one Hertz contact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CouplingRow {
    /// Cells per side over the contact benchmark's domain.
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
    /// The loads of the plasticity decisions, N: the paper's and [`ELASTIC_LOAD_N`].
    pub loads_n: [f64; 2],
}

/// Friction coefficients of the coupling study: around the threshold at the scene's default
/// tolerance 1e-6 (`|mu delta-nu| = 1e-6 / 1.2` is mu = 2.1e-5) up to mu = 1; 0.45 is the
/// paper's.
pub const FRICTION: [f64; 6] = [1e-5, 1e-4, 1e-3, 1e-2, 0.45, 1.0];

/// The coupling study's solver options: the scene's default tolerance, the one `auto`
/// decides against in a run.
fn coupling_options() -> SolverOptions {
    SolverOptions {
        tolerance: DEFAULT_TOLERANCE,
        ..SolverOptions::default()
    }
}

/// Runs every study (about half a minute).
pub fn auto_studies() -> Result<AutoStudies, BenchError> {
    let tolerance = coupling_options().tolerance;
    let coupling = COUPLING_STUDY_SIZES
        .into_iter()
        .flat_map(|n| FRICTION.map(|mu| coupling_row(n, mu)))
        .collect::<Result<_, _>>()?;
    let quick = |s: &mut crate::scene::Scene| s.numerics.grid = GridSize::Cells(QUICK_GRID);
    let base = simulate_with(quick)?;
    let mut wear = domain_rows(&base)?;
    let domain_growth = reasons(&base, Model::DomainGrowth);

    // Coupling: the paper's mu delta-nu, modelled (auto) or left out.
    let uncoupled = simulate_with(|s| {
        quick(s);
        s.numerics.coupling = Switch::Off;
    })?;
    let study = WearStudy::Coupling;
    wear.push(row(study, "auto (on), reference".into(), &base, &base));
    wear.push(row(study, "off".into(), &uncoupled, &base));

    let (rows, light_auto) = plasticity_rows(&base)?;
    wear.extend(rows);
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
        loads_n: [base.scene.test.load_n, ELASTIC_LOAD_N],
    })
}

/// The auto domain (`base`) against fixed ones at the quick grid's cells.
fn domain_rows(base: &SimulationResult) -> Result<Vec<WearRow>, SimulationError> {
    let quick = paper_scene_with(|s| s.numerics.grid = GridSize::Cells(QUICK_GRID));
    let cell_um = first_grid(&quick)?.dx * 1e6;
    let fixed = FIXED_DOMAIN_CELLS
        .into_iter()
        .map(|n| {
            simulate_with(|s| {
                s.numerics.grid = GridSize::Cells(n);
                s.numerics.domain_um = DomainSize::Micrometres(n as f64 * cell_um);
            })
            .map(|r| (n, r))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let reference = &fixed[fixed.len() - 1].1;
    let radii = |n: usize| n as f64 / QUICK_GRID as f64 * DOMAIN_PER_CONTACT_RADIUS;
    let study = WearStudy::Domain;
    let auto = format!("auto: {DOMAIN_PER_CONTACT_RADIUS} radii, grown near the edge");
    let mut rows = vec![row(study, auto, base, reference)];
    for (i, (n, result)) in fixed.iter().enumerate() {
        let tag = if i + 1 == fixed.len() {
            ", reference"
        } else {
            ""
        };
        let setting = format!("fixed {:.1} radii ({n} cells{tag})", radii(*n));
        rows.push(row(study, setting, result, reference));
    }
    Ok(rows)
}

/// Plasticity at the paper's load (p0 above Y, `base`) and at [`ELASTIC_LOAD_N`], each
/// against the other choice; also returns the run at the light load with `auto`.
fn plasticity_rows(
    base: &SimulationResult,
) -> Result<(Vec<WearRow>, SimulationResult), SimulationError> {
    let quick = |s: &mut crate::scene::Scene| s.numerics.grid = GridSize::Cells(QUICK_GRID);
    let elastic = simulate_with(|s| {
        quick(s);
        s.wear.plasticity = Switch::Off;
    })?;
    let light = |s: &mut crate::scene::Scene| {
        quick(s);
        s.test.load_n = ELASTIC_LOAD_N;
    };
    let light_auto = simulate_with(light)?;
    let light_on = simulate_with(|s| {
        light(s);
        s.wear.plasticity = Switch::On;
    })?;
    let load_n = base.scene.test.load_n;
    let rows = vec![
        row(
            WearStudy::Plasticity,
            format!("auto (on) at {load_n} N, reference"),
            base,
            base,
        ),
        row(
            WearStudy::Plasticity,
            format!("off at {load_n} N"),
            &elastic,
            base,
        ),
        row(
            WearStudy::ElasticLoad,
            format!("auto (off) at {ELASTIC_LOAD_N} N, reference"),
            &light_auto,
            &light_auto,
        ),
        row(
            WearStudy::ElasticLoad,
            format!("on at {ELASTIC_LOAD_N} N"),
            &light_on,
            &light_auto,
        ),
    ];
    Ok((rows, light_auto))
}

/// The preset's grid, and the contact radius it is sized to: a requested cell count with an
/// auto domain spans exactly `DOMAIN_PER_CONTACT_RADIUS` radii, so that grid gives the radius.
fn auto_grid() -> Result<AutoGrid, SimulationError> {
    let sized = first_grid(&paper_scene_with(|s| {
        s.numerics.grid = GridSize::Cells(QUICK_GRID);
    }))?;
    let radius = sized.nx as f64 * sized.dx / DOMAIN_PER_CONTACT_RADIUS;
    let grid = first_grid(&paper_scene_with(|_| {}))?;
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
    let options = coupling_options();
    let grid = Grid::square(n, DOMAIN_M)?;
    let separation = grid.sample(|x, y| hertz.separation_m(x, y));
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: hertz.load_n,
        yield_pressure_pa: f64::INFINITY,
        pass_wear_per_pa: 0.0,
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
        out += &format!("Domain growth (grid {QUICK_GRID}, auto domain): {reason}\n");
    }
    for reason in &studies.plasticity {
        out += &format!("Plasticity: {reason}\n");
    }
    out
}
