//! Reciprocating sliding (ASTM G133's ball on a flat): where the ball is along its stroke,
//! how fast it goes, when it passes a point of the track, and the wear a stretch of the
//! stroke leaves on the flat.
//!
//! Archard's law removes `k / H` times the pressure integrated over the sliding distance,
//! not over time: a point of the flat at `x` loses `(k / H) int p(x - X, y) dX` over the
//! ball positions `X` a pass covers, whatever the speed along the way. The velocity law
//! therefore shapes only the times (between the passes over a point, which the
//! electrochemistry needs), and the wear map of a pass is the overlap sum of
//! [`WearMap::add_pass`], exact for pressures constant over each cell.

use serde::{Deserialize, Serialize};

use crate::contact::Grid;

/// How the speed varies along the stroke, named in the JSON as `sinusoidal` and `constant`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VelocityLaw {
    /// As a crank drives it: `X(t) = -(L / 2) cos(2 pi f t)`, at rest at both ends.
    #[default]
    Sinusoidal,
    /// At `2 L f` throughout, turning at once at the ends.
    Constant,
}

/// A reciprocating stroke: its length, frequency and velocity law. The ball's centre
/// moves between `-L / 2` and `L / 2`, starting at `-L / 2` at `t = 0`; a cycle is one
/// stroke forward and one back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Stroke length L, m.
    pub length_m: f64,
    /// Cycles per second f, Hz.
    pub frequency_hz: f64,
    /// The speed along the stroke.
    pub law: VelocityLaw,
}

impl Stroke {
    /// One cycle's duration, `1 / f`, s.
    pub fn period_s(&self) -> f64 {
        1.0 / self.frequency_hz
    }

    /// The sliding distance of one cycle, `2 L`, m.
    pub fn sliding_distance_per_cycle_m(&self) -> f64 {
        2.0 * self.length_m
    }

    /// The mean speed, `2 L f`, m/s.
    pub fn mean_speed_m_s(&self) -> f64 {
        2.0 * self.length_m * self.frequency_hz
    }

    /// The largest speed, m/s: `pi L f` for the crank, `2 L f` for the constant law.
    pub fn peak_speed_m_s(&self) -> f64 {
        match self.law {
            VelocityLaw::Sinusoidal => std::f64::consts::PI * self.length_m * self.frequency_hz,
            VelocityLaw::Constant => self.mean_speed_m_s(),
        }
    }

    /// The fraction of a cycle, `0..1`, at time `t_s`.
    fn phase(&self, t_s: f64) -> f64 {
        (t_s * self.frequency_hz).rem_euclid(1.0)
    }

    /// The ball centre's position at `t_s`, m.
    pub fn position_m(&self, t_s: f64) -> f64 {
        let phase = self.phase(t_s);
        let half = self.length_m / 2.0;
        match self.law {
            VelocityLaw::Sinusoidal => -half * (std::f64::consts::TAU * phase).cos(),
            // Forward over the first half cycle, back over the second.
            VelocityLaw::Constant => -half + self.length_m * (1.0 - (2.0 * phase - 1.0).abs()),
        }
    }

    /// The ball's speed at `t_s` (the magnitude), m/s.
    pub fn speed_m_s(&self, t_s: f64) -> f64 {
        match self.law {
            VelocityLaw::Sinusoidal => {
                self.peak_speed_m_s() * (std::f64::consts::TAU * self.phase(t_s)).sin().abs()
            }
            VelocityLaw::Constant => self.mean_speed_m_s(),
        }
    }

    /// The two times between the passes of the ball's centre over `x_m` (`|x| <= L / 2`),
    /// s: from the forward pass to the return, and from the return to the next forward
    /// pass. They add up to the period; both are half of it at the middle, and one
    /// vanishes at an end.
    pub fn times_between_passes_s(&self, x_m: f64) -> (f64, f64) {
        let period = self.period_s();
        let to_return = period - 2.0 * self.forward_pass_time_s(x_m);
        (to_return, period - to_return)
    }

    /// When in the cycle the ball's centre passes `x_m` going forward, s: from 0 at the
    /// start (`-L / 2`) to half the period at the far end; the return passes at the
    /// period less this. `x_m` beyond the stroke is taken at its nearer end.
    pub fn forward_pass_time_s(&self, x_m: f64) -> f64 {
        let half = self.length_m / 2.0;
        let x = x_m.clamp(-half, half);
        let phase = match self.law {
            VelocityLaw::Sinusoidal => (-x / half).acos() / std::f64::consts::TAU,
            VelocityLaw::Constant => (x + half) / (2.0 * self.length_m),
        };
        phase * self.period_s()
    }
}

