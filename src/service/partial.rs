//! What a failed or cancelled job computed before it stopped, in the shape of a whole
//! result with `complete: false`: the scene, the setup's model choices, the cycles its log
//! holds and a summary over them. Profiles and pressure maps are made when a run finishes,
//! so a stopped run has none.

use std::io;

use thiserror::Error;

use super::job::Job;
use super::registry::Jobs;
use super::store::Damage;
use super::surfaces::{SurfaceLoadError, surface_id};
use crate::scene::Scene;
use crate::simulation::{CycleRecord, Plan, RunOptions, Setup, SimulationError, SimulationResult};
use crate::surface::HeightMap;

/// Why a stopped job's partial result cannot be given.
#[derive(Debug, Error)]
pub enum PartialError {
    /// The stored scene cannot be read back.
    #[error("the stored scene is damaged: {0}")]
    Scene(#[from] Damage),
    /// The cycle log cannot be read.
    #[error("cycles.jsonl cannot be read: {0}")]
    Cycles(#[from] io::Error),
    /// The scene cannot be set up, so the run stopped before its first cycle.
    #[error("{0}")]
    Setup(#[from] SimulationError),
    /// The height map the scene names is gone or damaged.
    #[error("{0}")]
    Surface(#[from] SurfaceLoadError),
    /// The result cannot be written as JSON.
    #[error("the result cannot be written: {0}")]
    Json(#[from] serde_json::Error),
}

impl Jobs {
    /// The partial result of a failed or cancelled `job`, as JSON. Blocking (files).
    pub fn partial_result(&self, job: &Job) -> Result<Vec<u8>, PartialError> {
        let record = job.record();
        let scene = self.store.read_scene(job.id)?;
        let log = match self.store.read_partial_cycles(job.id) {
            Ok(log) => log,
            // A job cancelled while it waited never opened its log.
            Err(e) if e.kind() == io::ErrorKind::NotFound => Vec::new(),
            Err(e) => return Err(e.into()),
        };
        let wall_s = match (record.started_at, record.finished_at) {
            (Some(started), Some(finished)) => (finished - started).as_seconds_f64().max(0.0),
            _ => 0.0,
        };
        let map = surface_id(&scene)
            .map(|id| self.surfaces.load(id))
            .transpose()?;
        let result = partial(&scene, map.as_ref(), cycles(&log), wall_s)?;
        Ok(serde_json::to_vec(&result)?)
    }
}

/// A succeeded job's stored result, saying `"complete": true` as its first field: a result
/// stored without the field (by a version that did not write it) is a succeeded job's, so
/// complete.
pub fn marked_complete(mut stored: Vec<u8>) -> Vec<u8> {
    const FLAG: &[u8] = br#"{"complete":"#;
    if !stored.starts_with(FLAG) && stored.first() == Some(&b'{') {
        stored.splice(1..1, br#""complete":true,"#.iter().copied());
    }
    stored
}

/// The records of a cycle log, up to the first line that is not one (a line cut short when
/// the process stopped mid-write).
fn cycles(log: &[u8]) -> Vec<CycleRecord> {
    log.split(|&byte| byte == b'\n')
        .map_while(|line| serde_json::from_slice(line).ok())
        .collect()
}

/// The result of a run of `scene` stopped after `cycles`, which took `wall_s`.
fn partial(
    scene: &Scene,
    map: Option<&HeightMap>,
    cycles: Vec<CycleRecord>,
    wall_s: f64,
) -> Result<SimulationResult, SimulationError> {
    let options = RunOptions {
        surface: map,
        ..RunOptions::default()
    };
    let setup = Setup::new(&Plan::new(scene.clone())?, &options)?;
    let summary = setup.summary(&cycles, wall_s);
    Ok(SimulationResult {
        complete: false,
        surface: setup.surface_report(),
        scene: setup.plan.into_scene(),
        models: setup.models,
        warnings: setup.warnings,
        cycles,
        profiles: Vec::new(),
        pressure_maps: Vec::new(),
        ocp_trace: Vec::new(),
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::parse_scene_str;

    #[test]
    fn the_summary_is_the_last_logged_cycle_and_a_cut_line_ends_the_log() {
        let scene = parse_scene_str(
            r#"{"preset": "dalmau2018-316l", "overrides": {"numerics": {"grid": 32}}}"#,
        )
        .expect("valid scene")
        .into_scene();
        let line = |cycle: u64, volume: f64| {
            format!(
                r#"{{"cycle": {cycle}, "time_s": 1.0, "wear_volume_mm3": {volume}, "max_depth_um": 0.5, "max_pressure_mpa": 900.0, "contact_area_mm2": 0.02, "plastic_area_mm2": 0.0, "hardness_mpa": 2500.0, "approach_um": 1.5, "iterations": 7, "potential_v": -0.3}}"#
            )
        };
        let log = format!("{}\n{}\n{{\"cycle\": 9, \"ti", line(1, 1e-4), line(4, 3e-4));
        let result = partial(&scene, None, cycles(log.as_bytes()), 2.5).expect("partial");
        assert!(!result.complete);
        assert_eq!(result.cycles.len(), 2);
        assert_eq!(result.summary.cycles, 4);
        // Copied from the last record, not computed: the same bits.
        assert_eq!(result.summary.wear_volume_mm3.to_bits(), 3e-4_f64.to_bits());
        assert_eq!(result.summary.potential_v, Some(-0.3));
        assert_eq!((result.summary.solves, result.summary.iterations), (2, 14));
        assert!(result.profiles.is_empty() && result.pressure_maps.is_empty());
        let empty = partial(&scene, None, cycles(b""), 0.0).expect("partial");
        assert_eq!(empty.summary.cycles, 0);
        let whole = serde_json::to_vec(&result).expect("serialises");
        assert_eq!(marked_complete(whole.clone()), whole, "the flag is first");
        let unmarked = marked_complete(br#"{"scene":{}}"#.to_vec());
        assert_eq!(unmarked, br#"{"complete":true,"scene":{}}"#);
    }
}
