//! A solve split across threads against the same solve on one thread: the FFT passes split
//! bit for bit, and the solver's own passes over a grid of `SPLIT_MIN_CELLS` cells or more
//! go in the same fixed blocks on one thread as on two, so the answer does not depend on the
//! thread count to the last bit.

mod common {
    pub mod physics;
}

use common::physics::{LOAD_N, paper_hertz as hertz, paper_pair};
use tribosim::contact::{
    ContactProblem, ContactSolution, DcFft, Grid, Kernel, SPLIT_MIN_CELLS, SolverOptions, solve,
};

/// The paper contact under the cap `cap` on `n` x `n` cells over a domain that keeps 44
/// cells per contact radius, with the FFT passes split `threads` ways.
fn paper_solve(n: usize, cap: f64, threads: usize) -> ContactSolution {
    let pair = paper_pair();
    let grid = Grid::square(n, n as f64 * 1e-6).expect("valid grid");
    let separation = grid.sample(|x, y| hertz(&pair, LOAD_N).separation_m(x, y));
    let mut operator = DcFft::new(&Kernel::normal(&grid, &pair)).threaded(threads);
    let problem = ContactProblem {
        grid,
        separation: &separation,
        load_n: LOAD_N,
        yield_pressure_pa: cap,
        pass_wear_per_pa: 0.0,
    };
    solve(&mut operator, &problem, &SolverOptions::default(), None).expect("converges")
}

/// The cells whose pressure differs between `one` and `two` in any bit, with both solves'
/// iterations and approaches required equal.
fn differing_cells(one: &ContactSolution, two: &ContactSolution) -> usize {
    assert_eq!(one.iterations, two.iterations);
    assert_eq!(one.approach_m.to_bits(), two.approach_m.to_bits());
    one.pressure
        .iter()
        .zip(&two.pressure)
        .filter(|(a, b)| a.to_bits() != b.to_bits())
        .count()
}

#[test]
fn a_solve_in_blocks_gives_the_same_bits_on_one_thread_and_on_two() {
    // The smallest square grid the solver's passes go in blocks on.
    let min = SPLIT_MIN_CELLS.expect("the passes split on large grids");
    let n = (min as f64).sqrt().ceil() as usize;
    // Capped (Y = H(10 cycles) / 2.8, Table 3): the load is restored by the shift. Elastic:
    // the step's own load sum rescales the pressures, so every pass's sums are used.
    for cap in [2551e6 / 2.8, f64::INFINITY] {
        let (one, two) = (paper_solve(n, cap, 1), paper_solve(n, cap, 2));
        assert_eq!(differing_cells(&one, &two), 0, "under the cap {cap} Pa");
    }
}
