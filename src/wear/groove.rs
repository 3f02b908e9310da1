//! The disc's surface in the wear track and the two ways it wears (paper Section 3.2):
//! yielding while pressures sit at the cap (eq. 13) and the depth a wear law removes
//! (eqs. 15-17 for Archard's, [`super::WearLaw`]).
//!
//! The surface under the ball is `H(x, y) = min(r(x, y), c(y)) - D(y)`: `r` the initial
//! roughness (zero on a smooth disc; heights on the first grid's cells, repeating beyond
//! them), `D(y)` the worn groove and `c(y)` the level yielding has truncated row `y` to
//! (+inf until it yields). Both are uniform along the track, since the ball passes over
//! every point of the track once per cycle: every asperity of a row passes under the
//! row's most-pressed point. Yielding truncates a row at the lowest level a capped cell of
//! it was pressed to; on a smooth disc this deepens the row by its largest interpenetration,
//! the paper's rule, while on a rough one it flattens the asperity tops without sinking the
//! valleys between them. The depth reported per row is the mean over one period of the
//! roughness along the track of `r - H`, `D + mean(r - min(r, c))`: the worn volume per
//! unit length of track.

use crate::contact::{ContactSolution, Grid};

/// The fraction of the deepest point at which the groove's edges are drawn. For the
/// parabolic groove a ball wears, the width at 1% of the depth is sqrt(0.99) = 99.5% of the
/// full width, and a row the contact has only just reached stays below it.
pub const EDGE_DEPTH_FRACTION: f64 = 0.01;

/// The disc's initial roughness: heights on the cells of the grid it was made on, repeating
/// beyond them (a grid grown from that one, centred on the apex with the same cells, sees
/// it periodically).
#[derive(Debug, Clone, PartialEq)]
struct Roughness {
    heights_m: Vec<f64>,
    nx: usize,
    ny: usize,
}

impl Roughness {
    /// One period along the track of the roughness under row `iy` of a grid of `ny` rows.
    fn row(&self, iy: usize, ny: usize) -> &[f64] {
        let start = periodic_index(iy, ny, self.ny) * self.nx;
        &self.heights_m[start..start + self.nx]
    }
}

/// The cell of a period of `period` cells under cell `i` of a grid of `n` cells, both
/// centred on the apex with the same cells (grids grow by the same cells on both sides, so
/// `n - period` is even).
fn periodic_index(i: usize, n: usize, period: usize) -> usize {
    let shift = (n as i64 - period as i64).div_euclid(2);
    (i as i64 - shift).rem_euclid(period as i64) as usize
}

/// The disc surface in the track: the groove, the truncation of the asperities, and the
/// depth per grid row (each `y`) they make together.
#[derive(Debug, Clone, PartialEq)]
pub struct Groove {
    /// The worn groove `D(y)`, m.
    worn_m: Vec<f64>,
    /// The truncation level `c(y)`, m above the original surface's mean plane.
    ceiling_m: Vec<f64>,
    /// `D + mean(r - min(r, c))` per row, m.
    depth_m: Vec<f64>,
    roughness: Option<Roughness>,
    dy: f64,
}

impl Groove {
    /// An unworn smooth disc on `grid`.
    pub fn new(grid: &Grid) -> Self {
        Self {
            worn_m: vec![0.0; grid.ny],
            ceiling_m: vec![f64::INFINITY; grid.ny],
            depth_m: vec![0.0; grid.ny],
            roughness: None,
            dy: grid.dy,
        }
    }

    /// An unworn disc on `grid` whose surface rises `heights_m` above its mean plane at each
    /// of `grid`'s cells (row by row), repeating beyond them.
    pub fn rough(grid: &Grid, heights_m: Vec<f64>) -> Self {
        debug_assert_eq!(heights_m.len(), grid.len(), "one height per cell");
        Self {
            roughness: Some(Roughness {
                heights_m,
                nx: grid.nx,
                ny: grid.ny,
            }),
            ..Self::new(grid)
        }
    }

    /// Depth per row, m: below the original surface, averaged along the track.
    pub fn depth_m(&self) -> &[f64] {
        &self.depth_m
    }

    /// The roughness as yielding has left it, `min(r, c)`, at each cell of `grid` (the grid
    /// the groove is on): m above the original mean plane, the groove `D` left out.
    pub fn roughness_m(&self, grid: &Grid) -> Vec<f64> {
        self.rows_of(grid, |_, row, out| out.extend_from_slice(row))
    }

    /// The separation of the undeformed surfaces: the ball's height plus the disc's depth
    /// below the original mean plane at each cell, `D - min(r, c)` (eq. 17; removed disc
    /// material widens the gap, an asperity narrows it).
    pub fn separation(&self, ball: &[f64], grid: &Grid) -> Vec<f64> {
        self.rows_of(grid, |iy, row, out| {
            let (d, ball) = (self.worn_m[iy], &ball[iy * grid.nx..][..grid.nx]);
            out.extend(row.iter().zip(ball).map(|(&r, &b)| b + (d - r)));
        })
    }

