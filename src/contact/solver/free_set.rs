//! The preconditioner corrected for the free set's edges
//! ([`crate::contact::Preconditioning::FreeSet`]).
//!
//! The conjugate gradient runs on the free cells `F`, where the ideal preconditioner is the
//! inverse of the operator's block `K_FF`. The operator's inverse on the whole grid,
//! `A = K^-1` ([`crate::contact::FourierInverse`]), offers its block `A_FF` instead; by block
//! inversion, with `C` the cells out of `F`,
//!
//! `(K_FF)^-1 = A_FF - A_FC (A_CC)^-1 A_CF`,
//!
//! so `A_FF` alone is wrong where `A` couples the free cells to the others: along the
//! contact's edges, where the solves' worst residuals sit (at the groove's rims in the
//! paper scene). The correction keeps the second term with `(A_CC)^-1` lumped to the
//! inverse of its row sums `rho_i = sum_{j in C} A_ij = -(A 1_F)_i` (`A 1 = 0`: the inverse
//! drops the mean). `A` is nearly local (its nearest neighbour is -0.16 of its diagonal,
//! the next below 0.003), so `rho` is a cell's own share of the complement: about 0.35 of
//! the diagonal beside a straight edge of a large contact, nearly all of it between small
//! islands. `rho` vanishes far from the contact, where `A_CF r` does too, and is floored
//! at [`ROW_SUM_FLOOR`] of the diagonal.
//!
//! With `r` the gap on the free cells (zero elsewhere) and `z = A r`, the corrected
//! direction is `A (r - s)` on `F`, where `s = z / max(rho, floor)` on `C`: one more apply
//! of the inverse; `rho` follows the free set by the near field of the cells that moved
//! (an apply of the inverse when many did). Measured with
//! `tribosim run scenes/dalmau2018.json` (`summary.iterations / summary.solves`) and
//! `tribosim bench rough` (N = 2048): 6.30 -> 4.70 iterations a warm solve, 67 -> 33 on
//! the rough flat (4.65 and 35 with `rho` summed afresh by an apply at every move); `rho`
//! kept from the solve's start instead gave 7.8 (the cells that left the free set carry
//! the row sum of a free cell).

use crate::contact::grid::Grid;
use crate::contact::{NEAR_REACH, Preconditioner};

/// The floor of the row sums, a share of the inverse's diagonal. Measured as above, `rho`
/// summed afresh at every move (warm iterations a solve / rough N = 2048 iterations): 0.5
/// gives 4.80 / 34, 0.25 gives 4.65 / 35, 0.1 gives 4.49 / 38, 0.02 gives 4.76 / 516 (a
/// large correction on the cells far from an island overshoots).
const ROW_SUM_FLOOR: f64 = 0.25;

/// The row sums of the inverse over the cells out of the free set, kept up to date with
/// the free set.
#[derive(Debug)]
pub(super) struct FreeSetCorrection {
    grid: Grid,
    /// `ROW_SUM_FLOOR` times the inverse's diagonal.
    floor: f64,
    /// The inverse's [`Preconditioner::near_field`].
    near: Vec<f64>,
    /// `A 1_F` (minus the row sums `rho`) for the free set of the last apply; zero, as for
    /// an empty free set, before it.
    free_response: Vec<f64>,
    /// The cells that joined (+1) or left (-1) the free set since the last apply.
    moved: Vec<(usize, f64)>,
}

impl FreeSetCorrection {
    /// The correction of `inverse` on `grid`.
    pub(super) fn new(inverse: &dyn Preconditioner, grid: Grid) -> Self {
        Self {
            grid,
            floor: ROW_SUM_FLOOR * inverse.diagonal(),
            near: inverse.near_field().to_vec(),
            free_response: vec![0.0; grid.len()],
            moved: Vec::new(),
        }
    }

    /// Records that `cell` joined (`true`) or left the free set, as the solver classifies
    /// the cells. Past as many cells as [`Self::follow`] updates one by one, the list stops
    /// growing ([`Self::most_recorded`]): the next apply sums afresh anyway.
    pub(super) fn record(&mut self, cell: usize, joined: bool) {
        if self.moved.len() <= self.most_moved() {
            self.moved.push((cell, if joined { 1.0 } else { -1.0 }));
        }
    }

    /// The most cells [`Self::record`] keeps between applies: one past [`Self::most_moved`],
    /// which tells [`Self::follow`] to sum afresh. A pass may stop collecting there.
    pub(super) fn most_recorded(&self) -> usize {
        self.most_moved() + 1
    }

    /// The most moved cells [`Self::follow`] updates by the near field: beyond, an apply of
    /// the inverse costs less than their near fields.
    fn most_moved(&self) -> usize {
        let side = 2 * NEAR_REACH + 1;
        self.grid.len() / (side * side)
    }

