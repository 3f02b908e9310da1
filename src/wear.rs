//! The wear track: the groove depth `D(y)` across the track, uniform along it (the ball passes
//! over every point of the track once per cycle), and the two ways it deepens (paper
//! Section 3.2): yielding while pressures sit at the cap (eq. 13) and Archard wear (eqs. 15-16).

use crate::contact::{ContactSolution, Grid};

/// The fraction of the deepest point at which the groove's edges are drawn. For the
/// parabolic groove a ball wears, the width at 1% of the depth is sqrt(0.99) = 99.5% of the
/// full width, and a row the contact has only just reached stays below it.
pub const EDGE_DEPTH_FRACTION: f64 = 0.01;

/// Depth below the original disc surface for each grid row (each `y`), m.
#[derive(Debug, Clone, PartialEq)]
pub struct Groove {
    depth_m: Vec<f64>,
    dy: f64,
}

impl Groove {
    /// An unworn disc on `grid`.
    pub fn new(grid: &Grid) -> Self {
        Self {
            depth_m: vec![0.0; grid.ny],
            dy: grid.dy,
        }
    }

    /// Depth per row, m.
    pub fn depth_m(&self) -> &[f64] {
        &self.depth_m
    }

    /// The separation of the undeformed surfaces: the ball's height plus the groove (removed
    /// disc material widens the gap; eq. 17).
    pub fn separation(&self, ball: &[f64], grid: &Grid) -> Vec<f64> {
        let mut h = ball.to_vec();
        for (row, &d) in h.chunks_exact_mut(grid.nx).zip(&self.depth_m) {
            row.iter_mut().for_each(|v| *v += d);
        }
        h
    }

    /// Adds `scale * increment` to the depth of every row.
    pub fn deepen(&mut self, increment: &[f64], scale: f64) {
        for (d, &i) in self.depth_m.iter_mut().zip(increment) {
            *d += scale * i;
        }
    }

    /// Cross-section area of the groove, m^2; times the track length, the wear volume.
    pub fn area_m2(&self) -> f64 {
        self.depth_m.iter().sum::<f64>() * self.dy
    }

    /// Deepest point, m.
    pub fn max_depth_m(&self) -> f64 {
        self.depth_m.iter().fold(0.0, |m, &d| m.max(d))
    }

    /// Width of the worn band, m: between the outermost points where the depth, linearly
    /// interpolated between row centres, crosses [`EDGE_DEPTH_FRACTION`] of the deepest
    /// point. Counting the rows with any depth makes the width jump by a whole row when the
    /// contact reaches a new one, and the potential computed from it fall in stairs; a
    /// crossing between rows moves continuously as the depths grow.
    pub fn worn_width_m(&self) -> f64 {
        let depth = &self.depth_m;
        let threshold = EDGE_DEPTH_FRACTION * self.max_depth_m();
        if threshold <= 0.0 {
            return 0.0;
        }
        let (Some(first), Some(last)) = (
            depth.iter().position(|&d| d >= threshold),
            depth.iter().rposition(|&d| d >= threshold),
        ) else {
            return 0.0;
        };
        // Distance beyond the row `inside` (at or above the threshold) towards its unworn
        // neighbour `outside` where the depth crosses the threshold; half a cell at the
        // domain's edge, where there is no neighbour.
        let beyond = |inside: usize, outside: Option<usize>| match outside {
            Some(o) => (depth[inside] - threshold) / (depth[inside] - depth[o]) * self.dy,
            None => 0.5 * self.dy,
        };
        let left = beyond(first, first.checked_sub(1));
        let right = beyond(last, (last + 1 < depth.len()).then_some(last + 1));
        (last - first) as f64 * self.dy + left + right
    }

    /// The groove on a larger grid with the same cells, centred: the new outer rows are
    /// unworn. `offset` rows are added on each side.
    pub fn widened(&self, offset: usize) -> Self {
        let mut depth_m = vec![0.0; self.depth_m.len() + 2 * offset];
        depth_m[offset..offset + self.depth_m.len()].copy_from_slice(&self.depth_m);
        Self {
            depth_m,
            dy: self.dy,
        }
    }
}

