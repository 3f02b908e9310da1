//! The cycle loop of the paper's Fig. 4. Each solved cycle, in order:
//!
//! 1. the hardness of the cycle gives the pressure cap (eq. 12, Section 4.5);
//! 2. the contact is solved on the current surface (eqs. 2-12, [`crate::contact`]);
//! 3. where the pressure sits at the cap the disc yields: each row under a capped cell is
//!    cut to the level that cell was pressed to, which on a smooth disc deepens the row by
//!    the remaining interpenetration (eq. 13, [`crate::wear::Groove::yield_under`]);
//! 4. one pass of wear: Archard's removes `k / H` times the pressure integrated along the
//!    sliding direction (eqs. 15-16, [`crate::wear::WearLaw`]);
//! 5. the profile update: the groove moves the surface for the next solve (eq. 17,
//!    [`crate::wear::Groove`]);
//! 6. the corrosion: the potential during rubbing (eq. 18) and the volume dissolved
//!    (Faraday), [`super::electrochemistry`];
//! 7. the record; then the cycles the solve stands for ([`super::stepping`]) wear at the
//!    same pressure, and an auto domain grows if the contact nears its edge
//!    ([`super::growth`]).

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use crate::contact::{
    ContactError, ContactProblem, ContactSolution, ContactSolver, Grid, Window, WindowedSolver,
    cold_start,
};
use crate::hardness::pass_strain;
use crate::scene::{CycleStep, DomainSize, Spots, Tolerance};
use crate::wear::Groove;

mod band;
mod stalls;

use super::balance::{balance, overdrawn};
use super::electrochemistry::{Cell, Reading, Surface, fill_corrosion};
use super::growth::{GROW_AT_EDGE_CELLS, GROW_AT_FRACTION, near_edges, widen};
use super::loaded::{disc_share, full_displacement, loaded_max_depth_m, loaded_profile_m};
use super::ocp_trace::ocp_trace;
use super::provenance::Provenance;
use super::stepping::{Stepper, step_stop};
use super::warm::WarmStart;
use super::{
    CycleRecord, Model, ModelChoice, Plan, PressureMap, Profile, RunOptions, Setup,
    SimulationError, SimulationResult, each_cycle,
};
use band::Band;
use stalls::Stalls;

/// Cycles at which the depth profile is kept when solved (paper Figs. 12 and 15 use 10 and
/// 300), besides the scene's record cycles and the last cycle.
const PROFILE_CYCLES: [u64; 16] = [
    1, 2, 5, 10, 20, 50, 60, 100, 200, 300, 500, 1000, 1800, 2000, 3600, 5000,
];

/// Runs `plan`. Calls `on_cycle` after every solved cycle and stops with
/// [`SimulationError::Cancelled`] once `cancel` is set (checked once per solved cycle).
pub fn run(
    plan: &Plan,
    on_cycle: &mut (dyn FnMut(&CycleRecord) + Send),
    cancel: &AtomicBool,
) -> Result<SimulationResult, SimulationError> {
    run_with(plan, &RunOptions::default(), on_cycle, cancel)
}

/// [`run`] with `options`: a measured surface, other runs sharing the cores.
pub fn run_with(
    plan: &Plan,
    options: &RunOptions,
    on_cycle: &mut (dyn FnMut(&CycleRecord) + Send),
    cancel: &AtomicBool,
) -> Result<SimulationResult, SimulationError> {
    run_setup(&Setup::new(plan, options)?, on_cycle, cancel)
}

/// [`run`] of a scene already set up, e.g. with its solver options changed.
pub fn run_setup(
    setup: &Setup,
    on_cycle: &mut (dyn FnMut(&CycleRecord) + Send),
    cancel: &AtomicBool,
) -> Result<SimulationResult, SimulationError> {
    if setup.loop_on_pool() && rayon::current_thread_index().is_none() {
        // `rayon::scope` runs its closure on one of the pool's threads (rayon's docs, "A
        // note on threading"), where this call goes on.
        return rayon::scope(|_| run_setup(setup, on_cycle, cancel));
    }
    if let Some(stroke) = setup.scene().stroke() {
        return super::stroke_run::run_stroke(setup, stroke, on_cycle, cancel);
    }
    let started = Instant::now();
    let mut state = Run::new(setup, |grid: &Grid| setup.solver(grid));
    each_cycle(setup.scene().test.cycles, cancel, |cycle| {
        state.cycle(cycle, on_cycle)
    })?;
    Ok(state.finish(started))
}