    /// A field of `grid` built row by row: `push(iy, roughness, out)` appends row `iy` to
    /// `out` from the row's [`Self::roughness_row`]. Into a buffer of the final length, so
    /// that no row grows it and no whole grid is zeroed first.
    fn rows_of(&self, grid: &Grid, mut push: impl FnMut(usize, &[f64], &mut Vec<f64>)) -> Vec<f64> {
        let mut out = Vec::with_capacity(grid.len());
        let mut row = vec![0.0; grid.nx];
        for iy in 0..grid.ny {
            self.roughness_row(iy, &mut row);
            push(iy, &row, &mut out);
        }
        out
    }

    /// [`Self::roughness_m`] along row `iy`, into `out` (one row of the grid the groove is
    /// on). The roughness repeats along the row, so the row is its period's row copied from
    /// the cell under the row's first: copied by runs, not indexed cell by cell (on the 2 um
    /// example's 300 um domain that lookup, a division per cell, and the whole grid's
    /// separation around it were an eighth of the run's serial samples, `perf record
    /// --call-graph dwarf` of `tribosim run scenes/bench-rough-2um-300um.json`).
    fn roughness_row(&self, iy: usize, out: &mut [f64]) {
        let c = self.ceiling_m[iy];
        let Some(roughness) = &self.roughness else {
            out.fill(c.min(0.0));
            return;
        };
        let heights = roughness.row(iy, self.depth_m.len());
        let mut from = periodic_index(0, out.len(), roughness.nx);
        let mut rest = out;
        while !rest.is_empty() {
            let run = (heights.len() - from).min(rest.len());
            let (head, tail) = rest.split_at_mut(run);
            for (o, &h) in head.iter_mut().zip(&heights[from..]) {
                *o = h.min(c);
            }
            (rest, from) = (tail, 0);
        }
    }

    /// Eq. 13: where the pressure sits at the cap the material yields by the interpenetration
    /// that remains, `t = (delta - h) - u = -g`. The ball sweeps every `x` of a row, so every
    /// point of the row passes under each capped cell and is cut to the lowest level one was
    /// pressed to, `min(r, c) - t` on the scale of `c`. `separation` is the one the contact
    /// was solved on. Returns whether any capped cell interpenetrated (the disc yielded).
    pub fn yield_under(
        &mut self,
        grid: &Grid,
        solution: &ContactSolution,
        separation: &[f64],
        cap: f64,
    ) -> bool {
        // Only the capped rows' heights are needed: most rows of a grown grid, and most
        // cycles of a smooth disc, have none. Looked up cell by cell (the row's iterator
        // advanced to the cell), they were 3.8% of the samples of 100 cycles of the 2 um
        // example on a 300 um domain (`perf record -F 99 --call-graph dwarf`).
        let mut ceiling = self.ceiling_m.clone();
        let mut yielded = false;
        let mut roughness = vec![0.0; grid.nx];
        let rows = solution.pressure.chunks_exact(grid.nx).enumerate();
        for (iy, pressure) in rows.filter(|(_, row)| row.iter().any(|&p| p >= cap)) {
            let cells = iy * grid.nx..(iy + 1) * grid.nx;
            let (u, h) = (&solution.displacement[cells.clone()], &separation[cells]);
            self.roughness_row(iy, &mut roughness);
            for (((&p, &u), &h), &r) in pressure.iter().zip(u).zip(h).zip(&roughness) {
                if p >= cap {
                    let gap = u + h - solution.approach_m;
                    yielded |= gap < 0.0;
                    // A capped cell the solver left a hair short of contact was pressed to
                    // its own surface.
                    ceiling[iy] = ceiling[iy].min(r + gap.min(0.0));
                }
            }
        }
        for (iy, level) in ceiling.into_iter().enumerate() {
            if level < self.ceiling_m[iy] {
                self.ceiling_m[iy] = level;
                self.depth_m[iy] = self.worn_m[iy] + self.cut_m(iy);
            }
        }
        yielded
    }

    /// The material yielding has cut from row `iy`, averaged along the track:
    /// `mean(r - min(r, c))`, m.
    fn cut_m(&self, iy: usize) -> f64 {
        let c = self.ceiling_m[iy];
        match &self.roughness {
            Some(r) => {
                let row = r.row(iy, self.depth_m.len());
                row.iter().map(|&h| h - h.min(c)).sum::<f64>() / row.len() as f64
            }
            None => -c.min(0.0),
        }
    }

