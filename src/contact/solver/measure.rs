//! The solver's pass over the grid at the start of each iteration.

use super::super::blocks::{Lanes, lanes_and_tails_sum, lanes_sum};
use super::super::residual::{Bound, Residual, approach};
use super::PolonskyKeer;
use super::free_set::FreeSetCorrection;

/// One block's share of [`PolonskyKeer::measure`]'s sums: the residual, then the sums in
/// four lanes (a cell's lane is its index modulo four; the cells past the last whole slice
/// of four go to lane 0).
#[derive(Default)]
struct Measured {
    residual: Residual,
    load: [f64; 4],
    free_cells: usize,
    /// `free * t`, summed as `dot` sums (four lanes and the tail apart).
    free_t: Lanes,
    /// The first cells that joined (`true`) or left the free set, in order, as many as
    /// were asked for.
    moved: Vec<(usize, bool)>,
}

/// The fields a block reads: pressure, displacement, separation and the old direction.
type Reads<'a> = (&'a [f64], &'a [f64], &'a [f64], &'a [f64]);
/// The fields a block writes: the gap, the free mask and the gap on the free cells.
type Writes<'a> = (&'a mut [f64], &'a mut [f64], &'a mut [f64]);

impl PolonskyKeer<'_> {
    /// One fused pass: the approach, the gap, the free mask, the gap on the free cells
    /// (into `r`, unused until the next apply), the load, the relative residual, and the
    /// free cells' count and sum of the old direction that [`Self::direction`] needs.
    /// Returns the approach.
    ///
    /// The last two sums ride on this pass rather than taking two of their own, as the other
    /// sums ride on [`dot2`](crate::contact::sums::dot2) and
    /// [`update_direction`](crate::contact::sums::update_direction): the passes are
    /// memory-bound at N = 2048 (4.2M cells). Measured by `perf record` of `cargo test --release --test
    /// stability_rough -- --ignored --nocapture bench_rough_solve` (a count of samples, so
    /// load-independent): the solver's own samples per sample of the FFT library's fell
    /// from 1.29 to 1.00 at N = 2048, a fifth of the passes' time, and from 0.50 to 0.47 on
    /// the Hertz N = 256 solve (`--test contact -- --ignored hertz_256_solve_time`).
    pub(super) fn measure(&mut self) -> f64 {
        let (cap, blocks) = (self.cap, self.blocks);
        // The moved cells a block collects: no more than the correction keeps.
        let record = self
            .correction
            .as_ref()
            .map_or(0, FreeSetCorrection::most_recorded);
        let delta = approach(blocks, &self.p, &self.u, self.separation, cap);
        let (p, u, h, t) = (&self.p[..], &self.u[..], self.separation, &self.t[..]);
        let len = blocks.len;
        let parts = blocks
            .ranges(p.len())
            .zip(self.g.chunks_mut(len))
            .zip(self.free.chunks_mut(len).zip(self.r.chunks_mut(len)))
            .map(|((range, g), (free, r))| {
                let reads = (
                    &p[range.clone()],
                    &u[range.clone()],
                    &h[range.clone()],
                    &t[range.clone()],
                );
                (range.start, reads, (g, free, r))
            })
            .collect();
        let measured = blocks.each(parts, |(first, reads, writes)| {
            measure_block(first, reads, writes, (delta, cap), record)
        });
        let mut residual = Vec::with_capacity(measured.len());
        let (mut load, mut free_t) = (Vec::new(), Vec::new());
        self.free_cells = 0.0;
        for block in measured {
            residual.push(block.residual);
            load.push(block.load);
            free_t.push(block.free_t);
            self.free_cells += block.free_cells as f64;
            if let Some(correction) = self.correction.as_mut() {
                block
                    .moved
                    .into_iter()
                    .for_each(|(i, joined)| correction.record(i, joined));
            }
        }
        self.free_t = lanes_and_tails_sum(free_t);
        self.residual = Residual::merged(&residual).value();
        self.load = lanes_sum(load);
        delta
    }
}

