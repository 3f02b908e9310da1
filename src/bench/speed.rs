//! The solver's speed levers, each measured against the code without it in the same run:
//!
//! - warm solves in the cycle loop: the paper's 3600-cycle default scene `{}` at the
//!   default tolerance against the previous default ([`PREVIOUS_TOLERANCE`]), and at the
//!   default tolerance preconditioned on the whole grid ([`Preconditioning::WholeGrid`]):
//!   iterations per solve, wall time, and what the wear volume, depth and final potential
//!   move by;
//! - cold solves: the Hertz case from a coarse-to-fine start ([`crate::contact::coarse_start`])
//!   against the uniform start, and with the whole-grid preconditioner, at
//!   [`COARSE_STUDY_SIZES`];
//!   with the peak resident memory of the process after each grid (the memory per cell
//!   at N = 2048);
//! - threads: one apply against its FFT passes split across threads ([`super::threads`]).

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use serde::Serialize;

use super::contact::{DOMAIN_M, paper_hertz};
use super::error::BenchError;
pub use super::threads::ThreadRow;
use crate::contact::{
    ContactProblem, DcFft, Grid, Kernel, Preconditioning, SolverOptions, coarse_start, solve,
};
use crate::scene::{DEFAULT_TOLERANCE, Scene, Tolerance};
use crate::simulation::{Plan, RunOptions, Setup, SimulationError, SimulationResult, run_setup};

/// The scene default's tolerance before it was set by what the error needs.
pub const PREVIOUS_TOLERANCE: f64 = 1e-8;

/// Runs of each setting in the warm-solve study, alternating.
pub const WARM_ROUNDS: usize = 3;

/// Grid sides of the coarse-to-fine study.
pub const COARSE_STUDY_SIZES: [usize; 3] = [256, 1024, 2048];

/// The studies of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedStudies {
    /// The warm-solve study.
    pub warm: Vec<WarmRow>,
    /// The coarse-to-fine study.
    pub coarse: Vec<CoarseRow>,
    /// The thread study.
    pub threads: Vec<ThreadRow>,
}

/// Every row as a JSON line.
pub fn print_json(studies: &SpeedStudies) -> Result<(), BenchError> {
    for row in &studies.warm {
        println!("{}", serde_json::to_string(row)?);
    }
    for row in &studies.coarse {
        println!("{}", serde_json::to_string(row)?);
    }
    for row in &studies.threads {
        println!("{}", serde_json::to_string(row)?);
    }
    Ok(())
}

/// One setting of the warm-solve study on the default scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WarmRow {
    /// Always `speed_warm`.
    pub study: &'static str,
    /// The solver tolerance.
    pub tolerance: f64,
    /// The solver's preconditioner (`free_set` or `whole_grid`).
    #[serde(serialize_with = "preconditioning_name")]
    pub preconditioning: Preconditioning,
    /// Contact solves of the run.
    pub solves: usize,
    /// CG iterations of the run.
    pub iterations: usize,
    /// Iterations per solve.
    pub iterations_per_solve: f64,
    /// Wall time of the run, s (median over the rounds).
    pub wall_s: f64,
    /// CPU time of the run, s (median over the rounds; `None` where it cannot be read).
    pub cpu_s: Option<f64>,
    /// Wear volume relative to the [`PREVIOUS_TOLERANCE`] run's, minus 1.
    pub err_volume: f64,
    /// Deepest point relative to the [`PREVIOUS_TOLERANCE`] run's, minus 1.
    pub err_depth: f64,
    /// Final potential minus the [`PREVIOUS_TOLERANCE`] run's, mV.
    pub potential_change_mv: f64,
}

/// One grid of the coarse-to-fine study (Hertz, the contact benchmark's case).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CoarseRow {
    /// Always `speed_coarse`.
    pub study: &'static str,
    /// Cells per side.
    pub n: usize,
    /// Iterations of the cold solve.
    pub cold_iterations: usize,
    /// Wall time of the cold solve (operator built beforehand), s.
    pub cold_s: f64,
    /// Iterations of the fine solve from the coarse start.
    pub fine_iterations: usize,
    /// Wall time of the coarse solves and the fine one, coarse operators included, s.
    pub coarse_to_fine_s: f64,
    /// Iterations of the fine solve from the coarse start, preconditioned on the whole
    /// grid ([`Preconditioning::WholeGrid`]).
    pub whole_grid_iterations: usize,
    /// Wall time of the coarse-to-fine solves preconditioned on the whole grid, s.
    pub whole_grid_s: f64,
    /// `cold_s / coarse_to_fine_s`.
    pub speedup: f64,
    /// `max |p - p_cold| / max p_cold`: both stop at the same tolerance.
    pub difference: f64,
    /// Peak resident memory of the process during this grid's solves, bytes (Linux's
    /// `VmHWM`, reset when the grid starts; `None` where it cannot be reset or read).
    pub peak_rss_bytes: Option<u64>,
}

