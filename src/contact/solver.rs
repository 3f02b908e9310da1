//! The bounded contact solver: find pressures `0 <= p <= Y` carrying the load `W` such that
//! the gap `g = K p + h - delta` meets the complementarity conditions of [`super::residual`]
//! (the elastic-perfectly-plastic cap of eq. 12 as the upper bound).
//!
//! # Algorithm
//! Polonsky & Keer's conjugate gradient (Wear 231, 1999) with load control, extended with the
//! upper bound. CG runs on the free cells `F = {0 < p < Y}`; `delta` is the mean of
//! `K p + h` over `F`. The search direction is projected to sum to zero over `F`, so a step
//! preserves the load exactly and needs no rescaling. Cells leaving `F` are truncated to the
//! bound they cross; cells on a bound whose gap says they should not be there (zero
//! pressure but penetrating, or at the cap but open) re-enter `F` by the Polonsky-Keer
//! rule and restart the conjugacy (on the whole grid, only when many cells moved:
//! `progress`). When the free cells cannot move (at most one is free, nearly every loaded
//! cell at the cap), one projected steepest-descent step over the free and the wrongly
//! bounded cells takes the place of the CG step.
//!
//! One iteration of [`solve`], step by step (the methods of its private state): measure the
//! gap and the residual (`measure`); stop, or restore the load, once the residual meets the
//! tolerance (`converged`); build the conjugate direction (`direction`), or fall back to
//! steepest descent (`steepest_descent`); find the step length (`step_length`); step,
//! truncate and re-enter (`advance`).
//!
//! # Preconditioning
//! When the operator offers one ([`Operator::preconditioner`]; [`super::DcFft`] does), the
//! direction is built from `z = M^-1 g` over the free cells instead of `g`, with the
//! Fletcher-Reeves ratio `(g.z) / (g.z)_old`: preconditioned CG on the free set. `M^-1` is
//! the inverse of the kernel wrapped onto the grid ([`super::FourierInverse`]), which
//! undoes the `1 / |k|` spread of the half-space's spectrum. Measured on the paper's Hertz
//! case (`tribosim bench contact`): 42 -> 21 iterations at N = 256, 72 -> 27 at N = 1024;
//! a warm-started wear cycle of the paper scene: about 37 -> 9. By default
//! ([`Preconditioning::FreeSet`]) `M^-1` is also corrected where it couples the free cells
//! to the others, at the contact's edges (`free_set`): 6.3 -> 4.7 iterations a warm solve
//! of the paper scene, 67 -> 33 on the rough flat at N = 2048.
//!
//! The correction can stall a solve whose free set churns: on a rough disc under the cap,
//! thousands of cells leave and re-enter the cap at every step, and the corrected steps
//! raise the energy the solution minimises instead of lowering it. The second cycle of the
//! rough example of `docs/scene.md` never improved on its starting residual (6.6e-2) in
//! 2000 iterations; on the whole grid it converges in 46. So a solve that stops making
//! progress (`progress`) drops the correction and goes on on the whole grid: that solve
//! converged in 57 iterations, the fallback after the 11th. The fallbacks are counted in
//! [`ContactSolution::preconditioner_fallbacks`]. A warm start that stalls on the whole grid
//! too begins again from the uniform pressure (`progress`), counted in
//! [`ContactSolution::uniform_restarts`].
//!
//! # Cost: one operator apply per iteration
//! The displacement `u = K p` is updated as `u - tau K t`, reusing the `K t` that the step
//! length needs. An iteration that moved cells onto or off a bound changes them by more
//! than the step and the load by their sum: when no cell sits at the cap the rescale to the
//! load is one factor on every pressure, and the few changed cells are added to `u` by
//! direct summation ([`Operator::add_sparse`]); otherwise (cells at the cap, or more
//! changed cells than a sparse update can take for less than an apply) the load is
//! restored by the general rescale and `u` takes `K` of the change. Measured on the
//! paper's 3600-cycle scene (`tribosim run`, the sparse update switched off by hand for the
//! comparison): 3.8-4.0 s against 4.35-4.5 s, the same results.
//!
//! That `K` of the change came from a second apply, of the restored pressure. Where the
//! operator keeps the transform of the direction ([`Operator::keep`]:
//! [`super::DcFft`]), the step length's `t . K t` is read off that transform, and after the
//! step `u` takes `K (w - tau t)`, `w` the moves off the direction (the truncations, the
//! re-entries and the shift), from the transform of `w` and the kept one: three transforms
//! in the place of four. A step that restores under the cap asks for it when the step
//! before did (`Keeping`). On the 4 um rough disc of `docs/accuracy.md`, where nearly every
//! step does, the run's instructions fell to 0.919 of the two applies' (`valgrind
//! --tool=cachegrind`, 60 cycles, the same 383 iterations), and on the paper scene, where
//! one step in eight does, to 0.997 (1200 cycles). The gap, the free set and
//! the residual come from one fused pass over the grid. The grid-sized vectors are
//! allocated once a solve; an iteration allocates only its passes' short lists of blocks
//! and their sums (an entry a block: one below `SPLIT_MIN_CELLS`, eight from there on) and
//! the blocks' lists of changed cells. On the 4 um rough disc of `docs/accuracy.md`, whose
//! windows are one block, the solve in blocks took 0.995 of the CPU time of the loops before
//! it (`scripts/rough_ab.py`, 3 pairs), the results the same to the bit.
//!
//! # Stopping test
//! The solve succeeds when the relative residual of [`super::residual`] meets the tolerance
//! and the load is carried to 1e-11 (`LOAD_TOLERANCE`). The residual is measured on the
//! updated `u`; its round-off drift from `K p` is bounded by [`UPDATE_ROUNDOFF`] per update,
//! and success is confirmed on a freshly computed `u` only when that bound could reach a
//! hundredth of the tolerance (`DRIFT_SHARE`): at the scene's default tolerance, never.
//! On the paper scene the confirmation apply cost one of 7.3 iterations a solve.
//!
//! The bound is double precision's. In single precision (tolerances from 1e-4 on,
//! [`super::SINGLE_PRECISION_MIN_TOLERANCE`]) an update errs by the f32 transforms'
//! round-off of the update's own size, a step's and not `u`'s: at the end of each of the 4
//! um rough disc's 600 solves, `u` differed from a fresh f32 apply of the pressure by at
//! most 5.5e-7 of its largest value (median 4.0e-7), the fresh apply's own round-off, and
//! under the hundredth of the tolerance, 1e-6 (counted once with a build that compared the
//! two at each solve's end; `tests/contact.rs` bounds it on a capped Hertz contact).