/// [`PolonskyKeer::measure`] on one block whose first cell is `first` (the approach
/// `delta` and the cap given), recording the first `record` cells that joined or left the
/// free set.
///
/// The residual is a largest value, the same in any order, so it takes one accumulator;
/// the load and `free * t` are sums, in four lanes as `dot` sums them. The loop's body is
/// small enough to unroll (`measure_cell`, the rare moved cell recorded out of line by
/// `note_moved`), so the lanes stay in registers: with the record inline and the residual
/// in lanes, the loop stayed rolled and every sum went through the stack, and this pass was
/// 9.9% of the samples of the 4 um rough disc over 600 cycles (`perf record --call-graph
/// dwarf`, `docs/accuracy.md`).
fn measure_block(
    first: usize,
    (p, u, h, t): Reads,
    (g, free, r): Writes,
    (delta, cap): (f64, f64),
    record: usize,
) -> Measured {
    let mut out = Measured::default();
    let (mut residual, mut load, mut acc) = (Residual::default(), [0.0; 4], [0.0; 4]);
    let whole = p.len() - p.len() % 4;
    for start in (0..whole).step_by(4) {
        let range = start..start + 4;
        let (p, u, h, t) = (
            &p[range.clone()],
            &u[range.clone()],
            &h[range.clone()],
            &t[range.clone()],
        );
        let (g, free, r) = (
            &mut g[range.clone()],
            &mut free[range.clone()],
            &mut r[range],
        );
        for k in 0..4 {
            let written = (&mut g[k], &mut free[k], &mut r[k]);
            let (is_free, moved) =
                measure_cell((p[k], u[k], h[k]), (delta, cap), &mut residual, written);
            if moved {
                note_moved(&mut out.moved, record, (first + start + k, is_free));
            }
            out.free_cells += usize::from(is_free);
            load[k] += p[k];
            acc[k] += indicator(is_free) * t[k];
        }
    }
    let mut tail = 0.0;
    for i in whole..p.len() {
        let written = (&mut g[i], &mut free[i], &mut r[i]);
        let (is_free, moved) =
            measure_cell((p[i], u[i], h[i]), (delta, cap), &mut residual, written);
        if moved {
            note_moved(&mut out.moved, record, (first + i, is_free));
        }
        out.free_cells += usize::from(is_free);
        load[0] += p[i];
        tail += indicator(is_free) * t[i];
    }
    (out.residual, out.load, out.free_t) = (residual, load, (acc, tail));
    out
}

/// One cell of [`measure_block`]: writes its gap, its free mask and its gap where free, and
/// adds it to `residual`. Returns whether it is free and whether that changed.
#[inline(always)]
fn measure_cell(
    (pi, ui, hi): (f64, f64, f64),
    (delta, cap): (f64, f64),
    residual: &mut Residual,
    (g, free, r): (&mut f64, &mut f64, &mut f64),
) -> (bool, bool) {
    let gi = ui + hi - delta;
    let bound = Bound::of(pi, cap);
    residual.add(bound, ui, gi);
    let is_free = bound == Bound::Free;
    let moved = (*free > 0.5) != is_free;
    let fi = indicator(is_free);
    (*g, *free, *r) = (gi, fi, fi * gi);
    (is_free, moved)
}

/// 1 for a free cell, 0 for another: the free mask's value.
#[inline]
fn indicator(is_free: bool) -> f64 {
    if is_free { 1.0 } else { 0.0 }
}

/// Records `cell` (its index, and whether it joined the free set) while fewer than `record`
/// are: out of the hot loop, since few cells move once a solve settles.
#[cold]
#[inline(never)]
fn note_moved(moved: &mut Vec<(usize, bool)>, record: usize, cell: (usize, bool)) {
    if moved.len() < record {
        moved.push(cell);
    }
}
