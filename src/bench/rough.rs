//! The rough-surface study: one seeded self-affine surface pressed by a rigid flat at a
//! fixed mean pressure on the periodic half-space ([`PeriodicHalfSpace`]), solved on grids
//! of [`ROUGH_SIZES`] cells per side over the same square. The surface is generated once on
//! the finest grid, its short cut-off resolved by [`CELLS_PER_SHORT_CUTOFF`] cells there,
//! and sampled at the cell centres of each coarser grid as the simulation samples a map
//! ([`HeightMap::height_at`]). Errors in the real contact area and the mean gap are against
//! the finest grid.
//!
//! `scripts/peers.py` reads the rows (`study` `rough_grid`, `n`, and the fields of
//! [`RoughRow`]) from `tribosim bench rough --json --surfaces DIR` and gives the very same
//! height arrays, written to `DIR` as text matrices, to Tamaas and ContactMechanics, so the
//! JSON field names are kept stable.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

use super::contact::{DOMAIN_M, paper_hertz};
use super::error::BenchError;
use super::fft_pair::FftPair;
use super::median_time;
use super::speed::{peak_rss_since, reset_peak_rss, thread_cpu_s};
use crate::contact::{
    ContactProblem, ContactSolution, Grid, Operator, PeriodicHalfSpace, SolverOptions, solve,
};
use crate::surface::{HeightMap, Roughness, SelfAffine, rms_slope};

/// Cells per side of the study's grids, coarsest first; the last is the reference.
pub const ROUGH_SIZES: [usize; 5] = [128, 256, 512, 1024, 2048];

/// Cells across the short cut-off on the finest grid: the simulation's resolution rule.
pub const CELLS_PER_SHORT_CUTOFF: usize = 8;

/// Repeats of the long cut-off across the square: enough wavelengths for a mean.
pub const LONG_CUTOFF_REPEATS: usize = 4;

/// Hurst exponent of the surface.
pub const HURST: f64 = 0.8;

/// Root mean square slope of the surface on the finest grid.
pub const RMS_SLOPE: f64 = 0.1;

/// Seed of the surface's random phases.
pub const SEED: u64 = 1;

/// The mean pressure over `E* h'`: about 3.5% real contact area at the kappa of about 2.4
/// that `tests/surfaces.rs` measures.
pub const REDUCED_PRESSURE: f64 = 0.015;

/// The solver's tolerance: the contact study's.
pub fn options() -> SolverOptions {
    SolverOptions::default()
}

/// One grid of the study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoughRow {
    /// Always `rough_grid`.
    pub study: &'static str,
    /// Cells per side.
    pub n: usize,
    /// Cell side, m.
    pub pixel_m: f64,
    /// Cells across the short cut-off.
    pub cells_per_short_cutoff: f64,
    /// E*, Pa.
    pub reduced_modulus_pa: f64,
    /// Mean pressure over the square, Pa.
    pub mean_pressure_pa: f64,
    /// The solver tolerance.
    pub tolerance: f64,
    /// Fraction of the cells in contact (p > 0).
    pub area_fraction: f64,
    /// Mean of the gap `K p + h - delta` over all cells, m.
    pub mean_gap_m: f64,
    /// Iterations of the solve.
    pub iterations: usize,
    /// Operator applications of the solve.
    pub applies: usize,
    /// The residual reached.
    pub residual: f64,
    /// Operator construction plus solve, s (median).
    pub wall_s: f64,
    /// The solve alone, s (median).
    pub solve_s: f64,
    /// CPU time of the solve's thread, s (median; `None` where it cannot be read): its own
    /// work, which other work on a shared machine does not inflate as much. With
    /// `threads` > 1 the split's other threads are not in it.
    pub solve_cpu_s: Option<f64>,
    /// Threads the operator's FFT passes are split over (`numerics.threads` auto: from
    /// 1024 x 1024 cells on the periodic operator, over the cores the process may use).
    pub threads: usize,
    /// Runs behind each median.
    pub runs: usize,
    /// One application of the operator, s (median).
    pub apply_s: f64,
    /// One padded 2N x 2N FFT round trip, s (median, the contact study's yardstick).
    pub fft_pair_s: f64,
    /// `solve_s / iterations / fft_pair_s`.
    pub iteration_per_fft_pair: f64,
    /// Peak resident memory of the process during this grid's sampling and solves, bytes
    /// (reset when the grid starts; the finest surface, generated first, is held throughout).
    pub peak_rss_bytes: Option<u64>,
    /// `area_fraction / reference - 1`.
    pub err_area: f64,
    /// `mean_gap_m / reference - 1`.
    pub err_gap: f64,
    /// The height array this row solved, when the run wrote them.
    pub surface_file: Option<PathBuf>,
}

