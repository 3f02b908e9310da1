//! Studies on disk: `<data-dir>/studies/<uuid>.json` holds everything of a study that does
//! not change (its name, axes, and members with their jobs), written atomically. A file that
//! cannot be read or parsed, or that names another study, is moved to the quarantine and
//! logged; it never stops the others from loading.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use time::OffsetDateTime;
use uuid::Uuid;

use crate::service::files::{quarantine, sweep_temporaries, sync_dir, to_json, write_atomic};

/// Where study files live, under the data directory.
const STUDIES_DIR: &str = "studies";

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
            tracing::warn!(path = %path.display(), "not a study; left alone");
            return None;
        };
        let stored = fs::read(path)
            .map_err(|e| e.to_string())
            .and_then(|bytes| {
                serde_json::from_slice::<StoredStudy>(&bytes).map_err(|e| e.to_string())
            })
            .and_then(|stored| {
                if stored.id == id {
                    Ok(stored)
                } else {
                    Err(format!("it names study {}", stored.id))
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

    /// Writes a new study's file. Blocking.
    pub(super) fn write(&self, study: &StoredStudy) -> io::Result<()> {
        write_atomic(&self.dir, &format!("{}.json", study.id), &to_json(study)?)
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