/// A run between cycles: the surface, the solver of its grid, and what has been recorded.
struct Run<'a, F> {
    setup: &'a Setup,
    grid: Grid,
    /// The contact solver of `grid`, built with the run's factory (of a grid or a window).
    solver: WindowedSolver<F>,
    /// The unworn ball's height over `grid`.
    ball: Vec<f64>,
    groove: Groove,
    /// The disc's share of the elastic displacement, for the loaded surface.
    share: f64,
    stepper: Stepper,
    /// The cycles that must be solved and their profiles kept, ascending.
    record_cycles: Vec<u64>,
    history: WarmStart,
    cell: Option<Cell<'a>>,
    /// Whether the domain may grow (it is left to the simulation).
    grows: bool,
    models: Vec<ModelChoice>,
    records: Vec<CycleRecord>,
    profiles: Vec<Profile>,
    maps: Vec<PressureMap>,
    solves: usize,
    iterations: usize,
    /// How the solves stalled, and the preconditioner the next starts on.
    stalls: Stalls,
    max_step: u64,
    /// The surface's cumulative plastic strain, for a cap that hardens with it.
    plastic_strain: f64,
}

impl<'a, F: FnMut(&Grid) -> Box<dyn ContactSolver> + Copy> Run<'a, F> {
    fn new(setup: &'a Setup, factory: F) -> Self {
        let scene = setup.scene();
        let grid = setup.grid;
        Self {
            setup,
            grid,
            solver: WindowedSolver::new(grid, factory),
            ball: setup.ball_height(&grid),
            groove: setup.unworn_disc(),
            share: disc_share(setup),
            stepper: Stepper::of(setup.scene()),
            record_cycles: scene.record_cycles(),
            history: WarmStart::new(
                setup.plan.pair().reduced_modulus_pa,
                grid.dx.min(grid.dy),
                setup.surface.is_some(),
            ),
            cell: Cell::of(scene, setup.plan.hertz().contact_radius_m()),
            grows: scene.numerics.domain_um == DomainSize::Auto,
            models: setup.models.clone(),
            records: Vec::new(),
            profiles: Vec::new(),
            maps: Vec::new(),
            solves: 0,
            iterations: 0,
            stalls: Stalls::default(),
            max_step: 1,
            plastic_strain: 0.0,
        }
    }

