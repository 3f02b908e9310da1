//! The bounds' side of the solver: restoring the load, the fallback step when the free
//! cells cannot move, and the refusal of a contact that reaches the domain edge.

use super::super::error::ContactError;
use super::super::grid::Grid;
use super::super::operator::Operator;
use super::sums::dot;

/// Scales the cells below the cap so the total is `target`; cells pushed over the cap are
/// clipped to it and the rest rescaled again (each pass caps at least one more cell, so
/// this ends). If the capped cells alone exceed the target, every cell is scaled down. If
/// every loaded cell is capped and the load is still short, the contact must grow: the
/// deficit goes to unloaded cells in order of increasing `u + h`, the order in which a
/// larger approach would bring them into contact. Without that, a contact that is almost
/// entirely at the cap has an empty free set and the iteration stalls.
pub(super) fn rescale_to_load(pressure: &mut [f64], cap: f64, target: f64, raw_gap: &[f64]) {
    loop {
        let (mut capped, mut free) = (0.0, 0.0);
        for &p in pressure.iter() {
            if p >= cap {
                capped += cap;
            } else {
                free += p;
            }
        }
        if capped >= target {
            let scale = target / (capped + free);
            pressure.iter_mut().for_each(|p| *p *= scale);
            return;
        }
        if free <= 0.0 {
            grow_contact(pressure, cap, target - capped, raw_gap);
            return;
        }
        let scale = (target - capped) / free;
        let mut clipped = false;
        for p in pressure.iter_mut().filter(|p| **p < cap) {
            *p *= scale;
            if *p >= cap {
                *p = cap;
                clipped = true;
            }
        }
        if !clipped {
            return;
        }
    }
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