    /// Adds `scale * increment` to the groove `D` of every row (a wear law's depth).
    pub fn deepen(&mut self, increment: &[f64], scale: f64) {
        for ((w, d), &i) in self.worn_m.iter_mut().zip(&mut self.depth_m).zip(increment) {
            *w += scale * i;
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

    /// The groove on `wider`, a grid grown from its own (the same cells, centred): the new
    /// outer rows are unworn, and the roughness repeats into them.
    pub fn widened(&self, wider: &Grid) -> Self {
        let offset = wider.ny.saturating_sub(self.depth_m.len()) / 2;
        let pad = |rows: &[f64], unworn: f64| {
            let mut out = vec![unworn; wider.ny];
            out[offset..offset + rows.len()].copy_from_slice(rows);
            out
        };
        Self {
            worn_m: pad(&self.worn_m, 0.0),
            ceiling_m: pad(&self.ceiling_m, f64::INFINITY),
            depth_m: pad(&self.depth_m, 0.0),
            roughness: self.roughness.clone(),
            dy: self.dy,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn on_a_smooth_disc_a_row_deepens_by_its_largest_interpenetration() {
        // The paper's rule (eq. 13): rows 0 and 1 already worn 0.1 and 0.2 um; at approach
        // 0.5 um row 0's capped cells interpenetrate by 0.3 and 0.1 um, row 1's stays 0.3 um
        // short of contact, row 2 has none.
        let grid = Grid::new(4, 3, 1e-6, 1e-6).expect("valid");
        let mut groove = Groove::new(&grid);
        groove.deepen(&[0.1, 0.2, 0.0], 1e-6);
        let ball = vec![0.0; grid.len()];
        let press = |groove: &mut Groove, displacement_um: &[(usize, f64)]| {
            let mut solution = ContactSolution {
                pressure: vec![0.0; grid.len()],
                displacement: vec![0.0; grid.len()],
                approach_m: 0.5e-6,
                iterations: 0,
                operator_applies: 0,
                residual: 0.0,
                preconditioner_fallbacks: 0,
                uniform_restarts: 0,
            };
            for &(i, u) in displacement_um {
                solution.pressure[i] = 1e9;
                solution.displacement[i] = u * 1e-6;
            }
            let separation = groove.separation(&ball, &grid);
            groove.yield_under(&grid, &solution, &separation, 1e9)
        };
        assert!(press(&mut groove, &[(1, 0.1), (3, 0.3), (6, 0.6)]));
        // Sums of a few sub-um lengths: within a few ulps (1e-22 m).
        let close = |depth: &[f64], um: [f64; 3]| {
            depth
                .iter()
                .zip(um)
                .all(|(d, um)| (d - um * 1e-6).abs() < 1e-20)
        };
        assert!(
            close(groove.depth_m(), [0.4, 0.2, 0.0]),
            "{:?}",
            groove.depth_m()
        );
        // The next cycle, 0.05 um further into row 0: it deepens by that much again.
        assert!(press(&mut groove, &[(2, 0.05)]));
        assert!(
            close(groove.depth_m(), [0.45, 0.2, 0.0]),
            "{:?}",
            groove.depth_m()
        );
        assert!(
            !press(&mut groove, &[(2, 0.2)]),
            "short of contact: no yield"
        );
    }

    #[test]
    fn widening_keeps_the_groove_centred() {
        let grid = Grid::square(4, 4e-6).expect("valid");
        let mut groove = Groove::new(&grid);
        groove.deepen(&[1.0, 2.0, 2.0, 1.0], 1e-6);
        let wider = Grid::new(4, 8, grid.dx, grid.dy).expect("valid");
        let wide = groove.widened(&wider);
        assert_eq!(wide.depth_m().len(), 8);
        assert!((wide.area_m2() - groove.area_m2()).abs() < 1e-24);
        assert!((wide.depth_m()[3] - 2e-6).abs() < 1e-20);
    }

    #[test]
    fn a_grown_grid_sees_the_roughness_repeat() {
        // Heights numbered by cell on a 4 x 2 grid; grown to 8 x 6, two cells and two rows
        // on each side, the grid's cell (ix, iy) lies over the original cell
        // ((ix - 2) mod 4, (iy - 2) mod 2).
        let grid = Grid::new(4, 2, 1e-6, 1e-6).expect("valid");
        let heights: Vec<f64> = (0..8).map(f64::from).collect();
        let groove = Groove::rough(&grid, heights.clone());
        assert_eq!(groove.roughness_m(&grid), heights);
        let wider = Grid::new(8, 6, 1e-6, 1e-6).expect("valid");
        let seen = groove.widened(&wider).roughness_m(&wider);
        for (i, &h) in seen.iter().enumerate() {
            let (ix, iy) = (i % 8, i / 8);
            let original = ((iy + 2) % 2) * 4 + (ix + 2) % 4;
            assert_eq!(
                h.to_bits(),
                heights[original].to_bits(),
                "cell ({ix}, {iy})"
            );
        }
    }
}