    /// One solved cycle and the cycles it stands for; returns how many that is.
    fn cycle(
        &mut self,
        cycle: u64,
        on_cycle: &mut dyn FnMut(&CycleRecord),
    ) -> Result<u64, SimulationError> {
        let setup = self.setup;
        let n = cycle as f64;
        // The hardness of this cycle and the cap it gives (eq. 12) after the passes so far.
        let cap = setup.yield_pressure_pa(n, self.plastic_strain);
        let hardness_pa = setup.plan.hardness().hardness_pa(n);
        // The contact on the current surface (eqs. 2-12), on a rough disc worn by the passes
        // of its own step.
        let pass_wear_per_pa = self.pass_wear_per_pa(cycle);
        let (solution, separation) = self.solve_contact(cycle, cap, pass_wear_per_pa)?;
        // Yielding truncates the rows under capped cells (eq. 13); the profile of one pass of
        // wear (eqs. 15-16).
        let worn_before = self.groove.area_m2();
        let yielded = self
            .groove
            .yield_under(&self.grid, &solution, &separation, cap);
        // A cut smaller than the step bound's share of the groove changes it less than a
        // step may; only a larger one (the yield groove of the first cycles) restarts the
        // stepping. Paper scene `{}`: 480 solves with or without this rule (the count moves
        // by a few percent with differences inside the solver's tolerance), errors against
        // solving every cycle volume +1.42e-4 against +1.92e-4, WAC -1.46e-3 against
        // -1.60e-3.
        let cut = self.groove.area_m2() - worn_before;
        let scene = setup.scene();
        let reshaped =
            yielded && cut > scene.numerics.step_bound(scene.numerics_case()) * worn_before;
        let wear = setup.plan.wear();
        let pass = wear.pass_profile(&self.grid, &solution.pressure);
        // A step never passes a record cycle, so that cycle is solved; nor the first cycle
        // of a new wear rate (an Archard regime), whose rate the step was not chosen for.
        let stop = step_stop(
            cycle,
            setup.scene().test.cycles,
            &self.record_cycles,
            wear.rate_change_cycle(),
        );
        // The step controller's rate of change was measured at the old rate: it starts
        // afresh (solving every cycle, then doubling) at the first cycle of a new one.
        if wear.rate_change_cycle() == Some(cycle) {
            self.stepper = Stepper::of(setup.scene());
        }
        let step = self.stepper.next(cycle, stop, reshaped, &pass);
        self.max_step = self.max_step.max(step);
        // The strain is counted only while it can still raise the cap: a scan of the
        // pressures saved on every other solve.
        if setup.plan.yield_cap().still_hardens(self.plastic_strain) {
            self.plastic_strain += step as f64 * self.pass_strain(&solution, cap);
        }
        // The profile update (eq. 17): the pass at this cycle's hardness, after the yielding.
        self.groove.deepen(
            &pass,
            wear.depth_scale(cycle..cycle + 1, setup.plan.hardness()),
        );
        // Corrosion (eq. 18, Faraday), the record, then the cycles the solve stands for.
        let band = Band::of(&self.grid, &solution.pressure, self.solver.loaded_rows());
        let in_contact = band.in_contact();
        let reading = self.corrode(cycle, (&band, &in_contact), (hardness_pa, cap))?;
        let islands = band.islands(&in_contact);
        self.record(
            cycle,
            &solution,
            islands,
            (cap, pass_wear_per_pa),
            reading,
            on_cycle,
        );
        self.wear_skipped(cycle, step, &pass, reading.as_ref());
        // The gap of the solve, for the warm start's extrapolation of cells entering contact.
        let gap = self
            .history
            .needs_gap()
            .then(|| solution.gap_m(&separation));
        self.grow_if_crowded(cycle, solution.pressure, gap);
        Ok(step)
    }

    /// The plastic strain a pass of `solution` gives the surface ([`pass_strain`]), from
    /// the half-width across the track of the rows where it sits at the cap `cap`: Tabor's
    /// `a` is the plastically indented zone's, so a pass where a few cells touch the cap
    /// strains the surface by little.
    fn pass_strain(&self, solution: &ContactSolution, cap: f64) -> f64 {
        let mut rows = solution
            .pressure
            .chunks_exact(self.grid.nx)
            .enumerate()
            .filter(|(_, row)| row.iter().any(|&p| p >= cap))
            .map(|(iy, _)| iy);
        let Some(first) = rows.next() else {
            return 0.0;
        };
        let last = rows.next_back().unwrap_or(first);
        let half_width_m = (last - first + 1) as f64 * self.grid.dy / 2.0;
        pass_strain(half_width_m, self.setup.scene().ball_radius_m())
    }

    /// The wear the solve at `cycle` includes, 1/Pa ([`crate::contact::worn_rows`]): on a
    /// rough disc the passes of the last cycle step, from this cycle on; the next step is at
    /// most twice as long, within what keeps the update stable. A smooth disc's groove has
    /// no wavelengths short enough for the explicit update to fail, and keeps the paper's.
    /// The first solve is the unworn contact, the one `tribosim contact` finds: the update's
    /// stability is a matter of many passes, not of one.
    fn pass_wear_per_pa(&self, cycle: u64) -> f64 {
        if self.setup.surface.is_none() || self.solves == 0 {
            return 0.0;
        }
        let passes = cycle..cycle + self.stepper.last_step();
        let setup = self.setup;
        setup.plan.wear().depth_scale(passes, setup.plan.hardness())
    }

