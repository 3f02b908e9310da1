//! Complementarity, the conditions a contact solution meets cell by cell, and the relative
//! residual that measures how far a pressure is from meeting them. The solver's stopping
//! test, the coupled solver's outer test and the independent check all judge by these.
//!
//! With the gap `g = u + h - delta` (`u = K p` the elastic displacement, `h` the
//! separation, `delta` the approach), a cell must have `g = 0` where `0 < p < Y`, `g >= 0`
//! where `p = 0` (no penetration outside the contact) and `g <= 0` where `p = Y` (no
//! opening under the cap).
//!
//! # The relative residual (documented in `numerics.tolerance`)
//! `residual = max_i v_i / max_i |u_i|`, where `v_i = |g_i|` on free cells, `max(-g_i, 0)`
//! on zero cells and `max(g_i, 0)` on capped cells: the worst complementarity violation,
//! cell by cell, relative to the largest elastic displacement.

use super::blocks::{Blocks, lanes_sum};

/// Where a cell's pressure sits against its bounds `0 <= p <= Y`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// `p <= 0`: out of contact.
    Zero,
    /// `0 < p < Y`: in contact, below the cap.
    Free,
    /// `p >= Y`: at the cap.
    Cap,
}

impl Bound {
    /// The bound `pressure` sits on under the cap `cap`.
    #[inline]
    pub fn of(pressure: f64, cap: f64) -> Self {
        if pressure <= 0.0 {
            Self::Zero
        } else if pressure >= cap {
            Self::Cap
        } else {
            Self::Free
        }
    }

    /// How far `gap` violates this cell's condition: penetration out of contact, opening at
    /// the cap, any gap in between; zero when the condition holds.
    #[inline]
    pub fn violation(self, gap: f64) -> f64 {
        match self {
            Self::Zero => (-gap).max(0.0),
            Self::Cap => gap.max(0.0),
            Self::Free => gap.abs(),
        }
    }
}

/// The relative residual accumulated cell by cell, so a solver can fold it into a pass over
/// the grid it makes anyway.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Residual {
    worst: f64,
    scale: f64,
}

impl Residual {
    /// Adds a cell on `bound` with displacement `displacement` and gap `gap`.
    #[inline]
    pub(crate) fn add(&mut self, bound: Bound, displacement: f64, gap: f64) {
        self.scale = self.scale.max(displacement.abs());
        self.worst = self.worst.max(bound.violation(gap));
    }

    /// The residual of the cells of all of `parts`.
    pub(crate) fn merged(parts: &[Self]) -> Self {
        parts.iter().fold(Self::default(), |all, part| Self {
            worst: all.worst.max(part.worst),
            scale: all.scale.max(part.scale),
        })
    }

    /// The worst violation relative to the largest displacement.
    pub(crate) fn value(&self) -> f64 {
        self.worst / self.scale
    }
}