use super::blocks::Blocks;
use super::error::ContactError;
use super::grid::Grid;
use super::operator::Operator;
use super::problem::{
    ContactProblem, ContactSolution, ContactSolver, KnownStart, Preconditioning, SolverOptions,
};
use super::worn_rows::WornRows;

mod advance;
mod bounds;
mod free_set;
mod measure;
mod progress;

use super::sums::{dot, dot2, free_dots, sum, update_direction};
use bounds::{check_edges, rescale_to_load, violator_step};
use free_set::FreeSetCorrection;
use progress::Progress;

pub(super) use advance::Keeping;

/// Relative load error accepted at convergence. Summing N^2 pressures in f64 errs by up to
/// N^2 * 1.1e-16 in the worst case (1.2e-10 at N = 1024), typically sqrt(N^2) times that;
/// 1e-11 is met after the final rescale and stays far inside the 1e-9 the contact tests
/// require of the carried load (`tests/contact.rs`).
const LOAD_TOLERANCE: f64 = 1e-11;

/// A bound on the round-off one update of the displacement (along a step, or at a few
/// cells) adds to it, relative to its largest value. Measured by `tests/contact.rs`
/// (`an_updated_displacement_drifts_...`): at most 6.3e-17 per iteration on Hertz cases
/// from N = 64 to 512, about one apply's own round-off after 20-odd iterations.
pub const UPDATE_ROUNDOFF: f64 = 1e-14;

/// The share of the tolerance the updates' round-off may take before success is confirmed
/// on a displacement computed afresh.
const DRIFT_SHARE: f64 = 0.01;

