//! Calibrations run by the service: each fit on a thread of its own, off the async runtime,
//! its record kept in memory; listed, cancelled and deleted as jobs are.
//!
//! Not on the worker pool: the pool's unit is a job (a scene, with a durable record, cycle
//! events and a result), and a fit is none of these. The Archard fit is a golden-section
//! search whose every run depends on the ones before, so it occupies one core from start to
//! end, like one job; a job queued behind it would wait seconds to minutes for nothing the
//! fit needs. At most [`MAX_RUNNING`] fits run at once, beside the pool, and a further
//! request gets 429; DELETE stops a running fit within a cycle of its run under way. An
//! ended fit keeps its result as JSON text, not its table or scene, in memory and on disk
//! (`store.rs`), so a restart keeps it; the ended fits kept are at most [`MAX_KEPT`] and at
//! most `--calibration-kept-bytes` of results together, the oldest forgotten first.

use std::collections::HashMap;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use serde::{Deserialize, Serialize, Serializer};
use serde_json::value::RawValue;
use time::OffsetDateTime;
use uuid::Uuid;

use crate::calibration::{CalibrationError, CommandOptions, FitKind, Table, calibrate_until};
use crate::scene::Scene;
use crate::service::listing::{Filter, Listed};

use super::store::CalibrationStore;

/// Fits running at once: two keeps a lab's two-core workstation responsive while a
/// simulation job runs beside them.
pub const MAX_RUNNING: usize = 2;

/// Ended fits kept in memory, whatever their size; the oldest are forgotten first.
pub const MAX_KEPT: usize = 100;

/// Where a fit is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CalibrationStatus {
    /// The fit is running.
    Running,
    /// The fit ended with a result.
    Succeeded,
    /// The fit ended without one; `error` says why.
    Failed,
    /// A client stopped it (DELETE).
    Cancelled,
}

impl CalibrationStatus {
    /// Every status, as the API spells it.
    pub const NAMES: &'static [&'static str] = &["running", "succeeded", "failed", "cancelled"];

    /// The status as the API spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Running => "running",
            Self::Succeeded => "succeeded",
            Self::Failed => "failed",
            Self::Cancelled => "cancelled",
        }
    }
}

/// A fit as the list shows it: everything but its result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationInfo {
    /// The fit's id.
    pub id: Uuid,
    /// Which fit.
    pub kind: FitKind,
    /// Where it is.
    pub status: CalibrationStatus,
    /// When it was accepted (and started).
    #[serde(with = "time::serde::rfc3339")]
    pub created_at: OffsetDateTime,
    /// When it ended (or was cancelled).
    #[serde(with = "time::serde::rfc3339::option")]
    pub finished_at: Option<OffsetDateTime>,
    /// Why it failed.
    pub error: Option<String>,
}

/// A fit's result, the JSON `tribosim calibrate -o` writes, kept as text: a few bytes a
/// number where a parsed JSON value takes tens (an 830 KB hardness table's fit held 60 MB
/// as a `serde_json::Value`).
#[derive(Debug, Clone)]
pub struct FitResult(Arc<str>);

impl FitResult {
    /// The result's JSON text.
    pub(super) fn text(&self) -> &str {
        &self.0
    }

    /// A result from its JSON text.
    pub(super) fn from_text(text: &str) -> Self {
        Self(text.into())
    }
}

impl Serialize for FitResult {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let raw: &RawValue = serde_json::from_str(&self.0).map_err(serde::ser::Error::custom)?;
        raw.serialize(serializer)
    }
}

/// A fit as `GET /api/v1/calibrations/{id}` shows it.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrationRecord {
    /// Everything but the result.
    #[serde(flatten)]
    pub info: CalibrationInfo,
    /// The fit, once succeeded.
    pub result: Option<FitResult>,
}

impl Listed for CalibrationInfo {
    fn created_at(&self) -> OffsetDateTime {
        self.created_at
    }
    fn id(&self) -> Uuid {
        self.id
    }
}

