//! The solver's reductions over the grid, each with four independent accumulators, and the
//! passes that fold a reduction into an update: the passes are memory-bound on large grids,
//! so a sum rides on a pass that reads its data anyway. The passes of the solve's
//! iterations go block by block ([`Blocks`]).

use super::blocks::{Blocks, Lanes, lanes_and_tails_sum};

/// Dot product with four independent accumulators: a single running sum is a serial chain
/// of additions (kept on the stack), a third of the solver's own time at N = 256 in a profile of
/// `tribosim bench contact`.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}

/// `(a.b, c.d)` in one pass, each summed as [`dot`] sums it block by block (so, on one
/// block, equal to two calls to the last bit): the grids are read once where two passes
/// read `t` or `z` twice.
pub(crate) fn dot2(
    blocks: Blocks,
    (a, b): (&[f64], &[f64]),
    (c, d): (&[f64], &[f64]),
) -> (f64, f64) {
    let parts = blocks
        .ranges(a.len())
        .map(|r| (&a[r.clone()], &b[r.clone()], &c[r.clone()], &d[r]))
        .collect();
    let (ab, cd): (Vec<_>, Vec<_>) = blocks
        .each(parts, |(a, b, c, d)| dot2_lanes((a, b), (c, d)))
        .into_iter()
        .unzip();
    (lanes_and_tails_sum(ab), lanes_and_tails_sum(cd))
}

fn dot2_lanes((a, b): (&[f64], &[f64]), (c, d): (&[f64], &[f64])) -> (Lanes, Lanes) {
    let (mut ab, mut cd) = ([0.0; 4], [0.0; 4]);
    let whole = a.len() - a.len() % 4;
    for first in (0..whole).step_by(4) {
        let (a, b, c, d) = (
            &a[first..first + 4],
            &b[first..first + 4],
            &c[first..first + 4],
            &d[first..first + 4],
        );
        for k in 0..4 {
            ab[k] += a[k] * b[k];
            cd[k] += c[k] * d[k];
        }
    }
    let tail_ab: f64 = (whole..a.len()).map(|i| a[i] * b[i]).sum();
    let tail_cd: f64 = (whole..a.len()).map(|i| c[i] * d[i]).sum();
    ((ab, tail_ab), (cd, tail_cd))
}

/// `(sum free r z, sum free z)` in one pass, each summed as [`dot`] sums: [`dot2`]'s sums
/// where `r` holds values off the free set that must not count.
pub(crate) fn free_dots(blocks: Blocks, free: &[f64], r: &[f64], z: &[f64]) -> (f64, f64) {
    let parts = blocks
        .ranges(free.len())
        .map(|range| (&free[range.clone()], &r[range.clone()], &z[range]))
        .collect();
    let (rz, fz): (Vec<_>, Vec<_>) = blocks
        .each(parts, |(free, r, z)| free_dots_lanes(free, r, z))
        .into_iter()
        .unzip();
    (lanes_and_tails_sum(rz), lanes_and_tails_sum(fz))
}

fn free_dots_lanes(free: &[f64], r: &[f64], z: &[f64]) -> (Lanes, Lanes) {
    let (mut rz, mut fz) = ([0.0; 4], [0.0; 4]);
    let whole = free.len() - free.len() % 4;
    for first in (0..whole).step_by(4) {
        let range = first..first + 4;
        let (f, r, z) = (&free[range.clone()], &r[range.clone()], &z[range]);
        for k in 0..4 {
            let masked = f[k] * z[k];
            rz[k] += r[k] * masked;
            fz[k] += masked;
        }
    }
    let tail_rz: f64 = (whole..free.len()).map(|i| r[i] * free[i] * z[i]).sum();
    let tail_fz: f64 = (whole..free.len()).map(|i| free[i] * z[i]).sum();
    ((rz, tail_rz), (fz, tail_fz))
}

/// `t = free (source + beta t - mean)`, the conjugate direction over the free cells,
/// returning `g.t` summed as [`dot`] sums it, in the same pass.
pub(crate) fn update_direction(
    blocks: Blocks,
    t: &mut [f64],
    (source, free, g): (&[f64], &[f64], &[f64]),
    beta: f64,
    mean: f64,
) -> f64 {
    let parts = blocks
        .ranges(g.len())
        .zip(t.chunks_mut(blocks.len))
        .map(|(r, t)| (t, &source[r.clone()], &free[r.clone()], &g[r]))
        .collect();
    lanes_and_tails_sum(blocks.each(parts, |(t, source, free, g)| {
        direction_lanes(t, (source, free, g), beta, mean)
    }))
}

fn direction_lanes(
    t: &mut [f64],
    (source, free, g): (&[f64], &[f64], &[f64]),
    beta: f64,
    mean: f64,
) -> Lanes {
    let whole = g.len() - g.len() % 4;
    let mut acc = [0.0; 4];
    // Slices of four, so the inner loop has no bounds checks and vectorises (an indexed
    // loop over the whole grids did not, and made the Hertz N = 256 solve slower).
    for first in (0..whole).step_by(4) {
        let range = first..first + 4;
        let (t, source, free, g) = (
            &mut t[range.clone()],
            &source[range.clone()],
            &free[range.clone()],
            &g[range],
        );
        for k in 0..4 {
            t[k] = free[k] * (source[k] + beta * t[k] - mean);
            acc[k] += g[k] * t[k];
        }
    }
    let mut tail = 0.0;
    for i in whole..g.len() {
        t[i] = free[i] * (source[i] + beta * t[i] - mean);
        tail += g[i] * t[i];
    }
    (acc, tail)
}

/// Sum with four independent accumulators, as [`dot`].
pub(crate) fn sum(a: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let chunks = a.chunks_exact(4);
    let tail: f64 = chunks.remainder().iter().sum();
    for x in chunks {
        for k in 0..4 {
            acc[k] += x[k];
        }
    }
    acc.iter().sum::<f64>() + tail
}
