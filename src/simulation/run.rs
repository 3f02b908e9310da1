//! The cycle loop (paper Fig. 4): solve the contact on the current surface, deepen the groove
//! by yielding and by Archard wear, estimate the corrosion, record, repeat.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use crate::contact::{
    ContactProblem, ContactSolver, Grid, MARGIN_FRACTION, MIN_MARGIN, Window, WindowedSolver,
    fft_friendly,
};
use crate::scene::{AnodicArea, DomainSize, Scene};
use crate::wear::{Groove, pass_pressure_integral, yield_depth};

use super::stepping::Stepper;
use super::{
    CycleRecord, ModelChoice, PressureMap, Profile, Setup, SimulationError, SimulationResult,
    Summary,
};

/// The domain grows when pressure reaches this fraction of the half-width from the centre...
const GROW_AT_FRACTION: f64 = 0.8;
/// ... or comes within this many cells of the edge, whichever is first: on grids under 20
/// cells 20% is under two cells, and the contact reached the edge ring (failing the solve)
/// before the growth saw it.
const GROW_AT_EDGE_CELLS: f64 = 2.0;

/// Growth factor of the domain side (then rounded up to an FFT-friendly size).
const GROWTH: f64 = 1.25;

/// Cycles at which the depth profile is kept (paper Figs. 12 and 15 use 10 and 300; Table 3
/// times at 60 rpm are 10, 60, 300, 1800 and 3600), plus the last cycle.
const PROFILE_CYCLES: [u64; 16] = [
    1, 2, 5, 10, 20, 50, 60, 100, 200, 300, 500, 1000, 1800, 2000, 3600, 5000,
];

