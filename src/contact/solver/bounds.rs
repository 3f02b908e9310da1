//! The bounds' side of the solver: restoring the load, the fallback step when the free
//! cells cannot move, and the refusal of a contact that reaches the domain edge.

use super::super::blocks::{Blocks, lanes_sum};
use super::super::error::ContactError;
use super::super::grid::Grid;
use super::super::operator::Operator;
use super::super::sums::dot;

/// Restores the load to `target` by one shift of every loaded cell below the cap, the
/// projection onto the load's hyperplane within the bounds; cells the shift carries past a
/// bound are clipped to it and the rest shifted again (each pass clips at least one more
/// cell, so this ends). If the capped cells alone exceed the target, every cell is scaled
/// down. If every loaded cell is capped and the load is still short, the contact must grow:
/// the deficit goes to unloaded cells in order of increasing `u + h`, the order in which a
/// larger approach would bring them into contact. Without that, a contact that is almost
/// entirely at the cap has an empty free set and the iteration stalls.
///
/// A shift rather than a scale: scaling gives the most to the cells nearest the cap, so a
/// rescale after a step clips more cells than the step did, and on a rough disc under the
/// cap the iteration fell into a cycle of 400 to 15,000 capped cells. Cycle 143 of the
/// 4 um rough disc of `tests/hard_cases.rs` with seed 2 at `cycle_step_bound` 0.1, run to
/// 150 cycles, took 955 iterations scaled and 112 shifted (both with the uniform restart of
/// `progress`); the paper scene's 464 solves take 2181 iterations against 2180, with the
/// same results to 1e-8.
pub(super) fn rescale_to_load(
    blocks: Blocks,
    pressure: &mut [f64],
    (cap, target): (f64, f64),
    raw_gap: &[f64],
) {
    loop {
        let parts = pressure.chunks(blocks.len).collect();
        let sums = blocks.each(parts, |p| bound_sums(p, cap));
        let total = |pick: fn(&[[f64; 4]; 3]) -> [f64; 4]| lanes_sum(sums.iter().map(pick));
        let (capped, free, shifted) = (total(|s| s[0]), total(|s| s[1]), total(|s| s[2]));
        // Capped cells counted, then times the cap: without yielding the cap is infinite,
        // and a factor of 0 times it is not 0.
        let capped = if capped > 0.0 { capped * cap } else { 0.0 };
        if capped >= target {
            let scale = target / (capped + free);
            pressure.iter_mut().for_each(|p| *p *= scale);
            return;
        }
        if shifted < 1.0 {
            grow_contact(pressure, cap, target - capped, raw_gap);
            return;
        }
        let shift = (target - capped - free) / shifted;
        let parts = pressure.chunks_mut(blocks.len).collect();
        let clipped = blocks.each(parts, |p| shift_free(p, shift, cap));
        if !clipped.contains(&true) {
            return;
        }
    }
}

/// Shifts the cells of `pressure` strictly between 0 and `cap` by `shift`, clipped to the
/// bounds; whether any was clipped.
fn shift_free(pressure: &mut [f64], shift: f64, cap: f64) -> bool {
    let mut clipped = false;
    for p in pressure.iter_mut() {
        // `&`, not `&&`: no branch per cell, as in `bound_sums`.
        let inside = (*p > 0.0) & (*p < cap);
        let moved = *p + shift;
        clipped |= inside & ((moved < 0.0) | (moved > cap));
        *p = if inside { moved.clamp(0.0, cap) } else { *p };
    }
    clipped
}

/// The count of the capped cells, the load of the free ones and their count, each in four
/// lanes with each cell's bound a 0/1 factor: on a rough disc the bounds interleave cell by cell,
/// and the branchy loop with one running sum was about 5% of the 4 um disc's run in `perf`
/// samples (`docs/accuracy.md`, "Rough wear: the solver's passes, and the levers measured
/// and not taken"). Selects in place of the factors compiled to branches again: the run
/// took 0.993 of 29571a1's CPU time with them, 0.975 with the factors
/// (`scripts/rough_ab.py`, 5 pairs each).
fn bound_sums(pressure: &[f64], cap: f64) -> [[f64; 4]; 3] {
    let (mut capped, mut free, mut count) = ([0.0; 4], [0.0; 4], [0.0; 4]);
    let chunks = pressure.chunks_exact(4);
    let tail = chunks.remainder();
    let mut add = |k: usize, p: f64| {
        let at_cap = if p >= cap { 1.0 } else { 0.0 };
        let is_free = if (p > 0.0) & (p < cap) { 1.0 } else { 0.0 };
        capped[k] += at_cap;
        free[k] += is_free * p;
        count[k] += is_free;
    };
    for x in chunks {
        x.iter().enumerate().for_each(|(k, &p)| add(k, p));
    }
    tail.iter().for_each(|&p| add(0, p));
    [capped, free, count]
}

fn grow_contact(pressure: &mut [f64], cap: f64, mut deficit: f64, raw_gap: &[f64]) {
    let mut unloaded: Vec<usize> = (0..pressure.len())
        .filter(|&i| pressure[i] <= 0.0)
        .collect();
    unloaded.sort_unstable_by(|&i, &j| raw_gap[i].total_cmp(&raw_gap[j]));
    for i in unloaded {
        if deficit <= 0.0 {
            break;
        }
        pressure[i] = deficit.min(cap);
        deficit -= pressure[i];
    }
}

