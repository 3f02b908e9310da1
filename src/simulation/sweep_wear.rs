//! What the positions of a reciprocating sweep press into the flat ([`SweepWear`]): the
//! pressure integral over the stretch of the stroke each position stands for, and the
//! groove yielding pushes in.

use crate::contact::Grid;
use crate::wear::WearMap;

/// What the positions of a sweep press into the flat: the pressure integral and each map
/// cell's deepest interpenetration at the cap.
pub(super) struct SweepWear {
    grid: Grid,
    half_m: f64,
    step_m: f64,
    /// The sweep's pressure integral, Pa m.
    pub(super) pressure: WearMap,
    /// Each map cell's deepest interpenetration at the cap in the sweep, m.
    pub(super) yielded: Vec<f64>,
    /// The first and last positions of a run pressing one pressure, not yet pressed.
    run: Option<(usize, usize)>,
}

impl SweepWear {
    pub(super) fn new(grid: &Grid, length_m: f64, steps: usize) -> Self {
        let pressure = WearMap::new(grid, length_m);
        Self {
            grid: *grid,
            half_m: length_m / 2.0,
            step_m: length_m / steps as f64,
            yielded: vec![0.0; pressure.depth.len()],
            pressure,
            run: None,
        }
    }

    /// The ball's centre at position `j` of the stroke, m.
    pub(super) fn position_m(&self, j: usize) -> f64 {
        -self.half_m + j as f64 * self.step_m
    }

    /// The stretch of the stroke nearest to positions `first..=last`, m.
    fn stretch_m(&self, first: usize, last: usize) -> (f64, f64) {
        let half = self.half_m;
        (
            (self.position_m(first) - self.step_m / 2.0).max(-half),
            (self.position_m(last) + self.step_m / 2.0).min(half),
        )
    }

    /// Presses `pressure` over the stretch of the stroke nearest to position `j`.
    pub(super) fn press(&mut self, j: usize, pressure: &[f64]) {
        let (from, to) = self.stretch_m(j, j);
        self.pressure.add_pass(&self.grid, pressure, from, to);
    }

    /// Adds position `j`, next to the run's, to the run of positions that press one
    /// pressure, pressed at once by [`Self::flush`]: in the middle of a long stroke,
    /// hundreds of positions keep one solve.
    pub(super) fn keep(&mut self, j: usize) {
        self.run = Some(match self.run {
            None => (j, j),
            Some((first, last)) => {
                debug_assert!(
                    j + 1 == first || j == last + 1,
                    "{j} next to {first}..={last}"
                );
                (first.min(j), last.max(j))
            }
        });
    }

    /// Presses `pressure` over the stretch of the run of [`Self::keep`], and ends it.
    pub(super) fn flush(&mut self, pressure: &[f64]) {
        if let Some((first, last)) = self.run.take() {
            let (from, to) = self.stretch_m(first, last);
            self.pressure.add_pass(&self.grid, pressure, from, to);
        }
    }

    /// Records the interpenetrations `pressed_in` at position `j`: each map cell keeps its
    /// deepest.
    pub(super) fn push_in(&mut self, j: usize, pressed_in: &[(usize, usize, f64)]) {
        let (grid, x, map) = (self.grid, self.position_m(j), &self.pressure);
        for &(c, iy, depth_m) in pressed_in {
            let column = ((x + grid.x(c)) / map.dx + map.nx as f64 / 2.0).floor();
            if (0.0..map.nx as f64).contains(&column) {
                let cell = &mut self.yielded[iy * map.nx + column as usize];
                *cell = cell.max(depth_m);
            }
        }
    }
}
