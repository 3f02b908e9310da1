//! A reciprocating run (`test.reciprocating`): the cycles of [`StrokeEngine`] under the
//! scene's step controller, the electrochemistry that follows the stroke
//! ([`crate::corrosion::stroke`]), and the result, the disc's records with the wear map,
//! the axial profile and the traces over a cycle ([`StrokeReport`]).
//!
//! Cycle stepping works as on the disc ([`super::stepping`]): a solved cycle's pressure
//! integral (both sweeps) stands for the cycles after it while it changes slowly, each
//! skipped cycle worn at its own hardness; a cycle whose yielding reshapes the track is
//! never stepped over.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use crate::contact::{ContactSolution, Grid};
use crate::corrosion::stroke::{Footprint, StrokeExposure};
use crate::corrosion::{ContactGeometry, real_contact_area_m2};
use crate::scene::{AnodicArea, CycleStep, FieldWarning, Scene};
use crate::surface::count_islands;
use crate::wear::{Stroke, WearMap};

use super::electrochemistry::{Cell, Reading, fill_corrosion};
use super::provenance::Provenance;
use super::reciprocating::{
    RETURN_SOLVED_ABOVE_CUT_SHARE, REUSE_FRACTION_OF_APPROACH, SOLVE_EVERY_POSITIONS, StrokeCycle,
    StrokeEngine, StrokeNumerics,
};
use super::stepping::{Stepper, step_stop};
use super::stroke_report::{AxialProfile, CycleTrace, StrokeReport, TRACE_SAMPLES, WearMapReport};
use super::{
    CycleRecord, Model, ModelChoice, PressureMap, Profile, Setup, SimulationError,
    SimulationResult, each_cycle,
};

/// The rig's numerics for `scene`: every sweep solved where it asks for every cycle.
fn stroke_numerics(scene: &Scene) -> StrokeNumerics {
    StrokeNumerics {
        solve_return: scene.numerics.solve_cycle_step(scene.numerics_case())
            == CycleStep::EveryCycle,
        ..StrokeNumerics::default()
    }
}

/// Cycles whose profile across the middle is kept, besides the record cycles and the last.
const PROFILE_CYCLES: [u64; 10] = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000];

/// Runs the reciprocating scene of `setup` along `stroke`; `on_cycle` after each solved
/// cycle, stopping once `cancel` is set.
pub(super) fn run_stroke(
    setup: &Setup,
    stroke: Stroke,
    on_cycle: &mut dyn FnMut(&CycleRecord),
    cancel: &AtomicBool,
) -> Result<SimulationResult, SimulationError> {
    let started = Instant::now();
    let mut run = StrokeRun::new(setup, stroke);
    each_cycle(setup.scene().test.cycles, cancel, |cycle| {
        run.cycle(cycle, on_cycle)
    })?;
    Ok(run.finish(started))
}

/// A reciprocating run between cycles.
struct StrokeRun<'a> {
    setup: &'a Setup,
    stroke: Stroke,
    engine: StrokeEngine,
    stepper: Stepper,
    cell: Option<Cell<'a>>,
    record_cycles: Vec<u64>,
    records: Vec<CycleRecord>,
    profiles: Vec<Profile>,
    maps: Vec<PressureMap>,
    traces: Vec<CycleTrace>,
    models: Vec<ModelChoice>,
    solves: usize,
    /// Solved cycles whose return sweep was solved too.
    returns_solved: usize,
    max_step: u64,
    /// The last solved cycle's contact at the middle and the grid it was solved on, which
    /// the grid may have grown beyond since.
    last_middle: Option<(Grid, ContactSolution)>,
    /// The traced cycles whose potential reached E_corr within the cycle, with how many
    /// of the samples did: eq. 18 is capped there.
    capped_in_trace: Vec<(u64, usize)>,
}

