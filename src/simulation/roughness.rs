//! The disc's initial roughness on the contact grid: the scene's `disc.surface` generated
//! or taken from the supplied map, sized into the grid ([`CELLS_PER_SHORT_WAVELENGTH`]),
//! and reported (`surface` in `models`, its statistics in the result).
//!
//! How a surface meets the grid: a synthetic surface is generated on the first grid's own
//! cells, one period over the grid, and repeats beyond it when the domain grows; a measured
//! map is centred on the apex and sampled bilinearly at the cell centres, repeating
//! periodically where the domain is larger than the map ([`HeightMap::height_at`]). The
//! surface is a patch of the disc under the ball, the same at every solved cycle: the wear
//! model's state is uniform along the track, so it has no other patch to show. The map is
//! the initial roughness `r` of the disc's surface state ([`crate::wear::Groove`]), which
//! wears it: yielding (eq. 13) truncates each row's asperities at the level its most-pressed
//! capped cell was pressed to, so they flatten, and Archard wear lowers the row as on a
//! smooth disc. The paper's scene with a 0.1 um rms surface (H 0.8, cut-offs 2 and 50 um,
//! seed 1) wears 4.60e-4 mm^3 in 20 cycles with the cap on, 1.81 times the smooth disc's
//! 2.54e-4 (`tribosim run`): Archard's volume is the same, but the ball sinks deeper
//! (approach 0.87 against 0.78 um at cycle 20) before the truncated asperities, with the
//! valleys between them, bear the load below the cap. The tests of `simulation::run` check
//! the flattening and the volume's accounting on the same disc with a 4 um short cut-off.

use std::f64::consts::TAU;

use crate::contact::Grid;
use crate::scene::{FieldError, MAX_RMS_SLOPE, SceneErrors, SurfaceKind, SurfaceSpec};
use crate::surface::{HeightMap, Roughness, SelfAffine, Statistics, measured_fit_range};

use super::plausibility::check_map;
use super::{Model, ModelChoice, SimulationError};

/// Cells across the short cut-off wavelength of a synthetic surface. Measured on the
/// periodic rough contact of `tests/surfaces.rs`: the real contact area's kappa is 2.41 to
/// 2.63 at 8 cells and 2.30 to 2.45 at 16, so 8 cells put the area within about 7% of the
/// finer grid's, at a quarter of its cells. Fewer cells leave the asperity tops a cell or
/// two wide, where counting cells overstates the area most.
pub const CELLS_PER_SHORT_WAVELENGTH: f64 = 8.0;

/// The surface on the grid, with what the result says of it.
#[derive(Debug, Clone)]
pub struct DiscSurface {
    /// The heights the contact sees: on the first grid's cells, periodic over it.
    pub map: HeightMap,
    /// The statistics of `map`.
    pub statistics: Statistics,
    /// A measured map's own statistics, before sampling.
    pub source: Option<Statistics>,
    /// The `surface` model entry.
    pub model: ModelChoice,
}

/// The finest cell `spec` asks for, m: the short cut-off over
/// [`CELLS_PER_SHORT_WAVELENGTH`], or a measured map's pixel.
pub fn wanted_cell_m(spec: &SurfaceSpec, supplied: Option<&HeightMap>) -> Option<f64> {
    match spec.kind {
        SurfaceKind::Synthetic => spec
            .short_cutoff_um
            .map(|um| um * 1e-6 / CELLS_PER_SHORT_WAVELENGTH),
        SurfaceKind::Measured => supplied.map(|m| m.dx_m.min(m.dy_m)),
    }
}

/// The surface of `spec` on `grid`, from the `supplied` map when it is measured.
pub fn build(
    spec: &SurfaceSpec,
    supplied: Option<&HeightMap>,
    grid: &Grid,
) -> Result<DiscSurface, SimulationError> {
    match spec.kind {
        SurfaceKind::Synthetic => synthetic(spec, grid),
        SurfaceKind::Measured => {
            let id = spec.id.clone().unwrap_or_default();
            let map =
                supplied.ok_or_else(|| SimulationError::SurfaceNotSupplied { id: id.clone() })?;
            check_map(&id, map).map_err(|e| SimulationError::Scene(SceneErrors(vec![e])))?;
            Ok(measured(spec, map, grid))
        }
    }
}

/// The `(long, short)` wavelengths a map's spectrum is fitted over: a synthetic surface's
/// own cut-offs within the map, or a measured map's [`measured_fit_range`].
fn fit_range(map: &HeightMap, cutoffs: Option<(f64, f64)>) -> (f64, f64) {
    let side = map.width_m().min(map.height_side_m());
    let pixel = map.dx_m.max(map.dy_m);
    match cutoffs {
        Some((long, short)) => (long.min(side), short.max(2.0 * pixel)),
        None => measured_fit_range(map),
    }
}

