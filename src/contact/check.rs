//! An independent check of a contact solution that does not trust the solver: the
//! displacement is recomputed from the pressure by an operator of the caller's choice (the
//! dense direct sum on small grids, the FFT operator on large ones), and every cell is
//! tested against the complementarity conditions of [`super::residual`], one kind of
//! violation at a time.

use super::operator::Operator;
use super::problem::{ContactProblem, ContactSolution};
use super::residual::{Bound, displacement_scale};

/// What the check found; [`Verification::passes`] decides against a tolerance.
#[derive(Debug, Clone, PartialEq)]
pub struct Verification {
    /// Cells whose pressure is outside `[0, Y]` or not finite.
    pub out_of_bounds: usize,
    /// Worst gap in a cell with `0 < p < Y`, relative to the largest displacement.
    pub worst_open_or_penetrating_in_contact: f64,
    /// Worst penetration `-g` in a cell with `p = 0`, relative.
    pub worst_penetration_outside: f64,
    /// Worst opening `g` in a cell with `p = Y`, relative.
    pub worst_opening_at_cap: f64,
    /// `|sum p A - W| / W`.
    pub load_error: f64,
}

impl Verification {
    /// Every cell within `tolerance` (relative to the largest displacement) and the load
    /// carried to `load_tolerance`.
    pub fn passes(&self, tolerance: f64, load_tolerance: f64) -> bool {
        self.out_of_bounds == 0
            && self.worst_open_or_penetrating_in_contact <= tolerance
            && self.worst_penetration_outside <= tolerance
            && self.worst_opening_at_cap <= tolerance
            && self.load_error <= load_tolerance
    }
}

/// Recomputes `u = K p` with `operator` (which must include the coupling term if the
/// solution did) and tests each cell of `solution` against `problem` with its reported
/// approach.
pub fn verify(
    operator: &mut dyn Operator,
    problem: &ContactProblem,
    solution: &ContactSolution,
) -> Verification {
    let p = &solution.pressure;
    let mut u = vec![0.0; p.len()];
    operator.apply(p, &mut u);
    let scale = displacement_scale(&u);
    let cap = problem.yield_pressure_pa;
    let mut report = Verification {
        out_of_bounds: 0,
        worst_open_or_penetrating_in_contact: 0.0,
        worst_penetration_outside: 0.0,
        worst_opening_at_cap: 0.0,
        load_error: 0.0,
    };
    for ((&pi, &ui), &hi) in p.iter().zip(&u).zip(problem.separation) {
        let gap = (ui + hi - solution.approach_m) / scale;
        if !(pi.is_finite() && (0.0..=cap).contains(&pi)) {
            report.out_of_bounds += 1;
            continue;
        }
        let bound = Bound::of(pi, cap);
        let worst = match bound {
            Bound::Zero => &mut report.worst_penetration_outside,
            Bound::Cap => &mut report.worst_opening_at_cap,
            Bound::Free => &mut report.worst_open_or_penetrating_in_contact,
        };
        *worst = worst.max(bound.violation(gap));
    }
    let carried = p.iter().sum::<f64>() * problem.grid.cell_area();
    report.load_error = (carried - problem.load_n).abs() / problem.load_n;
    report
}