/// The warm-solve study: the default scene at the previous and the current default
/// tolerance, and at the current one preconditioned on the whole grid, run alternately
/// [`WARM_ROUNDS`] times; times are the medians.
pub fn warm_rows() -> Result<Vec<WarmRow>, BenchError> {
    let settings = [
        (PREVIOUS_TOLERANCE, Preconditioning::FreeSet),
        (DEFAULT_TOLERANCE, Preconditioning::FreeSet),
        (DEFAULT_TOLERANCE, Preconditioning::WholeGrid),
    ];
    let mut runs = Vec::new();
    for _ in 0..WARM_ROUNDS {
        for setting in settings {
            let cpu = thread_cpu_s();
            let result = warm_run(setting)?;
            let cpu_s = thread_cpu_s()
                .zip(cpu)
                .map(|(after, before)| after - before);
            runs.push((result.summary, cpu_s));
        }
    }
    let median = |values: Vec<f64>| {
        let mut v = values;
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let base = runs[0].0.clone();
    Ok(settings
        .into_iter()
        .enumerate()
        .map(|(k, (tolerance, preconditioning))| {
            let s = &runs[k].0;
            let mine = runs.iter().skip(k).step_by(settings.len());
            WarmRow {
                study: "speed_warm",
                tolerance,
                preconditioning,
                solves: s.solves,
                iterations: s.iterations,
                iterations_per_solve: s.iterations as f64 / s.solves as f64,
                wall_s: median(mine.clone().map(|r| r.0.wall_s).collect()).unwrap_or(s.wall_s),
                cpu_s: median(mine.filter_map(|r| r.1).collect()),
                err_volume: s.wear_volume_mm3 / base.wear_volume_mm3 - 1.0,
                err_depth: s.max_depth_um / base.max_depth_um - 1.0,
                potential_change_mv: 1e3
                    * (s.potential_v.unwrap_or(0.0) - base.potential_v.unwrap_or(0.0)),
            }
        })
        .collect())
}

/// The name of a [`Preconditioning`] in the JSON rows and the report.
pub fn preconditioning_label(preconditioning: Preconditioning) -> &'static str {
    match preconditioning {
        Preconditioning::FreeSet => "free_set",
        Preconditioning::WholeGrid => "whole_grid",
    }
}

fn preconditioning_name<S: serde::Serializer>(
    preconditioning: &Preconditioning,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(preconditioning_label(*preconditioning))
}

/// The default scene at `tolerance` with `preconditioning`.
fn warm_run(
    (tolerance, preconditioning): (f64, Preconditioning),
) -> Result<SimulationResult, BenchError> {
    let mut scene = Scene::default();
    scene.numerics.tolerance = Tolerance::Relative(tolerance);
    let plan = Plan::new(scene).map_err(SimulationError::from)?;
    let mut setup = Setup::new(&plan, &RunOptions::default())?;
    setup.options.preconditioning = preconditioning;
    Ok(run_setup(&setup, &mut |_| {}, &AtomicBool::new(false))?)
}

/// CPU time of the calling thread so far, s (Linux's `schedstat`; `None` elsewhere): the
/// run's own work, whatever else the machine is doing.
pub(super) fn thread_cpu_s() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let nanoseconds: f64 = stat.split_whitespace().next()?.parse().ok()?;
    Some(nanoseconds * 1e-9)
}

/// The Hertz case on an `n`-cell grid: the grid and the separation.
fn hertz_case(n: usize) -> Result<(Grid, Vec<f64>), BenchError> {
    let (_, hertz) = paper_hertz();
    let grid = Grid::square(n, DOMAIN_M)?;
    let separation = grid.sample(|x, y| hertz.separation_m(x, y));
    Ok((grid, separation))
}

/// The coarse-to-fine study at each of [`COARSE_STUDY_SIZES`].
pub fn coarse_rows() -> Result<Vec<CoarseRow>, BenchError> {
    let (pair, hertz) = paper_hertz();
    let options = SolverOptions::default();
    let mut rows = Vec::new();
    for n in COARSE_STUDY_SIZES {
        let reset = reset_peak_rss();
        let (grid, separation) = hertz_case(n)?;
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: hertz.load_n,
            yield_pressure_pa: f64::INFINITY,
            pass_wear_per_pa: 0.0,
        };
        let mut operator = DcFft::new(&Kernel::normal(&grid, &pair));
        let started = Instant::now();
        let cold = solve(&mut operator, &problem, &options, None)?;
        let cold_s = started.elapsed().as_secs_f64();
        let started = Instant::now();
        let start = coarse_start(&problem, &pair, &options)?;
        let fine = solve(&mut operator, &problem, &options, start.as_deref())?;
        let coarse_to_fine_s = started.elapsed().as_secs_f64();
        let whole = SolverOptions {
            preconditioning: Preconditioning::WholeGrid,
            ..options
        };
        let started = Instant::now();
        let start = coarse_start(&problem, &pair, &whole)?;
        let whole_fine = solve(&mut operator, &problem, &whole, start.as_deref())?;
        let whole_grid_s = started.elapsed().as_secs_f64();
        let peak = cold.max_pressure_pa();
        let difference = cold
            .pressure
            .iter()
            .zip(&fine.pressure)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / peak;
        rows.push(CoarseRow {
            study: "speed_coarse",
            n,
            cold_iterations: cold.iterations,
            cold_s,
            fine_iterations: fine.iterations,
            coarse_to_fine_s,
            whole_grid_iterations: whole_fine.iterations,
            whole_grid_s,
            speedup: cold_s / coarse_to_fine_s,
            difference,
            peak_rss_bytes: peak_rss_since(reset),
        });
    }
    Ok(rows)
}

/// Starts a measurement of peak memory: resets the process's peak resident memory to its
/// current one (Linux: `5` written to `/proc/self/clear_refs`). Without the reset, a larger
/// grid solved earlier in the process (`bench all` runs the contact study's N = 2048 before
/// this one) would stand as every later row's peak. `false` where the reset is refused.
pub(super) fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The process's peak resident memory since [`reset_peak_rss`] (Linux's `VmHWM`), bytes;
/// `None` when the reset was refused (`reset`), since the peak would then be the process's.
pub(super) fn peak_rss_since(reset: bool) -> Option<u64> {
    reset.then(peak_rss_bytes).flatten()
}

/// The process's peak resident memory so far (Linux's `VmHWM`), bytes.
fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