/// Eq. 13: where the pressure sits at the cap, the material yields by the interpenetration
/// that remains, `(delta - h) - u = -g`; the ball sweeps every `x`, so each row deepens by the
/// largest such value along it. Rows with no capped cell get 0.
pub fn yield_depth(
    grid: &Grid,
    solution: &ContactSolution,
    separation: &[f64],
    cap: f64,
) -> Vec<f64> {
    let mut depth = vec![0.0f64; grid.ny];
    for (i, &p) in solution.pressure.iter().enumerate() {
        if p >= cap {
            let gap = solution.displacement[i] + separation[i] - solution.approach_m;
            let row = &mut depth[i / grid.nx];
            *row = row.max(-gap);
        }
    }
    depth
}

/// Eqs. 15-16: one pass of the ball removes `k / H` times the pressure integrated along the
/// sliding direction, `int p(x, y) dx`, from each row. Returned without the `k / H` factor
/// (Pa m), since H changes with the cycle. Summed over rows and times `dy` it is the load:
/// one pass removes `k F L / H` in volume, Archard's law (eq. 14) for a track of length L.
pub fn pass_pressure_integral(grid: &Grid, pressure: &[f64]) -> Vec<f64> {
    pressure
        .chunks_exact(grid.nx)
        .map(|row| row.iter().sum::<f64>() * grid.dx)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn archard_pass_integrates_to_the_load() {
        let grid = Grid::square(16, 16e-6).expect("valid");
        let pressure: Vec<f64> = (0..grid.len()).map(|i| (i % 5) as f64 * 1e8).collect();
        let load: f64 = pressure.iter().sum::<f64>() * grid.cell_area();
        let per_row = pass_pressure_integral(&grid, &pressure);
        let integral: f64 = per_row.iter().sum::<f64>() * grid.dy;
        assert!((integral / load - 1.0).abs() < 1e-14);
    }

    #[test]
    fn worn_width_finds_the_edges_of_a_tent_between_rows() {
        // A tent d = w / 2 - |y - y0|, continued below zero so that both rows around each
        // crossing lie on its straight flanks: the interpolated crossing of 1% of the sampled
        // peak is then exact wherever it falls between row centres, up to the rounding of the
        // row positions (about 1e-14 um, far below the 1e-9 allowed).
        let grid = Grid::square(64, 64e-6).expect("valid");
        for (w_um, y0_um) in [(20.3, 32.0), (20.9, 32.0), (21.4, 31.7), (7.3, 30.2)] {
            let tent: Vec<f64> = (0..grid.ny)
                .map(|iy| w_um / 2.0 - (grid.y(iy) * 1e6 + 32.0 - y0_um).abs())
                .collect();
            let mut groove = Groove::new(&grid);
            groove.deepen(&tent, 1e-9);
            let peak_um = tent.iter().fold(0.0f64, |m, &d| m.max(d));
            // The sampled peak may sit below the tent's apex: the crossing is at 1% of it.
            let expected_um = w_um - 2.0 * EDGE_DEPTH_FRACTION * peak_um;
            let width_um = groove.worn_width_m() * 1e6;
            assert!(
                (width_um - expected_um).abs() < 1e-9 * w_um,
                "width {width_um} um for a {w_um} um tent, expected {expected_um}"
            );
        }
        assert_eq!(Groove::new(&grid).worn_width_m().to_bits(), 0f64.to_bits());
    }

    #[test]
    fn a_row_just_reached_moves_the_width_by_a_fraction_of_a_cell() {
        // A row entering the contact with a depth far below the threshold leaves the width as
        // it was: only the crossing between rows moves, by the depth it adds.
        let grid = Grid::square(16, 16e-6).expect("valid");
        let mut groove = Groove::new(&grid);
        let mut profile = vec![0.0; grid.ny];
        profile[6..10].copy_from_slice(&[1.0, 2.0, 2.0, 1.0]);
        groove.deepen(&profile, 1e-6);
        let before = groove.worn_width_m();
        let mut reached = vec![0.0; grid.ny];
        reached[5] = 1e-4;
        reached[10] = 1e-4;
        groove.deepen(&reached, 1e-6);
        let after = groove.worn_width_m();
        assert!(after > before, "the new rows add width");
        assert!(after - before < 1e-3 * grid.dy, "{before} -> {after}");
    }

    #[test]
    fn widening_keeps_the_groove_centred() {
        let grid = Grid::square(4, 4e-6).expect("valid");
        let mut groove = Groove::new(&grid);
        groove.deepen(&[1.0, 2.0, 2.0, 1.0], 1e-6);
        let wide = groove.widened(2);
        assert_eq!(wide.depth_m().len(), 8);
        assert!((wide.area_m2() - groove.area_m2()).abs() < 1e-24);
        assert!((wide.depth_m()[3] - 2e-6).abs() < 1e-20);
    }
}