/// The preconditioned Polonsky-Keer solver on one operator: [`solve`] as a
/// [`ContactSolver`].
#[derive(Debug)]
pub struct NormalSolver<O> {
    operator: O,
    keeping: Keeping,
}

impl<O: Operator> NormalSolver<O> {
    /// The solver of `operator` (e.g. [`super::DcFft`] of the normal kernel).
    pub fn new(operator: O) -> Self {
        Self {
            operator,
            keeping: Keeping::default(),
        }
    }
}

impl<O: Operator> ContactSolver for NormalSolver<O> {
    fn solve(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        let keeping = &mut self.keeping;
        solve_from(
            &mut self.operator,
            problem,
            options,
            warm_start,
            None,
            keeping,
        )
    }

    fn solve_known(
        &mut self,
        problem: &ContactProblem,
        options: &SolverOptions,
        start: KnownStart<'_>,
    ) -> Result<ContactSolution, ContactError> {
        let (warm, known) = (Some(start.pressure), Some(start.displacement));
        let keeping = &mut self.keeping;
        solve_from(&mut self.operator, problem, options, warm, known, keeping)
    }

    fn operator(&mut self) -> &mut dyn Operator {
        &mut self.operator
    }
}

/// Solves one contact problem on `operator`, optionally warm-started from `warm_start`
/// (e.g. the previous wear cycle's pressure). Fails with a named [`ContactError`], never
/// silently: an impossible load, a contact reaching the domain edge, or no convergence.
pub fn solve(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    options: &SolverOptions,
    warm_start: Option<&[f64]>,
) -> Result<ContactSolution, ContactError> {
    solve_from(
        operator,
        problem,
        options,
        warm_start,
        None,
        &mut Keeping::default(),
    )
}

/// [`solve`] from `start`, whose displacement is known: the start's apply is skipped when
/// the start is within `[0, Y]` and at the load (the solve would otherwise have moved it).
pub fn solve_known(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    options: &SolverOptions,
    start: KnownStart<'_>,
) -> Result<ContactSolution, ContactError> {
    let (warm, known) = (Some(start.pressure), Some(start.displacement));
    solve_from(
        operator,
        problem,
        options,
        warm,
        known,
        &mut Keeping::default(),
    )
}

/// [`solve`] from `warm_start` and, where known, its displacement `K warm_start` without
/// the wear term (`None`: one apply computes it), its first step keeping the direction's
/// transform as `keeping` says, which the solve then updates.
pub(super) fn solve_from(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    options: &SolverOptions,
    warm_start: Option<&[f64]>,
    known: Option<&[f64]>,
    keeping: &mut Keeping,
) -> Result<ContactSolution, ContactError> {
    problem.validate(options)?;
    let mut known = known.zip(warm_start).map(|(u, p)| (u.to_vec(), p));
    let mut worn;
    let operator: &mut dyn Operator = if problem.pass_wear_per_pa > 0.0 {
        worn = WornRows::new(operator, problem.pass_wear_per_pa, problem.grid.dx);
        // The known displacement under this operator: plus the wear term its apply adds.
        if let Some((u, pressure)) = known.as_mut() {
            worn.add_wear(pressure, u);
        }
        &mut worn
    } else {
        operator
    };
    let known = known.map(|(u, _)| u);
    let mut solve = PolonskyKeer::start(operator, problem, options, warm_start, known)?;
    solve.keep_next = keeping.first_step;
    let solution = solve.iterate(operator, options);
    keeping.first_step = solve.first_kept.unwrap_or(keeping.first_step);
    solution
}