/// Runs `scene`. Calls `on_cycle` after every solved cycle and stops with
/// [`SimulationError::Cancelled`] once `cancel` is set (checked once per solved cycle).
pub fn run(
    scene: &Scene,
    on_cycle: &mut dyn FnMut(&CycleRecord),
    cancel: &AtomicBool,
) -> Result<SimulationResult, SimulationError> {
    let started = Instant::now();
    let setup = Setup::new(scene)?;
    let scene = &setup.scene;
    let corrosion = scene.corrosion.as_ref().map(|c| (c.model(), c));
    let mut models = setup.models.clone();
    let mut grid = setup.grid;
    let factory = |grid: &Grid| setup.solver(grid);
    let mut solver = WindowedSolver::new(grid, factory);
    let mut ball = setup.ball_separation(&grid);
    let mut groove = Groove::new(&grid);
    let mut stepper = Stepper::new(scene.numerics.cycle_step, scene.numerics.cycle_step_bound);
    let mut history = WarmStart::default();
    let (period, track_length) = (scene.cycle_period_s(), scene.track_length_m());
    let total = scene.test.cycles;
    let grows = scene.numerics.domain_um == DomainSize::Auto;

    let mut records = Vec::new();
    let mut profiles = Vec::new();
    let mut maps = Vec::new();
    let (mut wac_m3, mut solves, mut iterations, mut max_step) = (0.0, 0usize, 0usize, 1u64);
    let mut window_fraction_sum = 0.0;
    let mut cycle = 1;
    while cycle <= total {
        if cancel.load(Ordering::Relaxed) {
            return Err(SimulationError::Cancelled {
                cycles_done: cycle - 1,
            });
        }
        let n = cycle as f64;
        let cap = setup.yield_pressure_pa(n);
        let separation = groove.separation(&ball, &grid);
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: scene.load_n(),
            yield_pressure_pa: cap,
        };
        let solution = solver
            .solve(
                &problem,
                &setup.options,
                history.guess(cycle, cap).as_deref(),
            )
            .map_err(|source| SimulationError::Contact { cycle, source })?;
        solves += 1;
        iterations += solution.iterations;

        let plastic = yield_depth(&grid, &solution, &separation, cap);
        let is_plastic = plastic.iter().any(|&d| d > 0.0);
        let pass = pass_pressure_integral(&grid, &solution.pressure);
        let step = stepper.next(cycle, total, is_plastic, &pass);
        max_step = max_step.max(step);

        // This cycle: yielding, then one pass of Archard wear at this cycle's hardness.
        groove.deepen(&plastic, 1.0);
        groove.deepen(&pass, setup.archard_k / setup.hardness.hardness_pa(n));
        let contact_area = solution.contact_area_m2(&grid);
        let anodic = corrosion.as_ref().map(|(_, c)| {
            let area = match c.anodic_area {
                AnodicArea::WearTrack => groove.worn_width_m() * track_length,
                AnodicArea::RealContact => crate::corrosion::real_contact_area_m2(
                    scene.load_n(),
                    setup.hardness.hardness_pa(n),
                ),
                AnodicArea::BemContact => contact_area,
            };
            area * c.anodic_area_factor
        });
        let potential = match (&corrosion, anodic) {
            (Some((model, _)), Some(area)) => {
                wac_m3 += model.wac_volume_m3(area, period);
                Some(
                    model
                        .potential_v(area)
                        .map_err(|source| SimulationError::Corrosion { cycle, source })?,
                )
            }
            _ => None,
        };
        let record = CycleRecord {
            cycle,
            time_s: n * period,
            wear_volume_mm3: groove.area_m2() * track_length * 1e9,
            max_depth_um: groove.max_depth_m() * 1e6,
            max_pressure_mpa: solution.max_pressure_pa() / 1e6,
            contact_area_mm2: contact_area * 1e6,
            plastic_area_mm2: solution.plastic_area_m2(&grid, cap) * 1e6,
            hardness_mpa: setup.hardness.hardness_pa(n) / 1e6,
            approach_um: solution.approach_m * 1e6,
            iterations: solution.iterations,
            potential_v: potential,
            anodic_area_mm2: anodic.map(|a| a * 1e6),
            wac_volume_mm3: potential.map(|_| wac_m3 * 1e9),
        };
        on_cycle(&record);
        records.push(record);
        if cycle == 1 {
            maps.push(pressure_map(cycle, &grid, &solution.pressure));
        }
        if PROFILE_CYCLES.contains(&cycle) || cycle == total {
            profiles.push(profile(cycle, &grid, &groove));
        }

        // The cycles this solve stands for, after the first.
        let skipped = (cycle + 1..cycle + step)
            .map(|j| setup.archard_k / setup.hardness.hardness_pa(j as f64));
        groove.deepen(&pass, skipped.sum());
        if let (Some((model, _)), Some(area)) = (&corrosion, anodic) {
            wac_m3 += model.wac_volume_m3(area, (step - 1) as f64 * period);
        }

        let mut pressure = solution.pressure;
        let crowded = near_edges(&grid, &pressure);
        if grows && (crowded.0 || crowded.1) {
            if let Some(wider) = widen(&grid, crowded) {
                let old = Window {
                    x0: (wider.nx - grid.nx) / 2,
                    y0: (wider.ny - grid.ny) / 2,
                    nx: grid.nx,
                    ny: grid.ny,
                };
                pressure = old.embed(&wider, &pressure);
                groove = groove.widened(old.y0);
                grid = wider;
                window_fraction_sum += solver.window_fraction_sum();
                solver = WindowedSolver::new(grid, factory);
                solver.focus_on(&pressure);
                ball = setup.ball_separation(&grid);
                models.push(ModelChoice {
                    name: "domain_growth".to_owned(),
                    active: true,
                    reason: format!(
                        "at cycle {cycle} the contact came within {:.0}% (or {GROW_AT_EDGE_CELLS} cells) of the edge: grown to {} x {} cells ({:.1} x {:.1} um)",
                        100.0 * (1.0 - GROW_AT_FRACTION),
                        grid.nx,
                        grid.ny,
                        grid.nx as f64 * grid.dx * 1e6,
                        grid.ny as f64 * grid.dy * 1e6
                    ),
                });
            }
        }
        history.push(cycle, pressure);
        cycle += step;
    }

    // The last solved pressure, on the grid as it ended (embedded if the domain grew).
    if let (Some(record), Some(pressure)) = (records.last(), history.last()) {
        if record.cycle != 1 {
            maps.push(pressure_map(record.cycle, &grid, pressure));
        }
    }
    models.push(ModelChoice {
        name: "cycle_step".to_owned(),
        active: max_step > 1,
        reason: format!(
            "{:?}: {solves} solves for {total} cycles, longest step {max_step}; a step keeps the per-pass wear profile within {:.2}% of the solved one",
            scene.numerics.cycle_step,
            scene.numerics.cycle_step_bound * 100.0
        ),
    });
    window_fraction_sum += solver.window_fraction_sum();
    models.push(ModelChoice {
        name: "solve_window".to_owned(),
        active: true,
        reason: format!(
            "each solve on the last contact's bounding box plus {:.0}% (at least {} cells), checked on the whole grid: on average {:.0}% of the grid's cells",
            100.0 * MARGIN_FRACTION,
            MIN_MARGIN,
            100.0 * window_fraction_sum / solves as f64
        ),
    });
    models.push(ModelChoice {
        name: "archard".to_owned(),
        active: setup.archard_k > 0.0,
        reason: format!("k = {:.4e}", setup.archard_k),
    });
    models.push(ModelChoice {
        name: "corrosion".to_owned(),
        active: corrosion.is_some(),
        reason: match &corrosion {
            Some((_, c)) => format!(
                "eq. 18 galvanic coupling, anodic area {:?} x {}",
                c.anodic_area, c.anodic_area_factor
            ),
            None => "no corrosion section in the scene".to_owned(),
        },
    });
    let summary = Summary {
        cycles: total,
        wear_volume_mm3: groove.area_m2() * track_length * 1e9,
        max_depth_um: groove.max_depth_m() * 1e6,
        wac_volume_mm3: corrosion.as_ref().map(|_| wac_m3 * 1e9),
        wall_s: started.elapsed().as_secs_f64(),
        solves,
        iterations,
    };
    Ok(SimulationResult {
        scene: scene.clone(),
        models,
        cycles: records,
        profiles,
        pressure_maps: maps,
        summary,
    })
}

