//! The guard against a solve that has stopped converging: the best relative residual of
//! the last [`STALL_ITERATIONS`] iterations must fall below [`STALL_FACTOR`] times the best
//! before them. When it does not, the solve falls back to a step known to converge
//! (`PolonskyKeer::fall_back`).
//!
//! The two numbers come from residual traces (every iteration of every solve) of solves
//! that converge and of solves that stall. Over 10 iterations, the best residual of a
//! converging solve fell at worst to 0.020 of its value in the cold rough solves of
//! `tests/stability_rough.rs` (free-set preconditioner; 0.068 on the whole grid), and below
//! 0.012 over 5 iterations in the warm solves of `tribosim run scenes/dalmau2018.json`. The
//! stalling solves, the second and third cycles of the rough discs of `tests/hard_cases.rs`
//! on the free-set preconditioner alone (12 solves cut at 60 iterations, one of which never
//! improved on its start in 2000), first failed to halve their best residual over 10
//! iterations at iteration 10 to 18. Halving over 10 iterations asks 7 times less than the
//! slowest converging solve did, and stops a stalled solve within about 10 iterations of
//! its last gain.
//!
//! A warm start's first residuals are the guess's, not the iteration's: its first steps
//! rebuild the bounds the guess carried over ([`WARM_SETTLING_ITERATIONS`]).

use super::super::operator::Operator;
use super::PolonskyKeer;
use super::bounds::rescale_to_load;

/// Iterations over which the best residual must fall by [`STALL_FACTOR`].
pub(super) const STALL_ITERATIONS: usize = 10;

/// The factor the best residual must fall by over [`STALL_ITERATIONS`].
pub(super) const STALL_FACTOR: f64 = 0.5;

/// The residuals of a warm-started solve left out of the stall test: that of the start and
/// of the first step after it.
///
/// A wear cycle's warm start carries over the last cycle's bounds, which yielding and wear
/// have since moved. Traced on cycle 59 of the rough example of `docs/scene.md` (2 um short
/// cut-off; capped cells, residual): the start had 24,144 capped cells at 1.0e-2; the first
/// step released nearly all of them (950 capped, 2.6e-2, then 3), the next put 14,595 back
/// (5.8e-2), and from there the residual fell to 7.3e-3 by the 11th iteration. Judged
/// against the start, that was a stall, and the solve began again from the uniform pressure
/// (2.0), which took 65 more iterations to converge. Measured with `tribosim run`
/// (iterations; solves restarted from the uniform pressure) for 0 / 1 / 2 / 3 / 5
/// residuals left out: that example over 40 cycles 2199 (26) / 1935 (13) / 1828 (8) /
/// 1835 (8) / 1836 (7); the 4 um rough disc of `docs/accuracy.md` over 150 cycles 1546 /
/// 1548 / 1557 / 1558 / 1558; the paper scene over 600 cycles 596 in all. That example
/// over its 3600 cycles, at 2: 39,127 -> 34,461 iterations (14,553 -> 8,930 in the first 400
/// cycles), 2536 -> 2650 solves (the cycle steps follow the slightly different pressures),
/// 1417 -> 1366 s with both runs side by side on the 2 cores. A stall of a warm
/// start is still caught: the cycling at residuals of 0.17 to 0.85 that
/// `PolonskyKeer::fall_back` describes never halves its best.
pub(super) const WARM_SETTLING_ITERATIONS: usize = 2;

/// The share of the free cells a step must move other than along its direction (truncated
/// at a bound or re-entering) to restart the conjugacy on the whole-grid preconditioner.
///
/// Polonsky and Keer restart at any re-entry. A solve that stalled on a rough disc under
/// the cap then restarted at every iteration to its end, as a few of the tens of thousands
/// of cells on the plateaus that yielding cut re-entered at each step: preconditioned
/// steepest descent, a residual falling by about 0.8 an iteration. Measured on the rough
/// example of `docs/scene.md` over 40 cycles (`tribosim run`, 40 solves), iterations with
/// the conjugacy kept below each share (the free-set correction's restarts unchanged):
/// 4075 at 0 (restart at any re-entry), 2897 at 0.01, 2620 at 0.05, 2751 at 0.1, 3097 at
/// 0.2. With the correction the same rule slows converging solves (the 4 um rough disc of
/// `docs/accuracy.md`, 150 cycles: 1615 -> 2442 iterations at 0.05; the paper scene's 600
/// cycles: 596 -> 703), so it holds on the whole grid alone.
pub(super) const CONJUGACY_RESTART_SHARE: f64 = 0.05;

/// Whether a step that moved `moved` cells other than along its direction, some of them
/// re-entering, restarts the conjugacy, with `free_cells` free and the free-set correction
/// in use (`corrected`) or not.
pub(super) fn restarts_conjugacy(moved: usize, free_cells: f64, corrected: bool) -> bool {
    corrected || moved as f64 >= CONJUGACY_RESTART_SHARE * free_cells
}

/// The best residual of each of the last [`STALL_ITERATIONS`] + 1 iterations.
#[derive(Debug)]
pub(super) struct Progress {
    /// The best residual up to iteration `i`, at `i % (STALL_ITERATIONS + 1)`.
    best: [f64; STALL_ITERATIONS + 1],
    /// Residuals recorded.
    recorded: usize,
    /// Residuals still to leave out before recording.
    settling: usize,
}