/// The filters of `GET /api/v1/calibrations`.
pub(super) const FILTERS: &[Filter<CalibrationInfo>] = &[
    Filter::OneOf("status", CalibrationStatus::NAMES, |c| c.status.name()),
    Filter::OneOf("kind", &["hardness", "tafel", "ocp", "archard"], |c| {
        kind_name(c.kind)
    }),
];

/// The fit's kind as the API spells it.
fn kind_name(kind: FitKind) -> &'static str {
    match kind {
        FitKind::Hardness => "hardness",
        FitKind::Tafel => "tafel",
        FitKind::Ocp => "ocp",
        FitKind::Archard => "archard",
    }
}

/// Why a fit was not started.
#[derive(Debug)]
pub enum StartError {
    /// [`MAX_RUNNING`] fits are running.
    Busy,
    /// No thread could be started.
    Thread(std::io::Error),
}

/// Why a fit ended without a result; its text is the fit's `error`.
#[derive(Debug, thiserror::Error)]
enum FitFailure {
    /// The fit itself failed.
    #[error(transparent)]
    Fit(#[from] CalibrationError),
    /// The fit's result cannot be written as JSON.
    #[error(transparent)]
    Result(#[from] serde_json::Error),
    /// The fit panicked.
    #[error("internal error: the fit panicked")]
    Panicked,
}

/// What DELETE did to a fit.
pub enum CalibrationDeletion {
    /// It was running: it is cancelled, and its run stops within a cycle.
    Cancelled(CalibrationInfo),
    /// It had ended: it is forgotten.
    Removed,
}

/// The limits fits run under (`--calibration-*`).
#[derive(Debug, Clone, Copy)]
pub struct FitLimits {
    /// The most cells per side of a fit's runs.
    pub max_grid: usize,
    /// The most cell-cycles of one run.
    pub max_cell_cycles: u64,
    /// Bytes of ended fits' results kept.
    pub kept_bytes: usize,
}

/// One fit in memory.
struct Entry {
    info: CalibrationInfo,
    result: Option<FitResult>,
    /// Set by DELETE; the fit's runs poll it.
    cancel: Arc<AtomicBool>,
}

impl Entry {
    /// The bytes it keeps beyond its fixed size: its result's text and its error's.
    fn bytes(&self) -> usize {
        self.result.as_ref().map_or(0, |r| r.0.len())
            + self.info.error.as_ref().map_or(0, String::len)
    }
}

/// Every fit by id, and the fit threads still running.
#[derive(Default)]
struct Inner {
    entries: HashMap<Uuid, Entry>,
    /// Threads of fits not yet returned (a cancelled fit's thread counts until it returns).
    threads: usize,
}

/// Every fit by id.
pub struct Calibrations {
    inner: Mutex<Inner>,
    pub(super) limits: FitLimits,
    /// Where ended fits are kept across restarts; `None` keeps them in memory only.
    store: Option<CalibrationStore>,
}

impl Calibrations {
    /// The fits `store` kept, under `limits`.
    pub fn new(limits: FitLimits, store: Option<CalibrationStore>) -> Self {
        let mut inner = Inner::default();
        let loaded = store
            .as_ref()
            .map_or_else(|| Ok(Vec::new()), CalibrationStore::load);
        match loaded {
            Ok(fits) => {
                for (info, result) in fits {
                    let entry = Entry {
                        info,
                        result,
                        cancel: Arc::default(),
                    };
                    inner.entries.insert(entry.info.id, entry);
                }
            }
            Err(e) => tracing::error!("cannot read the stored calibrations: {e}"),
        }
        let calibrations = Self {
            inner: Mutex::new(inner),
            limits,
            store,
        };
        let forgotten = forget_oldest(&mut calibrations.lock().entries, limits.kept_bytes);
        calibrations.unstore(&forgotten);
        calibrations
    }

    /// Keeps the ended fit `id` on disk, as `record` holds it.
    fn keep(&self, record: Option<CalibrationRecord>) {
        if let (Some(store), Some(record)) = (&self.store, record) {
            if let Err(e) = store.save(&record.info, record.result.as_ref()) {
                tracing::error!(id = %record.info.id, "cannot keep the calibration: {e}");
            }
        }
    }

    /// Removes the fits `ids` from disk.
    fn unstore(&self, ids: &[Uuid]) {
        let Some(store) = &self.store else {
            return;
        };
        for id in ids {
            if let Err(e) = store.remove(*id) {
                tracing::error!(%id, "cannot remove the stored calibration: {e}");
            }
        }
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The fit with this id.
    pub fn get(&self, id: Uuid) -> Option<CalibrationRecord> {
        self.lock().entries.get(&id).map(|entry| CalibrationRecord {
            info: entry.info.clone(),
            result: entry.result.clone(),
        })
    }

    /// Every fit, without results, in no order.
    pub fn list(&self) -> Vec<CalibrationInfo> {
        self.lock()
            .entries
            .values()
            .map(|entry| entry.info.clone())
            .collect()
    }

    /// Starts a checked fit on its own thread; its record, `running`.
    pub fn start(
        self: &Arc<Self>,
        kind: FitKind,
        table: Table,
        scene: Scene,
        options: CommandOptions,
    ) -> Result<CalibrationInfo, StartError> {
        let info = CalibrationInfo {
            id: Uuid::new_v4(),
            kind,
            status: CalibrationStatus::Running,
            created_at: OffsetDateTime::now_utc(),
            finished_at: None,
            error: None,
        };
        let id = info.id;
        let cancel = Arc::new(AtomicBool::new(false));
        {
            let mut inner = self.lock();
            if inner.threads >= MAX_RUNNING {
                return Err(StartError::Busy);
            }
            inner.threads += 1;
            let entry = Entry {
                info: info.clone(),
                result: None,
                cancel: Arc::clone(&cancel),
            };
            inner.entries.insert(id, entry);
        }
        let calibrations = Arc::clone(self);
        let spawned = std::thread::Builder::new()
            .name(format!("tribosim-calibration-{}", id.simple()))
            .spawn(move || {
                // A panic in a fit must fail the fit, not leave it `running` for ever.
                let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
                    let fit = calibrate_until(kind, &table, &scene, options, &cancel)?;
                    Ok(result_text(&fit)?)
                }))
                .unwrap_or(Err(FitFailure::Panicked));
                // The inputs go before the result is kept.
                drop((table, scene));
                calibrations.finish(id, outcome);
            });
        if let Err(e) = spawned {
            let mut inner = self.lock();
            inner.entries.remove(&id);
            inner.threads -= 1;
            return Err(StartError::Thread(e));
        }
        tracing::info!(%id, ?kind, "calibration running");
        Ok(info)
    }