/// The state of one solve between iterations. The work vectors are allocated once, at the
/// start.
struct PolonskyKeer<'a> {
    grid: Grid,
    /// How the passes over the grid are cut, and whether other threads take some.
    blocks: Blocks,
    separation: &'a [f64],
    cap: f64,
    /// The load in pressure units: `W / cell area`, the sum the pressures must reach.
    target: f64,
    /// Pressure.
    p: Vec<f64>,
    /// Displacement `K p`, updated along with the steps.
    u: Vec<f64>,
    /// Gap `u + h - delta`.
    g: Vec<f64>,
    /// Search direction.
    t: Vec<f64>,
    /// The gap on the free cells, then `K t` once the direction is applied.
    r: Vec<f64>,
    /// The preconditioned gap `M^-1 r` (empty without a preconditioner).
    z: Vec<f64>,
    /// 1 on the free cells, 0 elsewhere: the sums over the free set become dot products,
    /// with no branch and no accumulator chained through memory.
    free: Vec<f64>,
    /// Whether the operator offers a preconditioner.
    preconditioned: bool,
    /// The preconditioner's correction at the free set's edges, where chosen and until
    /// the solve stalls with it.
    correction: Option<FreeSetCorrection>,
    /// The best residuals of the last iterations, to tell a stalled solve.
    progress: Progress,
    /// Whether the correction was dropped because the solve stalled.
    fell_back: bool,
    /// Whether the solve began from a warm start and has not yet left it for the uniform
    /// pressure.
    warm: bool,
    /// Whether a stalled warm start was left for the uniform pressure.
    restarted: bool,
    /// Operator applications so far.
    applies: usize,
    /// Updates of `u` since it was last computed from `p` by an apply (0: fresh).
    updates: usize,
    /// The cells the last step moved other than along the direction (truncated at a bound,
    /// re-entering), with how far: what the displacement update along the step misses.
    changes: Vec<(usize, f64)>,
    /// Pressure per unit of gap given to a re-entering cell (Polonsky-Keer: the last step
    /// length, for a direction made of gaps).
    entry_rate: f64,
    /// `r.z` (or `r.r`) of the last direction, the denominator of the Fletcher-Reeves ratio.
    rho_old: f64,
    /// Whether the next direction starts afresh, after a re-entry or a fallback step.
    restart: bool,
    /// Whether the operator kept the transform of the direction ([`Operator::keep`])
    /// instead of applying to it: `r` then does not hold `K t`, and the step's displacement
    /// update waits for the moves it makes off the direction.
    kept: bool,
    /// Whether the next step asks the operator to keep the direction's transform
    /// ([`Keeping`]).
    keep_next: bool,
    /// Whether the first step restored the load under the cap (`None` before it).
    first_kept: Option<bool>,
    /// The last positive step length.
    tau_last: f64,
    /// The relative residual of the last measure.
    residual: f64,
    /// The load of the last measure, in pressure units.
    load: f64,
    /// The free cells of the last measure.
    free_cells: f64,
    /// The sum of the search direction over the free cells of the last measure.
    free_t: f64,
}

impl<'a> PolonskyKeer<'a> {
    /// The uniform pressure, or the warm start clipped to `[0, Y]`, at the load, and its
    /// displacement: `known` (`K warm_start` under `operator`) when the warm start needed
    /// neither, else one apply. Refuses a load the domain cannot carry at the cap.
    fn start(
        operator: &mut dyn Operator,
        problem: &ContactProblem<'a>,
        options: &SolverOptions,
        warm_start: Option<&[f64]>,
        known: Option<Vec<f64>>,
    ) -> Result<Self, ContactError> {
        let grid = problem.grid;
        let (n, h, cap) = (grid.len(), problem.separation, problem.yield_pressure_pa);
        let blocks = Blocks::of(n, operator.threads());
        let target = problem.load_n / grid.cell_area();
        if target >= cap * n as f64 {
            return Err(ContactError::LoadExceedsCapacity {
                load_n: problem.load_n,
                capacity_n: cap * grid.area(),
            });
        }
        let warm = warm_start.filter(|w| w.len() == n && w.iter().any(|&v| v > 0.0));
        let known = known.filter(|u| u.len() == n);
        let as_is = warm.filter(|w| {
            known.is_some()
                && w.iter().all(|v| (0.0..=cap).contains(v))
                && (sum(w) - target).abs() <= LOAD_TOLERANCE * target
        });
        let (p, u, applies) = match (as_is, known) {
            (Some(w), Some(u)) => (w.to_vec(), u, 0),
            _ => {
                let mut p = match warm {
                    Some(w) => w.iter().map(|&v| v.clamp(0.0, cap)).collect(),
                    None => vec![target / n as f64; n],
                };
                // Before the first apply the displacement is unknown: order by the
                // separation alone.
                rescale_to_load(blocks, &mut p, (cap, target), h);
                let mut u = vec![0.0; n];
                operator.apply(&p, &mut u);
                (p, u, 1)
            }
        };
        let inverse = operator.preconditioner();
        let preconditioned = inverse.is_some();
        let correction = inverse
            .filter(|_| options.preconditioning == Preconditioning::FreeSet)
            .map(|inverse| FreeSetCorrection::new(inverse, grid));
        Ok(Self {
            grid,
            blocks,
            separation: h,
            cap,
            target,
            p,
            u,
            g: vec![0.0; n],
            t: vec![0.0; n],
            r: vec![0.0; n],
            z: if preconditioned {
                vec![0.0; n]
            } else {
                Vec::new()
            },
            free: vec![0.0; n],
            preconditioned,
            correction,
            progress: Progress::new(warm.is_some()),
            fell_back: false,
            warm: warm.is_some(),
            restarted: false,
            applies,
            updates: 0,
            changes: Vec::new(),
            entry_rate: 0.0,
            rho_old: 0.0,
            restart: true,
            kept: false,
            keep_next: false,
            first_kept: None,
            tau_last: 0.0,
            residual: f64::INFINITY,
            load: 0.0,
            free_cells: 0.0,
            free_t: 0.0,
        })
    }

