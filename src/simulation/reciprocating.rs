//! Reciprocating sliding on a smooth flat: the ball solved at positions along its stroke on
//! the flat as its wear has left it, the groove yielding pushes in (eq. 13) and Archard's
//! wear of the passes (eqs. 15-16) kept on a map along and across the stroke
//! ([`WearMap`]).
//!
//! Each cycle the ball's centre visits positions a cell apart from one end of the stroke to
//! the other. The contact is solved at every few of them ([`SOLVE_EVERY_POSITIONS`]), and
//! the positions between press the two solves' pressures blended. A position whose flat
//! under the contact is the last solved position's, shifted by the ball's move, keeps its
//! pressure without a solve: in the middle of a long stroke the track is uniform along it,
//! and the contact is solved again only where its depth changes along the stroke, near the
//! ends. Both sweeps press alike (the friction coupling, whose sign turns with the sliding
//! direction, is left out); a sweep wears the flat before the next is solved, and a return
//! after a forward sweep that cut little presses the forward's pressure again
//! ([`RETURN_SOLVED_ABOVE_CUT_SHARE`]).

use std::ops::Range;

use crate::contact::{
    ContactProblem, ContactSolution, ContactSolver, Grid, WindowFractions, WindowedSolver,
};
use crate::wear::{Stroke, WearMap};

use super::growth::{embedded, near_edges, widen};
use super::sweep_wear::SweepWear;
use super::{Setup, SimulationError};

/// How far the flat under the loaded cells may differ from the last solve's, as a fraction
/// of Hertz's elastic approach, for a position to keep the last solve's pressure, which
/// moves by about this fraction of itself. Measured by `tests/reciprocating.rs` (10 cycles
/// of a 2 mm stroke, the middle against the disc's groove, error of the deepest point;
/// solves in the 10th cycle, of 1070 positions) at 1e-4 / 1e-5 / 1e-6: elastic 2.9e-5 /
/// 2.4e-6 / 2.6e-7 with 106 / 148 / 178 solves; yielding 9.3e-5 / 6.3e-6 / 7.2e-7 with 228
/// / 286 / 332. 1e-5 errs far below the grid (2-5%) for a quarter more solves than 1e-4.
pub const REUSE_FRACTION_OF_APPROACH: f64 = 1e-5;

/// Positions of a sweep from one solve to the next ([`StrokeNumerics::solve_every`]), the
/// pressures blended between. Measured by `tests/reciprocating.rs` against a solve at each
/// position (20 cycles of a 2 mm stroke, the largest cell's error over the deepest point,
/// and the time), every 2 / 4 / 8 / 16: elastic 8.8e-4 / 2.7e-3 / 5.9e-3 / 1.0e-2 in
/// 0.62 / 0.40 / 0.26 / 0.22 of the time; yielding (the paper's bulk hardness) 4.8e-4 /
/// 9.5e-4 / 2.3e-3 / 7.1e-3 in 0.67 / 0.58 / 0.53 / 0.46. 4 is the largest whose error
/// stays below the auto grid's own (5.2e-3 against a grid twice as fine).
pub const SOLVE_EVERY_POSITIONS: usize = 4;

/// A cycle's return sweep is solved only when its forward sweep cut (the groove yielding
/// pushed in) more than this share of the volume worn before the cycle; otherwise it
/// presses the forward's pressure again: both press alike on the same flat, and the
/// return's is the forward's less one sweep's wear and cut (a cycle step's approximation,
/// over half a cycle). A sweep that cuts much reshapes the flat under the
/// return's contact, whose own solves then decide its groove: pressing the forward again
/// at every cut lost the returns' cuts, -4.5e-3 of the volume. Over 1000 strokes against
/// solving every position of both sweeps (volume / deepest point / WAC / axial profile;
/// solves; `docs/rig-accuracy.md`): both sweeps +1.6e-5 / +3.3e-6 / +1.1e-4 / 1.2e-3,
/// 26,067; 1e-3 +1.4e-5 / +1.6e-6 / +7.0e-5 / 1.8e-3, 13,478; 1e-2 -1.6e-4 / -1.2e-4.
pub const RETURN_SOLVED_ABOVE_CUT_SHARE: f64 = 1e-3;

