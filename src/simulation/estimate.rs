//! What a run will cost before it starts: its solves, its wall time and the size of its
//! result, extrapolated from two measured runs of the paper's scene (of the rig's default
//! scene on the reciprocating rig), and its peak memory, from the cells of its grid (and of
//! its wear map on the rig). A rough guide (a factor of about three either way), for a
//! warning before a long run and the service's memory budget, not a schedule.

use super::sizing::GridPlan;
use crate::contact::Grid;
use crate::scene::{CycleStep, DomainSize, Scene};

/// The paper's scene (the defaults: auto grid of [`PAPER_CELLS`] cells, auto stepping) run
/// with `tribosim run '-' -o result.json` at two lengths, on the development machine (2
/// cores shared with other builds): 3600 cycles in 464 solves, 5.9 s and a 1,010,628-byte
/// result; 36,000 cycles in 3175 solves, 59.1 s and 2,708,393 bytes. The power laws below
/// pass through both points. A quiet machine is faster (the 3600-cycle run used 2.15 s of
/// CPU for its 5.9 s), and the paper's groove, which keeps widening, sets the step sizes.
const MEASURED_CYCLES: [f64; 2] = [3600.0, 36_000.0];
/// Solves of the two measured runs (see [`MEASURED_CYCLES`]).
const MEASURED_SOLVES: [f64; 2] = [464.0, 3175.0];
/// Wall time of the two measured runs, s (see [`MEASURED_CYCLES`]).
const MEASURED_WALL_S: [f64; 2] = [5.9, 59.1];
/// Cells per side of the paper's first grid (its `grid` model: 144 x 144).
const PAPER_CELLS: f64 = 144.0;
/// Bytes of one cycle record in the pretty-printed result: 1,591,352 bytes for the 3175
/// records of the 36,000-cycle run (501), 233,346 for 464 at 3600 (503).
const RECORD_BYTES: f64 = 502.0;
/// Bytes of the rest of the result, mostly the two pressure maps and the profiles: 777 kB
/// at 3600 cycles, 937 kB at 36,000 (the maps grow with the domain); the larger is taken.
const OTHER_BYTES: f64 = 937e3;

/// Peak memory per cell of the contact grid, bytes: the upper envelope of the paper's scene
/// run for 2 cycles at a fixed grid, peak RSS by `/usr/bin/time -f %M tribosim run`:
/// 47.9 MB at 256 cells per side (730 B a cell), 216 MB at 512 (825), 752 MB at 1024 (717),
/// 2.99 GB at 2048 (713). The FFT's padded transforms of the influence coefficients and
/// the pressures dominate, which is why the cost goes as the cells.
const PEAK_BYTES_PER_CELL: f64 = 830.0;
/// Memory a run holds whatever its grid, bytes: the program, the cycle records and the
/// result as it is written (the 2048-cell run above held 3.5 GiB as a job of the service,
/// which keeps its cycles for event streams and writes the result JSON from memory).
const BASE_PEAK_BYTES: f64 = 64e6;
/// How far an auto domain's cells may multiply as the groove widens it: the side doubles at
/// most in the paper's scene over 36,000 cycles, and the cells go as its square.
const AUTO_DOMAIN_CELL_GROWTH: f64 = 4.0;

