//! Ended fits on disk, one JSON file each in `<data-dir>/calibrations/`, so that a restart
//! keeps them: a lab's Tafel or Archard fit, cited in a report, must still be there the next
//! morning. The file is the record `GET /api/v1/calibrations/{id}` answers, written
//! atomically and durably when the fit ends; DELETE and the registry's limits remove it. A
//! fit still running when the server stops never ended, so nothing of it is kept. A file
//! that does not read as a record is moved to `<data-dir>/quarantine/`, never deleted.

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use uuid::Uuid;

use super::registry::{CalibrationInfo, FitResult};
use crate::service::files::{quarantine, sweep_temporaries, sync_dir, to_json, write_atomic};

/// Where ended fits are kept.
#[derive(Debug)]
pub struct CalibrationStore {
    dir: PathBuf,
    quarantine_dir: PathBuf,
}

/// A stored fit: the record, its result as the JSON it was.
#[derive(Serialize, Deserialize)]
struct Stored<'a> {
    #[serde(flatten)]
    info: CalibrationInfo,
    #[serde(borrow)]
    result: Option<&'a RawValue>,
}

impl CalibrationStore {
    /// The store under `data_dir`, created if absent, cleared of interrupted writes.
    pub fn open(data_dir: &Path) -> io::Result<Self> {
        let dir = data_dir.join("calibrations");
        fs::create_dir_all(&dir)?;
        sweep_temporaries(&dir)?;
        Ok(Self {
            dir,
            quarantine_dir: data_dir.join("quarantine"),
        })
    }

    fn file(id: Uuid) -> String {
        format!("{id}.json")
    }

    /// Keeps the ended fit `info` with its `result`.
    pub fn save(&self, info: &CalibrationInfo, result: Option<&FitResult>) -> io::Result<()> {
        let raw = result
            .map(|r| RawValue::from_string(r.text().to_owned()))
            .transpose()
            .map_err(io::Error::other)?;
        let stored = Stored {
            info: info.clone(),
            result: raw.as_deref(),
        };
        write_atomic(&self.dir, &Self::file(info.id), &to_json(&stored)?)
    }

    /// Forgets the fit `id`; a fit never stored is no error.
    pub fn remove(&self, id: Uuid) -> io::Result<()> {
        match fs::remove_file(self.dir.join(Self::file(id))) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
            other => other.and_then(|()| sync_dir(&self.dir)),
        }
    }

    /// Every stored fit; files that do not read as one are quarantined.
    pub fn load(&self) -> io::Result<Vec<(CalibrationInfo, Option<FitResult>)>> {
        let mut fits = Vec::new();
        for entry in fs::read_dir(&self.dir)? {
            let path = entry?.path();
            if path.extension().is_none_or(|e| e != "json") {
                continue;
            }
            let bytes = fs::read(&path)?;
            match serde_json::from_slice::<Stored>(&bytes) {
                Ok(stored) => fits.push((
                    stored.info,
                    stored.result.map(|raw| FitResult::from_text(raw.get())),
                )),
                Err(e) => {
                    tracing::warn!(path = %path.display(), "not a calibration record: {e}");
                    quarantine(&self.quarantine_dir, &path);
                }
            }
        }
        Ok(fits)
    }
}
