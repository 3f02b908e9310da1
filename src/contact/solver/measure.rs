//! The solver's pass over the grid at the start of each iteration.

use super::super::residual::{Bound, Residual, approach};
use super::PolonskyKeer;

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
        let cap = self.cap;
        let delta = approach(&self.p, &self.u, self.separation, cap);
        let (p, u, h, t) = (&self.p[..], &self.u[..], self.separation, &self.t[..]);
        let (g, free, r) = (&mut self.g[..], &mut self.free[..], &mut self.r[..]);
        // The residual's maxima and the load in four lanes, as the sums: each is a serial
        // chain through every cell otherwise.
        let (mut residual, mut load, mut free_cells) = ([Residual::default(); 4], [0.0; 4], 0usize);
        // The cells that joined or left the free set, for the preconditioner's correction.
        let mut correction = self.correction.as_mut();
        // Returns `free * t` of the cell, summed as `dot` sums (four accumulators, over
        // slices of four so the inner loop has no bounds checks).
        let mut cell = |(i, lane): (usize, usize),
                        (pi, ui, hi, ti): (f64, f64, f64, f64),
                        out: (&mut f64, &mut f64, &mut f64)| {
            let gi = ui + hi - delta;
            *out.0 = gi;
            load[lane] += pi;
            let bound = Bound::of(pi, cap);
            residual[lane].add(bound, ui, gi);
            let is_free = bound == Bound::Free;
            let fi = if is_free { 1.0 } else { 0.0 };
            free_cells += usize::from(is_free);
            if let Some(correction) = correction.as_mut().filter(|_| (*out.1 > 0.5) != is_free) {
                correction.record(i, is_free);
            }
            *out.1 = fi;
            *out.2 = fi * gi;
            fi * ti
        };
        let whole = p.len() - p.len() % 4;
        let mut acc = [0.0; 4];
        for first in (0..whole).step_by(4) {
            let range = first..first + 4;
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
                let fields = (p[k], u[k], h[k], t[k]);
                acc[k] += cell((first + k, k), fields, (&mut g[k], &mut free[k], &mut r[k]));
            }
        }
        let mut tail = 0.0;
        for i in whole..p.len() {
            let fields = (p[i], u[i], h[i], t[i]);
            tail += cell((i, 0), fields, (&mut g[i], &mut free[i], &mut r[i]));
        }
        self.free_t = acc.iter().sum::<f64>() + tail;
        self.free_cells = free_cells as f64;
        self.residual = Residual::merged(&residual).value();
        self.load = load.iter().sum();
        delta
    }
}