/// What a run of reciprocating cycles left.
#[derive(Debug, Clone, PartialEq)]
pub struct StrokeWear {
    /// The flat's depth below its original surface, m, along and across the stroke.
    pub map: WearMap,
    /// The worn volume after each cycle, m^3.
    pub volume_m3: Vec<f64>,
    /// Contact solves per cycle (the other positions kept the last solve's pressure).
    pub solves: Vec<usize>,
}

/// One solved cycle of [`StrokeEngine::cycle`]: what it cost, the wear it left and the
/// contact at the stroke's middle.
#[derive(Debug, Clone)]
pub struct StrokeCycle {
    /// Contact solves in the two sweeps.
    pub solves: usize,
    /// Whether the return sweep was solved, rather than pressing the forward's pressure.
    pub return_solved: bool,
    /// Solver iterations of those solves.
    pub iterations: usize,
    /// The pressure integral the two sweeps left on the flat, Pa m (before `k / H`): the
    /// wear of a cycle at this pressure, which the cycles a step skips repeat.
    pub pressed: WearMap,
    /// The volume yielding pushed in (cut) this cycle, m^3.
    pub cut_m3: f64,
    /// The volume worn before this cycle, m^3.
    pub worn_before_m3: f64,
    /// The contact with the ball at the stroke's middle on the forward sweep, and the cap
    /// it was solved under, Pa.
    pub middle: ContactSolution,
    /// The cap of this cycle, Pa.
    pub cap_pa: f64,
}

/// The last solve, the flat under the contact it was made on, the gap it left, and its
/// capped cells that interpenetrate the flat: `(column, row, depth)` on the contact grid.
struct Kept {
    depth: Vec<f64>,
    gap: Vec<f64>,
    solution: ContactSolution,
    pressed_in: Vec<(usize, usize, f64)>,
}

impl Kept {
    /// Whether this solve's pressure stands for a position whose flat under the contact is
    /// `depth`: no cell's flat differs by more than `reuse_m`, but for open cells that stay
    /// open (a flat away from the contact, as near the end of a worn track, changes nothing
    /// the solve decided while it does not reach the ball).
    fn stands_for(&self, depth: &[f64], reuse_m: f64) -> bool {
        self.depth
            .iter()
            .zip(depth)
            .zip(self.solution.pressure.iter().zip(&self.gap))
            .all(|((old, new), (&p, gap))| {
                let change = new - old;
                change.abs() <= reuse_m || (p == 0.0 && gap + change > 0.0)
            })
    }
}

/// Writes into `out` the flat under the contact grid `grid` with the ball's centre at
/// `ball_x_m`: the map's depth interpolated along the stroke (linear between column
/// centres; unworn beyond).
fn depth_under(map: &WearMap, grid: &Grid, ball_x_m: f64, out: &mut [f64]) {
    for c in 0..grid.nx {
        let position = (ball_x_m + grid.x(c)) / map.dx + map.nx as f64 / 2.0 - 0.5;
        let left = position.floor();
        let weight = position - left;
        let column = |i: f64| (0.0..map.nx as f64).contains(&i).then_some(i as usize);
        let (a, b) = (column(left), column(left + 1.0));
        for iy in 0..grid.ny {
            let at = |i: Option<usize>| i.map_or(0.0, |i| map.depth[iy * map.nx + i]);
            out[iy * grid.nx + c] = (1.0 - weight) * at(a) + weight * at(b);
        }
    }
}

/// The capped cells of `solution` that interpenetrate the flat, with how far: where the
/// flat yields to the ball's deformed surface (eq. 13).
fn pressed_in(
    grid: &Grid,
    solution: &ContactSolution,
    separation: &[f64],
    cap_pa: f64,
) -> Vec<(usize, usize, f64)> {
    solution
        .pressure
        .iter()
        .enumerate()
        .filter_map(|(i, &p)| {
            let gap = solution.displacement[i] + separation[i] - solution.approach_m;
            (p >= cap_pa && gap < 0.0).then_some((i % grid.nx, i / grid.nx, -gap))
        })
        .collect()
}

