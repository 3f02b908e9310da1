//! What a job gives back from its files: the scene as run, the result (a succeeded job's,
//! checked against its manifest; a damaged one sends the job back to the queue) and, for a
//! failed or cancelled job, what it computed before it stopped, in the shape of a whole
//! result with `complete: false`: the scene, the setup's model choices, the cycles its log
//! holds and a summary over them. Profiles and pressure maps are made when a run finishes,
//! so a stopped run has none.

use std::io;

use uuid::Uuid;

use super::error::{JobError, PartialError};
use super::export;
use super::job::{Job, JobStatus};
use super::registry::Jobs;
use crate::scene::Scene;
use crate::service::surfaces::surface_id;
use crate::simulation::{
    CycleRecord, Plan, Provenance, RunOptions, Setup, SimulationError, SimulationResult,
};
use crate::surface::HeightMap;

impl Jobs {
    /// The scene as run, every default filled in, as stored when the job was accepted.
    /// Blocking (a file).
    pub fn scene(&self, id: Uuid) -> Result<Scene, JobError> {
        let record = self.find(id)?.record();
        if record.status == JobStatus::Damaged {
            return Err(JobError::Damaged(record.error.unwrap_or_default()));
        }
        self.store.read_scene(id).map_err(|damage| {
            if self.get(id).is_none() {
                // Deleted since it was looked up.
                JobError::Unknown(id)
            } else if damage.is_read_failure() {
                JobError::SceneUnreadable(damage)
            } else {
                JobError::SceneDamaged(damage)
            }
        })
    }

    /// The result of a finished job as JSON: a succeeded job's `result.json` (checked against
    /// its manifest), what a failed or cancelled one computed. A damaged result sends the job
    /// back to the queue. Blocking (files).
    pub fn result_json(&self, id: Uuid) -> Result<Vec<u8>, JobError> {
        let job = self.find(id)?;
        let record = job.record();
        match (record.status, record.error) {
            (JobStatus::Succeeded, _) => {}
            (JobStatus::Failed | JobStatus::Cancelled, _) => {
                return self.partial_result(&job).map_err(JobError::Partial);
            }
            (JobStatus::Damaged, Some(error)) => return Err(JobError::Damaged(error)),
            (status, _) => return Err(JobError::Unfinished(status)),
        }
        let damage = match self.store.read_result(id) {
            Ok(stored) => return Ok(marked_complete(stored)),
            Err(damage) if damage.is_read_failure() => {
                return Err(JobError::ResultUnreadable(damage));
            }
            Err(damage) => damage,
        };
        Err(match self.rerun(&job, &damage) {
            // Deleted between the status check and the read.
            None => JobError::Unknown(id),
            Some(record) => match record.error {
                Some(error) if record.status == JobStatus::Damaged => JobError::Damaged(error),
                _ => JobError::RunsAgain {
                    damage,
                    now: record.status,
                },
            },
        })
    }

    /// The cycles of a finished job's result as CSV ([`export::cycles_csv`]). Blocking (files).
    pub fn result_csv(&self, id: Uuid) -> Result<String, JobError> {
        export::cycles_csv(&self.result_json(id)?).map_err(JobError::Export)
    }

    /// The profiles of a finished job's result as CSV ([`export::profiles_csv`]). Blocking
    /// (files).
    pub fn profiles_csv(&self, id: Uuid) -> Result<String, JobError> {
        export::profiles_csv(&self.result_json(id)?).map_err(JobError::Export)
    }

    /// The pressure maps of a finished job's result as CSV ([`export::pressure_csv`]).
    /// Blocking (files).
    pub fn pressure_csv(&self, id: Uuid) -> Result<String, JobError> {
        export::pressure_csv(&self.result_json(id)?).map_err(JobError::Export)
    }

    /// A finished job's result without its pressure maps ([`export::compact`]). Blocking
    /// (files).
    pub fn compact_result_json(&self, id: Uuid) -> Result<Vec<u8>, JobError> {
        export::compact(&self.result_json(id)?).map_err(JobError::Export)
    }

    /// The partial result of a failed or cancelled `job`, as JSON. Blocking (files).
    fn partial_result(&self, job: &Job) -> Result<Vec<u8>, PartialError> {
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
        let mut result = partial(&scene, map.as_ref(), cycles(&log), wall_s).map_err(|source| {
            PartialError::Setup {
                source,
                recorded: record.error,
            }
        })?;
        // The run's date is when it stopped, not when its result is read.
        if let (Some(provenance), Some(finished)) = (&mut result.provenance, record.finished_at) {
            provenance.build.computed_at = finished;
        }
        Ok(serde_json::to_vec(&result)?)
    }
}

/// A succeeded job's stored result, saying `"complete": true` as its first field: a result
/// stored without the field (by a version that did not write it) is a succeeded job's, so
/// complete.
fn marked_complete(mut stored: Vec<u8>) -> Vec<u8> {
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
    let summary = setup
        .summary(&cycles, wall_s)
        .with_warnings(&setup.warnings);
    let warnings = setup.warning_lines();
    let provenance = Some(Provenance::of(scene));
    Ok(SimulationResult {
        complete: false,
        surface: setup.surface_report(),
        scene: setup.plan.into_scene(),
        models: setup.models,
        warnings,
        field_warnings: setup.warnings,
        cycles,
        profiles: Vec::new(),
        pressure_maps: Vec::new(),
        ocp_trace: Vec::new(),
        stroke: None,
        summary,
        provenance,
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
