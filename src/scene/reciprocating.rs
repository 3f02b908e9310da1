//! `test.reciprocating`: the ball-on-flat rig (ASTM G133), where the ball slides back and
//! forth along a straight stroke instead of round a disc's track. Present, it replaces the
//! disc's `track_radius_mm` and `speed_rpm`: a cycle is one stroke forward and one back.

use serde::{Deserialize, Serialize};

use super::fields::{FREQUENCY, STROKE};
use super::{AnodicArea, FieldError, Scene, Switch, YieldCapLaw};
use crate::wear::{Stroke, VelocityLaw};

/// The JSON names of [`VelocityLaw`], for the field's `OneOf` range (a test keeps them
/// equal to the enum's).
pub const VELOCITY_LAW_NAMES: &[&str] = &["sinusoidal", "constant"];

/// The stroke of a reciprocating test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Reciprocating {
    /// Stroke length, the distance between the ball centre's two turning points, mm.
    pub stroke_mm: f64,
    /// Cycles (one stroke forward and one back) per second, Hz.
    pub frequency_hz: f64,
    /// How the speed varies along the stroke.
    pub velocity_law: VelocityLaw,
}

impl Default for Reciprocating {
    fn default() -> Self {
        Self {
            stroke_mm: 5.0,
            frequency_hz: 1.0,
            velocity_law: VelocityLaw::Sinusoidal,
        }
    }
}

impl Reciprocating {
    /// The stroke in the core's SI units.
    pub fn stroke(&self) -> Stroke {
        Stroke {
            length_m: self.stroke_mm * 1e-3,
            frequency_hz: self.frequency_hz,
            law: self.velocity_law,
        }
    }
}

/// The problems of `scene`'s `test.reciprocating` and of what the rig cannot run with:
/// each field's range, and the parts of the scene the reciprocating engine does not carry
/// along the stroke (named, rather than silently left out).
pub(super) fn check(scene: &Scene) -> Vec<FieldError> {
    let Some(rig) = &scene.test.reciprocating else {
        return Vec::new();
    };
    let mut errors = Vec::new();
    for (field, value) in [(&STROKE, rig.stroke_mm), (&FREQUENCY, rig.frequency_hz)] {
        if !field.range.admits(value) {
            errors.push(FieldError::new(field.path, field.number_message(value)));
        }
    }
    let mut refuse = |path: &str, what: &str, fix: &str| {
        errors.push(FieldError::new(
            path,
            format!(
                "the reciprocating rig (`test.reciprocating`) does not model {what} yet: {fix}"
            ),
        ));
    };
    if scene.disc.surface.is_some() {
        refuse("disc.surface", "a rough flat", "omit `disc.surface`");
    }
    if scene.disc.yield_cap == YieldCapLaw::StrainHardening {
        refuse(
            "disc.yield_cap",
            "a cap that rises with plastic strain (the wear map does not carry the strain)",
            "use `hardness`",
        );
    }
    if scene.numerics.coupling == Switch::On {
        refuse(
            "numerics.coupling",
            "the friction coupling (the traction's sign turns with the sliding direction)",
            "use `auto` or `off`",
        );
    }
    for (path, seconds) in [
        ("test.ocp_before_s", scene.test.ocp_before_s),
        ("test.ocp_after_s", scene.test.ocp_after_s),
    ] {
        if seconds > 0.0 {
            refuse(
                path,
                "the open-circuit record before and after the rubbing",
                "set 0",
            );
        }
    }
    let follows = |area: AnodicArea| {
        matches!(
            area,
            AnodicArea::DepassivatedWake | AnodicArea::ContactSpots | AnodicArea::AsperitySpots
        )
    };
    if let Some(corrosion) = scene.corrosion.as_ref().filter(|c| !follows(c.anodic_area)) {
        refuse(
            "corrosion.anodic_area",
            &format!(
                "the `{}` area, which does not follow the contact along the stroke",
                crate::json::variant_name(corrosion.anodic_area)
            ),
            "use `depassivated_wake`, `contact_spots` or `asperity_spots`",
        );
    }
    errors
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_velocity_law_names_are_the_enums() {
        for (law, name) in [
            (VelocityLaw::Sinusoidal, VELOCITY_LAW_NAMES[0]),
            (VelocityLaw::Constant, VELOCITY_LAW_NAMES[1]),
        ] {
            assert_eq!(crate::json::variant_name(law), name);
        }
        assert_eq!(VELOCITY_LAW_NAMES.len(), 2);
    }

    #[test]
    fn the_stroke_is_in_si_units() {
        let stroke = Reciprocating::default().stroke();
        // One multiplication by 1e-3: one rounding.
        assert!((stroke.length_m - 5e-3).abs() <= 5e-3 * f64::EPSILON);
        assert_eq!(stroke.frequency_hz.to_bits(), 1.0_f64.to_bits());
        assert_eq!(stroke.law, VelocityLaw::Sinusoidal);
    }
}