/// How the positions of a stroke are solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeNumerics {
    /// A solve's pressure is kept while the loaded flat moves by at most this fraction of
    /// Hertz's approach; 0 keeps it only for a flat equal to the solved one (the unworn
    /// flat of the first sweep).
    pub reuse_fraction: f64,
    /// The contact is solved (or kept) at every this many positions and at the middle, and
    /// blended between; 1 solves at each.
    pub solve_every: usize,
    /// Whether every return sweep is solved; otherwise only those after a forward sweep
    /// that cut much ([`RETURN_SOLVED_ABOVE_CUT_SHARE`]), the others pressing the
    /// forward's pressure again.
    pub solve_return: bool,
}

impl Default for StrokeNumerics {
    fn default() -> Self {
        Self {
            reuse_fraction: REUSE_FRACTION_OF_APPROACH,
            solve_every: SOLVE_EVERY_POSITIONS,
            solve_return: false,
        }
    }
}

/// Runs `cycles` of `stroke` on the smooth flat of `setup` (its ball, load, hardness law,
/// cap and wear law; its grid centred on the ball), solving every cycle with `numerics`.
/// The cap is the hardness law's at no plastic strain: the map does not carry the strain
/// a `strain_hardening` cap rises with, so that cap stays at the initial yield strength
/// here. The positions are `n + 1` points a little less than a cell apart covering the
/// stroke, each pressing the stretch of the stroke nearest to it.
pub fn reciprocate(
    setup: &Setup,
    stroke: Stroke,
    cycles: Range<u64>,
    numerics: StrokeNumerics,
) -> Result<StrokeWear, SimulationError> {
    let mut engine = StrokeEngine::new(setup, stroke, numerics);
    let (mut volume_m3, mut solves) = (Vec::new(), Vec::new());
    for cycle in cycles {
        solves.push(engine.cycle(cycle)?.solves);
        volume_m3.push(engine.volume_m3());
    }
    Ok(StrokeWear {
        map: engine.map,
        volume_m3,
        solves,
    })
}

/// Reciprocating cycles on a flat: the map, the normal contact's solver on the setup's
/// grid, the ball, the positions along the stroke and the last solve.
pub struct StrokeEngine {
    setup: Setup,
    grid: Grid,
    solver: WindowedSolver<Factory>,
    ball: Vec<f64>,
    reuse_m: f64,
    solve_every: usize,
    solve_return: bool,
    length_m: f64,
    depth: Vec<f64>,
    steps: usize,
    last: Option<Kept>,
    /// The last pressure carried onto a grown grid: the next solve's start.
    carried: Option<Vec<f64>>,
    map: WearMap,
    /// Whether a solve since the last growth came near the grid's edge, along x and y.
    crowded: (bool, bool),
}

impl StrokeEngine {
    /// An unworn flat under `stroke`, its positions solved by `numerics`.
    pub fn new(setup: &Setup, stroke: Stroke, numerics: StrokeNumerics) -> Self {
        let setup = Setup {
            coupling: false,
            ..setup.clone()
        };
        let grid = setup.grid;
        Self {
            solver: windowed(&setup, grid),
            ball: setup.ball_height(&grid),
            reuse_m: numerics.reuse_fraction * setup.plan.hertz().approach_m(),
            solve_every: numerics.solve_every.max(1),
            solve_return: numerics.solve_return,
            length_m: stroke.length_m,
            steps: (stroke.length_m / grid.dx).ceil().max(1.0) as usize,
            depth: vec![0.0; grid.len()],
            map: WearMap::new(&grid, stroke.length_m),
            grid,
            setup,
            last: None,
            carried: None,
            crowded: (false, false),
        }
    }