/// The share of the re-entry rate at which a capped cell that opened leaves the cap.
///
/// The rate is one cell's compliance along the direction, but on a rough disc's plateau
/// thousands of neighbouring capped cells open together, and released together each lowers
/// its neighbours' displacement as well as its own: at the full rate the release overshot,
/// the next step capped them again, and the capped set swung (22,202 capped cells, then 0,
/// 18,080, 22,409) until the free-set preconditioner was dropped. Measured with `tribosim
/// run` (iterations; solves that fell back to the whole-grid preconditioner; solves restarted
/// from the uniform pressure) at 1 / 0.5 / 0.25: the 4 um rough disc of `docs/accuracy.md`
/// over 600 cycles 3441 (2; 3) / 3493 (0; 0) / 3487 (0; 0); the rough example of
/// `docs/scene.md` over 150 cycles 1633 (2; 2) / 1518 (1; 0) / 1593 (1; 1); the paper scene
/// 2181 / 2170 / 2179 iterations with the same results. A cell at zero pressure re-enters at
/// the full rate: the contact's edge re-enters a few cells at a time.
pub(super) const CAP_RELEASE_DAMPING: f64 = 0.5;

/// One cell of the solver's step (`PolonskyKeer::advance`): a free cell steps by `-tau t`
/// and is truncated at the bound it crosses, a wrongly bounded cell re-enters at `rate` per
/// unit of gap (a capped one at [`CAP_RELEASE_DAMPING`] of it), setting `entered`. Returns
/// how far the cell moved other than along the step, if it did.
pub(super) fn step_cell(
    pi: &mut f64,
    (ti, gi): (f64, f64),
    (tau, rate, cap): (f64, f64, f64),
    entered: &mut bool,
) -> Option<f64> {
    if *pi > 0.0 && *pi < cap {
        let stepped = *pi - tau * ti;
        *pi = stepped.clamp(0.0, cap);
        (stepped <= 0.0 || stepped >= cap).then_some(*pi - stepped)
    } else if *pi <= 0.0 && gi < 0.0 {
        let new = (-rate * gi).min(cap);
        let by = new - *pi;
        *pi = new;
        *entered = true;
        Some(by)
    } else if *pi >= cap && gi > 0.0 {
        let new = (cap - CAP_RELEASE_DAMPING * rate * gi).max(0.0);
        let by = new - *pi;
        *pi = new;
        *entered = true;
        Some(by)
    } else {
        None
    }
}

/// Projected steepest descent over the cells that may move: the free ones and those on a
/// bound whose gap says they should leave it (zero pressure but penetrating, at the cap but
/// open). The direction is the gap there, less its mean so the load is kept; the step is the
/// exact line search `g.t / t.Kt`, then cut at the bounds. False (and `p` unchanged) when
/// there is no descent direction: at most one such cell, or their gaps all equal.
pub(super) fn violator_step(
    operator: &mut dyn Operator,
    p: &mut [f64],
    g: &[f64],
    t: &mut [f64],
    kt: &mut [f64],
    cap: f64,
    applies: &mut usize,
) -> bool {
    let movable = |pi: f64, gi: f64| {
        (pi > 0.0 && pi < cap) || (pi <= 0.0 && gi < 0.0) || (pi >= cap && gi > 0.0)
    };
    let (mut sum, mut count) = (0.0, 0usize);
    for (&pi, &gi) in p.iter().zip(g) {
        if movable(pi, gi) {
            sum += gi;
            count += 1;
        }
    }
    let mean = sum / count.max(1) as f64;
    for ((ti, &pi), &gi) in t.iter_mut().zip(p.iter()).zip(g) {
        *ti = if movable(pi, gi) { gi - mean } else { 0.0 };
    }
    let num = dot(g, t);
    if num <= 0.0 {
        return false;
    }
    operator.apply(t, kt);
    *applies += 1;
    let den = dot(t, kt);
    if den <= 0.0 {
        return false;
    }
    let tau = num / den;
    for (pi, &ti) in p.iter_mut().zip(t.iter()) {
        *pi = (*pi - tau * ti).clamp(0.0, cap);
    }
    true
}

/// Success is refused when the outermost ring of cells carries load: the half-space outside
/// the domain would have carried some too, so the answer is not that of the real contact.
pub(super) fn check_edges(grid: &Grid, pressure: &[f64], target: f64) -> Result<(), ContactError> {
    let (mut cells, mut sum) = (0usize, 0.0);
    for (i, &p) in pressure.iter().enumerate() {
        if p > 0.0 && grid.is_edge(i) {
            cells += 1;
            sum += p;
        }
    }
    if cells > 0 {
        return Err(ContactError::ContactAtEdge {
            edge_cells: cells,
            edge_load_fraction: sum / target,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_load_is_restored_by_one_shift_of_the_loaded_cells_below_the_cap() {
        // 0.2 short: a third each would carry the first cell past the cap, so it is clipped
        // there and the two others share the rest, 0.075 each; the unloaded cell stays so.
        let mut p = [0.95, 0.5, 0.1, 0.0];
        rescale_to_load(Blocks::of(4, 1), &mut p, (1.0, 1.75), &[0.0; 4]);
        let expected = [1.0, 0.575, 0.175, 0.0];
        assert!(
            p.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15),
            "{p:?}"
        );
        // Too much load: the shift lowers them and a cell it would take below zero stops at 0.
        let mut p = [0.5, 0.3, 0.05];
        rescale_to_load(Blocks::of(3, 1), &mut p, (1.0, 0.55), &[0.0; 3]);
        let expected = [0.375, 0.175, 0.0];
        assert!(
            p.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15),
            "{p:?}"
        );
    }
}