    /// The contact on the current surface, warm-started from the last pressures (the first
    /// from the coarse-to-fine start); with the separation it was solved on.
    fn solve_contact(
        &mut self,
        cycle: u64,
        cap: f64,
        pass_wear_per_pa: f64,
    ) -> Result<(ContactSolution, Vec<f64>), SimulationError> {
        let separation = self.groove.separation(&self.ball, &self.grid);
        let problem = ContactProblem {
            grid: self.grid,
            separation: &separation,
            load_n: self.setup.scene().load_n(),
            yield_pressure_pa: cap,
            pass_wear_per_pa,
        };
        let start = self
            .history
            .guess(cycle, cap)
            .or_else(|| cold_start(&problem, self.setup.plan.pair(), &self.setup.options));
        let options = self.stalls.options(&self.setup.options);
        let solved = self.solver.solve(&problem, &options, start.as_deref());
        if self.grows
            && self.solves == 0
            && matches!(solved, Err(ContactError::ContactAtEdge { .. }))
        {
            // The first contact of a rough disc can reach past the domain sized for Hertz's
            // (0.65 um rms on the paper's ball: 2.1 Hertz radii, past the auto domain's 1.5;
            // `tests/stability_rough.rs`). Grow an auto domain as if the edge ring were
            // loaded (both axes), and solve again; at the grid limit the error stands.
            let before = (self.grid.nx, self.grid.ny);
            let edge_ring = (0..self.grid.len())
                .map(|i| f64::from(u8::from(self.grid.is_edge(i))))
                .collect();
            // The history is forgotten right after: no gap to keep.
            let no_gap = self.history.needs_gap().then(|| vec![0.0; self.grid.len()]);
            self.grow_if_crowded(cycle, edge_ring, no_gap);
            self.history.forget();
            if (self.grid.nx, self.grid.ny) != before {
                return self.solve_contact(cycle, cap, pass_wear_per_pa);
            }
        }
        let solution = solved.map_err(|source| SimulationError::Contact { cycle, source })?;
        self.solves += 1;
        self.iterations += solution.iterations;
        self.stalls.record(&solution);
        Ok((solution, separation))
    }

    /// Eq. 18 and Faraday for this cycle, when the scene has a corrosion section, from the
    /// pressure on the loaded `band` and its cells `in_contact`.
    fn corrode(
        &mut self,
        cycle: u64,
        (band, in_contact): (&Band, &[bool]),
        (hardness_pa, cap): (f64, f64),
    ) -> Result<Option<Reading>, SimulationError> {
        let scene = self.setup.scene();
        let Some(cell) = self.cell.as_mut() else {
            return Ok(None);
        };
        let spots = cell.settings().spots().map(|kind| match kind {
            Spots::Capped => band.spot_rows(&band.capped(cap)),
            Spots::InContact => band.spot_rows(in_contact),
        });
        let surface = Surface {
            spots,
            groove: &self.groove,
            contact: band.geometry(in_contact),
            load_n: scene.load_n(),
            hardness_pa,
            track_length_m: scene.track_length_m(),
        };
        cell.solved_cycle(cycle, &surface, scene.cycle_period_s())
            .map(Some)
            .map_err(|source| SimulationError::Corrosion { cycle, source })
    }