/// The rig's default scene (a 5 mm stroke at 1 Hz, sinusoidal; auto grid of
/// [`STROKE_MEASURED_CELLS`], auto stepping and tolerance) run with `tribosim run` at two
/// lengths on the development machine (2 cores): 50 cycles in 21 solved cycles (2018
/// positions solved), 1000 cycles in 123 solved cycles (9621 positions). The times are
/// those of the rig's earlier defaults (bound 0.01, 1e-6: 3.7 s and 41.0 s, the machine
/// quiet), scaled by the ratio of the CPU times of the two defaults run in one session
/// (1.50 / 2.40 s and 15.75 / 24.30 s), then by that of the solves on windows to those on
/// the whole grid (medians of three alternating pairs: 1.02 / 1.50 s and 8.02 / 15.71 s),
/// so that every measured time here stands on the same machine's speed, which moves by
/// tens of percent from session to session. A solved
/// cycle solves the positions near the ends, whose number does not depend on the stroke's
/// length; its cost grows as the worn contact widens.
const STROKE_MEASURED_CYCLES: [f64; 2] = [50.0, 1000.0];
/// Solved cycles of the two measured rig runs (see [`STROKE_MEASURED_CYCLES`]).
const STROKE_MEASURED_SOLVED: [f64; 2] = [21.0, 123.0];
/// Time of the two measured rig runs, s (see [`STROKE_MEASURED_CYCLES`]).
const STROKE_MEASURED_WALL_S: [f64; 2] = [
    3.7 * (1.50 / 2.40) * (1.02 / 1.50),
    41.0 * (15.75 / 24.30) * (8.02 / 15.71),
];
/// Positions solved per solved cycle with both sweeps of every cycle solved (`cycle_step:
/// 1`) over those of the measured runs, whose returns mostly press the forward sweep again:
/// 144,798 positions in 1000 cycles (`scripts/stroke_step_bound.py`'s reference) against
/// 9621 in 123 solved cycles.
const STROKE_BOTH_SWEEPS_FACTOR: f64 = (144_798.0 / 1000.0) / (9621.0 / 123.0);
/// Cells per side of the measured rig runs' first grid (16 per contact radius).
const STROKE_MEASURED_CELLS: f64 = 48.0;
/// Positions a sweep visits on the measured rig runs' first grid: one per cell of 2.763 um
/// along the 5 mm stroke.
const STROKE_MEASURED_POSITIONS: f64 = 1810.0;
/// CPU time a sweep spends at a position whatever it solves (the flat under the contact
/// read, compared and pressed into the map), s on 48 x 48 cells: 20% of the profile
/// (`perf record`) of a 75 mm stroke run for 2 cycles, 12.5 s over 4 sweeps of 27,192
/// positions, measured with a solve considered at each position (now at every
/// `simulation::SOLVE_EVERY_POSITIONS`: an upper bound; the run took 11.8 s after).
const STROKE_POSITION_S: f64 = 23e-6;
/// CPU time a traced cycle (200 samples of the potential) spends per position of the
/// stroke, s: 51% of the profile of the same 75 mm run, whose 2 cycles were both traced, in
/// 2.05 s, once the rows sharing a chord were merged (19e-6 s), on the scale of
/// [`STROKE_MEASURED_WALL_S`] (times 41.0 / 24.30).
const STROKE_TRACE_S_PER_POSITION: f64 = 32e-6;
/// How far the rig's auto grid grew in cells over the measured 1000 strokes: from 48 x 48
/// to 96 x 128; the wear map's rows grew as the grid's (48 to 128).
const STROKE_CELL_GROWTH: f64 = 96.0 * 128.0 / (48.0 * 48.0);
/// Rows of the rig's wear map at the end of the measured 1000 strokes over its first rows.
const STROKE_ROW_GROWTH: f64 = 128.0 / 48.0;
/// Peak memory per cell of the rig's wear map, bytes: a 75 mm stroke on 48 rows of 2.763 um
/// (1.31 million map cells) run for 2 cycles peaked at 87.3 MB, 70.4 MB above the
/// 16.9 MB of the 5 mm stroke's run (54 B a cell, rounded up: the map's copies of
/// `simulation::stroke_checks`, the exposure's points, and the forward sweep's pressure
/// integral kept for its return).
const STROKE_PEAK_BYTES_PER_MAP_CELL: f64 = 55.0;
/// Bytes of the result's `stroke` section, pretty-printed: 754 kB at 50 cycles, 1.36 MB at
/// 1000 (the map has a row per grid row, which grew); the larger, rounded up.
const STROKE_SECTION_BYTES: f64 = 1.4e6;

/// What a run is expected to cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunEstimate {
    /// Solved cycles (one cycle record each); on the reciprocating rig, each solves the
    /// contact at many positions.
    pub solves: u64,
    /// Wall time, s.
    pub wall_s: f64,
    /// Size of the result JSON as `tribosim run` writes it, bytes.
    pub bytes: f64,
    /// Peak memory of the run, bytes: what the service budgets its jobs by.
    pub memory_bytes: f64,
}

/// The power law through two measured runs, `values` at `measured` cycles, at `cycles`.
fn power_law(measured: [f64; 2], values: [f64; 2], cycles: f64) -> f64 {
    let exponent = (values[1] / values[0]).ln() / (measured[1] / measured[0]).ln();
    values[0] * (cycles / measured[0]).powf(exponent)
}

/// The estimate for `scene` on its first grid.
pub fn estimate(scene: &Scene, grid: &GridPlan) -> RunEstimate {
    if scene.test.reciprocating.is_some() {
        stroke_estimate(scene, grid)
    } else {
        disc_estimate(scene, grid.cells)
    }
}

