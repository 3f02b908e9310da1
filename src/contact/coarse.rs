//! A coarse-to-fine start for a cold solve: the same contact on a grid of half the cells
//! per side (each coarse cell the mean separation of the four fine cells it covers), solved
//! to a loose tolerance, its pressure interpolated bilinearly onto the fine cells. The fine
//! solve then starts near its answer instead of from a uniform pressure. Applied again on
//! the half grid down to [`COARSEST_CELLS`] per side, so each level starts warm too.
//!
//! The coarse solve only has to be as accurate as its own grid: its discretisation error
//! (1e-3 to 1e-4 of the peak pressure at 64 to 256 cells, `tribosim bench contact`) is
//! what the fine solve corrects, so [`COARSE_TOLERANCE`] is enough there.

use super::error::ContactError;
use super::fft::DcFft;
use super::grid::Grid;
use super::influence::Kernel;
use super::material::ElasticPair;
use super::problem::{ContactProblem, SolverOptions};
use super::solver::solve;

/// The smallest grid side a coarse level is made of: below it the coarse solve costs
/// more in set-up than it saves.
pub const COARSEST_CELLS: usize = 32;

/// The tolerance of the coarse solves: about the coarse grid's own error.
pub const COARSE_TOLERANCE: f64 = 1e-4;

/// The starting pressure for `problem` (on `pair`) from the solves on the coarser grids, or
/// `None` when the grid cannot be halved (an odd side, or under twice [`COARSEST_CELLS`]).
pub fn coarse_start(
    problem: &ContactProblem,
    pair: &ElasticPair,
    options: &SolverOptions,
) -> Result<Option<Vec<f64>>, ContactError> {
    let grid = problem.grid;
    let halves = |n: usize| n.is_multiple_of(2) && n / 2 >= COARSEST_CELLS;
    if !(halves(grid.nx) && halves(grid.ny)) {
        return Ok(None);
    }
    let coarse = Grid::new(grid.nx / 2, grid.ny / 2, 2.0 * grid.dx, 2.0 * grid.dy)?;
    let separation = restrict(&grid, &coarse, problem.separation);
    let coarse_problem = ContactProblem {
        grid: coarse,
        separation: &separation,
        ..*problem
    };
    let loose = SolverOptions {
        tolerance: options.tolerance.max(COARSE_TOLERANCE),
        ..*options
    };
    let start = coarse_start(&coarse_problem, pair, &loose)?;
    let mut operator = DcFft::new(&Kernel::normal(&coarse, pair));
    let solution = solve(&mut operator, &coarse_problem, &loose, start.as_deref())?;
    Ok(Some(prolong(&coarse, &grid, &solution.pressure)))
}

/// The start of a cold solve: [`coarse_start`]'s pressure, or `None` (the uniform start)
/// when the grid does not halve or a coarse level fails: a failed coarse solve only loses
/// the starting guess, never the fine solve, which reports its own errors.
pub fn cold_start(
    problem: &ContactProblem,
    pair: &ElasticPair,
    options: &SolverOptions,
) -> Option<Vec<f64>> {
    coarse_start(problem, pair, options).ok().flatten()
}

/// The mean of each 2 x 2 block of fine cells.
fn restrict(fine: &Grid, coarse: &Grid, field: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; coarse.len()];
    for (i, value) in field.iter().enumerate() {
        let (x, y) = (i % fine.nx, i / fine.nx);
        out[(y / 2) * coarse.nx + x / 2] += 0.25 * value;
    }
    out
}

/// Bilinear interpolation of a coarse field at the fine cells' centres, a quarter of a
/// coarse cell from the coarse centres (weights 3/4 and 1/4 per axis), with the edge
/// values held beyond the outermost centres.
fn prolong(coarse: &Grid, fine: &Grid, field: &[f64]) -> Vec<f64> {
    let neighbour = |i: usize, up: bool, n: usize| {
        if up {
            (i + 1).min(n - 1)
        } else {
            i.saturating_sub(1)
        }
    };
    (0..fine.len())
        .map(|i| {
            let (x, y) = (i % fine.nx, i / fine.nx);
            let (cx, cy) = (x / 2, y / 2);
            let nx = neighbour(cx, x % 2 == 1, coarse.nx);
            let ny = neighbour(cy, y % 2 == 1, coarse.ny);
            let at = |a: usize, b: usize| field[b * coarse.nx + a];
            0.5625 * at(cx, cy) + 0.1875 * (at(nx, cy) + at(cx, ny)) + 0.0625 * at(nx, ny)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{Hertz, Material, verify};

    fn paper_pair() -> ElasticPair {
        ElasticPair::new(
            Material::new(300e9, 0.21).expect("valid"),
            Material::new(205e9, 0.28).expect("valid"),
        )
    }

    #[test]
    fn restriction_averages_and_prolongation_keeps_linear_fields() {
        let fine = Grid::new(8, 6, 1e-6, 1e-6).expect("valid");
        let coarse = Grid::new(4, 3, 2e-6, 2e-6).expect("valid");
        let linear = |x: f64, y: f64| 3.0 + 2.0 * x + 5.0 * y;
        // Cell centres: the mean of the four fine centres is the coarse centre, and a
        // linear field is its own bilinear interpolant away from the held edges.
        let restricted = restrict(&fine, &coarse, &fine.sample(linear));
        let expected = coarse.sample(linear);
        for (r, e) in restricted.iter().zip(&expected) {
            assert!((r - e).abs() < 1e-12, "{r} vs {e}");
        }
        let prolonged = prolong(&coarse, &fine, &expected);
        let exact = fine.sample(linear);
        for i in 0..fine.len() {
            let (x, y) = (i % fine.nx, i / fine.nx);
            if (1..fine.nx - 1).contains(&x) && (1..fine.ny - 1).contains(&y) {
                assert!((prolonged[i] - exact[i]).abs() < 1e-12, "cell {i}");
            }
        }
    }

    #[test]
    fn a_coarse_started_solve_meets_the_same_conditions() {
        let pair = paper_pair();
        let hertz = Hertz {
            radius_m: 3e-3,
            load_n: 5.0,
            reduced_modulus_pa: pair.reduced_modulus_pa,
        };
        let grid = Grid::square(128, 0.256e-3).expect("valid");
        let separation = grid.sample(|x, y| hertz.separation_m(x, y));
        let problem = ContactProblem {
            grid,
            separation: &separation,
            load_n: 5.0,
            yield_pressure_pa: f64::INFINITY,
            pass_wear_per_pa: 0.0,
        };
        let options = SolverOptions::default();
        let start = coarse_start(&problem, &pair, &options)
            .expect("coarse solves converge")
            .expect("128 halves twice");
        let mut operator = DcFft::new(&Kernel::normal(&grid, &pair));
        let solution = solve(&mut operator, &problem, &options, Some(&start)).expect("converges");
        let check = verify(&mut operator, &problem, &solution);
        // The solver's tolerance, and the load to 1e-9 as the contact tests require.
        assert!(check.passes(options.tolerance, 1e-9), "{check:?}");
        let odd = Grid::square(63, 0.256e-3).expect("valid");
        let odd_separation = odd.sample(|x, y| hertz.separation_m(x, y));
        let odd_problem = ContactProblem {
            grid: odd,
            separation: &odd_separation,
            ..problem
        };
        assert!(
            coarse_start(&odd_problem, &pair, &options)
                .expect("nothing to solve")
                .is_none()
        );
    }
}
