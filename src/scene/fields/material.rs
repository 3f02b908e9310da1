//! The descriptors of `ball.material` and `disc.material`, which name an entry of the
//! materials library (`docs/materials.md`).

use crate::scene::field::{Field, Range};
use crate::scene::materials::{BALL_MATERIAL_NAMES, DISC_MATERIAL_NAMES};

/// `ball.material`.
pub(in crate::scene) const BALL_MATERIAL: Field = Field {
    path: "ball.material",
    unit: "",
    range: Range::OneOf(BALL_MATERIAL_NAMES),
    why: "the balls of docs/materials.md",
    meaning: "A ball of the materials library: its sourced E and nu fill the ball's fields \
              the scene does not give. A value the library lacks must be given. Naming a \
              pair other than the paper's 316L on alumina needs its own Archard k. null: \
              the fields as given.",
    feeds: "",
};

/// `disc.material`.
pub(in crate::scene) const DISC_MATERIAL: Field = Field {
    path: "disc.material",
    unit: "",
    range: Range::OneOf(DISC_MATERIAL_NAMES),
    why: "the discs of docs/materials.md",
    meaning: "A disc of the materials library. Its sourced E, nu, hardness, hardness law \
              (else a constant hardness), yield strength and `corrosion.faraday` fill the \
              fields the scene does not give. So do its electrochemical constants in \
              chloride. Where the library has none (every disc but `aisi_316l`), a scene \
              with `corrosion` must give E_corr, a_c, b_c, i_a and tau. null: the fields as \
              given.",
    feeds: "",
};
