//! The rows of the grid that carry a cycle's pressure. A windowed solve leaves every other
//! row without any ([`crate::contact::WindowedSolver::loaded_rows`]), so the masks of the
//! contact and of the cap, and what the corrosion and the record read off them, need only
//! these rows. On the 2 um example's grown grid (1728 rows) the groove the contact sits in
//! spans 1208 rows at cycle 3600, so late in that run the band skips about a third.

use std::ops::Range;

use crate::contact::Grid;
use crate::corrosion::ContactGeometry;
use crate::corrosion::spots::SpotRows;
use crate::surface::count_islands;

/// The pressure on a band of whole rows of a grid.
pub(super) struct Band<'s> {
    /// Cells along a row (the grid's).
    nx: usize,
    /// Cell sizes along and across the rows, m.
    dx: f64,
    dy: f64,
    /// `y` of the band's first row on the grid, m.
    y0_m: f64,
    /// The band's pressures, row-major.
    pressure: &'s [f64],
}

impl<'s> Band<'s> {
    /// The rows `rows` of `pressure`, a field of `grid` that carries none on its other rows.
    pub(super) fn of(grid: &Grid, pressure: &'s [f64], rows: Range<usize>) -> Self {
        let cells = grid.row_cells(rows.clone());
        debug_assert!(
            pressure[..cells.start]
                .iter()
                .chain(&pressure[cells.end..])
                .all(|&p| p == 0.0),
            "the rows beyond the band carry pressure"
        );
        Self {
            nx: grid.nx,
            dx: grid.dx,
            dy: grid.dy,
            y0_m: grid.y(rows.start),
            pressure: &pressure[cells],
        }
    }

    /// The cells in contact (`p > 0`), row-major over the band.
    pub(super) fn in_contact(&self) -> Vec<bool> {
        self.pressure.iter().map(|&p| p > 0.0).collect()
    }

    /// The cells at the cap `cap` (`p >= cap`), row-major over the band.
    pub(super) fn capped(&self, cap: f64) -> Vec<bool> {
        self.pressure.iter().map(|&p| p >= cap).collect()
    }

    /// The chords of the band's cells in `mask`, at their places on the grid.
    pub(super) fn spot_rows(&self, mask: &[bool]) -> SpotRows {
        SpotRows::of(mask, self.nx, self.dx, self.dy, self.y0_m)
    }

    /// The area and the swept width of the band's cells in `mask`.
    pub(super) fn geometry(&self, mask: &[bool]) -> ContactGeometry {
        ContactGeometry::of(mask, self.nx, self.dx, self.dy)
    }

    /// The 4-connected groups of the band's cells in `mask`.
    pub(super) fn islands(&self, mask: &[bool]) -> usize {
        count_islands(mask, self.nx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A field of 6 x 8 cells loaded on rows 2 to 4 only: the band of rows 1 to 4 finds
    /// what the whole grid finds, the spots at the same places.
    #[test]
    fn a_band_holding_the_loaded_rows_reads_what_the_whole_grid_reads() {
        let grid = Grid::new(6, 8, 1e-6, 2e-6).expect("valid");
        let mut pressure = vec![0.0; grid.len()];
        for (i, p) in [(13, 1.0), (14, 3.0), (16, 2.0), (20, 3.0), (27, 0.5)] {
            pressure[i] = p;
        }
        let whole = Band::of(&grid, &pressure, 0..grid.ny);
        let band = Band::of(&grid, &pressure, 1..5);
        let (all, some) = (whole.in_contact(), band.in_contact());
        assert_eq!(some.len(), 4 * grid.nx);
        assert_eq!(band.spot_rows(&some), whole.spot_rows(&all));
        assert_eq!(band.geometry(&some), whole.geometry(&all));
        assert_eq!(band.islands(&some), whole.islands(&all));
        assert_eq!(band.islands(&some), 3);
        let (all, some) = (whole.capped(3.0), band.capped(3.0));
        assert_eq!(band.spot_rows(&some), whole.spot_rows(&all));
        // Two capped cells of 1 x 2 um, up to the round-off of the chords' ends.
        let area_m2 = band.spot_rows(&some).area_m2();
        assert!(
            (area_m2 / (2.0 * 1e-6 * 2e-6) - 1.0).abs() < 1e-12,
            "{area_m2:e}"
        );
    }
}