/// The warm start of the next solve. Between solves the surface changes smoothly (Archard
/// wear nearly constant per cycle), so a linear extrapolation of the last two pressures in
/// the cycle number starts much closer than the last pressure alone (clipped to `[0, Y]`);
/// right after a regrid, with no earlier pressure on the new grid, the last one is used as
/// it is.
#[derive(Debug, Default)]
struct WarmStart {
    last: Option<(u64, Vec<f64>)>,
    before: Option<(u64, Vec<f64>)>,
}

impl WarmStart {
    /// Records the pressure of `cycle`; a pressure from before a regrid (another size)
    /// cannot be extrapolated from and is forgotten.
    fn push(&mut self, cycle: u64, pressure: Vec<f64>) {
        let size = pressure.len();
        self.before = self
            .last
            .replace((cycle, pressure))
            .filter(|(_, p)| p.len() == size);
    }

    fn last(&self) -> Option<&[f64]> {
        self.last.as_ref().map(|(_, p)| p.as_slice())
    }

    fn guess(&self, cycle: u64, cap: f64) -> Option<Vec<f64>> {
        let (c1, p1) = self.last.as_ref()?;
        let Some((c0, p0)) = self.before.as_ref() else {
            return Some(p1.clone());
        };
        let ratio = (cycle - c1) as f64 / (c1 - c0) as f64;
        Some(
            p1.iter()
                .zip(p0)
                .map(|(&a, &b)| (a + ratio * (a - b)).clamp(0.0, cap))
                .collect(),
        )
    }
}

/// Whether loaded cells lie outside `GROW_AT_FRACTION` of the half-width (or within
/// `GROW_AT_EDGE_CELLS` of the edge), along x and along y. The axes grow separately: as the
/// groove deepens the contact widens across the track but shortens along it (paper
/// Fig. 10), so only y keeps growing.
fn near_edges(grid: &Grid, pressure: &[f64]) -> (bool, bool) {
    let limit = |n: usize, d: f64| {
        let half = n as f64 * d / 2.0;
        (GROW_AT_FRACTION * half).min(half - GROW_AT_EDGE_CELLS * d)
    };
    let (limit_x, limit_y) = (limit(grid.nx, grid.dx), limit(grid.ny, grid.dy));
    let mut near = (false, false);
    for (i, &p) in pressure.iter().enumerate() {
        if p > 0.0 {
            near.0 |= grid.x(i % grid.nx).abs() > limit_x;
            near.1 |= grid.y(i / grid.nx).abs() > limit_y;
        }
    }
    near
}

/// The grid with the same cells and about `GROWTH` times the side along the crowded axes, or
/// `None` when neither can grow (the size limit).
fn widen(grid: &Grid, (grow_x, grow_y): (bool, bool)) -> Option<Grid> {
    // FFT-friendly sizes are even, so each axis grows by the same cells on both sides.
    let grown = |n: usize, grow: bool| {
        if grow {
            fft_friendly((n as f64 * GROWTH).ceil() as usize).min(Grid::MAX_CELLS_PER_SIDE)
        } else {
            n
        }
    };
    let (nx, ny) = (grown(grid.nx, grow_x), grown(grid.ny, grow_y));
    (nx > grid.nx || ny > grid.ny)
        .then(|| Grid::new(nx, ny, grid.dx, grid.dy).ok())
        .flatten()
}

fn profile(cycle: u64, grid: &Grid, groove: &Groove) -> Profile {
    Profile {
        cycle,
        y_um: (0..grid.ny).map(|iy| grid.y(iy) * 1e6).collect(),
        depth_um: groove.depth_m().iter().map(|d| d * 1e6).collect(),
    }
}

/// The pressure over the contact's bounding box plus two cells, MPa.
fn pressure_map(cycle: u64, grid: &Grid, pressure: &[f64]) -> PressureMap {
    let Some(shown) = Window::loaded(grid, pressure).map(|w| w.padded(2, grid)) else {
        return PressureMap {
            cycle,
            x_um: Vec::new(),
            y_um: Vec::new(),
            pressure_mpa: Vec::new(),
        };
    };
    PressureMap {
        cycle,
        x_um: shown.columns().map(|ix| grid.x(ix) * 1e6).collect(),
        y_um: shown.rows().map(|iy| grid.y(iy) * 1e6).collect(),
        pressure_mpa: shown
            .rows()
            .map(|iy| {
                shown
                    .columns()
                    .map(|ix| pressure[iy * grid.nx + ix] / 1e6)
                    .collect()
            })
            .collect(),
    }
}
