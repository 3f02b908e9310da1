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

#[cfg(test)]
mod tests {
    use time::OffsetDateTime;

    use super::*;
    use crate::calibration::FitKind;
    use crate::service::calibrations::registry::CalibrationStatus;

    #[test]
    fn a_kept_fit_reads_back_whole_and_a_stray_file_is_quarantined() {
        let data = std::env::temp_dir().join(format!("tribosim-fits-{}", Uuid::new_v4()));
        let store = CalibrationStore::open(&data).expect("a store");
        let info = CalibrationInfo {
            id: Uuid::new_v4(),
            kind: FitKind::Tafel,
            status: CalibrationStatus::Succeeded,
            created_at: OffsetDateTime::UNIX_EPOCH,
            finished_at: Some(OffsetDateTime::UNIX_EPOCH),
            error: None,
        };
        let result = FitResult::from_text(r#"{"b_c": 0.56, "points": [1, 2.5e-7]}"#);
        store.save(&info, Some(&result)).expect("saved");
        std::fs::write(data.join("calibrations/stray.json"), b"{\"not\": 1}").expect("written");
        let loaded = store.load().expect("read");
        assert_eq!(loaded.len(), 1);
        assert_eq!(loaded[0].0, info);
        assert_eq!(
            loaded[0].1.as_ref().map(FitResult::text),
            Some(result.text())
        );
        let quarantined = std::fs::read_dir(data.join("quarantine")).expect("a quarantine");
        assert_eq!(quarantined.count(), 1);
        store.remove(info.id).expect("removed");
        store.remove(info.id).expect("removing twice is no error");
        assert!(store.load().expect("read").is_empty());
        std::fs::remove_dir_all(&data).expect("cleaned up");
    }
}