/// Stretches longer than this many cells take [`WearMap::add_pass`]'s prefix sums. Counted
/// in cell operations, the column-by-column visit costs the grid's cells times the
/// stretch's cells plus two; the prefix sums one pass over the grid to build, then a few
/// operations per row for each of the stretch's cells plus the grid's columns: they break
/// even near two cells. A sweep's single positions, about a cell each, keep the visit.
const LONG_STRETCH_CELLS: f64 = 4.0;

/// The flat's wear along and across the track: depths on cells of the contact grid's size,
/// centred on the stroke's middle, columns along the stroke and rows across it.
#[derive(Debug, Clone, PartialEq)]
pub struct WearMap {
    /// Columns, along the stroke.
    pub nx: usize,
    /// Rows, across the track (the contact grid's rows).
    pub ny: usize,
    /// Cell size along the stroke, m (the contact grid's).
    pub dx: f64,
    /// Depth below the original surface per cell, row-major (x fastest), in the unit of
    /// what is added (m of depth, or Pa m of pressure integral before `k / H`).
    pub depth: Vec<f64>,
}

impl WearMap {
    /// An unworn map covering a stroke of `length_m` and the contact grid `grid` at
    /// both ends: the stroke's cells and the grid's columns, rounded up to an even count so
    /// that the map is symmetric about the stroke's middle.
    pub fn new(grid: &Grid, length_m: f64) -> Self {
        let along = (length_m / grid.dx).ceil() as usize + grid.nx;
        let nx = along + along % 2;
        Self {
            nx,
            ny: grid.ny,
            dx: grid.dx,
            depth: vec![0.0; nx * grid.ny],
        }
    }

    /// This map on the map of the wider grid `grid` (the same cells, more of them), its
    /// depths centred in the new one: both counts are even, so the margins are whole cells.
    pub fn embedded_in(&self, grid: &Grid, length_m: f64) -> Self {
        let mut wider = Self::new(grid, length_m);
        let (x0, y0) = ((wider.nx - self.nx) / 2, (wider.ny - self.ny) / 2);
        for (iy, row) in self.depth.chunks_exact(self.nx).enumerate() {
            let start = (iy + y0) * wider.nx + x0;
            wider.depth[start..start + self.nx].copy_from_slice(row);
        }
        wider
    }

    /// The depths along the row nearest the track's centre line, one per column.
    pub fn centre_row(&self) -> &[f64] {
        let iy = self.ny / 2;
        &self.depth[iy * self.nx..(iy + 1) * self.nx]
    }

    /// The depths across the track at the stroke's middle (the mean of the two middle
    /// columns, the map being symmetric about it), one per row.
    pub fn middle_column(&self) -> Vec<f64> {
        let ix = self.nx / 2;
        (0..self.ny)
            .map(|iy| 0.5 * (self.depth[iy * self.nx + ix - 1] + self.depth[iy * self.nx + ix]))
            .collect()
    }

    /// x of the centre of column `ix`, m, from the stroke's middle.
    pub fn x(&self, ix: usize) -> f64 {
        (ix as f64 + 0.5 - self.nx as f64 / 2.0) * self.dx
    }

    /// Adds `int p(x - X, y) dX` over the ball positions `X` from `from_m` to `to_m` (in
    /// either order), `pressure` on `grid`'s cells centred on the ball: a pass's share of
    /// the wear before `k / H`. A cell of `grid` at `xi` presses the map's column at `x`
    /// while `X` is within `dx / 2` of `x - xi`, so each pair adds its pressure times the
    /// length of that interval inside the stretch: exact for pressures constant over each
    /// cell, as the contact solution's are.
    ///
    /// A stretch of a few cells (a sweep's single position) visits, per grid column, the
    /// columns it reaches, with nothing allocated. A longer one (a run of positions that
    /// keep one solve's pressure) would visit the stretch's columns from every grid
    /// column; it sums each map column's wholly covered cells from prefix sums along the
    /// rows instead, so its cost is the map columns it reaches rather than their product
    /// with the grid's.
    pub fn add_pass(&mut self, grid: &Grid, pressure: &[f64], from_m: f64, to_m: f64) {
        debug_assert_eq!(pressure.len(), grid.len(), "one pressure per cell");
        debug_assert_eq!(grid.ny, self.ny, "the map has the grid's rows");
        let (lo, hi) = (from_m.min(to_m), from_m.max(to_m));
        if hi - lo > LONG_STRETCH_CELLS * grid.dx {
            self.add_long_pass(grid, pressure, lo, hi);
        } else {
            self.add_short_pass(grid, pressure, lo, hi);
        }
    }