/// The surface on the finest grid, heights in m.
pub fn finest_surface() -> Result<HeightMap, BenchError> {
    let n = ROUGH_SIZES[ROUGH_SIZES.len() - 1];
    let pixel = DOMAIN_M / n as f64;
    Ok(SelfAffine {
        roughness: Roughness::RmsSlope(RMS_SLOPE),
        hurst: HURST,
        short_cutoff_m: CELLS_PER_SHORT_CUTOFF as f64 * pixel,
        long_cutoff_m: DOMAIN_M / LONG_CUTOFF_REPEATS as f64,
        seed: SEED,
    }
    .generate(n, n, pixel, pixel)?)
}

fn repetitions(n: usize) -> usize {
    match n {
        0..=256 => 5,
        257..=512 => 3,
        _ => 1,
    }
}

/// The study; with `surfaces`, each grid's heights are also written there as
/// `rough-N.txt`, a text matrix in m (`tribosim run --surface FILE --pixel-um` reads it).
pub fn rough_rows(surfaces: Option<&Path>) -> Result<Vec<RoughRow>, BenchError> {
    let map = finest_surface()?;
    let (pair, _) = paper_hertz();
    let modulus = pair.reduced_modulus_pa;
    let mean_pa = REDUCED_PRESSURE * modulus * rms_slope(&map);
    let short = CELLS_PER_SHORT_CUTOFF as f64 * map.dx_m;
    let mut rows = Vec::new();
    for n in ROUGH_SIZES {
        let reset = reset_peak_rss();
        let grid = Grid::square(n, DOMAIN_M)?;
        let heights = grid.sample(|x, y| map.height_at(x, y));
        let surface_file = match surfaces {
            Some(dir) => Some(write_matrix(dir, n, grid.dx, &heights)?),
            None => None,
        };
        let top = heights.iter().fold(f64::MIN, |m, &h| m.max(h));
        let separation: Vec<f64> = heights.iter().map(|h| top - h).collect();
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: mean_pa * grid.area(),
            yield_pressure_pa: f64::INFINITY,
            pass_wear_per_pa: 0.0,
        };
        let build = || PeriodicHalfSpace::new(n, n, grid.dx, grid.dy, modulus);
        let reps = repetitions(n);
        let build_s = median_time(reps, || {
            std::hint::black_box(build());
        });
        let mut operator = build();
        let (solution, solve_s, solve_cpu_s) = timed_solves(&mut operator, &problem, reps)?;
        let peak_rss_bytes = peak_rss_since(reset);
        let apply_s = apply_time(&mut operator, &solution, reps);
        let mut fft = FftPair::new(n);
        let fft_pair_s = median_time(reps, || fft.round_trip());
        rows.push(RoughRow {
            study: "rough_grid",
            n,
            pixel_m: grid.dx,
            cells_per_short_cutoff: short / grid.dx,
            reduced_modulus_pa: modulus,
            mean_pressure_pa: mean_pa,
            tolerance: options().tolerance,
            area_fraction: solution.contact_area_m2(&grid) / grid.area(),
            mean_gap_m: mean_gap(&solution, &separation),
            iterations: solution.iterations,
            applies: solution.operator_applies,
            residual: solution.residual,
            wall_s: build_s + solve_s,
            solve_s,
            solve_cpu_s,
            threads: operator.threads(),
            runs: reps,
            apply_s,
            fft_pair_s,
            iteration_per_fft_pair: solve_s / solution.iterations as f64 / fft_pair_s,
            peak_rss_bytes,
            err_area: 0.0,
            err_gap: 0.0,
            surface_file,
        });
    }
    if let Some(reference) = rows.last().cloned() {
        for row in &mut rows {
            row.err_area = row.area_fraction / reference.area_fraction - 1.0;
            row.err_gap = row.mean_gap_m / reference.mean_gap_m - 1.0;
        }
    }
    Ok(rows)
}

