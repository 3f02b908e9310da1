//! Height maps uploaded to the service, referred to by id from a scene's `disc.surface`.
//! Each lives in `<data-dir>/surfaces/<uuid>/`:
//!
//! - `heights.f64`: the heights in m, little-endian f64 row by row (x fastest), so the map
//!   read back is the one parsed, bit for bit;
//! - `surface.json`: the record a client sees (name, format, size, statistics), the pixel
//!   sizes in m, and the length and CRC-32 of `heights.f64`.
//!
//! A surface directory is built under `<uuid>.new` and renamed into place, so it exists
//! completely or not at all; it is removed by renaming it to `<uuid>.deleted` first. Both
//! leftovers are swept at startup. Every surface is checked against its digest at startup
//! and whenever a run reads it: a damaged one is moved to `<data-dir>/quarantine/` and
//! logged, never served and never deleted.

use std::collections::BTreeMap;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use serde::{Deserialize, Serialize};
use time::OffsetDateTime;
use tokio::sync::Semaphore;
use uuid::Uuid;

use crate::service::files::{Damage, Digest, quarantine, sync_dir, to_json, write_atomic};
use crate::surface::{Format, HeightMap, Statistics};

const RECORD: &str = "surface.json";
const HEIGHTS: &str = "heights.f64";
const NEW_SUFFIX: &str = ".new";
const DELETED_SUFFIX: &str = ".deleted";

/// A stored surface as `GET /api/v1/surfaces/{id}` answers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceRecord {
    /// The surface's id, for `disc.surface.id`.
    pub id: Uuid,
    /// The name given at upload (or empty).
    pub name: String,
    /// The format the file was read as.
    pub format: Format,
    /// Pixels along x.
    pub nx: usize,
    /// Pixels along y.
    pub ny: usize,
    /// Pixel size along x, um.
    pub pixel_x_um: f64,
    /// Pixel size along y, um.
    pub pixel_y_um: f64,
    /// The map's statistics as read (before any tilt removal a scene asks for).
    pub statistics: Statistics,
    /// What to check before trusting the map ([`Statistics::caveats`]); none in records
    /// stored before they were given.
    #[serde(default)]
    pub warnings: Vec<String>,
    /// When it was uploaded.
    #[serde(with = "time::serde::rfc3339")]
    pub created_at: OffsetDateTime,
}

/// What `surface.json` holds: the record, the exact pixel sizes and the heights' digest.
#[derive(Debug, Serialize, Deserialize)]
struct Stored {
    record: SurfaceRecord,
    dx_m: f64,
    dy_m: f64,
    heights: Digest,
}

/// Why a stored surface could not be used.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceLoadError {
    /// No surface has this id.
    #[error("no surface {0}")]
    Unknown(String),
    /// Its files are damaged; it has been quarantined.
    #[error("surface {id} is damaged ({damage}) and was moved to the quarantine")]
    Damaged {
        /// The surface.
        id: Uuid,
        /// How.
        damage: Damage,
    },
}

/// What an upload may cost (`--max-surface-pixels`, `--surface-parses`).
#[derive(Debug, Clone, Copy)]
pub struct UploadLimits {
    /// The most pixels a map may declare.
    pub max_pixels: u64,
    /// Uploads read at once.
    pub parses: usize,
}

/// Why a surface was not stored.
#[derive(Debug, thiserror::Error)]
pub enum CreateError {
    /// Its record would not parse at the next start.
    #[error("the map's record would not read back after a restart: {0}")]
    Unreadable(serde_json::Error),
    /// Its record would parse at the next start as another record.
    #[error("the map's record would not read back after a restart: it reads back different")]
    ReadsBackDifferent,
    /// Its files could not be written.
    #[error("the map's files could not be written: {0}")]
    Storage(io::Error),
}

/// Why a surface was not removed.
#[derive(Debug)]
pub enum DeleteError {
    /// No surface has this id.
    Unknown(Uuid),
    /// Queued or running jobs name it.
    InUse {
        /// The surface.
        id: Uuid,
        /// The jobs.
        users: Vec<Uuid>,
    },
    /// Its directory could not be renamed aside.
    Storage(io::Error),
}

/// Who may still need a stored surface: the jobs that name it and have not finished. A
/// finished job keeps its result, which carries the surface's statistics, so it does not
/// hold the map.
pub trait SurfaceUsers: Send + Sync {
    /// The queued and running jobs whose scene names surface `id`, in order.
    fn using_surface(&self, id: Uuid) -> Vec<Uuid>;
}