    /// `z = (K_FF)^-1 r` approximately on the free cells (`free`: 1 there, 0 elsewhere),
    /// from `r` the gap on them (zero elsewhere); `r` is left holding the correction's input,
    /// `r` on the free cells and `-s` off them.
    pub(super) fn apply(
        &mut self,
        inverse: &mut dyn Preconditioner,
        free: &[f64],
        r: &mut [f64],
        z: &mut [f64],
    ) {
        inverse.apply(r, z);
        self.follow(inverse, free);
        let floor = self.floor;
        for ((ri, &zi), (&fi, &response)) in r
            .iter_mut()
            .zip(z.iter())
            .zip(free.iter().zip(&self.free_response))
        {
            *ri += (1.0 - fi) * (-zi / (-response).max(floor));
        }
        inverse.apply(r, z);
    }

    /// Brings `A 1_F` to the free set `free` by adding the near field of each cell that
    /// moved, or by an apply of the inverse when many did. The near field leaves out the
    /// inverse's tail beyond [`NEAR_REACH`] cells (a few hundredths of the diagonal, spread
    /// over the grid), and each solve starts afresh.
    fn follow(&mut self, inverse: &mut dyn Preconditioner, free: &[f64]) {
        if self.moved.len() > self.most_moved() {
            inverse.apply(free, &mut self.free_response);
            self.moved.clear();
            return;
        }
        let side = 2 * NEAR_REACH + 1;
        let nx = self.grid.nx;
        let wrap = |i: usize, n: usize| (i as isize - NEAR_REACH as isize).rem_euclid(n as isize);
        // Row by row, and a cell away from the side edges as one run of the row: indexed
        // entry by entry, with a wrap-around division for each, this loop was a fifth of
        // the solver's serial samples on the 2 um example's grown grid (`perf annotate` of
        // `tribosim run scenes/bench-rough-2um-300um.json`). The sums are the same.
        for &(cell, sign) in &self.moved {
            let (x, y) = (cell % nx, cell / nx);
            for (dy, near) in self.near.chunks_exact(side).enumerate() {
                let row = wrap(y + dy, self.grid.ny) as usize;
                let row = &mut self.free_response[row * nx..][..nx];
                if x >= NEAR_REACH && x + NEAR_REACH < nx {
                    let run = &mut row[x - NEAR_REACH..][..side];
                    for (out, &a) in run.iter_mut().zip(near) {
                        *out += sign * a;
                    }
                } else {
                    for (dx, &a) in near.iter().enumerate() {
                        row[wrap(x + dx, nx) as usize] += sign * a;
                    }
                }
            }
        }
        self.moved.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A preconditioner known only by its near field: numbered entries, so that an entry
    /// added to the wrong cell shows.
    struct Numbered(Vec<f64>);

    impl Preconditioner for Numbered {
        fn apply(&mut self, _input: &[f64], _output: &mut [f64]) {
            unreachable!("the test moves fewer cells than an apply takes");
        }
        fn diagonal(&self) -> f64 {
            1.0
        }
        fn near_field(&self) -> &[f64] {
            &self.0
        }
    }

    #[test]
    fn the_near_field_of_a_moved_cell_wraps_around_the_grid_as_entry_by_entry() {
        let side = 2 * NEAR_REACH + 1;
        let mut inverse = Numbered((1..=side * side).map(|k| k as f64).collect());
        let grid = Grid::new(20, 12, 1e-6, 1e-6).expect("valid");
        let mut correction = FreeSetCorrection::new(&inverse, grid);
        // Corners, side edges, the first and last rows, the middle; one cell twice.
        let moved = [
            (0, 0),
            (19, 11),
            (1, 5),
            (18, 6),
            (9, 0),
            (9, 11),
            (9, 5),
            (0, 0),
        ];
        let mut expected = vec![0.0; grid.len()];
        for (n, &(x, y)) in moved.iter().enumerate() {
            let joined = n % 2 == 0;
            correction.record(y * grid.nx + x, joined);
            let sign = if joined { 1.0 } else { -1.0 };
            for (k, &a) in inverse.0.iter().enumerate() {
                let dx = (k % side) as isize - NEAR_REACH as isize;
                let dy = (k / side) as isize - NEAR_REACH as isize;
                let at = (y as isize + dy).rem_euclid(12) * 20 + (x as isize + dx).rem_euclid(20);
                expected[at as usize] += sign * a;
            }
        }
        assert!(moved.len() <= correction.most_moved(), "no apply");
        correction.follow(&mut inverse, &[]);
        assert_eq!(correction.free_response, expected);
    }
}