    /// [`Self::add_pass`] column by column, for `lo <= hi`.
    fn add_short_pass(&mut self, grid: &Grid, pressure: &[f64], lo: f64, hi: f64) {
        let half = grid.dx / 2.0;
        let column_of = |x: f64| x / self.dx + self.nx as f64 / 2.0 - 0.5;
        for c in 0..grid.nx {
            let xi = grid.x(c);
            // The map columns whose centre x has x - xi - dx/2 < hi and x - xi + dx/2 > lo.
            let first = column_of(lo + xi - half).floor().max(0.0) as usize;
            let last = (column_of(hi + xi + half).ceil().max(0.0) as usize).min(self.nx - 1);
            for ix in first..=last {
                let centre = self.x(ix) - xi;
                let length = (centre + half).min(hi) - (centre - half).max(lo);
                if length <= 0.0 {
                    continue;
                }
                for iy in 0..self.ny {
                    self.depth[iy * self.nx + ix] += pressure[iy * grid.nx + c] * length;
                }
            }
        }
    }

    /// [`Self::add_pass`] from prefix sums, for `hi - lo` over a cell. Grid column `c`
    /// presses map column `ix` for the ball positions within `dx / 2` of
    /// `s = x(ix) - xi(c) = (ix - c + offset) dx`: wholly (length `dx`) for `s` in
    /// `[lo + dx/2, hi - dx/2]`, a contiguous run of `c` summed from the prefix sums, and
    /// in part for the at most two columns at either end of that run.
    fn add_long_pass(&mut self, grid: &Grid, pressure: &[f64], lo: f64, hi: f64) {
        let (dx, n) = (grid.dx, grid.nx);
        let half = dx / 2.0;
        let mut sums = vec![0.0; (n + 1) * grid.ny];
        for (row, out) in pressure.chunks_exact(n).zip(sums.chunks_exact_mut(n + 1)) {
            for c in 0..n {
                out[c + 1] = out[c] + row[c];
            }
        }
        let offset = (n as f64 - self.nx as f64) / 2.0;
        // The map columns some cell reaches: `s` within (lo - dx/2, hi + dx/2) for a `c`
        // in 0..n.
        let first_ix = ((lo - half) / dx - offset).floor().max(0.0) as usize;
        let last_ix = ((hi + half) / dx - offset + n as f64).ceil().max(0.0) as usize;
        let last_ix = last_ix.min(self.nx - 1);
        let clip = |c: f64| c.clamp(-1.0, n as f64) as isize;
        let mut partial: Vec<(usize, f64)> = Vec::with_capacity(4);
        for ix in first_ix..=last_ix {
            let base = ix as f64 + offset;
            let (whole_lo, whole_hi) = (
                clip((base - (hi - half) / dx).ceil()),
                clip((base - (lo + half) / dx).floor()),
            );
            let (reach_lo, reach_hi) = (
                clip((base - (hi + half) / dx).floor()).max(0),
                clip((base - (lo - half) / dx).ceil()).min(n as isize - 1),
            );
            let whole = (whole_lo.max(0), whole_hi.min(n as isize - 1));
            // Partial columns: those reached outside the whole run (all reached ones when
            // the run is empty).
            let outside = |c: isize| whole.0 > whole.1 || c < whole.0 || c > whole.1;
            partial.clear();
            partial.extend(
                (reach_lo..=reach_hi)
                    .filter(|&c| outside(c))
                    .filter_map(|c| {
                        let centre = (base - c as f64) * dx;
                        let length = (centre + half).min(hi) - (centre - half).max(lo);
                        (length > 0.0).then_some((c as usize, length))
                    }),
            );
            for iy in 0..self.ny {
                let row = &pressure[iy * n..(iy + 1) * n];
                let mut added: f64 = partial.iter().map(|&(c, l)| row[c] * l).sum();
                if whole.0 <= whole.1 {
                    let s = &sums[iy * (n + 1)..(iy + 1) * (n + 1)];
                    added += dx * (s[whole.1 as usize + 1] - s[whole.0 as usize]);
                }
                self.depth[iy * self.nx + ix] += added;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CRANK: Stroke = Stroke {
        length_m: 1e-3,
        frequency_hz: 2.0,
        law: VelocityLaw::Sinusoidal,
    };

    fn relative(got: f64, want: f64) -> f64 {
        ((got - want) / want).abs()
    }

    #[test]
    fn the_passes_over_a_point_split_the_period_by_where_it_lies() {
        let constant = Stroke {
            law: VelocityLaw::Constant,
            ..CRANK
        };
        for stroke in [CRANK, constant] {
            let (a, b) = stroke.times_between_passes_s(0.0);
            // The middle: half a period each way, to a rounding or two.
            assert!(relative(a, 0.25).max(relative(b, 0.25)) < 1e-15, "{a} {b}");
            let (a, b) = stroke.times_between_passes_s(stroke.length_m / 2.0);
            assert!(a.abs() < 1e-15 && relative(b, 0.5) < 1e-15, "{a} {b}");
        }
        // At x = L / 4: the crank passes at phase acos(-1/2) / 2 pi = 1/3, so returns after
        // 1 - 2/3 = 1/3 of the period; the constant law at phase 3/8, after 1/4.
        let (a, b) = CRANK.times_between_passes_s(0.25e-3);
        assert!(relative(a, 0.5 / 3.0) < 1e-14 && relative(b, 1.0 / 3.0) < 1e-14);
        let (a, _) = constant.times_between_passes_s(0.25e-3);
        assert!(relative(a, 0.125) < 1e-14, "{a}");
    }

    #[test]
    fn the_ball_covers_the_stroke_at_the_speed_of_its_law() {
        // The crank's mean speed over a cycle is 2 L f; its peak pi L f.
        let steps = 100_000;
        let dt = CRANK.period_s() / steps as f64;
        let distance: f64 = (0..steps)
            .map(|i| CRANK.speed_m_s((i as f64 + 0.5) * dt) * dt)
            .sum();
        // Midpoint rule on |sin|: error below 1e-8 relative at this step.
        assert!(relative(distance, CRANK.sliding_distance_per_cycle_m()) < 1e-8);
        let constant = Stroke {
            law: VelocityLaw::Constant,
            ..CRANK
        };
        for stroke in [CRANK, constant] {
            let at = |phase: f64| stroke.position_m(phase * stroke.period_s());
            // Both laws: an end, the middle going forward, the other end, the middle coming
            // back; a cosine near pi / 2 or a sum of half-millimetres rounds below 1e-18 m.
            for (phase, want) in [(0.0, -0.5e-3), (0.25, 0.0), (0.5, 0.5e-3), (0.75, 0.0)] {
                assert!((at(phase) - want).abs() < 1e-18, "{phase}: {}", at(phase));
            }
        }
    }

    /// A cap of pressure on a small grid, zero at its edges, uneven so that a wrong column
    /// or row would show.
    fn pressure(grid: &Grid) -> Vec<f64> {
        grid.sample(|x, y| {
            let r2 = (x / 40e-6).powi(2) + (y / 30e-6).powi(2);
            if r2 < 1.0 {
                1e9 * (1.0 - r2).sqrt() * (1.0 + 0.3 * x / 40e-6)
            } else {
                0.0
            }
        })
    }

    #[test]
    fn a_pass_is_the_time_integral_of_the_pressure_under_the_moving_ball() {
        let grid = Grid::new(16, 12, 6e-6, 6e-6).expect("a grid");
        let p = pressure(&grid);
        // A stroke that is not a whole number of cells, and short enough for the ends to
        // matter everywhere.
        let stroke = Stroke {
            length_m: 100e-6 + 0.37 * grid.dx,
            ..CRANK
        };
        let mut map = WearMap::new(&grid, stroke.length_m);
        let half_cycle = stroke.period_s() / 2.0;
        map.add_pass(&grid, &p, -stroke.length_m / 2.0, stroke.length_m / 2.0);
        // Brute force: the ball moved in time steps, each map cell adding the pressure of
        // the grid cell under it times the distance slid.
        let steps = 200_000;
        let dt = half_cycle / steps as f64;
        let mut brute = vec![0.0; map.depth.len()];
        for i in 0..steps {
            let t = (i as f64 + 0.5) * dt;
            let ball = stroke.position_m(t);
            let slid = stroke.speed_m_s(t) * dt;
            for ix in 0..map.nx {
                let xi = map.x(ix) - ball;
                let column = (xi / grid.dx + grid.nx as f64 / 2.0).floor();
                if column < 0.0 || column >= grid.nx as f64 {
                    continue;
                }
                for iy in 0..map.ny {
                    brute[iy * map.nx + ix] += p[iy * grid.nx + column as usize] * slid;
                }
            }
        }
        // Each column crosses at most nx + 1 cell edges in a pass; a step straddling one
        // errs by at most the largest pressure times the step's largest slide.
        let peak = p.iter().copied().fold(0.0, f64::max);
        let bound = (grid.nx + 1) as f64 * peak * stroke.peak_speed_m_s() * dt;
        let worst = map
            .depth
            .iter()
            .zip(&brute)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst <= bound, "{worst} > {bound}");
        // A column the whole contact passes: the pass pressure integral, sum p dx per row.
        let middle = map.nx / 2;
        for iy in 0..grid.ny {
            let row: f64 = p[iy * grid.nx..(iy + 1) * grid.nx].iter().sum::<f64>() * grid.dx;
            let got = map.depth[iy * map.nx + middle];
            assert!((got - row).abs() <= 1e-12 * row.max(1.0), "{got} {row}");
        }
    }

    #[test]
    fn stretches_of_a_pass_add_up_to_the_pass() {
        let grid = Grid::new(16, 12, 6e-6, 6e-6).expect("a grid");
        let p = pressure(&grid);
        let length = 250e-6;
        let mut whole = WearMap::new(&grid, length);
        whole.add_pass(&grid, &p, length / 2.0, -length / 2.0);
        let mut pieces = WearMap::new(&grid, length);
        let cuts = [-0.5, -0.31, 0.0, 0.07, 0.5].map(|f| f * length);
        for pair in cuts.windows(2) {
            pieces.add_pass(&grid, &p, pair[0], pair[1]);
        }
        let peak = whole.depth.iter().copied().fold(0.0, f64::max);
        for (a, b) in whole.depth.iter().zip(&pieces.depth) {
            // Sums of the same products in another order: rounding only.
            assert!((a - b).abs() <= 1e-13 * peak, "{a} {b}");
        }
    }

    #[test]
    fn the_prefix_sums_of_a_long_stretch_add_what_the_column_by_column_visit_adds() {
        // Odd and even grids (the map's columns sit half a cell off the grid's for an odd
        // one), stretches from just over the switch to the whole stroke, one ending off the
        // stroke, in either direction.
        for nx in [15, 16] {
            let grid = Grid::new(nx, 12, 6e-6, 6e-6).expect("a grid");
            let p = pressure(&grid);
            let length = 250e-6 + 0.29 * grid.dx;
            let stretches = [
                (-0.5, 0.5),
                (0.5, -0.5),
                (-0.13, 0.0),
                (-0.5, -0.38),
                (0.31, 0.7),
            ];
            for (from, to) in stretches.map(|(a, b)| (a * length, b * length)) {
                let mut long = WearMap::new(&grid, length);
                long.add_long_pass(&grid, &p, from.min(to), from.max(to));
                let mut short = WearMap::new(&grid, length);
                short.add_short_pass(&grid, &p, from.min(to), from.max(to));
                let peak = short.depth.iter().copied().fold(0.0, f64::max);
                assert!(peak > 0.0);
                for (a, b) in long.depth.iter().zip(&short.depth) {
                    // The same products summed in another order, the whole cells' lengths
                    // dx rather than two differences: rounding only.
                    assert!((a - b).abs() <= 1e-13 * peak, "{nx} {from} {to}: {a} {b}");
                }
            }
        }
    }

    #[test]
    fn a_map_embedded_in_a_wider_grid_keeps_each_depth_at_its_place() {
        let narrow = Grid::square(8, 80e-6).expect("grid");
        let wide = Grid::new(12, 16, 10e-6, 10e-6).expect("grid");
        let mut map = WearMap::new(&narrow, 0.2e-3);
        for (i, d) in map.depth.iter_mut().enumerate() {
            *d = i as f64;
        }
        let wider = map.embedded_in(&wide, 0.2e-3);
        assert_eq!((wider.nx, wider.ny), (map.nx + 4, 16));
        for iy in 0..map.ny {
            for ix in 0..map.nx {
                // The same column centre, the same depth (whole-cell margins: exact).
                let (wx, wy) = (ix + 2, iy + 4);
                assert_eq!(wider.x(wx).to_bits(), map.x(ix).to_bits());
                let (a, b) = (wider.depth[wy * wider.nx + wx], map.depth[iy * map.nx + ix]);
                assert_eq!(a.to_bits(), b.to_bits());
            }
        }
        let sum = |m: &WearMap| m.depth.iter().sum::<f64>();
        assert_eq!(sum(&wider).to_bits(), sum(&map).to_bits());
    }
}
