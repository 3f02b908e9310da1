//! The material balance of a run after ASTM G119: the total a profilometer measures is the
//! mechanical loss (the groove and Archard's wear, W0 + delta W_c) and the corrosion loss
//! (the wear-accelerated corrosion, delta C_w) together. A scene whose Archard k comes from a
//! measured volume derives it from such a total; this says what that means for the run
//! ([`VolumeBasis`] splits each record's loss).

use crate::corrosion::CorrosionModel;
use crate::hardness::HardnessLaw;
use crate::scene::{FieldWarning, Scene};
use crate::wear::VolumeBasis;

use super::result::CycleRecord;

/// What the run says about its balance against the measured point its k comes from: a
/// warning when the corrosion alone exceeds the measured total, and the words for the
/// corrosion model's reason. `None` when k is given, the point was measured in another
/// test, or the run has no corrosion.
pub(super) struct Balance {
    /// The corrosion exceeds the measured total: a warning about the anodic area.
    pub(super) warning: Option<FieldWarning>,
    /// The share of the measured total the run dissolves.
    pub(super) reason: String,
}

/// The balance of `records`, a run of `scene` with the hardness law `hardness` and the cell
/// `model`.
pub(super) fn balance(
    scene: &Scene,
    hardness: &HardnessLaw,
    model: &CorrosionModel,
    records: &[CycleRecord],
) -> Option<Balance> {
    if scene.wear.archard_k.is_some() {
        return None;
    }
    let point = scene.wear.calibration_point(&scene.test, hardness);
    let test = &scene.test;
    // A point that does not give its conditions takes the scene's own numbers: the same
    // test is the same bits.
    let same = |a: f64, b: f64| a.to_bits() == b.to_bits();
    let same_test = same(point.load_n, test.load_n)
        && same(point.speed_rpm, test.speed_rpm)
        && same(point.track_radius_mm, test.track_radius_mm);
    let last = records.last()?;
    if !same_test {
        return None;
    }
    // After a solve the run dissolves at its current until the next.
    let at = point.time_s.min(last.time_s);
    let before = records
        .iter()
        .rev()
        .find(|r| r.time_s <= at)
        .unwrap_or(last);
    let charge =
        before.charge_c? + before.anodic_current_ma? * 1e-3 * (at - before.time_s).max(0.0);
    let wac_at = model.dissolved_volume_m3(charge) * 1e9;
    let measured = point.wear_volume_mm3;
    let share = wac_at / measured;
    let warning = (wac_at > measured).then(|| {
        let message = format!(
            "the wear-accelerated corrosion alone, {wac_at:.4e} mm^3 after {at} s, exceeds \
             the total volume measured after {} s ({measured} mm^3, \
             `wear.archard_calibration`), which includes the corrosion: the anodic area \
             dissolves {share:.1} times what was measured",
            point.time_s
        );
        FieldWarning::new("corrosion.anodic_area", message)
    });
    let reason = match scene.wear.archard_k_basis {
        VolumeBasis::TotalLoss => format!(
            "Archard's k comes from the measured total {measured} mm^3 after {} s, which \
             includes the corrosion (`wear.archard_k_basis` total_loss): the wear track is the \
             total, of which the WAC after {at} s ({wac_at:.3e} mm^3) is {:.1}%; \
             `mechanical_volume_mm3` is the rest",
            point.time_s,
            100.0 * share
        ),
        VolumeBasis::Mechanical => format!(
            "Archard's k comes from the measured total {measured} mm^3 after {} s but is read \
             as mechanical (`wear.archard_k_basis` mechanical): the run's WAC after {at} s \
             ({wac_at:.3e} mm^3, {:.1}% of that total) is added to the wear track, so its \
             `total_volume_mm3` counts the corrosion twice against that point",
            point.time_s,
            100.0 * share
        ),
    };
    Some(Balance { warning, reason })
}

/// A warning when the run's corrosion outgrows the loss its k was fitted on: on the
/// total-loss basis the wear track is the whole loss, and a WAC beyond it leaves a
/// mechanical part of 0, which no measurement can give.
pub(super) fn overdrawn(scene: &Scene, records: &[CycleRecord]) -> Option<FieldWarning> {
    if scene.wear.archard_k_basis != VolumeBasis::TotalLoss {
        return None;
    }
    let last = records.last()?;
    let wac = last.wac_volume_mm3?;
    // The total is the larger of the wear track and the WAC: a mechanical part of 0 is a
    // WAC that reached the track.
    (wac > 0.0 && last.mechanical_volume_mm3 == Some(0.0)).then(|| {
        FieldWarning::new(
            "wear.archard_k_basis",
            format!(
                "the wear-accelerated corrosion after {} s, {wac:.4e} mm^3, reaches the wear \
                 track, which k fitted on total losses makes the whole loss: the total reads \
                 the WAC and the mechanical part 0; the anodic area or i_a dissolves too \
                 much, or k was fitted on the mechanical loss (`mechanical`)",
                last.time_s
            ),
        )
    })
}
