//! The solver's passes over a large field, cut into a fixed number of blocks that the
//! pool's threads take ([`Blocks`]).
//!
//! A pass that sums (the residual's measure, the load, a dot product) sums each block in
//! its own four lanes and then the blocks' lanes in order, so the result depends on the
//! field's length alone, never on how many threads ran the blocks: one thread runs the same
//! blocks one after the other and gets the same bits. A field shorter than
//! [`BLOCKED_MIN_CELLS`] is one block, whose sums are those of the one-pass loop to the last
//! bit (each lane starts from `+0.0`, and `0.0 + x == x`).

use std::ops::Range;

use rayon::prelude::*;

use super::transform::SPLIT_MIN_CELLS;

/// Fields of this many cells or more are passed over in [`BLOCKS`] blocks: from the size at
/// which the contact's FFT passes split across threads ([`SPLIT_MIN_CELLS`]), so that a
/// solve split at all splits its own passes too, and a solve below it (the paper scene, the
/// 4 um rough disc's windows) keeps the one-pass sums to the bit. With the blocks and the
/// pool, the 300 um domain of `docs/accuracy.md` ran in 0.885 of the wall time of the
/// applies split by spawned threads from 512 x 512 cells alone (`scripts/rough_ab.py A B
/// --scene scenes/bench-rough-2um-300um.json --pairs 3`).
pub(crate) const BLOCKED_MIN_CELLS: usize = match SPLIT_MIN_CELLS {
    Some(cells) => cells,
    None => usize::MAX,
};

/// Blocks of a large field: more than the cores of the machines it runs on, so that two,
/// four or eight threads each take an equal share.
pub(crate) const BLOCKS: usize = 8;

/// How a pass over a field of `len` cells is cut, and whether its blocks go to the pool.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Blocks {
    /// Cells of each block but the last, a multiple of four so that a cell's lane is its
    /// index modulo four in every block.
    pub(crate) len: usize,
    /// Whether the blocks run on the pool's threads.
    pub(crate) parallel: bool,
}

impl Blocks {
    /// The blocks of a field of `cells` cells, handed to the pool when `threads > 1`.
    pub(crate) fn of(cells: usize, threads: usize) -> Self {
        if cells < BLOCKED_MIN_CELLS {
            return Self {
                len: cells.max(1),
                parallel: false,
            };
        }
        Self {
            len: cells.div_ceil(BLOCKS).next_multiple_of(4),
            parallel: threads > 1,
        }
    }

    /// Whether a field of `cells` cells is one block.
    pub(crate) fn is_one(&self, cells: usize) -> bool {
        self.len >= cells
    }

    /// The cells of each block, in order.
    pub(crate) fn ranges(&self, cells: usize) -> impl Iterator<Item = Range<usize>> + use<> {
        let len = self.len;
        (0..cells)
            .step_by(len)
            .map(move |start| start..(start + len).min(cells))
    }

    /// `work` of each part (one per block, in order), on the pool's threads when the
    /// blocks are parallel; the results in the parts' order either way.
    pub(crate) fn each<P: Send, R: Send>(
        &self,
        parts: Vec<P>,
        work: impl Fn(P) -> R + Sync + Send,
    ) -> Vec<R> {
        if self.parallel {
            parts.into_par_iter().map(work).collect()
        } else {
            parts.into_iter().map(work).collect()
        }
    }
}

/// Four lanes and the tail beyond the last whole slice of four: one block's share of a sum.
pub(crate) type Lanes = ([f64; 4], f64);

/// The blocks' four lanes summed lane by lane in order, then the four: for one block, its
/// `lanes.iter().sum()` to the last bit (each lane of the total starts from `+0.0`).
pub(crate) fn lanes_sum(blocks: impl IntoIterator<Item = [f64; 4]>) -> f64 {
    let total = blocks.into_iter().fold([0.0; 4], |mut all, lanes| {
        for k in 0..4 {
            all[k] += lanes[k];
        }
        all
    });
    total.iter().sum()
}

/// [`lanes_sum`] of the blocks' [`Lanes`] plus their tails: for one block, its
/// `lanes.iter().sum() + tail` to the last bit.
pub(crate) fn lanes_and_tails_sum(blocks: impl IntoIterator<Item = Lanes>) -> f64 {
    let (lanes, tails): (Vec<_>, Vec<_>) = blocks.into_iter().unzip();
    lanes_sum(lanes) + tails.iter().fold(0.0, |all, tail| all + tail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_field_is_one_block_and_a_large_one_eight_aligned_to_four() {
        let small = Blocks::of(1000, 2);
        assert_eq!(small.ranges(1000).collect::<Vec<_>>(), vec![0..1000]);
        assert!(!small.parallel);
        let cells = BLOCKED_MIN_CELLS + 3;
        let large = Blocks::of(cells, 2);
        let ranges: Vec<_> = large.ranges(cells).collect();
        assert_eq!(ranges.len(), BLOCKS);
        assert!(ranges.iter().all(|r| r.start % 4 == 0));
        assert_eq!(ranges.last().map(|r| r.end), Some(cells));
        assert!(large.parallel);
        // One thread cuts the same blocks, so its sums are the same.
        assert_eq!(Blocks::of(cells, 1).len, large.len);
        assert!(!Blocks::of(cells, 1).parallel);
    }

    #[test]
    fn blocks_run_in_parallel_return_their_results_in_order() {
        let cells = BLOCKED_MIN_CELLS;
        let blocks = Blocks::of(cells, 2);
        let parts: Vec<_> = blocks.ranges(cells).collect();
        let starts = blocks.each(parts, |range| range.start);
        let expected: Vec<_> = (0..BLOCKS).map(|b| b * blocks.len).collect();
        assert_eq!(starts, expected);
    }
}