impl Progress {
    /// No residual recorded yet; from a `warm` start the first [`WARM_SETTLING_ITERATIONS`]
    /// are left out.
    pub(super) fn new(warm: bool) -> Self {
        Self {
            best: [f64::INFINITY; STALL_ITERATIONS + 1],
            recorded: 0,
            settling: if warm { WARM_SETTLING_ITERATIONS } else { 0 },
        }
    }

    /// Records the residual of the next iteration. True when the best residual has fallen
    /// by less than [`STALL_FACTOR`] over the last [`STALL_ITERATIONS`] iterations; never
    /// while settling.
    pub(super) fn stalled(&mut self, residual: f64) -> bool {
        if self.settling > 0 {
            self.settling -= 1;
            return false;
        }
        let slots = STALL_ITERATIONS + 1;
        let slot = self.recorded % slots;
        let last = self.best[(slot + STALL_ITERATIONS) % slots];
        let best = last.min(residual);
        self.best[slot] = best;
        self.recorded += 1;
        // The oldest slot holds the best of STALL_ITERATIONS iterations ago.
        self.recorded > STALL_ITERATIONS && best > STALL_FACTOR * self.best[(slot + 1) % slots]
    }
}

impl PolonskyKeer<'_> {
    /// The solve stalled. The first remedy drops the free-set correction, if any, and goes on
    /// preconditioned on the whole grid from a fresh direction. The second, for a solve
    /// that began from a warm start, starts again from the uniform pressure at the load, on
    /// the whole grid (true: the state must be measured afresh). After both, there is no
    /// safer step to take, and the solve goes on to its iteration limit.
    ///
    /// A warm start can hold the whole-grid iteration in a cycle: cycle 492 of the 4 um
    /// rough disc of `docs/accuracy.md` at `cycle_step_bound` 0.05, after a 5-cycle step,
    /// swung between 250 and 18,000 capped cells (the load's rescale pushing the free cells
    /// onto the cap, the re-entry rule releasing them) at residuals of 0.17 to 0.85 for 2000
    /// iterations. From the uniform pressure the same problem converged in 73.
    pub(super) fn fall_back(&mut self, operator: &mut dyn Operator) -> bool {
        if self.correction.take().is_some() {
            self.fell_back = true;
            self.restart = true;
            return false;
        }
        if !self.warm {
            return false;
        }
        self.warm = false;
        self.restarted = true;
        let n = self.p.len();
        self.p.fill(self.target / n as f64);
        rescale_to_load(
            self.blocks,
            &mut self.p,
            (self.cap, self.target),
            self.separation,
        );
        self.recompute(operator);
        self.progress = Progress::new(false);
        self.restart = true;
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_residual_halving_every_ten_iterations_is_progress_and_a_flat_one_is_not() {
        // Falling by 0.93 an iteration: 0.93^10 = 0.48 over ten, just past the factor.
        let mut falling = Progress::new(false);
        assert!((0..100).all(|i| !falling.stalled(0.93f64.powi(i))));
        // Flat after a good start: stalled exactly ten iterations after the last gain.
        let mut flat = Progress::new(false);
        let residuals = (0..30).map(|i| if i < 5 { 0.1f64.powi(i) } else { 1e-4 });
        let stalled: Vec<usize> = residuals
            .enumerate()
            .filter_map(|(i, r)| flat.stalled(r).then_some(i))
            .collect();
        assert_eq!(stalled.first(), Some(&14));
    }

    #[test]
    fn a_warm_start_is_judged_from_its_second_step_on() {
        // The trace of `WARM_SETTLING_ITERATIONS`: a good guess, two steps that rebuild the
        // bounds, then a residual halving every ten iterations.
        let settled = |i: i32| 2.6e-2 * 0.93f64.powi(i);
        let trace: Vec<f64> = [1.0e-2, 2.6e-2]
            .into_iter()
            .chain((0..40).map(settled))
            .collect();
        let mut cold = Progress::new(false);
        let stalled_cold = trace.iter().position(|&r| cold.stalled(r));
        assert!(
            stalled_cold.is_some(),
            "judged against the guess, it stalls"
        );
        let mut warm = Progress::new(true);
        assert!(
            trace.iter().all(|&r| !warm.stalled(r)),
            "judged from its steps, it converges"
        );
        // A warm start that never gains is still caught, two iterations later.
        let mut flat = Progress::new(true);
        let verdicts: Vec<bool> = (0..14).map(|_| flat.stalled(0.5)).collect();
        assert_eq!(verdicts.iter().position(|&v| v), Some(12));
    }

    #[test]
    fn a_rising_residual_is_judged_by_the_best_so_far() {
        // The residual rises after the first iteration: the best stays 1, so ten
        // iterations later the solve has stalled, however it wanders in between.
        let mut rising = Progress::new(false);
        let verdicts: Vec<bool> = (0..12)
            .map(|i| rising.stalled(1.0 + f64::from(i)))
            .collect();
        assert_eq!(verdicts.iter().position(|&v| v), Some(10));
    }
}