/// The scale the relative residual divides by: the largest `|u|` of `displacement`.
pub(crate) fn displacement_scale(displacement: &[f64]) -> f64 {
    displacement.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// The relative residual of `pressure` with displacement `displacement` over `separation`
/// at the approach `approach_m`, under the cap `cap`.
pub fn complementarity_residual(
    pressure: &[f64],
    displacement: &[f64],
    separation: &[f64],
    approach_m: f64,
    cap: f64,
) -> f64 {
    let mut residual = Residual::default();
    for ((&p, &u), &h) in pressure.iter().zip(displacement).zip(separation) {
        residual.add(Bound::of(p, cap), u, u + h - approach_m);
    }
    residual.value()
}

/// The approach `delta` that a pressure implies: the mean of `u + h` over the free cells
/// (where the gap must vanish), or over all loaded cells when every loaded cell sits at the
/// cap. Summed block by block ([`Blocks`]).
pub(crate) fn approach(
    blocks: Blocks,
    pressure: &[f64],
    displacement: &[f64],
    separation: &[f64],
    cap: f64,
) -> f64 {
    let parts = blocks
        .ranges(pressure.len())
        .map(|r| {
            (
                &pressure[r.clone()],
                &displacement[r.clone()],
                &separation[r],
            )
        })
        .collect();
    let sums = blocks.each(parts, |(p, u, h)| approach_sums(p, u, h, cap));
    let total = |pick: fn(&[[f64; 4]; 4]) -> [f64; 4]| lanes_sum(sums.iter().map(pick));
    let (free, free_n) = (total(|s| s[0]), total(|s| s[1]));
    if free_n > 0.0 {
        free / free_n
    } else {
        total(|s| s[2]) / total(|s| s[3]).max(1.0)
    }
}

/// One block's sums of [`approach`], in four lanes: of `u + h` and the count over the free
/// cells, then over the loaded cells.
fn approach_sums(
    pressure: &[f64],
    displacement: &[f64],
    separation: &[f64],
    cap: f64,
) -> [[f64; 4]; 4] {
    // Sums and counts in four lanes, each cell's membership a 0/1 factor (the level is
    // finite): on a rough disc the loaded and free cells interleave, and a branch per cell
    // mispredicted. In `perf` samples of the 4 um rough disc over 600 cycles
    // (`docs/accuracy.md`), the branchy loop was about 2% of the run.
    let (mut free, mut free_n, mut loaded, mut loaded_n) = ([0.0; 4], [0.0; 4], [0.0; 4], [0.0; 4]);
    let whole = pressure.len() - pressure.len() % 4;
    let mut add = |k: usize, p: f64, level: f64| {
        let is_loaded = if p > 0.0 { 1.0 } else { 0.0 };
        let is_free = if p < cap { is_loaded } else { 0.0 };
        loaded[k] += is_loaded * level;
        loaded_n[k] += is_loaded;
        free[k] += is_free * level;
        free_n[k] += is_free;
    };
    for first in (0..whole).step_by(4) {
        let range = first..first + 4;
        let (p, u, h) = (
            &pressure[range.clone()],
            &displacement[range.clone()],
            &separation[range],
        );
        for k in 0..4 {
            add(k, p[k], u[k] + h[k]);
        }
    }
    for i in whole..pressure.len() {
        add(0, pressure[i], displacement[i] + separation[i]);
    }
    [free, free_n, loaded, loaded_n]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_bound_is_violated_only_by_the_wrong_sign_of_gap() {
        // Exact: max and abs of small integers.
        assert_eq!(Bound::of(0.0, 5.0), Bound::Zero);
        assert_eq!(Bound::of(5.0, 5.0), Bound::Cap);
        assert_eq!(Bound::of(2.0, 5.0), Bound::Free);
        assert_eq!(Bound::Zero.violation(3.0).to_bits(), 0f64.to_bits());
        assert_eq!(Bound::Zero.violation(-3.0).to_bits(), 3f64.to_bits());
        assert_eq!(Bound::Cap.violation(-3.0).to_bits(), 0f64.to_bits());
        assert_eq!(Bound::Cap.violation(3.0).to_bits(), 3f64.to_bits());
        assert_eq!(Bound::Free.violation(-3.0).to_bits(), 3f64.to_bits());
    }

    #[test]
    fn residual_is_the_worst_violation_over_the_largest_displacement() {
        // Cells: free with gap 1, zero pressure with gap -2 (penetrating), capped with gap 4
        // (open), zero pressure with gap 8 (open: allowed). Largest |u| is 10, so 4 / 10.
        let pressure = [1.0, 0.0, 5.0, 0.0];
        let displacement = [10.0, -1.0, 2.0, 3.0];
        let separation = [-9.0, -1.0, 2.0, 5.0];
        let residual = complementarity_residual(&pressure, &displacement, &separation, 0.0, 5.0);
        assert!((residual - 0.4).abs() < 1e-15, "{residual}");
    }
}
