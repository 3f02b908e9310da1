//! The wear track: the groove depth `D(y)` across the track, uniform along it (the ball passes
//! over every point of the track once per cycle), and the two ways it deepens (paper
//! Section 3.2): yielding while pressures sit at the cap (eq. 13) and Archard wear (eqs. 15-16).

use crate::contact::{ContactSolution, Grid};

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

    /// Width of the worn band, m, between its two edges found to sub-cell precision: each
    /// edge is where the depth, extrapolated linearly from the two outermost worn rows, falls
    /// to zero, and lies within one cell of the outermost worn row (the next row is unworn).
    /// Counting whole rows instead makes the width, and the potential computed from it, move
    /// in steps of one cell as the groove widens. Linear is the right order: one pass of a
    /// Hertzian pressure removes a depth proportional to `a^2 - y^2`, which vanishes with a
    /// finite slope at the contact's edge.
    pub fn worn_width_m(&self) -> f64 {
        let depth = &self.depth_m;
        let (Some(first), Some(last)) = (
            depth.iter().position(|&d| d > 0.0),
            depth.iter().rposition(|&d| d > 0.0),
        ) else {
            return 0.0;
        };
        let beyond = |outer: usize, inner: Option<usize>| {
            let fall = inner.map_or(0.0, |i| depth[i] - depth[outer]);
            if fall > 0.0 {
                (depth[outer] / fall).min(1.0) * self.dy
            } else {
                self.dy
            }
        };
        let inner_of_first = (first < last).then_some(first + 1);
        let inner_of_last = (first < last).then(|| last - 1);
        (last - first) as f64 * self.dy
            + beyond(first, inner_of_first)
            + beyond(last, inner_of_last)
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
        // A tent d = c (w / 2 - |y - y0|) falls linearly to its edges, so the extrapolation is
        // exact wherever the edges fall between row centres: only rounding of the row
        // positions remains, about 1e-14 um, far below the 1e-9 relative allowed.
        let grid = Grid::square(64, 64e-6).expect("valid");
        for (w_um, y0_um) in [(20.3, 32.0), (20.9, 32.0), (21.4, 31.7), (7.3, 30.2)] {
            let mut groove = Groove::new(&grid);
            let tent: Vec<f64> = (0..grid.ny)
                .map(|iy| (w_um / 2.0 - (grid.y(iy) * 1e6 + 32.0 - y0_um).abs()).max(0.0))
                .collect();
            groove.deepen(&tent, 1e-9);
            let width_um = groove.worn_width_m() * 1e6;
            assert!(
                (width_um - w_um).abs() < 1e-9 * w_um,
                "width {width_um} um for a {w_um} um tent"
            );
        }
        assert_eq!(Groove::new(&grid).worn_width_m().to_bits(), 0f64.to_bits());
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
