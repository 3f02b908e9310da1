//! The area-load slope of a rough surface: the surface pressed by a rigid flat on the
//! periodic half-space ([`PeriodicHalfSpace`]) at light mean pressures p, and kappa =
//! (A / A0) / (p / (E* h')), h' the surface's rms slope. Persson's theory gives kappa =
//! sqrt(8 / pi) = 1.60 (J. Chem. Phys. 115 (2001) 3840); boundary elements find about 2
//! (Hyun, Pei, Molinari & Robbins, Phys. Rev. E 70 (2004) 026117; Yastrebov, Anciaux &
//! Molinari, Int. J. Solids Struct. 52 (2015) 83: 1.9 to 2.2), and more on coarse cells.
//!
//! A measured map sits on the periodic flat as it is read, less its tilt: its opposite edges
//! then meet with a step that no measured surface has, so the rows say how large that step
//! is against the map's rms height. The generated surface, periodic by construction, is the
//! yardstick beside it.

use std::path::Path;

use serde::Serialize;

use super::contact::paper_hertz;
use super::error::BenchError;
use crate::contact::{ContactProblem, Grid, PeriodicHalfSpace, SolverOptions, solve};
use crate::surface::{HeightMap, Roughness, SelfAffine, count_islands, read_file, rms_slope};

/// The mean pressures over `E* h'`: light loads, where the area grows linearly.
pub const REDUCED_PRESSURES: [f64; 3] = [0.005, 0.01, 0.02];

/// Pixels per side of the generated surface, with its short cut-off over 8 pixels and its
/// long one over 64 (8 repeats across it), Hurst 0.8, rms slope 0.1, seed 1: the resolution
/// at which `tests/surfaces.rs` measures kappa 2.41 to 2.63.
pub const GENERATED_N: usize = 512;

/// The generated surface's pixel, m.
const GENERATED_PIXEL_M: f64 = 0.125e-6;

/// The solver tolerance: the contact study's, tighter than a run's.
const TOLERANCE: f64 = 1e-8;

/// A measured map for the study: its file and, for a text matrix, its pixel size.
#[derive(Debug, Clone, Copy)]
pub struct MeasuredMap<'a> {
    /// The map's file (.gsf, x y z columns, or a text matrix of heights in m).
    pub path: &'a Path,
    /// A text matrix's pixel size, m.
    pub pixel_m: Option<f64>,
}

/// One surface at one mean pressure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KappaRow {
    /// Always `kappa`.
    pub study: &'static str,
    /// `generated`, or the measured map's file name.
    pub surface: String,
    /// Pixels along x and y.
    pub nx: usize,
    /// Pixels along y.
    pub ny: usize,
    /// Pixel side along x, m.
    pub pixel_m: f64,
    /// The rms slope h' the pressure is scaled by.
    pub rms_slope: f64,
    /// The largest step between the map's opposite edges over its rms height: 0 for a
    /// periodic surface.
    pub edge_step_over_rms: f64,
    /// `p / (E* h')`.
    pub reduced_pressure: f64,
    /// Fraction of the pixels in contact.
    pub area_fraction: f64,
    /// `area_fraction / reduced_pressure`.
    pub kappa: f64,
    /// Contact islands (4-connected).
    pub islands: usize,
    /// Solver iterations.
    pub iterations: usize,
}

/// The generated surface of the study.
pub fn generated_surface() -> Result<HeightMap, BenchError> {
    Ok(SelfAffine {
        roughness: Roughness::RmsSlope(0.1),
        hurst: 0.8,
        short_cutoff_m: 8.0 * GENERATED_PIXEL_M,
        long_cutoff_m: 64.0 * GENERATED_PIXEL_M,
        seed: 1,
    }
    .generate(
        GENERATED_N,
        GENERATED_N,
        GENERATED_PIXEL_M,
        GENERATED_PIXEL_M,
    )?)
}

