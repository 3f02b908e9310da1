//! The numbers of the reproduction that `tests/paper.rs` holds and `docs/paper.md` quotes.

use crate::scene::PAPER_TABLE3;
use crate::simulation::{CycleRecord, Profile, SimulationResult};

use super::PaperStudy;

/// Table 3 ([`PAPER_TABLE3`]) in the paper's units: rubbing time (s, cycles at 60 rpm),
/// hardness inside the track (MPa), wear volume and its spread (1e-3 mm^3).
pub const TABLE3: [(u64, f64, f64, f64); 5] = {
    let mut table = [(0, 0.0, 0.0, 0.0); 5];
    let mut i = 0;
    while i < table.len() {
        let r = PAPER_TABLE3[i];
        table[i] = (
            r.time_s,
            r.hardness_mpa,
            r.wear_volume_mm3 * 1e3,
            r.spread_mm3 * 1e3,
        );
        i += 1;
    }
    table
};

/// The cycles of Figs. 11-12 where Table 3 has a point.
pub const EARLY: [u64; 3] = [10, 60, 300];

/// What one elastic-perfectly-plastic run gives the paper's statements about its first
/// cycles: its groove.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CapNumbers {
    /// The groove's deepest point at cycles 10 and 300, um.
    pub groove_depth_um: [f64; 2],
    /// The groove's volume at cycles 10, 60 and 300, mm^3.
    pub groove_volume_mm3: [f64; 3],
    /// The first cycle from which no pressure sits at the cap.
    pub plastic_gone_cycle: u64,
}

impl CapNumbers {
    /// The numbers of `result`, a run of at least 300 cycles solving cycles 10, 60 and 300.
    pub fn of(result: &SimulationResult) -> Self {
        let depth = |c: u64| record(result, c).max_depth_um;
        Self {
            groove_depth_um: [depth(10), depth(300)],
            groove_volume_mm3: EARLY.map(|c| record(result, c).wear_volume_mm3),
            plastic_gone_cycle: plastic_gone(result),
        }
    }
}

/// The reproduced numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct PaperNumbers {
    /// The default (the paper's cap) EPP run's groove.
    pub epp: CapNumbers,
    /// The loaded surface's deepest point at cycles 10 and 300, um.
    pub loaded_depth_um: [f64; 2],
    /// The purely elastic disc's loaded surface at cycle 1, um: the elastic dent with no
    /// yielding and no groove to speak of.
    pub elastic_loaded_first_um: f64,
    /// The same by the single-number formula `D + s (delta - D)`, um.
    pub formula_depth_um: [f64; 2],
    /// The EPP loaded profile's volume over the window at cycles 10, 60 and 300, mm^3.
    pub loaded_volume_mm3: [f64; 3],
    /// The elastic material's groove volume at cycles 10, 60 and 300, mm^3.
    pub elastic_volume_mm3: [f64; 3],
    /// The elastic material's loaded volume at cycles 10, 60 and 300, mm^3.
    pub elastic_loaded_volume_mm3: [f64; 3],
    /// The whole test's wear track volume at Table 3's times, mm^3: the total loss, since k
    /// comes from a measured total (`wear.archard_k_basis` `total_loss`).
    pub whole_volume_mm3: [f64; 5],
    /// The whole test's mechanical part (the track less the corrosion) at Table 3's times,
    /// mm^3.
    pub whole_mechanical_mm3: [f64; 5],
}

impl PaperNumbers {
    /// The numbers of `study`.
    pub fn of(study: &PaperStudy) -> Self {
        let s = study.disc_share;
        let loaded = |c: u64| record(&study.epp, c).loaded_max_depth_um;
        let formula = |c: u64| {
            let r = record(&study.epp, c);
            r.max_depth_um + s * (r.approach_um - r.max_depth_um)
        };
        let at_early = |result: &SimulationResult, f: &dyn Fn(&SimulationResult, u64) -> f64| {
            EARLY.map(|c| f(result, c))
        };
        let groove = |r: &SimulationResult, c: u64| record(r, c).wear_volume_mm3;
        let loaded_volume = |r: &SimulationResult, c: u64| loaded_volume_mm3(r, c);
        let whole = |f: fn(&CycleRecord) -> f64| TABLE3.map(|(t, ..)| f(record(&study.whole, t)));
        Self {
            epp: CapNumbers::of(&study.epp),
            loaded_depth_um: [loaded(10), loaded(300)],
            elastic_loaded_first_um: record(&study.elastic, 1).loaded_max_depth_um,
            formula_depth_um: [formula(10), formula(300)],
            loaded_volume_mm3: at_early(&study.epp, &loaded_volume),
            elastic_volume_mm3: at_early(&study.elastic, &groove),
            elastic_loaded_volume_mm3: at_early(&study.elastic, &loaded_volume),
            whole_volume_mm3: whole(|r| r.wear_volume_mm3),
            whole_mechanical_mm3: whole(|r| r.mechanical_volume_mm3.unwrap_or(r.wear_volume_mm3)),
        }
    }
}

/// The record of `cycle`, which the study's runs solve (every cycle, or Table 3's times).
pub(super) fn record(result: &SimulationResult, cycle: u64) -> &CycleRecord {
    result
        .cycles
        .iter()
        .find(|r| r.cycle == cycle)
        .unwrap_or_else(|| panic!("cycle {cycle} is solved in the study's runs"))
}

/// The profile of `cycle`.
pub(super) fn profile(result: &SimulationResult, cycle: u64) -> &Profile {
    result
        .profiles
        .iter()
        .find(|p| p.cycle == cycle)
        .unwrap_or_else(|| panic!("cycle {cycle} keeps a profile in the study's runs"))
}

/// The track length times the area of the loaded profile of `cycle` over the domain, mm^3.
pub(super) fn loaded_volume_mm3(result: &SimulationResult, cycle: u64) -> f64 {
    let p = profile(result, cycle);
    let dy_um = p.y_um[1] - p.y_um[0];
    let area_um2: f64 = p.loaded_depth_um.iter().sum::<f64>() * dy_um;
    area_um2 * 1e-6 * result.scene.track_length_m() * 1e3
}

/// The first cycle from which no record of `result` has a plastic area.
pub(super) fn plastic_gone(result: &SimulationResult) -> u64 {
    result
        .cycles
        .iter()
        .rev()
        .take_while(|r| r.plastic_area_mm2 == 0.0)
        .last()
        .map_or(u64::MAX, |r| r.cycle)
}