impl<'a> StrokeRun<'a> {
    fn new(setup: &'a Setup, stroke: Stroke) -> Self {
        let scene = setup.scene();
        Self {
            setup,
            stroke,
            engine: StrokeEngine::new(setup, stroke, stroke_numerics(scene)),
            stepper: Stepper::of(scene),
            cell: Cell::of(scene, setup.plan.hertz().contact_radius_m()),
            record_cycles: scene.record_cycles(),
            records: Vec::new(),
            profiles: Vec::new(),
            maps: Vec::new(),
            traces: Vec::new(),
            models: Vec::new(),
            solves: 0,
            returns_solved: 0,
            max_step: 1,
            last_middle: None,
            capped_in_trace: Vec::new(),
        }
    }

    /// Solves `cycle` and wears the cycles it stands for; returns how many that is.
    fn cycle(
        &mut self,
        cycle: u64,
        on_cycle: &mut dyn FnMut(&CycleRecord),
    ) -> Result<u64, SimulationError> {
        let scene = self.setup.scene();
        let solved = self.engine.cycle(cycle)?;
        self.solves += solved.solves;
        self.returns_solved += usize::from(solved.return_solved);
        // As on the disc: a cut larger than the step bound's share of the track reshapes
        // it, and the step starts afresh.
        let reshaped = solved.cut_over(scene.numerics.step_bound(scene.numerics_case()));
        let rate_change = self.setup.plan.wear().rate_change_cycle();
        let stop = step_stop(cycle, scene.test.cycles, &self.record_cycles, rate_change);
        // As on the disc, the controller starts afresh at the first cycle of a new rate.
        if rate_change == Some(cycle) {
            self.stepper = Stepper::of(scene);
        }
        let step = self
            .stepper
            .next(cycle, stop, reshaped, &solved.pressed.depth);
        self.max_step = self.max_step.max(step);
        // The record is the state at the end of the solved cycle; the cycles it stands for
        // wear and dissolve after it.
        let reading = self.corrode(cycle, &solved)?;
        self.record(cycle, &solved, reading, on_cycle);
        self.engine.repeat(&solved.pressed, cycle + 1..cycle + step);
        if let (Some(cell), Some(reading)) = (self.cell.as_mut(), reading.as_ref()) {
            cell.skipped(reading, (step - 1) as f64 * scene.cycle_period_s());
        }
        self.last_middle = Some((*self.engine.grid(), solved.middle));
        self.grow_if_crowded(cycle);
        Ok(step)
    }

    /// The footprint of the contact at the middle as it strips the film, by the scene's
    /// anodic area model: the cells in contact, or at the cap for `asperity_spots`; only
    /// the real contact F / H of it for the wake.
    fn footprint(&self, middle: &ContactSolution, cap_pa: f64, hardness_pa: f64) -> Footprint {
        let grid = self.engine.grid();
        let settings = self.cell.as_ref().map(Cell::settings);
        let capped_only = settings.is_some_and(|s| s.anodic_area == AnodicArea::AsperitySpots);
        let stripped = |p: f64| if capped_only { p >= cap_pa } else { p > 0.0 };
        let mut chords_m = Vec::new();
        for row in middle.pressure.chunks_exact(grid.nx) {
            let first = row.iter().position(|&p| stripped(p));
            let last = row.iter().rposition(|&p| stripped(p));
            if let (Some(first), Some(last)) = (first, last) {
                chords_m.push((grid.x(first) - grid.dx / 2.0, grid.x(last) + grid.dx / 2.0));
            }
        }
        let area: f64 = chords_m.iter().map(|c| (c.1 - c.0) * grid.dy).sum();
        let wake = settings.is_some_and(|s| s.anodic_area == AnodicArea::DepassivatedWake);
        let real = real_contact_area_m2(self.setup.scene().load_n(), hardness_pa);
        Footprint {
            chords_m,
            row_width_m: grid.dy,
            stripped_share: if wake && area > 0.0 {
                (real / area).min(1.0)
            } else {
                1.0
            },
        }
    }

