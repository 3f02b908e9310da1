//! What a reciprocating run adds to its result (`docs/result.md`, "The reciprocating
//! rig"): the wear map along and across the stroke, the profile along its axis, and the
//! potential and current over a cycle.

use serde::{Deserialize, Serialize};

use crate::wear::WearMap;

/// The most columns the result's map keeps along the stroke: the map is averaged over
/// blocks of columns beyond it, which bounds the result's size whatever the stroke.
pub const MAP_COLUMNS: usize = 400;

/// The most points of the axial profile; averaged over blocks beyond it.
pub const AXIAL_POINTS: usize = 4000;

/// Samples of a cycle's potential and current trace: 100 a stroke, so the oscillation at
/// twice the frequency shows with each half period resolved to 1%.
pub const TRACE_SAMPLES: usize = 200;

/// The reciprocating rig's part of a result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrokeReport {
    /// The flat's depth at the end of the run, along and across the stroke.
    pub map: WearMapReport,
    /// The depth along the stroke's axis (the track's centre line) at the end of the run.
    pub axial_profile: AxialProfile,
    /// The potential and the current over one cycle, at the first solved cycle, the
    /// recorded cycles and the last; empty without corrosion.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub traces: Vec<CycleTrace>,
}

/// The wear map, block-averaged to at most [`MAP_COLUMNS`] columns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WearMapReport {
    /// Centres of the (averaged) columns along the stroke, um, from the stroke's middle.
    pub x_um: Vec<f64>,
    /// Centres of the rows across the track, um.
    pub y_um: Vec<f64>,
    /// Depth below the original surface, um (positive into the flat), indexed `[iy][ix]`.
    pub depth_um: Vec<Vec<f64>>,
}

/// The depth along the track's centre line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxialProfile {
    /// Positions along the stroke, um, from its middle.
    pub x_um: Vec<f64>,
    /// Depth, um.
    pub depth_um: Vec<f64>,
}

/// The potential and the current over one cycle: the periodic state of that cycle's
/// contact, sampled at [`TRACE_SAMPLES`] even times.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CycleTrace {
    /// The cycle.
    pub cycle: u64,
    /// Time of each sample since the rubbing started, s.
    pub time_s: Vec<f64>,
    /// The ball centre's position along the stroke, um.
    pub position_um: Vec<f64>,
    /// The depassivated (bare-equivalent) area, mm^2.
    pub anodic_area_mm2: Vec<f64>,
    /// The potential, V against `summary.potential_reference`.
    pub potential_v: Vec<f64>,
    /// The anodic current, mA.
    pub anodic_current_ma: Vec<f64>,
}

/// Blocks of at most `most` out of `n`: the block length.
fn block(n: usize, most: usize) -> usize {
    n.div_ceil(most).max(1)
}

/// The means of `values` over consecutive blocks of `size`.
fn block_means(values: &[f64], size: usize) -> Vec<f64> {
    values
        .chunks(size)
        .map(|c| c.iter().sum::<f64>() / c.len() as f64)
        .collect()
}

impl WearMapReport {
    /// `map` (m) in um, its columns averaged to at most [`MAP_COLUMNS`]; rows `y_m`.
    pub fn of(map: &WearMap, y_m: &[f64]) -> Self {
        let size = block(map.nx, MAP_COLUMNS);
        let x: Vec<f64> = (0..map.nx).map(|ix| map.x(ix) * 1e6).collect();
        Self {
            x_um: block_means(&x, size),
            y_um: y_m.iter().map(|y| y * 1e6).collect(),
            depth_um: map
                .depth
                .chunks_exact(map.nx)
                .map(|row| {
                    block_means(row, size)
                        .into_iter()
                        .map(|d| d * 1e6)
                        .collect()
                })
                .collect(),
        }
    }
}

impl AxialProfile {
    /// The centre row of `map` (m) in um, averaged to at most [`AXIAL_POINTS`].
    pub fn of(map: &WearMap) -> Self {
        let size = block(map.nx, AXIAL_POINTS);
        let x: Vec<f64> = (0..map.nx).map(|ix| map.x(ix) * 1e6).collect();
        let depth: Vec<f64> = map.centre_row().iter().map(|d| d * 1e6).collect();
        Self {
            x_um: block_means(&x, size),
            depth_um: block_means(&depth, size),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Grid;

    #[test]
    fn a_long_map_is_averaged_to_its_bound_keeping_its_volume() {
        let grid = Grid::square(8, 80e-6).expect("grid");
        let mut map = WearMap::new(&grid, 10e-3);
        for (i, d) in map.depth.iter_mut().enumerate() {
            *d = (i % 7) as f64 * 1e-6;
        }
        let y: Vec<f64> = (0..grid.ny).map(|iy| grid.y(iy)).collect();
        let report = WearMapReport::of(&map, &y);
        assert!(report.x_um.len() <= MAP_COLUMNS, "{}", report.x_um.len());
        assert_eq!(report.depth_um.len(), grid.ny);
        // Block means keep each row's sum when the blocks are whole: weigh by the blocks.
        let size = block(map.nx, MAP_COLUMNS);
        let whole = map.nx / size * size;
        let row: f64 = map.depth[..whole].iter().sum::<f64>() * 1e6;
        let averaged: f64 = report.depth_um[0][..whole / size].iter().sum::<f64>() * size as f64;
        // Sums of a few hundred numbers of order 1: a few roundings of 1e-16 relative.
        assert!((row - averaged).abs() < 1e-12 * row, "{row} {averaged}");
        let axial = AxialProfile::of(&map);
        assert_eq!(axial.x_um.len(), map.nx.min(AXIAL_POINTS));
    }
}