    fn finish(&self, id: Uuid, outcome: Result<String, FitFailure>) {
        let mut inner = self.lock();
        inner.threads -= 1;
        if let Some(entry) = inner.entries.get_mut(&id) {
            if entry.info.status == CalibrationStatus::Running {
                entry.info.finished_at = Some(OffsetDateTime::now_utc());
                match outcome {
                    Ok(result) => {
                        entry.info.status = CalibrationStatus::Succeeded;
                        entry.result = Some(FitResult(result.into()));
                        tracing::info!(%id, "calibration succeeded");
                    }
                    Err(error) => {
                        tracing::warn!(%id, %error, "calibration failed");
                        entry.info.status = CalibrationStatus::Failed;
                        entry.info.error = Some(error.to_string());
                    }
                }
            } else {
                tracing::info!(%id, "cancelled calibration stopped");
            }
        }
        let forgotten = forget_oldest(&mut inner.entries, self.limits.kept_bytes);
        let ended = inner.entries.get(&id).map(|entry| CalibrationRecord {
            info: entry.info.clone(),
            result: entry.result.clone(),
        });
        // Written under the lock, so that a DELETE that follows the status a client sees
        // finds the file to remove.
        self.keep(ended);
        self.unstore(&forgotten);
    }

    /// DELETE: cancels a running fit (its thread stops within a cycle of its run under way
    /// and frees its place then), forgets an ended one; `None` for an unknown id.
    pub fn delete(&self, id: Uuid) -> Option<CalibrationDeletion> {
        let mut inner = self.lock();
        let entry = inner.entries.get_mut(&id)?;
        if entry.info.status == CalibrationStatus::Running {
            entry.cancel.store(true, Ordering::Relaxed);
            entry.info.status = CalibrationStatus::Cancelled;
            entry.info.finished_at = Some(OffsetDateTime::now_utc());
            tracing::info!(%id, "running calibration asked to stop");
            return Some(CalibrationDeletion::Cancelled(entry.info.clone()));
        }
        inner.entries.remove(&id);
        self.unstore(&[id]);
        tracing::info!(%id, "ended calibration removed");
        Some(CalibrationDeletion::Removed)
    }
}