    /// The flat's depth, m, along and across the stroke.
    pub fn map(&self) -> &WearMap {
        &self.map
    }

    /// The contact grid, centred on the ball.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The shares of the grid the solves so far were solved and checked on, summed.
    pub fn window_fractions(&self) -> WindowFractions {
        self.solver.fractions()
    }

    /// The worn volume, m^3.
    pub fn volume_m3(&self) -> f64 {
        self.map.depth.iter().sum::<f64>() * self.map.dx * self.grid.dy
    }

    /// Solves `cycle`: forward, then back. A sweep is solved on the flat as the last one
    /// left it, and its yielding and wear are added after it, as a pass of the disc is (the
    /// groove that yielding pushes in is each cell's deepest interpenetration in the
    /// sweep: in the middle of the track, a row's deepest, the disc's rule). The return
    /// is solved after a forward sweep that cut over [`RETURN_SOLVED_ABOVE_CUT_SHARE`] of
    /// the worn volume, or with `solve_return`; otherwise it presses the forward's pressure
    /// again.
    pub fn cycle(&mut self, cycle: u64) -> Result<StrokeCycle, SimulationError> {
        let mut pressed = WearMap::new(&self.grid, self.length_m);
        let worn_before = self.volume_m3();
        let forward = self.sweep(&mut pressed, cycle, false)?;
        let return_solved = self.solve_return
            || cuts_over(forward.cut_m3, worn_before, RETURN_SOLVED_ABOVE_CUT_SHARE);
        let (solves, iterations, cut_m3) = if return_solved {
            let back = self.sweep(&mut pressed, cycle, true)?;
            (back.solves, back.iterations, back.cut_m3)
        } else {
            let scale = self.wear_scale(cycle);
            let pressure = &forward.pressure;
            wear_in(&mut self.map, &mut pressed, pressure, None, scale);
            (0, 0, 0.0)
        };
        let (middle, cap_pa) = forward.middle.expect("a forward sweep passes the middle");
        Ok(StrokeCycle {
            solves: forward.solves + solves,
            return_solved,
            iterations: forward.iterations + iterations,
            pressed,
            cut_m3: forward.cut_m3 + cut_m3,
            worn_before_m3: worn_before,
            middle,
            cap_pa,
        })
    }

    /// The cycles `cycles` worn at the pressure of a solved cycle's `pressed` map, each at
    /// its own hardness: what a step skips. Call it before the grid grows, on the map of
    /// the grid the cycle was solved on.
    pub fn repeat(&mut self, pressed: &WearMap, cycles: Range<u64>) {
        let plan = &self.setup.plan;
        let scale = plan.wear().depth_scale(cycles, plan.hardness());
        debug_assert_eq!(pressed.depth.len(), self.map.depth.len(), "the same grid");
        for (d, p) in self.map.depth.iter_mut().zip(&pressed.depth) {
            *d += scale * p;
        }
    }

    /// Widens the grid where a solve since the last growth came near its edge (the disc's
    /// rule), carrying the map and the last pressure over; the new grid, or `None`.
    pub fn grow_if_crowded(&mut self) -> Option<Grid> {
        let wider = widen(&self.grid, std::mem::take(&mut self.crowded))?;
        self.map = self.map.embedded_in(&wider, self.length_m);
        self.ball = self.setup.ball_height(&wider);
        self.depth = vec![0.0; wider.len()];
        // Cold, a grown grid's first solve stalled at residual 0.54 (a Ti-6Al-4V flat grown
        // to 64 x 96, `tests/reciprocating_scene.rs`).
        let old = std::mem::replace(&mut self.grid, wider);
        let kept = self.last.take().expect("only a solve crowds the grid");
        let carried = embedded(&kept.solution.pressure, &old, &wider);
        self.solver.grow(wider, &carried);
        self.carried = Some(carried);
        Some(wider)
    }