    /// The electrochemistry of `cycle`: the mean area of the stroke's exposure over the
    /// cycle, and the trace over it when it is one to keep.
    fn corrode(
        &mut self,
        cycle: u64,
        solved: &StrokeCycle,
    ) -> Result<Option<Reading>, SimulationError> {
        if self.cell.is_none() {
            return Ok(None);
        }
        let scene = self.setup.scene();
        let hardness_pa = self.setup.plan.hardness().hardness_pa(cycle as f64);
        let footprint = self.footprint(&solved.middle, solved.cap_pa, hardness_pa);
        let exposure = StrokeExposure::new(&self.stroke, &footprint, self.engine.map().dx);
        let grid = *self.engine.grid();
        let contact: Vec<bool> = solved.middle.pressure.iter().map(|&p| p > 0.0).collect();
        let chord = ContactGeometry::of(&contact, grid.nx, grid.dx, grid.dy).mean_chord_m();
        let real = real_contact_area_m2(scene.load_n(), hardness_pa);
        let period = scene.cycle_period_s();
        let cell = self.cell.as_mut().expect("checked above");
        let kinetics = cell.settings().repassivation();
        let reading = cell
            .stroke_cycle(
                cycle,
                exposure.mean_area_m2(&kinetics),
                (real, chord),
                period,
            )
            .map_err(|source| SimulationError::Corrosion { cycle, source })?;
        if cycle == 1 || self.record_cycles.contains(&cycle) || cycle == scene.test.cycles {
            let trace = self.trace(cycle, &exposure)?;
            let cell = self.cell.as_ref().expect("checked above");
            if cell.settings().held_v().is_none() {
                let e_corr = cell.model().corrosion_potential_v;
                let capped = trace.potential_v.iter().filter(|&&e| e >= e_corr).count();
                if capped > 0 {
                    self.capped_in_trace.push((cycle, capped));
                }
            }
            self.traces.push(trace);
        }
        Ok(Some(reading))
    }

    /// The potential and current over `cycle` under `exposure`, [`TRACE_SAMPLES`] even
    /// samples at the middle of their intervals.
    fn trace(&self, cycle: u64, exposure: &StrokeExposure) -> Result<CycleTrace, SimulationError> {
        let cell = self.cell.as_ref().expect("a cell traces");
        let kinetics = cell.settings().repassivation();
        let factor = cell.settings().anodic_area_factor;
        let period = self.stroke.period_s();
        let start = (cycle - 1) as f64 * period;
        let mut trace = CycleTrace {
            cycle,
            time_s: Vec::with_capacity(TRACE_SAMPLES),
            position_um: Vec::with_capacity(TRACE_SAMPLES),
            anodic_area_mm2: Vec::with_capacity(TRACE_SAMPLES),
            potential_v: Vec::with_capacity(TRACE_SAMPLES),
            anodic_current_ma: Vec::with_capacity(TRACE_SAMPLES),
        };
        for i in 0..TRACE_SAMPLES {
            let t = (i as f64 + 0.5) * period / TRACE_SAMPLES as f64;
            let area = exposure.area_at_m2(t, &kinetics) * factor;
            let (potential, current) = cell
                .couple(area)
                .map_err(|source| SimulationError::Corrosion { cycle, source })?;
            trace.time_s.push(start + t);
            trace.position_um.push(self.stroke.position_m(t) * 1e6);
            trace.anodic_area_mm2.push(area * 1e6);
            trace.potential_v.push(potential);
            trace.anodic_current_ma.push(current * 1e3);
        }
        Ok(trace)
    }

    fn record(
        &mut self,
        cycle: u64,
        solved: &StrokeCycle,
        reading: Option<Reading>,
        on_cycle: &mut dyn FnMut(&CycleRecord),
    ) {
        let (setup, grid) = (self.setup, *self.engine.grid());
        let scene = setup.scene();
        let n = cycle as f64;
        let middle = &solved.middle;
        let map = self.engine.map();
        let contact: Vec<bool> = middle.pressure.iter().map(|&p| p > 0.0).collect();
        let cap = solved.cap_pa;
        let mut record = CycleRecord {
            cycle,
            time_s: n * scene.cycle_period_s(),
            max_depth_um: map.depth.iter().copied().fold(0.0, f64::max) * 1e6,
            loaded_max_depth_um: 0.0,
            max_pressure_mpa: middle.max_pressure_pa() / 1e6,
            contact_area_mm2: middle.contact_area_m2(&grid) * 1e6,
            contact_islands: count_islands(&contact, grid.nx),
            plastic_area_mm2: middle.plastic_area_m2(&grid, cap) * 1e6,
            hardness_mpa: setup.plan.hardness().hardness_pa(n) / 1e6,
            yield_pressure_mpa: cap.is_finite().then_some(cap / 1e6),
            approach_um: middle.approach_m * 1e6,
            iterations: solved.iterations,
            ..CycleRecord::default()
        };
        let basis = scene.wear.archard_k_basis;
        fill_corrosion(&mut record, self.engine.volume_m3(), basis, reading);
        on_cycle(&record);
        self.records.push(record);
        if cycle == 1 {
            self.maps
                .push(PressureMap::of(cycle, &grid, &middle.pressure));
        }
        if PROFILE_CYCLES.contains(&cycle)
            || self.record_cycles.contains(&cycle)
            || cycle == scene.test.cycles
        {
            self.profiles.push(Profile {
                cycle,
                y_um: (0..grid.ny).map(|iy| grid.y(iy) * 1e6).collect(),
                depth_um: map.middle_column().iter().map(|d| d * 1e6).collect(),
                loaded_depth_um: Vec::new(),
            });
        }
    }