/// Every stored surface.
pub struct Surfaces {
    dir: PathBuf,
    quarantine_dir: PathBuf,
    /// What an upload may cost.
    pub(super) limits: UploadLimits,
    /// One permit per upload being read (`UploadLimits::parses`).
    pub(super) parses: Arc<Semaphore>,
    records: Mutex<BTreeMap<Uuid, SurfaceRecord>>,
    /// Held by whoever checks that a surface exists and acts on it (a job's submission, a
    /// surface's deletion), so a job is never accepted for a surface being deleted.
    referrals: Mutex<()>,
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Surfaces {
    /// Opens (creating if needed) `<data_dir>/surfaces`, sweeps interrupted uploads and
    /// deletions, and loads every surface whose files match their digest; the others are
    /// quarantined. Blocking.
    pub fn open(data_dir: &Path, quarantine_dir: &Path, limits: UploadLimits) -> io::Result<Self> {
        let dir = data_dir.join("surfaces");
        fs::create_dir_all(&dir)?;
        let surfaces = Self {
            dir,
            quarantine_dir: quarantine_dir.to_owned(),
            parses: Arc::new(Semaphore::new(limits.parses)),
            limits,
            records: Mutex::default(),
            referrals: Mutex::default(),
        };
        for entry in fs::read_dir(&surfaces.dir)? {
            let Ok(entry) = entry else { continue };
            surfaces.restore(&entry.path());
        }
        Ok(surfaces)
    }

    fn restore(&self, path: &Path) {
        let name = path
            .file_name()
            .map(|name| name.to_string_lossy().into_owned())
            .unwrap_or_default();
        if name.ends_with(NEW_SUFFIX) || name.ends_with(DELETED_SUFFIX) {
            tracing::info!(path = %path.display(), "removing an incomplete surface directory");
            if let Err(e) = fs::remove_dir_all(path) {
                tracing::error!(path = %path.display(), "cannot remove: {e}");
                quarantine(&self.quarantine_dir, path);
            }
            return;
        }
        let Ok(id) = Uuid::parse_str(&name) else {
            tracing::warn!(path = %path.display(), "not a surface; left alone");
            return;
        };
        match read_stored(path).and_then(|stored| {
            read_heights(path, &stored)?;
            Ok(stored)
        }) {
            Ok(stored) if stored.record.id == id => {
                lock(&self.records).insert(id, stored.record);
            }
            Ok(stored) => {
                tracing::error!(%id, "surface.json names surface {}", stored.record.id);
                quarantine(&self.quarantine_dir, path);
            }
            Err(damage) if damage.is_read_failure() => {
                tracing::error!(%id, "cannot read the surface: {damage}; left in place");
            }
            Err(damage) => {
                tracing::error!(%id, "surface damaged: {damage}");
                quarantine(&self.quarantine_dir, path);
            }
        }
    }

    /// Held while a submission checks the surfaces its scenes name and queues them.
    pub fn hold(&self) -> MutexGuard<'_, ()> {
        lock(&self.referrals)
    }

    /// Every surface, oldest first.
    pub fn list(&self) -> Vec<SurfaceRecord> {
        let mut records: Vec<SurfaceRecord> = lock(&self.records).values().cloned().collect();
        records.sort_by_key(|record| (record.created_at, record.id));
        records
    }

    /// The surface with this id.
    pub fn get(&self, id: Uuid) -> Option<SurfaceRecord> {
        lock(&self.records).get(&id).cloned()
    }