    /// One sweep of `cycle`, backward or not, its pressure integral added to `pressed` and
    /// its yielding and wear to the map after it. The contact is solved (unless kept) at
    /// every `solve_every`-th position, the middle, and each position after a solve that
    /// yielded; a position between two such anchors presses their pressures blended
    /// linearly by its place between them. It pushes no groove in: pushed from an anchor's
    /// flat onto a position's, a groove overshot where the flat ramps, and the overshoot
    /// grew cycle after cycle (20 cycles of a 2 mm stroke at the paper's bulk hardness, an
    /// anchor every 16 positions: the deepest point 7.4 times too deep); one left out is
    /// pushed at the next solve that reaches the cap.
    fn sweep(
        &mut self,
        pressed: &mut WearMap,
        cycle: u64,
        backward: bool,
    ) -> Result<Sweep, SimulationError> {
        let cap = self.setup.yield_pressure_pa(cycle as f64, 0.0);
        let scale = self.wear_scale(cycle);
        let mut wear = SweepWear::new(&self.grid, self.length_m, self.steps);
        let (mut solves, mut iterations, mut middle_contact) = (0, 0, None);
        let middle = self.steps / 2;
        // The last anchor's place in the sweep and its pressure, and a blend's buffer.
        let mut before: Option<usize> = None;
        let mut anchor = vec![0.0; self.grid.len()];
        let mut blended = vec![0.0; self.grid.len()];
        let steps = self.steps;
        let at = move |k: usize| if backward { steps - k } else { k };
        for k in 0..=self.steps {
            let j = at(k);
            let in_middle = !backward && j == middle;
            let yielding = self
                .last
                .as_ref()
                .is_some_and(|kept| !kept.pressed_in.is_empty());
            if k % self.solve_every != 0 && k != self.steps && !in_middle && !yielding {
                continue;
            }
            let solved = self.solve_unless_kept(wear.position_m(j), cycle, cap)?;
            if let Some(solve_iterations) = solved {
                solves += 1;
                iterations += solve_iterations;
            }
            let kept = self.last.as_ref().expect("solved or kept");
            if in_middle {
                middle_contact = Some((kept.solution.clone(), cap));
            }
            // The run of positions so far pressed the last anchor's pressure.
            if solved.is_some() {
                wear.flush(&anchor);
            }
            if let Some(previous) = before {
                for between in previous + 1..k {
                    if solved.is_some() {
                        let w = (between - previous) as f64 / (k - previous) as f64;
                        blend(&anchor, &kept.solution.pressure, w, &mut blended);
                        wear.press(at(between), &blended);
                    } else {
                        // A kept solve stands for the positions between, as for its anchor.
                        wear.keep(at(between));
                    }
                }
            }
            // A kept anchor's pressure is the last anchor's: copied only where it solved.
            if solved.is_some() || before.is_none() {
                anchor.copy_from_slice(&kept.solution.pressure);
            }
            wear.keep(j);
            wear.push_in(j, &kept.pressed_in);
            before = Some(k);
        }
        wear.flush(&anchor);
        let pressure = &wear.pressure;
        wear_in(&mut self.map, pressed, pressure, Some(&wear.yielded), scale);
        Ok(Sweep {
            solves,
            iterations,
            cut_m3: wear.yielded.iter().sum::<f64>() * self.map.dx * self.grid.dy,
            middle: middle_contact,
            pressure: wear.pressure,
        })
    }

    /// Archard's depth per unit of pressure integral in one sweep of `cycle`, `k / H`.
    fn wear_scale(&self, cycle: u64) -> f64 {
        let plan = &self.setup.plan;
        plan.wear().depth_scale(cycle..cycle + 1, plan.hardness())
    }