    /// Widens an auto domain whose contact came near its edge; the step controller's last
    /// pressure integral is carried onto the wider map, on which it holds the same values.
    fn grow_if_crowded(&mut self, cycle: u64) {
        let scene = self.setup.scene();
        if scene.numerics.domain_um != crate::scene::DomainSize::Auto {
            return;
        }
        let (nx, ny, dx) = {
            let map = self.engine.map();
            (map.nx, map.ny, map.dx)
        };
        if let Some(wider) = self.engine.grow_if_crowded() {
            let length = self.stroke.length_m;
            self.stepper.carry(|profile| {
                let before = WearMap {
                    nx,
                    ny,
                    dx,
                    depth: profile.to_vec(),
                };
                before.embedded_in(&wider, length).depth
            });
            self.models.push(ModelChoice {
                name: Model::DomainGrowth,
                active: true,
                reason: format!(
                    "at cycle {cycle} the contact came near the grid's edge: grown to {} x {} cells ({:.1} x {:.1} um)",
                    wider.nx,
                    wider.ny,
                    wider.nx as f64 * wider.dx * 1e6,
                    wider.ny as f64 * wider.dy * 1e6
                ),
            });
        }
    }

    fn finish(mut self, started: Instant) -> SimulationResult {
        let setup = self.setup;
        let scene = setup.scene();
        if let (Some(record), Some((solved_on, middle))) = (self.records.last(), &self.last_middle)
        {
            if record.cycle != 1 {
                self.maps
                    .push(PressureMap::of(record.cycle, solved_on, &middle.pressure));
            }
        }
        let grid: Grid = *self.engine.grid();
        let mut warnings = setup.warnings.clone();
        let mut models = setup_models(setup);
        models.extend(std::mem::take(&mut self.models));
        models.extend(self.stroke_models());
        models.extend(self.corrosion_models());
        if let Some(cell) = &self.cell {
            warnings.extend(cell.warnings());
        }
        warnings.extend(self.capped_warning());
        let mut summary = setup
            .summary(&self.records, started.elapsed().as_secs_f64())
            .with_warnings(&warnings);
        summary.solves = self.solves;
        let y: Vec<f64> = (0..grid.ny).map(|iy| grid.y(iy)).collect();
        let map = self.engine.map();
        SimulationResult {
            complete: true,
            scene: scene.clone(),
            surface: None,
            models,
            warnings: warnings.iter().map(ToString::to_string).collect(),
            field_warnings: warnings,
            cycles: self.records,
            profiles: self.profiles,
            pressure_maps: self.maps,
            ocp_trace: Vec::new(),
            stroke: Some(StrokeReport {
                map: WearMapReport::of(map, &y),
                axial_profile: AxialProfile::of(map),
                traces: self.traces,
            }),
            summary,
            provenance: Some(Provenance::of(scene)),
        }
    }

