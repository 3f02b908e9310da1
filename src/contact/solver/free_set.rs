//! The preconditioner corrected for the free set's edges ([`Preconditioning::FreeSet`]).
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
//! of the inverse, and one for `rho` when the free set changed. Measured with
//! `tribosim run scenes/dalmau2018.json` (`summary.iterations / summary.solves`) and
//! `tribosim bench rough` (N = 2048): 6.30 -> 4.65 iterations a warm solve, 67 -> 35 on
//! the rough flat; `rho` kept from the solve's start instead gave 7.8 (the cells that left
//! the free set carry the row sum of a free cell).

use crate::contact::Preconditioner;

/// The floor of the row sums, a share of the inverse's diagonal. Measured as above (warm
/// iterations a solve / rough N = 2048 iterations): 0.5 gives 4.80 / 34, 0.25 gives 4.65 /
/// 35, 0.1 gives 4.49 / 38, 0.02 gives 4.76 / 516 (a large correction on the cells far
/// from an island overshoots).
const ROW_SUM_FLOOR: f64 = 0.25;

/// The row sums of the inverse over the cells out of the free set, and whether the free
/// set moved since they were summed.
#[derive(Debug)]
pub(super) struct FreeSetCorrection {
    /// `ROW_SUM_FLOOR` times the inverse's diagonal.
    floor: f64,
    /// `A 1_F` (minus the row sums `rho`), for the free set of the last apply.
    free_response: Vec<f64>,
    stale: bool,
}

impl FreeSetCorrection {
    /// The correction of `inverse` on a grid of `cells` cells.
    pub(super) fn new(inverse: &dyn Preconditioner, cells: usize) -> Self {
        Self {
            floor: ROW_SUM_FLOOR * inverse.diagonal(),
            free_response: vec![0.0; cells],
            stale: true,
        }
    }

    /// The free set changed: the row sums are summed afresh at the next apply.
    pub(super) fn free_set_changed(&mut self) {
        self.stale = true;
    }

    /// `z = (K_FF)^-1 r` approximately, on the free cells (`free`: 1 there, 0 elsewhere);
    /// `r`, zero off the free set, serves as scratch and is left as it came.
    pub(super) fn apply(
        &mut self,
        inverse: &mut dyn Preconditioner,
        free: &[f64],
        r: &mut [f64],
        z: &mut [f64],
    ) {
        inverse.apply(r, z);
        if self.stale {
            inverse.apply(free, &mut self.free_response);
            self.stale = false;
        }
        let floor = self.floor;
        for ((ri, &zi), (&fi, &response)) in r
            .iter_mut()
            .zip(z.iter())
            .zip(free.iter().zip(&self.free_response))
        {
            *ri += (1.0 - fi) * (-zi / (-response).max(floor));
        }
        inverse.apply(r, z);
        r.iter_mut().zip(free).for_each(|(ri, &fi)| *ri *= fi);
    }
}