/// The fit's JSON text as the API has always answered it: through a JSON value, whose
/// objects list their keys in order, so a client sees the same text as before the result
/// was kept as text. The value lives only while the text is written.
fn result_text(fit: &crate::calibration::Fit) -> serde_json::Result<String> {
    serde_json::to_string(&serde_json::to_value(fit)?)
}

/// Forgets the oldest ended fits beyond [`MAX_KEPT`] of them or `kept_bytes` of results;
/// their ids.
fn forget_oldest(entries: &mut HashMap<Uuid, Entry>, kept_bytes: usize) -> Vec<Uuid> {
    let mut ended: Vec<(OffsetDateTime, Uuid, usize)> = entries
        .values()
        .filter(|e| e.info.status != CalibrationStatus::Running)
        .map(|e| (e.info.created_at, e.info.id, e.bytes()))
        .collect();
    ended.sort();
    let mut bytes: usize = ended.iter().map(|(_, _, b)| b).sum();
    let mut count = ended.len();
    let mut forgotten = Vec::new();
    for (_, id, size) in ended {
        if count <= MAX_KEPT && bytes <= kept_bytes {
            break;
        }
        entries.remove(&id);
        forgotten.push(id);
        count -= 1;
        bytes -= size;
    }
    forgotten
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(at: i64, status: CalibrationStatus, bytes: usize) -> Entry {
        Entry {
            info: CalibrationInfo {
                id: Uuid::new_v4(),
                kind: FitKind::Hardness,
                status,
                created_at: OffsetDateTime::from_unix_timestamp(at)
                    .unwrap_or(OffsetDateTime::UNIX_EPOCH),
                finished_at: None,
                error: None,
            },
            result: Some(FitResult("0".repeat(bytes).into())),
            cancel: Arc::default(),
        }
    }

    #[test]
    fn the_oldest_ended_fits_go_first_beyond_the_bytes_kept() {
        let mut entries = HashMap::new();
        let mut ids = Vec::new();
        for at in 0..5 {
            let e = entry(at, CalibrationStatus::Succeeded, 100);
            ids.push(e.info.id);
            entries.insert(e.info.id, e);
        }
        let running = entry(-1, CalibrationStatus::Running, 1000);
        let running_id = running.info.id;
        entries.insert(running_id, running);
        let forgotten = forget_oldest(&mut entries, 250);
        assert_eq!(forgotten, ids[..3].to_vec());
        let mut kept: Vec<Uuid> = entries.keys().copied().collect();
        kept.sort();
        let mut want = vec![ids[3], ids[4], running_id];
        want.sort();
        assert_eq!(kept, want);
    }

    #[test]
    fn a_result_is_served_as_the_json_it_was() {
        let record = CalibrationRecord {
            info: entry(0, CalibrationStatus::Succeeded, 0).info,
            result: Some(FitResult(r#"{"a": [1, 2.5e-7]}"#.into())),
        };
        let json = serde_json::to_value(&record).unwrap_or_default();
        assert_eq!(json["result"], serde_json::json!({"a": [1, 2.5e-7]}));
        assert_eq!(json["status"], "succeeded");
    }
}