/// The estimate for a disc on a first grid of `cells` per side.
fn disc_estimate(scene: &Scene, cells: usize) -> RunEstimate {
    let cycles = scene.test.cycles as f64;
    let power = |values| power_law(MEASURED_CYCLES, values, cycles);
    let auto_solves = power(MEASURED_SOLVES);
    let solves = match scene.numerics.solve_cycle_step(scene.numerics_case()) {
        CycleStep::EveryCycle => cycles,
        CycleStep::Auto => auto_solves.clamp(1.0, cycles),
    };
    // A solve's cost grows with the domain as the groove widens (wall time per solve over
    // solves per cycle), and with the cells of the grid (the FFT's N^2 log N, taken as N^2).
    let per_solve_s = power(MEASURED_WALL_S) / power(MEASURED_SOLVES);
    let grid = (cells as f64 / PAPER_CELLS).powi(2);
    let growth = match scene.numerics.domain_um {
        DomainSize::Auto => AUTO_DOMAIN_CELL_GROWTH,
        DomainSize::Micrometres(_) => 1.0,
    };
    let cells_then = (cells as f64).powi(2) * growth;
    let cells_max = (Grid::MAX_CELLS_PER_SIDE as f64).powi(2);
    RunEstimate {
        solves: solves.round() as u64,
        wall_s: solves * per_solve_s * grid,
        bytes: solves * RECORD_BYTES + OTHER_BYTES,
        memory_bytes: BASE_PEAK_BYTES + PEAK_BYTES_PER_CELL * cells_then.min(cells_max),
    }
}

/// The estimate for the reciprocating rig of `scene` on its first grid: the measured
/// runs' cost per solved cycle, scaled as the cube of the cells per side (the positions
/// near the ends go as the density, a solve as its square; `docs/rig-accuracy.md`), plus what
/// a stroke longer than the measured one adds at each position of each sweep and trace.
fn stroke_estimate(scene: &Scene, grid: &GridPlan) -> RunEstimate {
    let cycles = scene.test.cycles as f64;
    let power = |values| power_law(STROKE_MEASURED_CYCLES, values, cycles);
    let auto_solved = power(STROKE_MEASURED_SOLVED).clamp(1.0, cycles);
    let (solved, sweeps) = match scene.numerics.solve_cycle_step(scene.numerics_case()) {
        CycleStep::EveryCycle => (cycles, STROKE_BOTH_SWEEPS_FACTOR),
        CycleStep::Auto => (auto_solved, 1.0),
    };
    let per_solved_s = power(STROKE_MEASURED_WALL_S) / power(STROKE_MEASURED_SOLVED);
    let density = grid.cells as f64 / STROKE_MEASURED_CELLS;
    let cell_m = grid.domain_m / grid.cells as f64;
    let length_m = scene.stroke().map_or(0.0, |stroke| stroke.length_m);
    let positions = length_m / cell_m;
    let traced = scene.record_cycles().len() as f64 + 2.0;
    let extra_positions = (positions - STROKE_MEASURED_POSITIONS).max(0.0);
    let extra_s = extra_positions
        * (2.0 * solved * STROKE_POSITION_S * density.powi(2)
            + traced * STROKE_TRACE_S_PER_POSITION);
    let growth = match scene.numerics.domain_um {
        DomainSize::Auto => (STROKE_CELL_GROWTH, STROKE_ROW_GROWTH),
        DomainSize::Micrometres(_) => (1.0, 1.0),
    };
    let cells = (grid.cells as f64).powi(2);
    let cells_max = (Grid::MAX_CELLS_PER_SIDE as f64).powi(2);
    let map_cells = (positions + grid.cells as f64) * grid.cells as f64 * growth.1;
    RunEstimate {
        solves: solved.round() as u64,
        wall_s: solved * sweeps * per_solved_s * density.powi(3) + extra_s,
        bytes: solved * RECORD_BYTES + OTHER_BYTES + STROKE_SECTION_BYTES,
        memory_bytes: BASE_PEAK_BYTES
            + PEAK_BYTES_PER_CELL * (cells * growth.0).min(cells_max)
            + STROKE_PEAK_BYTES_PER_MAP_CELL * map_cells,
    }
}

/// `seconds` as a person reads it: "40 s", "12 min", "3.2 h".
pub fn describe_duration(seconds: f64) -> String {
    if seconds < 90.0 {
        format!("{seconds:.0} s")
    } else if seconds < 5400.0 {
        format!("{:.0} min", seconds / 60.0)
    } else {
        format!("{:.1} h", seconds / 3600.0)
    }
}

