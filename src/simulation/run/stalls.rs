//! The preconditioner a run's solves start on, chosen from how its last solves went.
//!
//! Each solve starts with the free-set correction ([`Preconditioning::FreeSet`]) and drops
//! it for the whole grid when it stalls (`contact::solver`). On some surfaces it stalls in
//! nearly every solve: on the rough example of `docs/scene.md` (2 um short cut-off, 768 x 768
//! cells), the plateaus that yielding cuts leave tens of thousands of cells at the cap whose
//! free set churns at every step, and 39 of its first 40 solves stalled, each after about
//! 12 iterations spent on the correction. So after a stall the next solves start on the
//! whole grid, and the run tries the correction again after them: one solve after the first
//! stall, twice as many after each stall of a retried correction, none once a retry
//! converges without stalling. A surface that always stalls pays for about `log2` of its
//! solves' stalls, and one that stalls in a few hard cycles keeps the correction. Measured
//! with `tribosim run`, solver iterations (the whole grid's conjugacy rule of `contact::solver`
//! in all):
//!
//! | Run | Free set always | Whole grid for good after 2 stalls in a row | Backing off |
//! |---|---|---|---|
//! | that example, 40 cycles | 2620 | 2173 | 2199 |
//! | 4 um rough disc of `docs/accuracy.md`, 150 cycles | 1578 | 2270 | 1546 |
//! | the paper scene (smooth), 600 cycles | 596 | 596 | 596 |
//!
//! The 4 um disc stalls in its second and third solves, while the asperities first
//! flatten: for good on the whole grid, it stays there for its other 147 solves, which
//! converge faster with the correction.

use crate::contact::{ContactSolution, Preconditioning, SolverOptions};

/// The stalls of a run's solves so far, and the preconditioner they choose.
#[derive(Debug, Default)]
pub(super) struct Stalls {
    /// Solves still to start on the whole grid before the correction is tried again.
    whole_grid_left: usize,
    /// How many solves the last stall of the correction sent to the whole grid (0 once a
    /// solve with it converged without stalling).
    backoff: usize,
    /// Solves that stalled with the free-set correction and fell back to the whole grid.
    fallback_solves: usize,
    /// Solves that started on the whole grid after a stall.
    whole_grid_solves: usize,
    /// Solves whose warm start stalled on the whole grid and began again uniform.
    restarted_solves: usize,
}

impl Stalls {
    /// The solver options of the next solve: the run's `options`, on the whole grid while
    /// a stall's solves last.
    pub(super) fn options(&self, options: &SolverOptions) -> SolverOptions {
        if self.whole_grid_left == 0 {
            return *options;
        }
        SolverOptions {
            preconditioning: Preconditioning::WholeGrid,
            ..*options
        }
    }

    /// Records how `solution`'s solve, started with [`Self::options`], went.
    pub(super) fn record(&mut self, solution: &ContactSolution) {
        self.restarted_solves += usize::from(solution.uniform_restarts > 0);
        if self.whole_grid_left > 0 {
            self.whole_grid_left -= 1;
            self.whole_grid_solves += 1;
        } else if solution.preconditioner_fallbacks > 0 {
            self.fallback_solves += 1;
            self.backoff = (2 * self.backoff).max(1);
            self.whole_grid_left = self.backoff;
        } else {
            self.backoff = 0;
        }
    }

    /// The clauses of the `solve_window` model that say how the solves stalled, if they
    /// did, out of the run's `solves`: each begins with "; ".
    pub(super) fn describe(&self, solves: usize) -> String {
        let mut clauses = String::new();
        if self.fallback_solves > 0 {
            clauses += &format!(
                "; the free-set preconditioner stalled and fell back to the whole grid in {} of {} solves",
                self.fallback_solves, solves
            );
        }
        if self.whole_grid_solves > 0 {
            clauses += &format!(
                "; after each stall the next solves started on the whole grid (one after the first, twice as many after each stall of a retried correction): {} of {} solves",
                self.whole_grid_solves, solves
            );
        }
        if self.restarted_solves > 0 {
            clauses += &format!(
                "; a warm start stalled on the whole grid and the solve began again from the uniform pressure in {} of {} solves",
                self.restarted_solves, solves
            );
        }
        clauses
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Preconditioning::{FreeSet, WholeGrid};

    fn solution(fallbacks: usize, restarts: usize) -> ContactSolution {
        ContactSolution {
            pressure: Vec::new(),
            displacement: Vec::new(),
            approach_m: 0.0,
            iterations: 1,
            operator_applies: 1,
            residual: 0.0,
            preconditioner_fallbacks: fallbacks,
            uniform_restarts: restarts,
        }
    }

    #[test]
    fn a_stall_sends_the_next_solves_to_the_whole_grid_doubling_while_retries_stall() {
        let base = SolverOptions::default();
        let mut stalls = Stalls::default();
        // Each solve: did it fall back, and which preconditioner did the one after start on?
        let solves = [
            (1, WholeGrid), // the first stall: one solve on the whole grid
            (0, FreeSet),
            (1, WholeGrid), // the retry stalled: two
            (0, WholeGrid),
            (0, FreeSet),
            (0, FreeSet), // the retry converged: the backoff is forgotten
            (1, WholeGrid),
            (0, FreeSet),
        ];
        for (i, (fallbacks, next)) in solves.into_iter().enumerate() {
            stalls.record(&solution(fallbacks, usize::from(i == 1)));
            assert_eq!(
                stalls.options(&base).preconditioning,
                next,
                "after solve {}",
                i + 1
            );
        }
        assert_eq!(
            stalls.describe(8),
            "; the free-set preconditioner stalled and fell back to the whole grid in 3 of 8 solves\
             ; after each stall the next solves started on the whole grid (one after the first, twice as many after each stall of a retried correction): 4 of 8 solves\
             ; a warm start stalled on the whole grid and the solve began again from the uniform pressure in 1 of 8 solves"
        );
    }

    #[test]
    fn a_run_without_stalls_says_nothing_of_them() {
        let mut stalls = Stalls::default();
        stalls.record(&solution(0, 0));
        assert_eq!(stalls.describe(1), "");
    }
}