fn synthetic(spec: &SurfaceSpec, grid: &Grid) -> Result<DiscSurface, SimulationError> {
    let short = spec.short_cutoff_um.unwrap_or_default() * 1e-6;
    let long = spec.long_cutoff_um.unwrap_or_default() * 1e-6;
    let hurst = spec.hurst();
    let cell = grid.dx.max(grid.dy);
    // The shortest wavelength the grid resolves at the rule's density.
    let resolved = CELLS_PER_SHORT_WAVELENGTH * cell;
    let short_used = short.max(resolved);
    let roughness = asked_roughness(spec, hurst, (long, short, short_used));
    let generator = SelfAffine {
        roughness,
        hurst,
        short_cutoff_m: short_used,
        long_cutoff_m: long.max(short_used * 1.0001),
        seed: spec.seed.unwrap_or(0),
    };
    let map = generator.generate(grid.nx, grid.ny, grid.dx, grid.dy)?;
    let (fit_long, fit_short) = fit_range(&map, Some((long, short_used)));
    let statistics = Statistics::of(&map, fit_long, fit_short);
    refuse_steep(spec, &statistics, cell)?;
    let mut reason = format!(
        "synthetic self-affine, H = {hurst}, cut-offs {:.3} to {:.3} um, seed {}, generated on \
         the grid's cells and periodic over it: rms height {:.4} um, rms slope {:.4}",
        short * 1e6,
        long * 1e6,
        generator.seed,
        statistics.rms_height_um,
        statistics.rms_slope
    );
    if short_used > short {
        reason.push_str(&format!(
            "; UNDER-RESOLVED: the short cut-off {:.3} um needs cells of {:.4} um \
             ({CELLS_PER_SHORT_WAVELENGTH} per wavelength) and the grid has {:.4} um, {:.2} \
             times coarser, so the wavelengths under {:.3} um are left out (not aliased)",
            short * 1e6,
            short / CELLS_PER_SHORT_WAVELENGTH * 1e6,
            cell * 1e6,
            short_used / short,
            short_used * 1e6
        ));
    }
    if long > map.width_m().min(map.height_side_m()) {
        reason.push_str(&format!(
            "; the long cut-off {:.1} um exceeds the grid's side {:.1} um: longer wavelengths \
             are left out",
            long * 1e6,
            map.width_m() * 1e6
        ));
    }
    Ok(DiscSurface {
        map,
        statistics,
        source: None,
        model: ModelChoice {
            name: Model::Surface,
            active: true,
            reason,
        },
    })
}

/// The roughness `spec` asks for, on the band the grid keeps (cut-offs `long` to
/// `short_used`, `short` asked): an rms height as given, or an rms slope scaled to the band
/// kept.
fn asked_roughness(
    spec: &SurfaceSpec,
    hurst: f64,
    (long, short, short_used): (f64, f64, f64),
) -> Roughness {
    match (spec.rms_height_um, spec.rms_slope) {
        (Some(um), _) => Roughness::RmsHeight(um * 1e-6),
        // The slope of the band the grid keeps, at the amplitude of the whole band:
        // h'^2 is proportional to the integral of q^(1 - 2H) dq from q_long up.
        (None, Some(slope)) => {
            let band = |shortest: f64| slope_integral(TAU / long, TAU / shortest, hurst);
            Roughness::RmsSlope(slope * (band(short_used) / band(short)).sqrt())
        }
        (None, None) => Roughness::RmsSlope(0.0),
    }
}

/// Refuses a height that makes the surface steeper than the half-space theory holds for,
/// on the grid's cells of side `cell` (m).
fn refuse_steep(
    spec: &SurfaceSpec,
    statistics: &Statistics,
    cell: f64,
) -> Result<(), SimulationError> {
    if spec.rms_height_um.is_some() && statistics.rms_slope > MAX_RMS_SLOPE {
        return Err(SceneErrors(vec![FieldError::new(
            "disc.surface.rms_height_um",
            format!(
                "gives an rms slope of {:.3} on the grid's {:.4} um cells, above \
                 {MAX_RMS_SLOPE} (beyond it the small-slope half-space theory of eqs. 5-10 \
                 does not hold); lower the height or lengthen the short cut-off",
                statistics.rms_slope,
                cell * 1e6
            ),
        )])
        .into());
    }
    Ok(())
}

/// `int q^(1 - 2H) dq` from `low` to `high` (up to a constant factor).
fn slope_integral(low: f64, high: f64, hurst: f64) -> f64 {
    let power = 2.0 - 2.0 * hurst;
    if power.abs() < 1e-12 {
        (high / low).ln()
    } else {
        (high.powf(power) - low.powf(power)) / power
    }
}

