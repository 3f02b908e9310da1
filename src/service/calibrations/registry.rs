//! Calibrations run by the service: each fit on a thread of its own, off the async runtime,
//! its record kept in memory.
//!
//! Not on the worker pool: the pool's unit is a job (a scene, with a durable record, cycle
//! events and a result), and a fit is none of these. The Archard fit is a golden-section
//! search whose every run depends on the ones before, so it occupies one core from start to
//! end, like one job; a job queued behind it would wait seconds to minutes for nothing the
//! fit needs. At most [`MAX_RUNNING`] fits run at once, beside the pool, and a further
//! request gets 429. Fits are not stored: a fit is recomputed from its request in seconds,
//! and its result (with the scene filled in) is the client's to keep, so a restart forgets
//! them; the last [`MAX_KEPT`] ended fits are kept in memory.

use std::collections::BTreeMap;
use std::panic::{self, AssertUnwindSafe};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use serde::Serialize;
use serde_json::Value;
use time::OffsetDateTime;
use uuid::Uuid;

use crate::calibration::{CommandOptions, FitKind, Table, calibrate};
use crate::scene::Scene;

/// Fits running at once: two keeps a lab's two-core workstation responsive while a
/// simulation job runs beside them.
pub const MAX_RUNNING: usize = 2;

/// Ended fits kept in memory; the oldest are forgotten first.
pub const MAX_KEPT: usize = 100;

/// Where a fit is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CalibrationStatus {
    /// The fit is running.
    Running,
    /// The fit ended with a result.
    Succeeded,
    /// The fit ended without one; `error` says why.
    Failed,
}

/// A fit as the API shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibrationRecord {
    /// The fit's id.
    pub id: Uuid,
    /// Which fit.
    pub kind: FitKind,
    /// Where it is.
    pub status: CalibrationStatus,
    /// When it was accepted (and started).
    #[serde(with = "time::serde::rfc3339")]
    pub created_at: OffsetDateTime,
    /// When it ended.
    #[serde(with = "time::serde::rfc3339::option")]
    pub finished_at: Option<OffsetDateTime>,
    /// The fit, as `tribosim calibrate -o` writes it, once succeeded.
    pub result: Option<Value>,
    /// Why it failed.
    pub error: Option<String>,
}

/// Why a fit was not started.
#[derive(Debug)]
pub enum StartError {
    /// [`MAX_RUNNING`] fits are running.
    Busy,
    /// No thread could be started.
    Thread(std::io::Error),
}

/// Every fit by id.
#[derive(Default)]
pub struct Calibrations {
    records: Mutex<BTreeMap<Uuid, CalibrationRecord>>,
}

impl Calibrations {
    fn lock(&self) -> MutexGuard<'_, BTreeMap<Uuid, CalibrationRecord>> {
        self.records.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The fit with this id.
    pub fn get(&self, id: Uuid) -> Option<CalibrationRecord> {
        self.lock().get(&id).cloned()
    }

    /// Starts a checked fit on its own thread; its record, `running`.
    pub fn start(
        self: &Arc<Self>,
        kind: FitKind,
        table: Table,
        scene: Scene,
        options: CommandOptions,
    ) -> Result<CalibrationRecord, StartError> {
        let record = CalibrationRecord {
            id: Uuid::new_v4(),
            kind,
            status: CalibrationStatus::Running,
            created_at: OffsetDateTime::now_utc(),
            finished_at: None,
            result: None,
            error: None,
        };
        let id = record.id;
        {
            let mut records = self.lock();
            let running = records
                .values()
                .filter(|r| r.status == CalibrationStatus::Running)
                .count();
            if running >= MAX_RUNNING {
                return Err(StartError::Busy);
            }
            records.insert(id, record.clone());
        }
        let calibrations = Arc::clone(self);
        let spawned = std::thread::Builder::new()
            .name(format!("tribosim-calibration-{}", id.simple()))
            .spawn(move || {
                // A panic in a fit must fail the fit, not leave it `running` for ever.
                let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
                    calibrate(kind, &table, &scene, options)
                        .map_err(|e| e.to_string())
                        .and_then(|fit| serde_json::to_value(fit).map_err(|e| e.to_string()))
                }))
                .unwrap_or_else(|_| Err("internal error: the fit panicked".to_owned()));
                calibrations.finish(id, outcome);
            });
        if let Err(e) = spawned {
            self.lock().remove(&id);
            return Err(StartError::Thread(e));
        }
        tracing::info!(%id, ?kind, "calibration running");
        Ok(record)
    }

    fn finish(&self, id: Uuid, outcome: Result<Value, String>) {
        let mut records = self.lock();
        if let Some(record) = records.get_mut(&id) {
            record.finished_at = Some(OffsetDateTime::now_utc());
            match outcome {
                Ok(result) => {
                    record.status = CalibrationStatus::Succeeded;
                    record.result = Some(result);
                    tracing::info!(%id, "calibration succeeded");
                }
                Err(error) => {
                    tracing::warn!(%id, %error, "calibration failed");
                    record.status = CalibrationStatus::Failed;
                    record.error = Some(error);
                }
            }
        }
        forget_oldest(&mut records);
    }
}

/// Drops the oldest ended fits beyond [`MAX_KEPT`].
fn forget_oldest(records: &mut BTreeMap<Uuid, CalibrationRecord>) {
    let mut ended: Vec<(OffsetDateTime, Uuid)> = records
        .values()
        .filter(|r| r.status != CalibrationStatus::Running)
        .map(|r| (r.created_at, r.id))
        .collect();
    if ended.len() <= MAX_KEPT {
        return;
    }
    ended.sort();
    for (_, id) in &ended[..ended.len() - MAX_KEPT] {
        records.remove(id);
    }
}