    /// The cycle's record, to the caller and the result; the first pressure map and the
    /// profiles of the chosen cycles. `islands`: the contact's 4-connected groups of cells.
    fn record(
        &mut self,
        cycle: u64,
        solution: &ContactSolution,
        islands: usize,
        (cap, pass_wear_per_pa): (f64, f64),
        reading: Option<Reading>,
        on_cycle: &mut dyn FnMut(&CycleRecord),
    ) {
        let (setup, grid) = (self.setup, &self.grid);
        let n = cycle as f64;
        let track_length = setup.scene().track_length_m();
        let groove_m3 = self.groove.area_m2() * track_length;
        let mut record = CycleRecord {
            cycle,
            time_s: n * setup.scene().cycle_period_s(),
            max_depth_um: self.groove.max_depth_m() * 1e6,
            loaded_max_depth_um: loaded_max_depth_m(
                &self.groove,
                grid,
                solution,
                pass_wear_per_pa,
                self.share,
            ) * 1e6,
            max_pressure_mpa: solution.max_pressure_pa() / 1e6,
            contact_area_mm2: solution.contact_area_m2(grid) * 1e6,
            contact_islands: islands,
            plastic_area_mm2: solution.plastic_area_m2(grid, cap) * 1e6,
            hardness_mpa: setup.plan.hardness().hardness_pa(n) / 1e6,
            yield_pressure_mpa: cap.is_finite().then_some(cap / 1e6),
            approach_um: solution.approach_m * 1e6,
            iterations: solution.iterations,
            ..CycleRecord::default()
        };
        let basis = setup.scene().wear.archard_k_basis;
        fill_corrosion(&mut record, groove_m3, basis, reading);
        on_cycle(&record);
        self.records.push(record);
        if cycle == 1 {
            self.maps
                .push(PressureMap::of(cycle, grid, &solution.pressure));
        }
        if PROFILE_CYCLES.contains(&cycle)
            || self.record_cycles.contains(&cycle)
            || cycle == setup.scene().test.cycles
        {
            let displacement = full_displacement(self.solver.operator(), grid, &solution.pressure);
            let loaded = loaded_profile_m(&self.groove, grid, &displacement, self.share);
            self.profiles
                .push(Profile::of(cycle, grid, &self.groove, &loaded));
        }
    }

    /// The cycles this solve stands for after its own wear at its pressure (`pass`) and
    /// dissolve at its anodic area, each at its own hardness.
    fn wear_skipped(&mut self, cycle: u64, step: u64, pass: &[f64], reading: Option<&Reading>) {
        let setup = self.setup;
        let skipped = setup
            .plan
            .wear()
            .depth_scale(cycle + 1..cycle + step, setup.plan.hardness());
        self.groove.deepen(pass, skipped);
        if let (Some(cell), Some(reading)) = (self.cell.as_mut(), reading) {
            cell.skipped(reading, (step - 1) as f64 * setup.scene().cycle_period_s());
        }
    }

    /// Grows an auto domain whose contact came near its edge, carrying the pressure and the
    /// groove over; keeps the pressure and its `gap` (where the warm start needs it) for the
    /// next warm start.
    fn grow_if_crowded(&mut self, cycle: u64, mut pressure: Vec<f64>, mut gap: Option<Vec<f64>>) {
        let crowded = near_edges(&self.grid, &pressure);
        let wider = (self.grows && (crowded.0 || crowded.1))
            .then(|| widen(&self.grid, crowded))
            .flatten();
        if let Some(wider) = wider {
            let old = Window {
                x0: (wider.nx - self.grid.nx) / 2,
                y0: (wider.ny - self.grid.ny) / 2,
                nx: self.grid.nx,
                ny: self.grid.ny,
            };
            pressure = old.embed(&wider, &pressure);
            gap = gap.map(|gap| old.embed(&wider, &gap));
            self.groove = self.groove.widened(&wider);
            self.grid = wider;
            self.solver.grow(wider, &pressure);
            self.ball = self.setup.ball_height(&wider);
            self.models.push(ModelChoice {
                name: Model::DomainGrowth,
                active: true,
                reason: format!(
                    "at cycle {cycle} the contact came within {:.0}% (or {GROW_AT_EDGE_CELLS} cells) of the edge: grown to {} x {} cells ({:.1} x {:.1} um)",
                    100.0 * (1.0 - GROW_AT_FRACTION),
                    wider.nx,
                    wider.ny,
                    wider.nx as f64 * wider.dx * 1e6,
                    wider.ny as f64 * wider.dy * 1e6
                ),
            });
        }
        self.history.push(cycle, pressure, gap.as_deref());
    }

