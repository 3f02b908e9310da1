//! The hardness a scene gives against the hardness of real metals: the one rule that names
//! a hardness typed in another unit (GPa or Pa for MPa). The scene's checks refuse by it
//! before they fit the hardness law, whose fit of points in GPa would only say that the
//! law falls below 0; the simulation's plausibility warns by it.

use super::Scene;
use super::format::{num, sig};

/// Annealed pure aluminium, about the softest structural metal, has HV 20-25 (200-250 MPa)
/// and annealed copper HV 40-50; only lead and tin (HV about 5, 50 MPa) and indium (HB
/// about 1, 9 MPa) are softer. Below this a disc is of lead or tin, or its hardness in GPa
/// was typed as MPa (316L's 2.473 GPa as 2.473).
pub const WARN_HARDNESS_MPA: f64 = 100.0;
/// Softer than indium (about 9 MPa), the softest metal solid at room temperature: no metal
/// disc, so a unit slip.
pub const REFUSE_HARDNESS_MPA: f64 = 5.0;
/// The hardest metals, through-hardened tool and bearing steels, reach about HV 1000, 9.8
/// GPa: a harder disc is a ceramic or a coating, worth a word.
pub const WARN_HARD_MPA: f64 = 10e3;
/// Diamond, the hardest solid, has HV 70-100 GPa: a harder disc is a unit slip (316L's
/// 2473 MPa typed in Pa is 2.473e9).
pub const REFUSE_HARD_MPA: f64 = 100e3;

/// What the rule finds at one hardness.
#[derive(Debug, Clone, PartialEq)]
pub struct HardnessSlip {
    /// The field's dotted path.
    pub path: String,
    /// True when no run could mean anything with it; false for a warning.
    pub refused: bool,
    /// The value against the metals', with the likely slip.
    pub message: String,
}

/// Each hardness of `scene` (`disc.hardness_mpa` and each table point) that leaves the
/// metals' range, with the unit it was likely typed in.
pub fn hardness_slips(scene: &Scene) -> Vec<HardnessSlip> {
    let table = scene.disc.hardness_table.iter().flatten().enumerate();
    std::iter::once(("disc.hardness_mpa".to_owned(), scene.disc.hardness_mpa))
        .chain(table.map(|(i, &(_, mpa))| (format!("disc.hardness_table[{i}][1]"), mpa)))
        .filter_map(|(path, mpa)| {
            judge(mpa).map(|(refused, message)| HardnessSlip {
                path,
                refused,
                message,
            })
        })
        .collect()
}

/// Whether `mpa` is refused, and why; `None` within the metals' range.
fn judge(mpa: f64) -> Option<(bool, String)> {
    if (WARN_HARDNESS_MPA..=WARN_HARD_MPA).contains(&mpa) || !mpa.is_finite() {
        return None;
    }
    let slip = slip(mpa);
    let value = num(mpa);
    Some(if mpa < REFUSE_HARDNESS_MPA {
        (
            true,
            format!(
                "{value} MPa is softer than any metal (indium, the softest, is about 9 MPa): {slip}"
            ),
        )
    } else if mpa < WARN_HARDNESS_MPA {
        (
            false,
            format!(
                "{value} MPa is softer than annealed pure aluminium (about 200 MPa); only lead, \
                 tin and indium are softer: {slip}"
            ),
        )
    } else if mpa > REFUSE_HARD_MPA {
        (
            true,
            format!("{value} MPa is harder than diamond (70-100 GPa), the hardest solid: {slip}"),
        )
    } else {
        (
            false,
            format!(
                "{value} MPa is harder than the hardest metals (hardened steels, about 10 GPa): \
                 {slip}"
            ),
        )
    })
}

/// The unit `mpa` was likely typed in: the one (GPa, kPa or Pa) that makes it a metal's
/// hardness, or a plea to check the unit when none does.
fn slip(mpa: f64) -> String {
    let units = [("GPa", 1e3), ("kPa", 1e-3), ("Pa", 1e-6)];
    units
        .iter()
        .find(|(_, to_mpa)| (WARN_HARDNESS_MPA..=WARN_HARD_MPA).contains(&(mpa * to_mpa)))
        .map_or_else(
            || "check that it is in MPa".to_owned(),
            |(unit, to_mpa)| {
                format!(
                    "was it in {unit}? {} {unit} = {} MPa",
                    num(mpa),
                    sig(mpa * to_mpa)
                )
            },
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_slip_is_named_by_the_unit_that_makes_it_a_metals_hardness() {
        let said = |mpa: f64| judge(mpa).expect("judged");
        assert_eq!(judge(2473.0), None);
        let (refused, message) = said(2.473e9);
        assert!(refused);
        assert!(
            message.contains("was it in Pa? 2.473e9 Pa = 2473 MPa"),
            "{message}"
        );
        let (refused, message) = said(2.473e6);
        assert!(refused);
        assert!(message.contains("was it in kPa?"), "{message}");
        let (refused, message) = said(2.473);
        assert!(refused);
        assert!(
            message.contains("was it in GPa? 2.473 GPa = 2473 MPa"),
            "{message}"
        );
        // A ceramic disc (alumina HV 1500-1650, about 15 GPa): warned, not a slip.
        let (refused, message) = said(15e3);
        assert!(!refused);
        assert!(message.contains("check that it is in MPa"), "{message}");
        // Lead (about 50 MPa): warned, not taken for a slip (50 GPa is no metal's).
        let (refused, message) = said(50.0);
        assert!(!refused);
        assert!(message.contains("check that it is in MPa"), "{message}");
    }
}