/// `reps` cold solves of `problem`: the last solution, the median wall time and the median
/// CPU time.
fn timed_solves(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    reps: usize,
) -> Result<(ContactSolution, f64, Option<f64>), BenchError> {
    let (mut walls, mut cpus) = (Vec::with_capacity(reps), Vec::with_capacity(reps));
    let mut timed = || {
        let (cpu, started) = (thread_cpu_s(), Instant::now());
        let solution = solve(&mut *operator, problem, &options(), None);
        walls.push(started.elapsed().as_secs_f64());
        if let Some(spent) = thread_cpu_s()
            .zip(cpu)
            .map(|(after, before)| after - before)
        {
            cpus.push(spent);
        }
        solution
    };
    let mut solution = timed()?;
    for _ in 1..reps {
        solution = timed()?;
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let wall = median(walls).unwrap_or(f64::NAN);
    Ok((solution, wall, median(cpus)))
}

/// The mean over all cells of the gap `K p + h - delta`: zero in contact, the separation
/// the deformed surfaces keep elsewhere.
fn mean_gap(solution: &ContactSolution, separation: &[f64]) -> f64 {
    solution.gap_m(separation).iter().sum::<f64>() / separation.len() as f64
}

/// The median time of one operator application to the solution's pressure.
fn apply_time(operator: &mut dyn Operator, solution: &ContactSolution, reps: usize) -> f64 {
    let mut out = vec![0.0; solution.pressure.len()];
    median_time(reps.max(3), || operator.apply(&solution.pressure, &mut out))
}

/// Writes `heights` as `DIR/rough-N.txt`: one row per line, each height in the shortest
/// form that reads back to the same f64, so every solver gets the very same array.
fn write_matrix(
    dir: &Path,
    n: usize,
    pixel_m: f64,
    heights: &[f64],
) -> Result<PathBuf, BenchError> {
    let path = dir.join(format!("rough-{n}.txt"));
    let fail = |source| BenchError::Write {
        path: path.clone(),
        source,
    };
    std::fs::create_dir_all(dir).map_err(fail)?;
    let file = std::fs::File::create(&path).map_err(fail)?;
    let mut out = std::io::BufWriter::new(file);
    writeln!(
        out,
        "# tribosim bench rough: {n} x {n} heights in m, pixel {pixel_m:e} m, periodic"
    )
    .map_err(fail)?;
    for row in heights.chunks(n) {
        let line: Vec<String> = row.iter().map(|h| format!("{h:e}")).collect();
        writeln!(out, "{}", line.join(" ")).map_err(fail)?;
    }
    out.flush().map_err(fail)?;
    Ok(path)
}

/// The rows as a fixed-width table.
pub fn table(rows: &[RoughRow]) -> String {
    let mut out = String::new();
    if let Some(first) = rows.first() {
        out += &format!(
            "Rough flat on a flat, periodic: mean pressure {:.1} MPa, E* {:.1} GPa, \
             tolerance {:.0e}; errors against N = {}\n",
            first.mean_pressure_pa / 1e6,
            first.reduced_modulus_pa / 1e9,
            first.tolerance,
            rows.last().map_or(0, |r| r.n)
        );
    }
    out += "     N  cells/short  area frac  mean gap um   err area    err gap  iters  applies  wall s  threads  solve CPU s  apply ms  iter/pair  peak MB\n";
    for r in rows {
        out += &format!(
            "{:>6} {:>12.2} {:>10.5} {:>12.5} {:>+10.2e} {:>+10.2e} {:>6} {:>8} {:>7.3} {:>7} {:>12} {:>9.2} {:>10.2} {:>8}\n",
            r.n,
            r.cells_per_short_cutoff,
            r.area_fraction,
            r.mean_gap_m * 1e6,
            r.err_area,
            r.err_gap,
            r.iterations,
            r.applies,
            r.wall_s,
            r.threads,
            r.solve_cpu_s
                .map_or("n/a".to_owned(), |c| format!("{c:.3}")),
            r.apply_s * 1e3,
            r.iteration_per_fft_pair,
            r.peak_rss_bytes
                .map_or("n/a".to_owned(), |b| format!("{:.0}", b as f64 / 1e6)),
        );
    }
    out
}