/// `bytes` as a person reads it: "940 kB", "27 MB".
pub fn describe_size(bytes: f64) -> String {
    if bytes < 1e6 {
        format!("{:.0} kB", bytes / 1e3)
    } else if bytes < 1e9 {
        format!("{:.0} MB", bytes / 1e6)
    } else {
        format!("{:.1} GB", bytes / 1e9)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_passes_through_the_measured_runs() {
        let mut scene = Scene::default();
        for (i, cycles) in MEASURED_CYCLES.into_iter().enumerate() {
            scene.test.cycles = cycles as u64;
            let e = disc_estimate(&scene, PAPER_CELLS as usize);
            // The power laws pass through both points: exact but for rounding (1e-9).
            assert_eq!(e.solves, MEASURED_SOLVES[i] as u64);
            assert!((e.wall_s / MEASURED_WALL_S[i] - 1.0).abs() < 1e-9, "{e:?}");
        }
    }

    #[test]
    fn every_cycle_solves_each_and_costs_more() {
        let mut scene = Scene::default();
        scene.test.cycles = 36_000;
        let auto = disc_estimate(&scene, 144);
        scene.numerics.cycle_step = CycleStep::EveryCycle;
        let every = disc_estimate(&scene, 144);
        assert_eq!(every.solves, 36_000);
        assert!(every.wall_s > auto.wall_s && every.bytes > auto.bytes);
        // A grid of half the cells per side costs a quarter.
        let half = disc_estimate(&scene, 72);
        assert!((half.wall_s / every.wall_s - 0.25).abs() < 1e-12);
    }

    #[test]
    fn the_memory_estimate_lies_above_each_measured_peak() {
        // Peak RSS of `tribosim run` on the paper's scene for 2 cycles at a fixed grid
        // (the measurements of PEAK_BYTES_PER_CELL), bytes.
        let measured = [
            (256, 47.9e6),
            (512, 216.2e6),
            (1024, 752.1e6),
            (2048, 2994.3e6),
        ];
        let mut scene = Scene::default();
        scene.test.cycles = 2;
        scene.numerics.domain_um = DomainSize::Micrometres(150.0);
        for (cells, peak) in measured {
            let estimate = disc_estimate(&scene, cells).memory_bytes;
            // Above each, and not so far above that it refuses what the machine can run: the
            // per-cell figure is within 20% of each point's own (830 against 713 to 825
            // bytes), so the estimate is within the base and 1.2 times the peak.
            assert!(
                estimate > peak && estimate <= BASE_PEAK_BYTES + 1.2 * peak,
                "{cells}: {estimate:e} against {peak:e}"
            );
        }
        // An auto domain may grow: its cells are budgeted four times over.
        scene.numerics.domain_um = DomainSize::Auto;
        let auto = disc_estimate(&scene, 512).memory_bytes;
        assert!((auto - (BASE_PEAK_BYTES + 4.0 * 512.0 * 512.0 * PEAK_BYTES_PER_CELL)).abs() < 1.0);
    }

    /// The rig's default scene on the measured runs' first grid (48 cells of 2.763 um).
    fn rig(cycles: u64, stroke_mm: f64) -> (Scene, GridPlan) {
        let mut scene = Scene::default();
        scene.test.cycles = cycles;
        scene.test.reciprocating = Some(crate::scene::Reciprocating {
            stroke_mm,
            ..crate::scene::Reciprocating::default()
        });
        let grid = GridPlan {
            cells: 48,
            domain_m: 48.0 * 2.763e-6,
            how: String::new(),
        };
        (scene, grid)
    }

    #[test]
    fn the_rig_estimate_passes_through_its_measured_runs() {
        for (i, cycles) in STROKE_MEASURED_CYCLES.into_iter().enumerate() {
            let (scene, grid) = rig(cycles as u64, 5.0);
            let e = estimate(&scene, &grid);
            assert_eq!(e.solves, STROKE_MEASURED_SOLVED[i] as u64);
            // Exact but for rounding: the 5 mm stroke is 1809.6 cells, within the measured
            // 1810 positions, so no position is added.
            assert!(
                (e.wall_s / STROKE_MEASURED_WALL_S[i] - 1.0).abs() < 1e-9,
                "{e:?}"
            );
        }
    }

    #[test]
    fn the_rig_memory_estimate_lies_above_its_measured_peaks() {
        // Peak RSS of `tribosim run`, bytes: 1000 cycles of 5 mm (the grid grew to 96 x
        // 128) and 2 cycles of 75 mm (the map of 1.31 million cells).
        for (cycles, stroke_mm, peak) in [(1000, 5.0, 33.6e6), (2, 75.0, 87.3e6)] {
            let (scene, grid) = rig(cycles, stroke_mm);
            let e = estimate(&scene, &grid);
            assert!(e.memory_bytes > peak, "{stroke_mm} mm: {e:?}");
        }
        // The longer stroke's time grows with its positions: 2 cycles of 75 mm took 2.05 s,
        // 3.46 s on the scale of the measured runs (times 41.0 / 24.30), and the estimate
        // is within the factor of three the module claims.
        let (scene, grid) = rig(2, 75.0);
        let wall_s = estimate(&scene, &grid).wall_s;
        assert!(wall_s > 3.46 / 3.0 && wall_s < 3.46 * 3.0, "{wall_s}");
    }

    #[test]
    fn durations_and_sizes_read_in_their_unit() {
        assert_eq!(describe_duration(40.0), "40 s");
        assert_eq!(describe_duration(1640.0), "27 min");
        assert_eq!(describe_duration(9000.0), "2.5 h");
        assert_eq!(describe_size(937e3), "937 kB");
        assert_eq!(describe_size(26.6e6), "27 MB");
    }
}
