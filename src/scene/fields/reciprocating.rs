//! The descriptors of `test.reciprocating`, the ball-on-flat rig's stroke (see
//! [`super::FIELDS`]).

use crate::scene::VELOCITY_LAW_NAMES;
use crate::scene::field::{Field, Range};

/// Longest stroke, mm: the map along it is kept at the contact grid's cell size, so its
/// memory grows with the stroke (100 mm at 3.75 um cells and 64 rows is 14 MB).
pub(in crate::scene) const MAX_STROKE_MM: f64 = 100.0;

/// Highest frequency, Hz.
pub(in crate::scene) const MAX_FREQUENCY_HZ: f64 = 100.0;

/// `test.reciprocating`.
pub(in crate::scene) const RECIPROCATING: Field = Field {
    path: "test.reciprocating",
    unit: "",
    range: Range::OptionalObject,
    why: "",
    meaning: "The reciprocating ball-on-flat rig (ASTM G133): the ball slides back and forth \
              along a straight stroke on a smooth flat. A cycle is one stroke forward and \
              one back; `track_radius_mm` and `speed_rpm` are not used. Absent or null: the \
              ball on a rotating disc, as in the paper. The result's `stroke` holds the \
              wear map and the potential over a cycle.",
    feeds: "the positions the contact is solved at, the wear map, and the times between \
            the passes over each point of the track",
};

/// `test.reciprocating.stroke_mm`.
pub(in crate::scene) const STROKE: Field = Field {
    path: "test.reciprocating.stroke_mm",
    unit: "mm",
    range: Range::Closed(1e-3, MAX_STROKE_MM),
    why: "and longer than the contact (2a, checked with the contact): a shorter stroke is \
          fretting; the map's memory grows with the stroke",
    meaning: "Distance between the ball centre's turning points. 5 mm when absent.",
    feeds: "the sliding distance 2L per cycle (Archard, eqs. 14-16) and the track's length",
};

/// `test.reciprocating.frequency_hz`.
pub(in crate::scene) const FREQUENCY: Field = Field {
    path: "test.reciprocating.frequency_hz",
    unit: "Hz",
    range: Range::Closed(1e-3, MAX_FREQUENCY_HZ),
    why: "tribometers reciprocate at 0.1 to tens of Hz; a millimetre stroke at 100 Hz \
          slides at a metre per second, where frictional heating, not modelled, takes over",
    meaning: "Cycles (forward and back) per second. 1 Hz when absent.",
    feeds: "the time of each cycle (`time_s`) and between the passes over a point, hence \
            the repassivation, the potential and the WAC volume",
};

/// `test.reciprocating.velocity_law`.
pub(in crate::scene) const VELOCITY_LAW: Field = Field {
    path: "test.reciprocating.velocity_law",
    unit: "",
    range: Range::OneOf(VELOCITY_LAW_NAMES),
    why: "",
    meaning: "`sinusoidal`: driven by a crank, X(t) = -(L/2) cos(2 pi f t), at rest at the \
              ends (the default); `constant`: at 2 L f throughout, turning at once.",
    feeds: "the times between passes (the electrochemistry); not the wear, which follows \
            the sliding distance",
};