    /// Stores a parsed map. When this returns the surface survives a crash; when it fails,
    /// nothing of it is left. Blocking.
    pub fn create(
        &self,
        name: String,
        format: Format,
        map: &HeightMap,
        statistics: Statistics,
    ) -> Result<SurfaceRecord, CreateError> {
        let id = Uuid::new_v4();
        let heights: Vec<u8> = map.heights_m.iter().flat_map(|h| h.to_le_bytes()).collect();
        let record = SurfaceRecord {
            id,
            name,
            format,
            nx: map.nx,
            ny: map.ny,
            pixel_x_um: map.dx_m * 1e6,
            pixel_y_um: map.dy_m * 1e6,
            warnings: statistics.caveats(),
            statistics,
            created_at: OffsetDateTime::now_utc(),
        };
        let stored = Stored {
            record: record.clone(),
            dx_m: map.dx_m,
            dy_m: map.dy_m,
            heights: Digest::of(&heights),
        };
        let json = to_json(&stored).map_err(CreateError::Storage)?;
        // Read back as the next start will read it: a record that would not load (a number
        // JSON cannot hold) would be accepted now and quarantined then.
        match serde_json::from_slice::<Stored>(&json) {
            Ok(again) if again.record == record => {}
            Ok(_) => return Err(CreateError::ReadsBackDifferent),
            Err(e) => return Err(CreateError::Unreadable(e)),
        }
        let staging = self.dir.join(format!("{id}{NEW_SUFFIX}"));
        let created = fs::create_dir(&staging)
            .and_then(|()| write_atomic(&staging, HEIGHTS, &heights))
            .and_then(|()| write_atomic(&staging, RECORD, &json))
            .and_then(|()| fs::rename(&staging, self.dir.join(id.to_string())))
            .and_then(|()| sync_dir(&self.dir));
        if let Err(e) = created {
            if let Err(e) = fs::remove_dir_all(&staging) {
                if e.kind() != io::ErrorKind::NotFound {
                    tracing::error!(path = %staging.display(), "cannot clean up: {e}");
                }
            }
            return Err(CreateError::Storage(e));
        }
        lock(&self.records).insert(id, record.clone());
        tracing::info!(%id, nx = map.nx, ny = map.ny, "surface stored");
        Ok(record)
    }

    /// The map of surface `id` (as `disc.surface.id` spells it), checked against its digest;
    /// a damaged surface is quarantined and forgotten. Blocking.
    pub fn load(&self, id: &str) -> Result<HeightMap, SurfaceLoadError> {
        let unknown = || SurfaceLoadError::Unknown(id.to_owned());
        let uuid = Uuid::try_parse(id).map_err(|_| unknown())?;
        if self.get(uuid).is_none() {
            return Err(unknown());
        }
        let path = self.dir.join(uuid.to_string());
        let loaded = read_stored(&path).and_then(|stored| {
            let heights = read_heights(&path, &stored)?;
            let record = &stored.record;
            HeightMap::new(record.nx, record.ny, stored.dx_m, stored.dy_m, heights).map_err(|e| {
                Damage::Invalid {
                    file: RECORD,
                    message: e.to_string(),
                }
            })
        });
        loaded.map_err(|damage| {
            if !damage.is_read_failure() {
                tracing::error!(id = %uuid, "surface damaged: {damage}");
                lock(&self.records).remove(&uuid);
                quarantine(&self.quarantine_dir, &path);
            }
            SurfaceLoadError::Damaged { id: uuid, damage }
        })
    }

    /// Removes surface `id` unless `users` has jobs that still need it. Blocking.
    pub fn delete(&self, id: Uuid, users: &dyn SurfaceUsers) -> Result<(), DeleteError> {
        let _hold = self.hold();
        if self.get(id).is_none() {
            return Err(DeleteError::Unknown(id));
        }
        let users = users.using_surface(id);
        if !users.is_empty() {
            return Err(DeleteError::InUse { id, users });
        }
        let doomed = self.dir.join(format!("{id}{DELETED_SUFFIX}"));
        fs::rename(self.dir.join(id.to_string()), &doomed)
            .and_then(|()| sync_dir(&self.dir))
            .map_err(DeleteError::Storage)?;
        lock(&self.records).remove(&id);
        if let Err(e) = fs::remove_dir_all(&doomed) {
            tracing::error!(path = %doomed.display(), "cannot remove: {e}; swept at the next start");
        }
        Ok(())
    }
}

fn read_stored(dir: &Path) -> Result<Stored, Damage> {
    let bytes = fs::read(dir.join(RECORD)).map_err(|e| Damage::reading(RECORD, e))?;
    serde_json::from_slice(&bytes).map_err(|e| Damage::Invalid {
        file: RECORD,
        message: e.to_string(),
    })
}

fn read_heights(dir: &Path, stored: &Stored) -> Result<Vec<f64>, Damage> {
    let bytes = fs::read(dir.join(HEIGHTS)).map_err(|e| Damage::reading(HEIGHTS, e))?;
    stored.heights.check(HEIGHTS, &bytes)?;
    let expected = stored.record.nx * stored.record.ny * 8;
    if bytes.len() != expected {
        return Err(Damage::Length {
            file: HEIGHTS,
            found: bytes.len() as u64,
            expected: expected as u64,
        });
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        .collect())
}
