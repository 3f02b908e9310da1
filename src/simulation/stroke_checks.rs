//! What the reciprocating rig (`test.reciprocating`) asks of a scene beyond each field's
//! range: a stroke longer than the contact, and a frequency whose half period leaves the
//! film time to regrow (a warning).

use super::sizing::GridPlan;
use crate::scene::format::{num, sig};
use crate::scene::{FieldError, FieldWarning, Scene};

/// The most cells the wear map along the stroke may hold on the first grid (its columns,
/// the stroke over a cell plus the grid's, times the grid's rows): 2 million cells are 16
/// MB a copy, and a run holds four (the map, the cycle's and the sweep's pressure integral
/// and the sweep's yield), which the growth of the grid across the track may double. It
/// bounds the positions a sweep visits too, one per cell of the stroke.
const MAX_MAP_CELLS: f64 = 2e6;

/// The stroke must be longer than the contact's width along it, 2 x the radius the grid is
/// sized by (`sizing_m`, Hertz's or the punch's at the lowest cap): shorter, no point of
/// the track is ever uncovered, which is fretting, not the sliding the model describes. Its
/// map on the first grid (`grid`) must hold at most [`MAX_MAP_CELLS`].
pub(super) fn stroke_limits(scene: &Scene, sizing_m: f64, grid: &GridPlan) -> Vec<FieldError> {
    let Some(rig) = &scene.test.reciprocating else {
        return Vec::new();
    };
    let cell_m = grid.domain_m / grid.cells as f64;
    let map_cells = (rig.stroke_mm * 1e-3 / cell_m + grid.cells as f64) * grid.cells as f64;
    if map_cells > MAX_MAP_CELLS {
        return vec![FieldError::new(
            "test.reciprocating.stroke_mm",
            format!(
                "the wear map along a {} mm stroke on {} um cells ({} rows) would hold {} \
                 cells, more than the {} a run may keep: a shorter stroke, or a coarser grid \
                 (`numerics.grid`, `numerics.domain_um`), at most {} mm here",
                num(rig.stroke_mm),
                sig(cell_m * 1e6),
                grid.cells,
                sig(map_cells),
                sig(MAX_MAP_CELLS),
                sig((MAX_MAP_CELLS / grid.cells as f64 - grid.cells as f64) * cell_m * 1e3)
            ),
        )];
    }
    let width_mm = 2.0 * sizing_m * 1e3;
    if rig.stroke_mm > width_mm {
        return Vec::new();
    }
    vec![FieldError::new(
        "test.reciprocating.stroke_mm",
        format!(
            "must be longer than the contact's width 2a = {} mm at this load, got {} mm: a \
             shorter stroke never uncovers the track's middle (fretting, which this model \
             does not describe). Was it in cm or m? {} cm = {} mm, {} m = {} mm",
            sig(width_mm),
            num(rig.stroke_mm),
            num(rig.stroke_mm),
            sig(rig.stroke_mm * 10.0),
            num(rig.stroke_mm),
            sig(rig.stroke_mm * 1e3)
        ),
    )]
}

/// A frequency at which a point of the track's middle is stripped again before its film
/// has regrown for one repassivation time: the track stays mostly bare, and the kinetics,
/// measured on single scratches, are used beyond what they describe.
pub(super) fn stroke_warnings(scene: &Scene) -> Vec<FieldWarning> {
    let (Some(rig), Some(corrosion)) = (&scene.test.reciprocating, &scene.corrosion) else {
        return Vec::new();
    };
    let between_s = 0.5 / rig.frequency_hz;
    let tau = corrosion.repassivation_time_s;
    if between_s >= tau {
        return Vec::new();
    }
    vec![FieldWarning::new(
        "test.reciprocating.frequency_hz",
        format!(
            "at {} Hz the middle of the track is stripped every {} s, before its film has \
             regrown for the repassivation time {} s: the track stays mostly bare, and the \
             potential rests on the kinetics beyond a single strip. Below {} Hz the film \
             has that time (was the frequency in cycles per minute? {} rpm = {} Hz)",
            num(rig.frequency_hz),
            sig(between_s),
            num(tau),
            sig(0.5 / tau),
            num(rig.frequency_hz),
            sig(rig.frequency_hz / 60.0)
        ),
    )]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Reciprocating;

    fn rig(stroke_mm: f64, frequency_hz: f64) -> Scene {
        let mut scene = Scene::default();
        scene.test.reciprocating = Some(Reciprocating {
            stroke_mm,
            frequency_hz,
            ..Reciprocating::default()
        });
        scene
    }

    /// `cells` cells of 3.75 um.
    fn grid(cells: usize) -> GridPlan {
        GridPlan {
            cells,
            domain_m: cells as f64 * 3.75e-6,
            how: String::new(),
        }
    }

    #[test]
    fn a_map_past_its_bound_is_refused_with_the_longest_stroke_that_fits() {
        // 100 mm on 3.75 um cells: 26,667 + 48 columns of 48 rows, 1.28 million cells.
        assert!(stroke_limits(&rig(100.0, 1.0), 60e-6, &grid(48)).is_empty());
        // On 96 rows: 2.57 million; the longest that fits is (2e6 / 96 - 96) x 3.75 um,
        // 77.765 mm, to four digits.
        let errors = stroke_limits(&rig(100.0, 1.0), 60e-6, &grid(96));
        assert_eq!(errors.len(), 1);
        assert!(
            errors[0].message.contains("at most 77.77 mm"),
            "{}",
            errors[0].message
        );
    }

    #[test]
    fn a_stroke_within_the_contact_is_refused_at_its_field_with_the_width() {
        // A 60 um contact radius: 0.12 mm wide.
        let errors = stroke_limits(&rig(0.1, 1.0), 60e-6, &grid(48));
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].path, "test.reciprocating.stroke_mm");
        assert!(
            errors[0].message.contains("2a = 0.12 mm"),
            "{}",
            errors[0].message
        );
        assert!(stroke_limits(&rig(0.13, 1.0), 60e-6, &grid(48)).is_empty());
        assert!(stroke_limits(&Scene::default(), 60e-6, &grid(48)).is_empty());
    }

    #[test]
    fn a_frequency_faster_than_the_film_regrows_is_warned_of() {
        // The paper's tau 0.148 s: every 0.5 / f s must be at least that, f <= 3.38 Hz.
        assert!(stroke_warnings(&rig(5.0, 3.0)).is_empty());
        let warnings = stroke_warnings(&rig(5.0, 4.0));
        assert_eq!(warnings.len(), 1);
        assert_eq!(warnings[0].path, "test.reciprocating.frequency_hz");
        let mut dry = rig(5.0, 4.0);
        dry.corrosion = None;
        assert!(stroke_warnings(&dry).is_empty());
    }
}
