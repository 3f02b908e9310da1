//! The solver's step over the grid: each cell stepped along the direction, truncated at
//! the bound it crosses or re-entering, and the displacement updated along.

use super::super::blocks::lanes_sum;
use super::super::operator::Operator;
use super::PolonskyKeer;
use super::bounds::step_cell;
use super::progress::restarts_conjugacy;

impl PolonskyKeer<'_> {
    /// Step, truncation at the bounds, re-entry of wrongly bounded cells; `u` follows the
    /// step, and the cells moved otherwise are recorded for [`Self::restore_load`].
    pub(super) fn advance(&mut self, operator: &mut dyn Operator, tau: f64) {
        let (blocks, params) = (self.blocks, (tau, self.entry_rate, self.cap));
        let (t, r, g) = (&self.t[..], &self.r[..], &self.g[..]);
        self.changes.clear();
        // Several blocks are stepped and summed block by block on one thread as on two
        // (`Blocks::each` runs them in turn), so the load's bits do not depend on the threads.
        let stepped = if !blocks.is_one(t.len()) {
            let parts: Vec<_> = blocks
                .ranges(t.len())
                .zip(
                    self.p
                        .chunks_mut(blocks.len)
                        .zip(self.u.chunks_mut(blocks.len)),
                )
                .map(|(range, pu)| {
                    (
                        range.start,
                        pu,
                        (&t[range.clone()], &r[range.clone()], &g[range]),
                    )
                })
                .collect();
            let stepped = blocks.each(parts, |(first, (p, u), reads)| {
                let mut changes = Vec::new();
                let stepped = step_block(first, (p, u), reads, params, &mut changes);
                (stepped, changes)
            });
            stepped
                .into_iter()
                .map(|(stepped, changes)| {
                    self.changes.extend(changes);
                    stepped
                })
                .collect()
        } else {
            // One block: the changes go straight to the list kept between iterations.
            let (p, u) = (&mut self.p[..], &mut self.u[..]);
            vec![step_block(0, (p, u), (t, r, g), params, &mut self.changes)]
        };
        let highest = stepped
            .iter()
            .flat_map(|s| s.highest)
            .fold(0.0f64, |m, v| m.max(v));
        let load = lanes_sum(stepped.iter().map(|s| s.load));
        let entered = stepped.iter().any(|s| s.entered);
        self.updates += 1;
        if !self.changes.is_empty() {
            self.restore_load(operator, highest, load);
        }
        let (moved, corrected) = (self.changes.len(), self.correction.is_some());
        self.restart = entered && restarts_conjugacy(moved, self.free_cells, corrected);
    }
}

/// One block's share of [`PolonskyKeer::advance`]'s sums: the largest pressure and the load,
/// in four lanes (a cell's lane is its index modulo four; the tail's cells go to lane 0),
/// and whether a cell re-entered.
struct Stepped {
    highest: [f64; 4],
    load: [f64; 4],
    entered: bool,
}

/// [`PolonskyKeer::advance`] on one block whose first cell is `first`: each cell stepped
/// by [`step_cell`] with `(tau, rate, cap)` and `u` by `-tau K t`; the cells moved other
/// than along the step go to `changes`.
fn step_block(
    first: usize,
    (p, u): (&mut [f64], &mut [f64]),
    (t, r, g): (&[f64], &[f64], &[f64]),
    params: (f64, f64, f64),
    changes: &mut Vec<(usize, f64)>,
) -> Stepped {
    let mut entered = false;
    // The largest pressure and the load in four lanes: one running maximum (with
    // `f64::max`'s NaN test) and one sum are serial chains through every cell. In
    // `perf` samples of cold Hertz N = 256 solves (coarse start included), the solver's
    // own per sample of the FFT library's fell from 0.64 to 0.57.
    let (mut highest, mut load) = ([0.0f64; 4], [0.0; 4]);
    let (cells, whole) = (p.len(), p.len() - p.len() % 4);
    // Lanes fixed per position in slices of four, so they stay in registers.
    for start in (0..whole).step_by(4) {
        for lane in 0..4 {
            let (i, sums) = (start + lane, (&mut highest[lane], &mut load[lane]));
            let cell = (&mut p[i], &mut u[i]);
            entered |= step_one((first, i), cell, (t[i], r[i], g[i]), params, changes, sums);
        }
    }
    for i in whole..cells {
        let (cell, sums) = ((&mut p[i], &mut u[i]), (&mut highest[0], &mut load[0]));
        entered |= step_one((first, i), cell, (t[i], r[i], g[i]), params, changes, sums);
    }
    Stepped {
        highest,
        load,
        entered,
    }
}

/// One cell of [`step_block`] (the `i`th of the block whose first cell is `first`): stepped
/// by [`step_cell`], its move other than along the step recorded in `changes`, `u` by
/// `-tau (K t)`, and its new pressure added to its lane's largest and sum. Returns whether
/// it re-entered.
///
/// A function forced inline rather than a closure: the closure's inlining into the lane
/// loop came and went with unrelated changes elsewhere in the crate (a `perf` profile of the
/// 4 um rough disc found it a symbol of its own, 8.8% of the samples, against 6.9% for the
/// step inlined).
#[inline(always)]
fn step_one(
    (first, i): (usize, usize),
    (pi, ui): (&mut f64, &mut f64),
    (ti, ri, gi): (f64, f64, f64),
    (tau, rate, cap): (f64, f64, f64),
    changes: &mut Vec<(usize, f64)>,
    (highest, load): (&mut f64, &mut f64),
) -> bool {
    let mut entered = false;
    if let Some(by) = step_cell(pi, (ti, gi), (tau, rate, cap), &mut entered) {
        changes.push((first + i, by));
    }
    *ui -= tau * ri;
    *highest = if *pi > *highest { *pi } else { *highest };
    *load += *pi;
    entered
}
