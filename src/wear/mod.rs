//! The disc's wear (paper Section 3.2): its surface in the track and how that wears
//! ([`Groove`]: yielding under the cap, eq. 13, and the depth a wear law removes, eq. 17),
//! and the wear law of a run ([`WearLaw`]: Archard's, eqs. 1 and 14-16, with its optional
//! change of regime). The law is the one home of its coefficient: nothing outside this
//! module divides k by H.
//!
//! A new law is a variant of [`WearLaw`] with its own file here, the scene's `wear` section
//! that parses into it, and the docs (`docs/architecture.md` lists the files).

mod archard;
mod basis;
mod groove;
mod law;
mod regime;
mod report;
mod stroke;

pub use archard::{
    Archard, ArchardK, MeasuredPoint, archard_k_from_measurement, archard_volume,
    pass_pressure_integral,
};
pub use basis::{LossSplit, VolumeBasis};
pub use groove::{EDGE_DEPTH_FRACTION, Groove};
pub use law::WearLaw;
pub use regime::ArchardRegimeChange;
pub use report::{LawChoice, WearSummary};
pub use stroke::{Stroke, VelocityLaw, WearMap};