fn measured(spec: &SurfaceSpec, supplied: &HeightMap, grid: &Grid) -> DiscSurface {
    let source_map = if spec.remove_tilt {
        supplied.without_tilt()
    } else {
        supplied.clone()
    };
    let (long, short) = fit_range(&source_map, None);
    let source = Statistics::of(&source_map, long, short);
    let heights = grid.sample(|x, y| source_map.height_at(x, y));
    let map = HeightMap {
        nx: grid.nx,
        ny: grid.ny,
        dx_m: grid.dx,
        dy_m: grid.dy,
        heights_m: heights,
        periodic: false,
    };
    let (long, short) = fit_range(&map, None);
    let statistics = Statistics::of(&map, long, short);
    let pixel = supplied.dx_m.max(supplied.dy_m);
    let cell = grid.dx.max(grid.dy);
    let mut reason = format!(
        "measured `{}`, {} x {} pixels of {:.4} um{}, centred on the apex and sampled \
         bilinearly at the {:.4} um cells' centres, repeating beyond its {:.1} um side",
        spec.id.as_deref().unwrap_or_default(),
        supplied.nx,
        supplied.ny,
        pixel * 1e6,
        if spec.remove_tilt {
            ", tilt removed"
        } else {
            ""
        },
        cell * 1e6,
        supplied.width_m() * 1e6
    );
    if cell > pixel * 1.0001 {
        reason.push_str(&format!(
            "; UNDER-RESOLVED: cells {:.2} times the pixel, so the map's wavelengths under two \
             cells ({:.3} um) alias onto longer ones",
            cell / pixel,
            2.0 * cell * 1e6
        ));
    }
    DiscSurface {
        map,
        statistics,
        source: Some(source),
        model: ModelChoice {
            name: Model::Surface,
            active: true,
            reason,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, parse_scene_str};
    use crate::simulation::{Plan, RunOptions, Setup};

    /// The setup of `scene`, with the measured `surface` if any.
    fn setup(scene: &Scene, surface: Option<&HeightMap>) -> Result<Setup, SimulationError> {
        let plan = Plan::new(scene.clone())?;
        let options = RunOptions {
            surface,
            ..RunOptions::default()
        };
        Setup::new(&plan, &options)
    }

    #[test]
    fn a_height_that_gives_a_slope_above_the_theorys_limit_is_refused_by_name() {
        // 13 um rms over cut-offs of 4 and 50 um: an rms slope of about 4 (the rough-sphere
        // case of docs/stability.md); 0.1 um on the same cut-offs stays near 0.03.
        let scene = |rms_um: f64| {
            parse_scene_str(&format!(
                r#"{{"disc": {{"surface": {{"kind": "synthetic", "rms_height_um": {rms_um},
                                           "short_cutoff_um": 4, "long_cutoff_um": 50}}}}}}"#
            ))
            .expect("valid")
        };
        match setup(&scene(13.0), None) {
            Err(SimulationError::Scene(SceneErrors(errors))) => {
                assert_eq!(errors.len(), 1);
                assert_eq!(errors[0].path, "disc.surface.rms_height_um");
                assert!(
                    errors[0].message.contains("rms slope"),
                    "{}",
                    errors[0].message
                );
            }
            other => panic!("expected the height refused, got {other:?}"),
        }
        let smooth = setup(&scene(0.1), None).expect("runs");
        let slope = smooth.surface.expect("rough").statistics.rms_slope;
        assert!(slope < MAX_RMS_SLOPE, "{slope}");
    }

    #[test]
    fn a_grid_too_coarse_for_the_short_cut_off_says_so_and_filters() {
        // 64 cells over 128 um: 2 um cells, and a 4 um short cut-off asks for 0.5 um.
        let scene = parse_scene_str(
            r#"{"numerics": {"grid": 64, "domain_um": 128},
                "disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.1,
                                     "short_cutoff_um": 4, "long_cutoff_um": 60}}}"#,
        )
        .expect("valid");
        let coarse = setup(&scene, None).expect("runs");
        let surface = coarse.surface.expect("rough");
        assert!(
            surface.model.reason.contains("UNDER-RESOLVED"),
            "{}",
            surface.model.reason
        );
        assert!(
            surface.model.reason.contains("4.00 times coarser"),
            "{}",
            surface.model.reason
        );
        // The generated band starts at 8 cells, 16 um: the fit sees only that band.
        assert!((surface.statistics.fit_wavelengths_um[1] - 16.0).abs() < 1e-9);
    }

    #[test]
    fn a_measured_surface_must_be_supplied() {
        let scene =
            parse_scene_str(r#"{"disc": {"surface": {"kind": "measured", "id": "lab.gsf"}}}"#)
                .expect("valid");
        assert!(matches!(
            setup(&scene, None),
            Err(SimulationError::SurfaceNotSupplied { ref id }) if id == "lab.gsf"
        ));
        // Supplied, 1 um pixels: the grid's cells follow the pixel.
        let heights = (0..64 * 64).map(|i| 1e-8 * ((i % 7) as f64)).collect();
        let map = HeightMap::new(64, 64, 1e-6, 1e-6, heights).expect("valid");
        let supplied = setup(&scene, Some(&map)).expect("runs");
        assert!(supplied.grid.dx <= 1e-6 + 1e-15, "{}", supplied.grid.dx);
        let surface = supplied.surface.expect("rough");
        assert!(surface.source.is_some());
        assert!(surface.model.reason.contains("lab.gsf"));
    }
}
