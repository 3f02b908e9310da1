//! Studies on disk: `<data-dir>/studies/<uuid>.json` holds everything of a study that does
//! not change (its name, axes, and members with their jobs), written atomically. A file that
//! cannot be read or parsed, or that names another study, is moved to the quarantine and
//! logged; it never stops the others from loading.
//!
//! A study and its member jobs are one step on disk: `<uuid>.pending`, naming the member
//! jobs, is written before the first of them, and removed once `<uuid>.json` is. At startup,
//! before the jobs load, a `.pending` without its `.json` is a study that was never
//! accepted: the member jobs it names are removed with it, so a crash leaves the whole study
//! or nothing.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use time::OffsetDateTime;
use uuid::Uuid;

use crate::service::files::{quarantine, sweep_temporaries, sync_dir, to_json, write_atomic};
use crate::service::jobs::Store;

/// Where study files live, under the data directory.
const STUDIES_DIR: &str = "studies";

/// The suffix of a study being accepted.
const PENDING_SUFFIX: &str = ".pending";

/// Why a study's file does not load: logged, and the file quarantined.
#[derive(Debug, thiserror::Error)]
enum StudyFileDamage {
    /// The file cannot be read.
    #[error(transparent)]
    Unreadable(#[from] io::Error),
    /// It does not parse as what it should hold.
    #[error(transparent)]
    Invalid(#[from] serde_json::Error),
    /// It parses, but names another study than its file name.
    #[error("it names study {0}")]
    OtherStudy(Uuid),
}

/// The file at `path`, parsed.
fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T, StudyFileDamage> {
    Ok(serde_json::from_slice(&fs::read(path)?)?)
}

/// What `<uuid>.pending` holds: the member jobs of a study being accepted.
#[derive(Debug, Serialize, Deserialize)]
struct Pending {
    job_ids: Vec<Uuid>,
}

/// An axis as the study file stores it and the study record shows it: the path and every
/// value, in order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisRecord {
    /// The dotted scene path.
    pub path: String,
    /// Its values.
    pub values: Vec<Value>,
}

/// A member as the study file stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct StoredMember {
    pub(super) index: usize,
    pub(super) job_id: Uuid,
    pub(super) values: Map<String, Value>,
}

/// What `<uuid>.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct StoredStudy {
    pub(super) id: Uuid,
    pub(super) name: String,
    #[serde(with = "time::serde::rfc3339")]
    pub(super) created_at: OffsetDateTime,
    pub(super) axes: Vec<AxisRecord>,
    pub(super) members: Vec<StoredMember>,
}

/// The study files under one data directory.
pub(super) struct StudyFiles {
    dir: PathBuf,
    quarantine_dir: PathBuf,
}

impl StudyFiles {
    /// Opens (creating if needed) `<data_dir>/studies` and sweeps the temporary files of
    /// interrupted writes. Blocking.
    pub(super) fn open(data_dir: &Path, quarantine_dir: &Path) -> io::Result<Self> {
        let dir = data_dir.join(STUDIES_DIR);
        fs::create_dir_all(&dir)?;
        sync_dir(data_dir)?;
        if let Err(e) = sweep_temporaries(&dir) {
            // Leftover temporary files are harmless: they are not named as studies.
            tracing::warn!(dir = %dir.display(), "cannot sweep temporary files: {e}");
        }
        Ok(Self {
            dir,
            quarantine_dir: quarantine_dir.to_owned(),
        })
    }

    /// Removes the studies whose acceptance a crash interrupted, with their member jobs
    /// (see the module's notes); a marker that cannot be read is quarantined, and its jobs,
    /// unknown, are left. Run before the jobs load. Blocking.
    pub(super) fn sweep_pending(&self, jobs: &Store) -> io::Result<()> {
        for entry in fs::read_dir(&self.dir)? {
            let Ok(entry) = entry else { continue };
            let path = entry.path();
            let Some(id) = path
                .file_name()
                .and_then(|name| name.to_str())
                .and_then(|name| name.strip_suffix(PENDING_SUFFIX))
                .and_then(|stem| Uuid::parse_str(stem).ok())
            else {
                continue;
            };
            if !self.dir.join(format!("{id}.json")).exists() {
                let pending = read_json::<Pending>(&path);
                let Ok(pending) = pending.inspect_err(|damage| {
                    tracing::error!(%id, "pending study damaged: {damage}");
                }) else {
                    quarantine(&self.quarantine_dir, &path);
                    continue;
                };
                tracing::warn!(%id, jobs = pending.job_ids.len(), "study interrupted as it was accepted: its member jobs are removed");
                for job in pending.job_ids {
                    match jobs.remove(job) {
                        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
                        _ => {}
                    }
                }
            }
            fs::remove_file(&path)?;
        }
        sync_dir(&self.dir)
    }