/// The rows of the generated surface, then of `measured` if given.
pub fn kappa_rows(measured: Option<MeasuredMap>) -> Result<Vec<KappaRow>, BenchError> {
    let mut rows = surface_rows(&generated_surface()?, "generated")?;
    if let Some(map) = measured {
        let (read, _) = read_file(map.path, map.pixel_m)?;
        let name = map.path.file_name().map_or_else(
            || map.path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        rows.extend(surface_rows(&read.without_tilt(), &name)?);
    }
    Ok(rows)
}

/// `map` pressed at each of [`REDUCED_PRESSURES`].
pub fn surface_rows(map: &HeightMap, name: &str) -> Result<Vec<KappaRow>, BenchError> {
    let (pair, _) = paper_hertz();
    let modulus = pair.reduced_modulus_pa;
    let slope = rms_slope(map);
    let grid = Grid::new(map.nx, map.ny, map.dx_m, map.dy_m)?;
    let top = map.heights_m.iter().fold(f64::MIN, |m, &h| m.max(h));
    let separation: Vec<f64> = map.heights_m.iter().map(|h| top - h).collect();
    let mut operator = PeriodicHalfSpace::new(map.nx, map.ny, map.dx_m, map.dy_m, modulus);
    let options = SolverOptions {
        tolerance: TOLERANCE,
        ..SolverOptions::default()
    };
    let edge_step = edge_step_over_rms(map);
    REDUCED_PRESSURES
        .iter()
        .map(|&reduced| {
            let problem = ContactProblem {
                grid,
                separation: &separation,
                load_n: reduced * modulus * slope * grid.area(),
                yield_pressure_pa: f64::INFINITY,
                pass_wear_per_pa: 0.0,
            };
            let solution = solve(&mut operator, &problem, &options, None)?;
            let mask: Vec<bool> = solution.pressure.iter().map(|&p| p > 0.0).collect();
            let area_fraction = solution.contact_area_m2(&grid) / grid.area();
            Ok(KappaRow {
                study: "kappa",
                surface: name.to_owned(),
                nx: map.nx,
                ny: map.ny,
                pixel_m: map.dx_m,
                rms_slope: slope,
                edge_step_over_rms: edge_step,
                reduced_pressure: reduced,
                area_fraction,
                kappa: area_fraction / reduced,
                islands: count_islands(&mask, map.nx),
                iterations: solution.iterations,
            })
        })
        .collect()
}

/// The largest height step where the periodic flat joins the map's opposite edges, over its
/// rms height; 0 for a map that is one period.
fn edge_step_over_rms(map: &HeightMap) -> f64 {
    if map.periodic {
        return 0.0;
    }
    let (nx, ny, h) = (map.nx, map.ny, &map.heights_m);
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let rms = (h.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / h.len() as f64).sqrt();
    let across_x = (0..ny).map(|y| (h[y * nx + nx - 1] - h[y * nx]).abs());
    let across_y = (0..nx).map(|x| (h[(ny - 1) * nx + x] - h[x]).abs());
    let step = across_x.chain(across_y).fold(0.0, f64::max);
    if rms > 0.0 { step / rms } else { 0.0 }
}

/// The rows as a markdown table, with Persson's and the boundary-element kappa beside them.
pub fn table(rows: &[KappaRow]) -> String {
    let mut text = format!(
        "\nArea-load slope on a periodic flat: kappa = (A/A0) / (p / (E* h')); Persson \
         sqrt(8/pi) = {:.2}, boundary elements about 2 (1.9-2.2)\n\n\
         | surface | pixels | pixel, um | h' | edge step / rms | p / (E* h') | A / A0 | kappa | \
         islands | iterations |\n|---|---|---|---|---|---|---|---|---|---|\n",
        (8.0 / std::f64::consts::PI).sqrt()
    );
    for r in rows {
        text.push_str(&format!(
            "| {} | {} x {} | {:.4} | {:.4} | {:.2} | {} | {:.4} | {:.3} | {} | {} |\n",
            r.surface,
            r.nx,
            r.ny,
            r.pixel_m * 1e6,
            r.rms_slope,
            r.edge_step_over_rms,
            r.reduced_pressure,
            r.area_fraction,
            r.kappa,
            r.islands,
            r.iterations
        ));
    }
    text
}
