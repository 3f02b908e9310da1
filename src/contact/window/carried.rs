//! The displacement a windowed solve's check computed, carried to the next solve: a solve
//! warm-started from the very pressure the check was of, in a window among the cells it
//! computed, starts from that displacement instead of an apply of its own.
//!
//! On the 4 um rough disc of `docs/accuracy.md` over 600 cycles, every one solved from the
//! last pressure, that apply was 7% of the cells of all applies (`operator_applies` and the
//! windows' shapes, logged once per solve); 596 of the 600 solves start so, and the run's
//! CPU time fell to 0.980 of the build's before ("Rough wear: the start of each solve").

use crate::contact::grid::{Grid, Window};

/// A checked pressure and its displacement `K p` (without the wear term) on the cells
/// `over`, zero elsewhere, both fields of the whole grid.
#[derive(Debug)]
pub(super) struct Carried {
    pub(super) pressure: Vec<f64>,
    pub(super) displacement: Vec<f64>,
    pub(super) over: Window,
}

impl Carried {
    /// The displacement of a solve from `warm` on `window` (both of `grid`), if `warm` is
    /// the checked pressure to the bit and the check computed every cell of `window`.
    pub(super) fn start_on(&self, grid: &Grid, window: &Window, warm: &[f64]) -> Option<Vec<f64>> {
        let same = warm.len() == self.pressure.len()
            && warm
                .iter()
                .zip(&self.pressure)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        (same && self.over.holds(window)).then(|| window.extract(grid, &self.displacement))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_checked_pressure_in_a_window_among_the_checked_cells_starts_known() {
        let grid = Grid::square(8, 8e-6).expect("valid");
        let over = Window::centred(&grid, (4, 4), 4, 4);
        let pressure: Vec<f64> = (0..grid.len()).map(|i| i as f64).collect();
        let displacement: Vec<f64> = (0..grid.len()).map(|i| 2.0 * i as f64).collect();
        let carried = Carried {
            pressure: pressure.clone(),
            displacement,
            over,
        };
        let inside = Window::centred(&grid, (4, 4), 2, 2);
        let expected: Vec<f64> = inside.indices(&grid).map(|i| 2.0 * i as f64).collect();
        assert_eq!(carried.start_on(&grid, &inside, &pressure), Some(expected));
        // One cell past the checked ones, or a pressure one ulp off: no known start.
        let wider = Window::centred(&grid, (4, 4), 5, 4);
        assert_eq!(carried.start_on(&grid, &wider, &pressure), None);
        let mut moved = pressure;
        moved[3] = f64::from_bits(moved[3].to_bits() + 1);
        assert_eq!(carried.start_on(&grid, &inside, &moved), None);
    }
}