    /// The result: the last pressure map, the run's own model choices and the totals.
    fn finish(mut self, started: Instant) -> SimulationResult {
        let setup = self.setup;
        let scene = setup.scene();
        // The last solved pressure, on the grid as it ended (embedded if the domain grew).
        if let (Some(record), Some(pressure)) = (self.records.last(), self.history.last()) {
            if record.cycle != 1 {
                self.maps
                    .push(PressureMap::of(record.cycle, &self.grid, pressure));
            }
        }
        let mut warnings = setup.warnings.clone();
        let mut models = self.run_models();
        let mut ocp = Vec::new();
        if let Some(cell) = &self.cell {
            warnings.extend(cell.warnings());
            let mut reason = cell.describe();
            warnings.extend(overdrawn(scene, &self.records));
            let measured = balance(scene, setup.plan.hardness(), cell.model(), &self.records);
            if let Some(measured) = measured {
                warnings.extend(measured.warning);
                reason.push_str("; ");
                reason.push_str(&measured.reason);
            }
            models.push(ModelChoice {
                name: Model::Corrosion,
                active: true,
                reason,
            });
            models.push(ModelChoice {
                name: Model::Faraday,
                active: true,
                reason: cell.settings().dissolving().reason,
            });
            ocp = ocp_trace(scene, cell, &self.records);
        } else {
            models.push(ModelChoice {
                name: Model::Corrosion,
                active: false,
                reason: "no corrosion section in the scene".to_owned(),
            });
        }
        let summary = setup
            .summary(&self.records, started.elapsed().as_secs_f64())
            .with_warnings(&warnings);
        SimulationResult {
            complete: true,
            scene: scene.clone(),
            surface: setup.surface_report(),
            models,
            warnings: warnings.iter().map(ToString::to_string).collect(),
            field_warnings: warnings,
            cycles: self.records,
            profiles: self.profiles,
            pressure_maps: self.maps,
            ocp_trace: ocp,
            stroke: None,
            summary,
            provenance: Some(Provenance::of(scene)),
        }
    }

    /// The setup's model choices and the run's: domain growths, then the cycle step, the
    /// solve window and the wear law (corrosion follows, in [`Run::finish`]).
    fn run_models(&mut self) -> Vec<ModelChoice> {
        let setup = self.setup;
        let numerics = &setup.scene().numerics;
        let mut models = std::mem::take(&mut self.models);
        let case = setup.scene().numerics_case();
        let every_by_auto = numerics.cycle_step == CycleStep::Auto
            && numerics.solve_cycle_step(case) == CycleStep::EveryCycle;
        let mut stepping = if every_by_auto {
            format!(
                "Auto on a rough disc: every cycle solved ({} solves for {} cycles), since there \
                 steps skip the yield cuts of their cycles and cost more accuracy than they save \
                 time (`docs/accuracy.md`, the default by speed against error; a scene that \
                 gives `cycle_step_bound` steps under it)",
                self.solves,
                setup.scene().test.cycles,
            )
        } else {
            format!(
                "{:?}: {} solves for {} cycles, longest step {}; a step keeps the per-pass wear profile within {:.2}% of the solved one",
                numerics.cycle_step,
                self.solves,
                setup.scene().test.cycles,
                self.max_step,
                numerics.step_bound(case) * 100.0
            )
        };
        if setup.surface.is_some() {
            if numerics.tolerance == Tolerance::Auto {
                stepping.push_str(&format!(
                    "; a rough disc's contacts solved to {:.0e} (`numerics.tolerance: auto`; \
                     `docs/accuracy.md`, the default by speed against error)",
                    numerics.solve_tolerance(case)
                ));
            }
            stepping.push_str(
                "; each solve includes the wear of the last step's passes (the implicit update: \
                 on a rough disc the paper's explicit one oscillates at the scale of the cells, \
                 `docs/accuracy.md`)",
            );
        }
        models.push(ModelChoice {
            name: Model::CycleStep,
            active: self.max_step > 1,
            reason: stepping,
        });
        let mut window = self.solver.fractions().describe(self.solves);
        window += &self.stalls.describe(self.solves);
        models.push(ModelChoice {
            name: Model::SolveWindow,
            active: true,
            reason: window,
        });
        let law = setup.plan.wear().choice();
        models.push(ModelChoice {
            name: Model::of_law(setup.plan.wear()),
            active: law.active,
            reason: law.reason,
        });
        models
    }
}

#[cfg(test)]
mod tests;