    /// The iterations, until the solution or the iteration limit.
    fn iterate(
        &mut self,
        operator: &mut dyn Operator,
        options: &SolverOptions,
    ) -> Result<ContactSolution, ContactError> {
        for iteration in 1..=options.max_iterations {
            let delta = self.measure();
            if self.residual <= options.tolerance {
                match self.converged(operator, delta, iteration - 1, options.tolerance)? {
                    Some(solution) => return Ok(solution),
                    None => continue,
                }
            }
            if self.progress.stalled(self.residual) && self.fall_back(operator) {
                continue;
            }
            let num = self.direction(operator);
            if num <= 0.0 {
                self.steepest_descent(operator);
                continue;
            }
            let tau = self.step_length(operator, num);
            self.advance(operator, tau);
        }
        Err(ContactError::NotConverged {
            iterations: options.max_iterations,
            residual: self.residual,
            tolerance: options.tolerance,
        })
    }

    /// The residual met the tolerance. The solution, if the load is carried and `u` is fresh
    /// (after `iterations` iterations); otherwise the load is restored or `u` recomputed,
    /// and the iteration goes on (`None`). A contact reaching the domain edge is refused.
    fn converged(
        &mut self,
        operator: &mut dyn Operator,
        delta: f64,
        iterations: usize,
        tolerance: f64,
    ) -> Result<Option<ContactSolution>, ContactError> {
        if (self.load - self.target).abs() > LOAD_TOLERANCE * self.target {
            // Round-off in many small steps moved the load: restore it exactly.
            self.rescale();
            self.recompute(operator);
            return Ok(None);
        }
        if self.updates as f64 * UPDATE_ROUNDOFF > DRIFT_SHARE * tolerance {
            // The updates may have drifted by a share of the tolerance: confirm on a fresh
            // displacement.
            self.recompute(operator);
            return Ok(None);
        }
        if !operator.is_periodic() {
            check_edges(&self.grid, &self.p, self.target)?;
        }
        Ok(Some(ContactSolution {
            pressure: std::mem::take(&mut self.p),
            displacement: std::mem::take(&mut self.u),
            approach_m: delta,
            iterations,
            operator_applies: self.applies,
            residual: self.residual,
            preconditioner_fallbacks: usize::from(self.fell_back),
            uniform_restarts: usize::from(self.restarted),
        }))
    }

    /// Restores the load by [`rescale_to_load`]'s shift.
    fn rescale(&mut self) {
        rescale_to_load(self.blocks, &mut self.p, (self.cap, self.target), &self.g);
    }

