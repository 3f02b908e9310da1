//! The solver's step over the grid: each cell stepped along the direction, truncated at
//! the bound it crosses or re-entering, and the displacement updated along.

use super::super::blocks::lanes_sum;
use super::super::operator::Operator;
use super::PolonskyKeer;
use super::bounds::step_cell;
use super::progress::restarts_conjugacy;

impl PolonskyKeer<'_> {
    /// Step, truncation at the bounds, re-entry of wrongly bounded cells; `u` follows the
    /// step (here, or in [`Self::restore_load`] from a kept transform), and the cells moved
    /// otherwise are recorded for [`Self::restore_load`].
    pub(super) fn advance(&mut self, operator: &mut dyn Operator, tau: f64) {
        let (blocks, params, kept) = (self.blocks, (tau, self.entry_rate, self.cap), self.kept);
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
                let stepped = step_either(kept, first, (p, u), reads, params, &mut changes);
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
            let changes = &mut self.changes;
            vec![step_either(kept, 0, (p, u), (t, r, g), params, changes)]
        };
        let highest = stepped
            .iter()
            .flat_map(|s| s.highest)
            .fold(0.0f64, |m, v| m.max(v));
        let load = lanes_sum(stepped.iter().map(|s| s.load));
        let entered = stepped.iter().any(|s| s.entered);
        self.updates += 1;
        self.restore_load(operator, tau, (highest, load));
        let (moved, corrected) = (self.changes.len(), self.correction.is_some());
        self.restart = entered && restarts_conjugacy(moved, self.free_cells, corrected);
    }

    /// Brings the load back to the target after the recorded changes (`highest`: the
    /// largest pressure now, `load` their sum) and brings `u` along, by `-tau K t` where the
    /// operator kept the direction's transform (`u` moved along the step already otherwise).
    /// With no cell at the cap before or after, the rescale is one factor `s` on every
    /// pressure, so `u = K p` becomes `s (u + K d)` with `d` the recorded changes: a sparse
    /// update where the operator offers one (with no cap to reach, a scale clips nothing, so
    /// it cannot cascade as it did under the cap). Otherwise the load is restored by
    /// [`rescale_to_load`](super::bounds::rescale_to_load)'s shift, and `u` takes
    /// `K (w - tau t)`, `w` the changes and the shift, from the kept transform; without one,
    /// `u` is recomputed.
    pub(super) fn restore_load(
        &mut self,
        operator: &mut dyn Operator,
        tau: f64,
        (highest, load): (f64, f64),
    ) {
        let scale = self.target / load;
        if self.changes.is_empty()
            || (highest < self.cap
                && scale * highest < self.cap
                && operator.add_sparse(&self.changes, &mut self.u))
        {
            self.took_restore(false);
            if self.kept {
                operator.add_kept(None, -tau, &mut self.u);
            }
            if !self.changes.is_empty() {
                self.p.iter_mut().for_each(|p| *p *= scale);
                self.u.iter_mut().for_each(|u| *u *= scale);
                self.updates += 1;
            }
            return;
        }
        self.took_restore(true);
        if !self.kept {
            self.rescale();
            self.recompute(operator);
            return;
        }
        // `r` (free since the step) takes the moves off the direction: the shift's, then
        // the recorded changes.
        self.r.copy_from_slice(&self.p);
        self.rescale();
        self.r
            .iter_mut()
            .zip(&self.p)
            .for_each(|(w, &p)| *w = p - *w);
        for &(i, by) in &self.changes {
            self.r[i] += by;
        }
        operator.add_kept(Some(&self.r), -tau, &mut self.u);
        self.applies += 1;
        self.updates += 1;
    }

    /// Records whether a step restored the load under the cap (`general`), for the next
    /// step's and the next solve's [`Keeping`].
    fn took_restore(&mut self, general: bool) {
        self.keep_next = general;
        self.first_kept.get_or_insert(general);
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

/// [`step_block`], moving `u` unless the direction's transform was `kept`.
fn step_either(
    kept: bool,
    first: usize,
    (p, u): (&mut [f64], &mut [f64]),
    reads: (&[f64], &[f64], &[f64]),
    params: (f64, f64, f64),
    changes: &mut Vec<(usize, f64)>,
) -> Stepped {
    if kept {
        step_block::<false>(first, (p, u), reads, params, changes)
    } else {
        step_block::<true>(first, (p, u), reads, params, changes)
    }
}

/// [`PolonskyKeer::advance`] on one block whose first cell is `first`: each cell stepped
/// by [`step_cell`] with `(tau, rate, cap)` and, if `MOVE_U`, `u` by `-tau K t` (`r`); the
/// cells moved other than along the step go to `changes`.
fn step_block<const MOVE_U: bool>(
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
            entered |=
                step_one::<MOVE_U>((first, i), cell, (t[i], r[i], g[i]), params, changes, sums);
        }
    }
    for i in whole..cells {
        let (cell, sums) = ((&mut p[i], &mut u[i]), (&mut highest[0], &mut load[0]));
        entered |= step_one::<MOVE_U>((first, i), cell, (t[i], r[i], g[i]), params, changes, sums);
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
fn step_one<const MOVE_U: bool>(
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
    if MOVE_U {
        *ui -= tau * ri;
    }
    *highest = if *pi > *highest { *pi } else { *highest };
    *load += *pi;
    entered
}

/// Whether a solve's first step asks the operator to keep the direction's transform
/// ([`Operator::keep`]): it pays only in a step that restores the load under the cap, and
/// costs a step that does not (the column pass is no longer one per column). Each later
/// step asks when the step before restored under the cap; the first, when the last solve's
/// first step did. Counted once (a build that printed each step's restore): on the 4 um
/// rough disc of `docs/accuracy.md` every step of the 600 solves but 4 restored under the
/// cap; on the paper scene's 464 solves 254 of 2180 steps did, 102 of them first steps.
/// Asked at every step, the paper scene took 1.073 of the CPU time (`scripts/rough_ab.py
/// --scene`, 5 pairs, 0.977 to 1.129).
#[derive(Debug, Default, Clone, Copy)]
pub(in crate::contact) struct Keeping {
    pub(super) first_step: bool,
}