    /// Where the potential reached E_corr within a traced cycle: near the turning points the
    /// bare area is least, and eq. 18 below the Tafel line's own current is capped there,
    /// as the records' potential is at a too small area.
    fn capped_warning(&self) -> Option<FieldWarning> {
        let &(first, samples) = self.capped_in_trace.first()?;
        Some(FieldWarning::new(
            "corrosion.anodic_area",
            format!(
                "within {} of the {} traced cycles, the first cycle {first} ({samples} of its \
                 {TRACE_SAMPLES} samples), the bare area fell so low (it is least near the \
                 turning points) that eq. 18 put the potential above E_corr, and it was \
                 capped there: the trace's flat tops are the cap, not a measurement",
                self.capped_in_trace.len(),
                self.traces.len()
            ),
        ))
    }

    /// The corrosion's and Faraday's entries in the result's models.
    fn corrosion_models(&self) -> Vec<ModelChoice> {
        let Some(cell) = &self.cell else {
            return vec![ModelChoice {
                name: Model::Corrosion,
                active: false,
                reason: "no corrosion section in the scene".to_owned(),
            }];
        };
        vec![
            ModelChoice {
                name: Model::Corrosion,
                active: true,
                reason: format!(
                    "{}; on the reciprocating rig the area follows the stroke: each point \
                     of the track is bare while the contact covers it and repassivates \
                     ({}) until the next pass, at a time that varies along the stroke; the \
                     record's area is the cycle's mean, its potential the cell's at that \
                     mean, and `stroke.traces` hold the cycle sampled {TRACE_SAMPLES} times \
                     (the periodic state of that cycle's contact)",
                    cell.describe(),
                    cell.settings().repassivation().describe()
                ),
            },
            ModelChoice {
                name: Model::Faraday,
                active: true,
                reason: cell.settings().dissolving().reason,
            },
        ]
    }

    /// The reciprocating rig, the cycle step and the wear law, in the result's models.
    fn stroke_models(&self) -> Vec<ModelChoice> {
        let scene = self.setup.scene();
        let numerics = &scene.numerics;
        let positions = (self.stroke.length_m / self.engine.grid().dx).ceil() as usize + 1;
        let law = self.setup.plan.wear().choice();
        vec![
            ModelChoice {
                name: Model::Reciprocating,
                active: true,
                reason: format!(
                    "a {:.3} mm stroke at {} Hz ({:?} speed): the ball's centre at {positions} \
                     positions a cell apart each sweep, every {SOLVE_EVERY_POSITIONS}th solved \
                     where the flat under the contact changed by more than \
                     {REUSE_FRACTION_OF_APPROACH:e} of Hertz's approach since the last solve \
                     and the pressures blended between ({} solves in all); the return sweep \
                     solved after a forward sweep that cut over {RETURN_SOLVED_ABOVE_CUT_SHARE:e} \
                     of the worn volume ({} of {} solved cycles), otherwise pressing the forward's \
                     pressure again; the friction coupling left out (its sign turns with the \
                     direction); the cap at the hardness law's, without plastic strain",
                    self.stroke.length_m * 1e3,
                    self.stroke.frequency_hz,
                    self.stroke.law,
                    self.solves,
                    self.returns_solved,
                    self.records.len(),
                ),
            },
            ModelChoice {
                name: Model::SolveWindow,
                active: true,
                reason: self.engine.window_fractions().describe(self.solves),
            },
            ModelChoice {
                name: Model::CycleStep,
                active: self.max_step > 1,
                reason: format!(
                    "{:?}: {} solved cycles for {} cycles, longest step {}; a step keeps the \
                     cycle's pressure integral within {:.2}% of the solved one",
                    numerics.cycle_step,
                    self.records.len(),
                    scene.test.cycles,
                    self.max_step,
                    numerics.step_bound(scene.numerics_case()) * 100.0
                ),
            },
            ModelChoice {
                name: Model::of_law(self.setup.plan.wear()),
                active: law.active,
                reason: law.reason,
            },
        ]
    }
}

/// The setup's model choices, with the coupling left out as the engine leaves it.
fn setup_models(setup: &Setup) -> Vec<ModelChoice> {
    let mut models = setup.models.clone();
    for model in models.iter_mut().filter(|m| m.name == Model::Coupling) {
        model.active = false;
        model.reason = "left out on the reciprocating rig: the tangential traction's sign \
                        turns with the sliding direction"
            .to_owned();
    }
    models
}