    /// Solves the contact with the ball's centre at `x_m` on the map, unless the last solve
    /// stands for it; the solve's iterations when it solved.
    fn solve_unless_kept(
        &mut self,
        x_m: f64,
        cycle: u64,
        cap: f64,
    ) -> Result<Option<usize>, SimulationError> {
        // Most positions keep the last solve, so the flat is read into a buffer kept
        // between positions, and handed to the solve's record only when one is made.
        depth_under(&self.map, &self.grid, x_m, &mut self.depth);
        if self
            .last
            .as_ref()
            .is_some_and(|kept| kept.stands_for(&self.depth, self.reuse_m))
        {
            return Ok(None);
        }
        let depth = std::mem::replace(&mut self.depth, vec![0.0; self.grid.len()]);
        let separation: Vec<f64> = self.ball.iter().zip(&depth).map(|(b, d)| b + d).collect();
        let problem = ContactProblem {
            grid: self.grid,
            separation: &separation,
            load_n: self.setup.scene().load_n(),
            yield_pressure_pa: cap,
            pass_wear_per_pa: 0.0,
        };
        let last = self
            .last
            .as_ref()
            .map(|kept| kept.solution.pressure.as_slice());
        let warm = last.or(self.carried.as_deref());
        let solution = self
            .solver
            .solve(&problem, &self.setup.options, warm)
            .map_err(|source| SimulationError::Contact { cycle, source })?;
        let iterations = solution.iterations;
        self.carried = None;
        let near = near_edges(&self.grid, &solution.pressure);
        self.crowded = (self.crowded.0 || near.0, self.crowded.1 || near.1);
        self.last = Some(Kept {
            pressed_in: pressed_in(&self.grid, &solution, &separation, cap),
            gap: solution.gap_m(&separation),
            depth,
            solution,
        });
        Ok(Some(iterations))
    }
}

/// Builds the solver of a grid or of a window of it.
type Factory = Box<dyn FnMut(&Grid) -> Box<dyn ContactSolver>>;

/// The solver of `grid` on windows around the last contact ([`WindowedSolver`]): the
/// grid holds the stroke's widest contact, the middle's, while most solves are the ends'.
/// Over 1000 strokes of the default rig their loaded cells spanned 13% of the last grid's
/// (96 x 128) and the windows 44% of the grid's cells on average; the run's CPU time fell
/// from 15.7 to 9.8 s (`tribosim run`, one run each).
fn windowed(setup: &Setup, grid: Grid) -> WindowedSolver<Factory> {
    let setup = setup.clone();
    WindowedSolver::new(grid, Box::new(move |window: &Grid| setup.solver(window)))
}

/// Adds a sweep's pressure integral `pressure` to the cycle's `pressed`, and its wear
/// (`scale` times it) and the groove it pushed in (`yielded`) to `map`.
fn wear_in(
    map: &mut WearMap,
    pressed: &mut WearMap,
    pressure: &WearMap,
    yielded: Option<&[f64]>,
    scale: f64,
) {
    for (i, ((d, p), total)) in map
        .depth
        .iter_mut()
        .zip(&pressure.depth)
        .zip(pressed.depth.iter_mut())
        .enumerate()
    {
        *d += yielded.map_or(0.0, |y| y[i]) + scale * p;
        *total += p;
    }
}

/// Writes into `out` the pressure `w` of the way from `a` to `b`.
fn blend(a: &[f64], b: &[f64], w: f64, out: &mut [f64]) {
    for ((o, a), b) in out.iter_mut().zip(a).zip(b) {
        *o = (1.0 - w) * a + w * b;
    }
}

impl StrokeCycle {
    /// Whether the cycle cut more than `share` of the volume worn before it: it reshaped
    /// the track.
    pub fn cut_over(&self, share: f64) -> bool {
        cuts_over(self.cut_m3, self.worn_before_m3, share)
    }
}

/// Whether a cut of `cut_m3` is more than `share` of the worn volume `worn_m3`.
fn cuts_over(cut_m3: f64, worn_m3: f64, share: f64) -> bool {
    cut_m3 > share * worn_m3
}

/// What one sweep cost and left.
struct Sweep {
    solves: usize,
    iterations: usize,
    /// The volume the sweep's yielding pushed in, m^3.
    cut_m3: f64,
    middle: Option<(ContactSolution, f64)>,
    /// The sweep's pressure integral, Pa m.
    pressure: WearMap,
}