    /// Every study that reads back; damaged files are quarantined. Blocking.
    pub(super) fn load(&self) -> io::Result<Vec<StoredStudy>> {
        let mut studies = Vec::new();
        for entry in fs::read_dir(&self.dir)? {
            let Ok(entry) = entry else { continue };
            studies.extend(self.load_one(&entry.path()));
        }
        Ok(studies)
    }

    fn load_one(&self, path: &Path) -> Option<StoredStudy> {
        let id = path
            .file_name()
            .and_then(|name| name.to_str())
            .and_then(|name| name.strip_suffix(".json"))
            .and_then(|stem| Uuid::parse_str(stem).ok());
        let Some(id) = id else {
            if !path.to_string_lossy().ends_with(PENDING_SUFFIX) {
                tracing::warn!(path = %path.display(), "not a study; left alone");
            }
            return None;
        };
        let stored = read_json::<StoredStudy>(path).and_then(|stored| {
            if stored.id == id {
                Ok(stored)
            } else {
                Err(StudyFileDamage::OtherStudy(stored.id))
            }
        });
        match stored {
            Ok(stored) => Some(stored),
            Err(damage) => {
                tracing::error!(%id, "study file damaged: {damage}");
                quarantine(&self.quarantine_dir, path);
                None
            }
        }
    }

    /// Marks study `id` as being accepted with these member jobs, before any of them is
    /// written. Blocking.
    pub(super) fn begin(&self, id: Uuid, job_ids: Vec<Uuid>) -> io::Result<()> {
        let pending = Pending { job_ids };
        write_atomic(
            &self.dir,
            &format!("{id}{PENDING_SUFFIX}"),
            &to_json(&pending)?,
        )
    }

    /// Writes a new study's file, which accepts it, then drops its mark. Blocking.
    pub(super) fn commit(&self, study: &StoredStudy) -> io::Result<()> {
        write_atomic(&self.dir, &format!("{}.json", study.id), &to_json(study)?)?;
        let id = study.id;
        if let Err(e) = fs::remove_file(self.dir.join(format!("{id}{PENDING_SUFFIX}"))) {
            // Harmless: the study's file stands, so the next start only drops the mark.
            tracing::warn!(%id, "cannot remove the pending mark: {e}");
        }
        Ok(())
    }

    /// Drops what study `id` wrote, whose acceptance failed after its member jobs were
    /// removed: its mark, and its file if the write that failed got as far as the rename,
    /// so a refused study leaves nothing behind. A mark that cannot be removed (the store
    /// has just refused a write) is swept at the next start, which removes the jobs it
    /// names, none by then. Blocking.
    pub(super) fn abandon(&self, id: Uuid) {
        for suffix in [".json", PENDING_SUFFIX] {
            let path = self.dir.join(format!("{id}{suffix}"));
            match fs::remove_file(&path) {
                Err(e) if e.kind() != io::ErrorKind::NotFound => {
                    tracing::warn!(%id, "cannot remove {suffix} of a refused study: {e}");
                }
                _ => {}
            }
        }
        if let Err(e) = sync_dir(&self.dir) {
            tracing::warn!(%id, "cannot sync the studies folder after a refused study: {e}");
        }
    }

    /// Removes a study's file; one already gone is not an error. Blocking.
    pub(super) fn remove(&self, id: Uuid) -> io::Result<()> {
        let removed =
            fs::remove_file(self.dir.join(format!("{id}.json"))).and_then(|()| sync_dir(&self.dir));
        match removed {
            Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
            _ => Ok(()),
        }
    }
}
