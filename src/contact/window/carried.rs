//! The displacement a windowed solve's check computed, carried to the next solve: a solve
//! warm-started from the very pressure the check was of, in a window among the cells it
//! computed, starts from that displacement instead of an apply of its own.
//!
//! On the 4 um rough disc of `docs/accuracy.md` over 600 cycles, every one solved from the
//! last pressure, that apply was 7% of the cells of all applies (`operator_applies` and the
//! windows' shapes, logged once per solve); 596 of the 600 solves start so, and the run's
//! CPU time fell to 0.980 of the build's before ("Rough wear: the start of each solve").

use crate::contact::grid::{Grid, Window};

/// A checked pressure, on the cells of the window it was solved on (zero elsewhere), and
/// its displacement `K p` (without the wear term) on the cells `over`. Kept on their own
/// cells rather than as fields of the whole grid: on the 2 um example's grown grid, copying
/// the two whole fields per solve, into freshly allocated pages, was 4.9% of the samples
/// of 100 cycles on a 300 um domain (`perf record -F 99 --call-graph dwarf`, the page
/// faults under `memcpy`).
#[derive(Debug)]
pub(super) struct Carried {
    pub(super) pressure: Vec<f64>,
    pub(super) solved: Window,
    pub(super) displacement: Vec<f64>,
    pub(super) over: Window,
}

impl Carried {
    /// The displacement of a solve from `warm` on `window` (both of `grid`), if `warm` is
    /// the checked pressure to the bit and the check computed every cell of `window`.
    pub(super) fn start_on(&self, grid: &Grid, window: &Window, warm: &[f64]) -> Option<Vec<f64>> {
        if !(self.over.holds(window) && self.is_pressure(grid, warm)) {
            return None;
        }
        let over = Grid::new(self.over.nx, self.over.ny, grid.dx, grid.dy).ok()?;
        let inside = Window {
            x0: window.x0 - self.over.x0,
            y0: window.y0 - self.over.y0,
            ..*window
        };
        Some(inside.extract(&over, &self.displacement))
    }

    /// Whether `field` (of `grid`) is the carried pressure to the bit: zero (+0.0) outside
    /// the solved window.
    fn is_pressure(&self, grid: &Grid, field: &[f64]) -> bool {
        let zero = |cells: &[f64]| cells.iter().all(|v| v.to_bits() == 0);
        let solved = self.solved;
        field.len() == grid.len()
            && field.chunks_exact(grid.nx).enumerate().all(|(iy, row)| {
                if !solved.rows().contains(&iy) {
                    return zero(row);
                }
                let inside = &self.pressure[(iy - solved.y0) * solved.nx..][..solved.nx];
                let (before, rest) = row.split_at(solved.x0);
                let (middle, after) = rest.split_at(solved.nx);
                zero(before)
                    && zero(after)
                    && middle
                        .iter()
                        .zip(inside)
                        .all(|(a, b)| a.to_bits() == b.to_bits())
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_checked_pressure_in_a_window_among_the_checked_cells_starts_known() {
        let grid = Grid::square(8, 8e-6).expect("valid");
        let solved = Window::centred(&grid, (4, 4), 3, 3);
        let over = Window::centred(&grid, (4, 4), 4, 4);
        let on = |window: &Window, scale: f64| -> Vec<f64> {
            window
                .indices(&grid)
                .map(|i| scale * (i + 1) as f64)
                .collect()
        };
        let carried = Carried {
            pressure: on(&solved, 1.0),
            solved,
            displacement: on(&over, 2.0),
            over,
        };
        let pressure = solved.embed(&grid, &carried.pressure);
        let inside = Window::centred(&grid, (4, 4), 2, 2);
        let expected = on(&inside, 2.0);
        assert_eq!(carried.start_on(&grid, &inside, &pressure), Some(expected));
        // One cell past the checked ones, a pressure one ulp off, or a load outside the
        // solved window: no known start.
        let wider = Window::centred(&grid, (4, 4), 5, 4);
        assert_eq!(carried.start_on(&grid, &wider, &pressure), None);
        let mut moved = pressure.clone();
        let in_solved = solved.indices(&grid).nth(4).expect("a cell");
        moved[in_solved] = f64::from_bits(moved[in_solved].to_bits() + 1);
        assert_eq!(carried.start_on(&grid, &inside, &moved), None);
        let mut outside = pressure;
        outside[0] = 1.0;
        assert_eq!(carried.start_on(&grid, &inside, &outside), None);
    }
}