    /// `u = K p`, from scratch.
    fn recompute(&mut self, operator: &mut dyn Operator) {
        operator.apply(&self.p, &mut self.u);
        self.applies += 1;
        self.updates = 0;
    }

    /// The preconditioned gap `z = M^-1 g` over the free cells (`z = g` without one), then
    /// the conjugate direction over the free cells, projected to sum to zero there, so a
    /// step keeps the load. (`g` sums to zero by the choice of delta, up to round-off.)
    /// Returns `g.t`, positive when the direction descends.
    fn direction(&mut self, operator: &mut dyn Operator) -> f64 {
        let (n_free, t_old_sum) = (self.free_cells, self.free_t);
        let (rho, z_sum) = match operator.preconditioner() {
            Some(inverse) => {
                match &mut self.correction {
                    Some(correction) => {
                        correction.apply(inverse, &self.free, &mut self.r, &mut self.z);
                        // `r` now holds the correction's input off the free set too.
                        free_dots(self.blocks, &self.free, &self.r, &self.z)
                    }
                    None => {
                        inverse.apply(&self.r, &mut self.z);
                        dot2(self.blocks, (&self.r, &self.z), (&self.free, &self.z))
                    }
                }
            }
            None => (dot(&self.r, &self.r), sum(&self.r)),
        };
        let beta = if self.restart || self.rho_old == 0.0 {
            0.0
        } else {
            rho / self.rho_old
        };
        self.rho_old = rho;
        let t_mean = if n_free > 0.0 {
            (z_sum + beta * t_old_sum) / n_free
        } else {
            0.0
        };
        let source = if self.preconditioned {
            &self.z
        } else {
            &self.g
        };
        let fields = (&source[..], &self.free[..], &self.g[..]);
        update_direction(self.blocks, &mut self.t, fields, beta, t_mean)
    }

    /// The free cells cannot move: at most one is free (a load-preserving step over one cell
    /// is zero), nearly every loaded cell at the cap. The re-entry rule alone then stalls
    /// (no step length yet) or cycles (the rescale to the load sends the re-entered cells
    /// back to the cap), as the softening-disc cases of `tests/stability.rs` do. Step
    /// instead along the gap over the free and the wrongly bounded cells; if there is no
    /// such direction, start again from the uniform pressure.
    fn steepest_descent(&mut self, operator: &mut dyn Operator) {
        let stepped = violator_step(
            operator,
            &mut self.p,
            &self.g,
            &mut self.t,
            &mut self.r,
            self.cap,
            &mut self.applies,
        );
        if !stepped {
            let uniform = self.target / self.p.len() as f64;
            self.p.fill(uniform);
        }
        self.rescale();
        self.recompute(operator);
        self.restart = true;
    }

    /// Applies the operator to the direction (`r = K t`) and returns the exact line search
    /// `g.t / t.Kt` (the last positive one when `t.Kt` is not positive). Also sets the
    /// re-entry rate.
    fn step_length(&mut self, operator: &mut dyn Operator, num: f64) -> f64 {
        let kept = if self.keep_next {
            operator.keep(&self.t)
        } else {
            None
        };
        self.kept = kept.is_some();
        self.applies += 1;
        let (den, tt) = match kept {
            Some(den) => (den, dot(&self.t, &self.t)),
            None => {
                operator.apply(&self.t, &mut self.r);
                dot2(self.blocks, (&self.t, &self.r), (&self.t, &self.t))
            }
        };
        let tau = if den > 0.0 { num / den } else { self.tau_last };
        if tau > 0.0 {
            self.tau_last = tau;
        }
        // A preconditioned direction is not made of gaps, so its step length is no
        // pressure per gap; the direction's own compliance t.t / t.Kt is, and matches
        // Polonsky-Keer's rate when t is the gap.
        // A direction without a positive t.Kt (only the non-symmetric coupled operator can
        // give one; no direction at all took the steepest-descent branch) keeps the last
        // rate: a preconditioned step length has other units and would stall re-entry.
        let rate = if !self.preconditioned {
            tau
        } else if den > 0.0 {
            tt / den
        } else {
            self.entry_rate
        };
        if rate > 0.0 {
            self.entry_rate = rate;
        }
        tau
    }
}
