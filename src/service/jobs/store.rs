//! Durable job storage: one directory per job, `<data-dir>/jobs/<uuid>/`, holding
//!
//! - `scene.json`: the scene as parsed (every default filled in), written once;
//! - `status.json`: the job record, rewritten at every transition;
//! - `cycles.jsonl`: one cycle record per line, appended while the job runs;
//! - `result.json`: the simulation result, written once when the job succeeds;
//! - `manifest.json`: the length and CRC-32 of `result.json` and `cycles.jsonl`, written
//!   after them and before the final status. A succeeded job's files are checked against it
//!   at startup and before they are served, so damage done to them on disk is found;
//! - `measured_<kind>.json`: a table of measured points, written by `measurements` (the job's
//!   directory is its home, so the table goes when the job does).
//!
//! Whole-file writes are atomic (`files::write_atomic`), so a crash leaves either the old or
//! the new file, never a torn one. A job directory is built
//! under `<uuid>.new` and renamed into place, so a job exists on disk completely or not at
//! all; it is removed by renaming it to `<uuid>.deleted` first. Leftovers of both are swept at
//! startup; what cannot be swept, and files where a job directory should be, are moved to
//! `<data-dir>/quarantine/` and logged, never deleted.
//!
//! `cycles.jsonl` is appended without an fsync per line: a job that was running when the
//! process died is run again from scratch (truncating the file), so only the lines of finished
//! jobs must be durable, and they are synced before `result.json` and the final status.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use time::OffsetDateTime;
use uuid::Uuid;

use super::job::JobRecord;
use crate::scene::Scene;
use crate::service::files::{
    Damage, Digest, quarantine, read_json, sweep_temporaries, sync_dir, to_json, write_atomic,
};
use crate::text::{Lines, NAME_MAX_CHARS};

const SCENE: &str = "scene.json";
const STATUS: &str = "status.json";
const RESULT: &str = "result.json";
const CYCLES: &str = "cycles.jsonl";
const MANIFEST: &str = "manifest.json";
const NEW_SUFFIX: &str = ".new";
const DELETED_SUFFIX: &str = ".deleted";

/// The job directories under one data directory.
#[derive(Debug)]
pub struct Store {
    jobs_dir: PathBuf,
    quarantine_dir: PathBuf,
}

/// What `manifest.json` holds.
#[derive(Debug, Serialize, Deserialize)]
struct Manifest {
    result_json: Digest,
    cycles_jsonl: Digest,
}

/// A job directory as found on disk at startup.
pub struct StoredJob {
    /// The job's id (its directory's name).
    pub id: Uuid,
    /// Its last persisted record.
    pub record: Result<JobRecord, Damage>,
    /// Its scene.
    pub scene: Result<Scene, Damage>,
    /// When its directory last changed, for a record rebuilt from the scene.
    pub modified: Option<OffsetDateTime>,
}

impl Store {
    /// Opens (creating if needed) the store under `data_dir` and sweeps half-created and
    /// half-deleted job directories.
    pub fn open(data_dir: &Path) -> io::Result<Self> {
        let jobs_dir = data_dir.join("jobs");
        fs::create_dir_all(&jobs_dir)?;
        sync_dir(data_dir)?;
        let store = Self {
            jobs_dir,
            quarantine_dir: data_dir.join("quarantine"),
        };
        store.sweep()?;
        Ok(store)
    }

    /// Removes the leftovers of interrupted creations and deletions, and moves aside files
    /// that stand where a job directory should be.
    fn sweep(&self) -> io::Result<()> {
        for entry in fs::read_dir(&self.jobs_dir)? {
            let path = match entry {
                Ok(entry) => entry.path(),
                Err(e) => {
                    tracing::error!("cannot list {}: {e}", self.jobs_dir.display());
                    continue;
                }
            };
            let name = path
                .file_name()
                .map(|name| name.to_string_lossy().into_owned())
                .unwrap_or_default();
            if name.ends_with(NEW_SUFFIX) || name.ends_with(DELETED_SUFFIX) {
                tracing::info!(path = %path.display(), "removing an incomplete job directory");
                if let Err(e) = remove_any(&path) {
                    tracing::error!(path = %path.display(), "cannot remove: {e}");
                    self.quarantine(&path);
                }
            } else if Uuid::parse_str(&name).is_ok() && !path.is_dir() {
                tracing::error!(path = %path.display(), "not a job directory");
                self.quarantine(&path);
            } else if Uuid::parse_str(&name).is_err() {
                tracing::warn!(path = %path.display(), "not a job; left alone");
            }
        }
        Ok(())
    }

    /// Moves `path` into the quarantine directory, logging where; logs if it cannot.
    fn quarantine(&self, path: &Path) {
        quarantine(&self.quarantine_dir, path);
    }

    /// Where damaged files are moved (`<data-dir>/quarantine`).
    pub fn quarantine_dir(&self) -> &Path {
        &self.quarantine_dir
    }

    /// The directory of job `id`.
    pub(super) fn dir(&self, id: Uuid) -> PathBuf {
        self.jobs_dir.join(id.to_string())
    }

    /// Persists a new job: its scene and first record. When this returns, the job survives a
    /// crash; when it fails, nothing of the job is left.
    pub fn create(&self, record: &JobRecord, scene: &Scene) -> io::Result<()> {
        let staging = self.jobs_dir.join(format!("{}{NEW_SUFFIX}", record.id));
        let created = fs::create_dir(&staging)
            .and_then(|()| write_atomic(&staging, SCENE, &to_json(scene)?))
            .and_then(|()| write_atomic(&staging, STATUS, &to_json(record)?))
            .and_then(|()| fs::rename(&staging, self.dir(record.id)))
            .and_then(|()| sync_dir(&self.jobs_dir));
        if created.is_err() {
            if let Err(e) = remove_any(&staging) {
                if e.kind() != io::ErrorKind::NotFound {
                    tracing::error!(path = %staging.display(), "cannot clean up: {e}");
                }
            }
        }
        created
    }

    /// Replaces a job's persisted record.
    pub fn write_status(&self, record: &JobRecord) -> io::Result<()> {
        write_atomic(&self.dir(record.id), STATUS, &to_json(record)?)
    }

    /// Persists a job's result with the digests of it and of its durable cycle log.
    pub fn write_result(&self, id: Uuid, result: &[u8], cycles: Digest) -> io::Result<()> {
        let dir = self.dir(id);
        write_atomic(&dir, RESULT, result)?;
        let manifest = Manifest {
            result_json: Digest::of(result),
            cycles_jsonl: cycles,
        };
        write_atomic(&dir, MANIFEST, &to_json(&manifest)?)
    }

    fn manifest(&self, id: Uuid) -> Result<Manifest, Damage> {
        let bytes =
            fs::read(self.dir(id).join(MANIFEST)).map_err(|e| Damage::reading(MANIFEST, e))?;
        serde_json::from_slice(&bytes).map_err(|e| Damage::Invalid {
            file: MANIFEST,
            message: e.to_string(),
        })
    }

    fn read_checked(
        &self,
        id: Uuid,
        file: &'static str,
        digest: Digest,
    ) -> Result<Vec<u8>, Damage> {
        let bytes = fs::read(self.dir(id).join(file)).map_err(|e| Damage::reading(file, e))?;
        digest.check(file, &bytes)?;
        Ok(bytes)
    }

    /// A succeeded job's `result.json`, checked against its manifest. Blocking.
    pub fn read_result(&self, id: Uuid) -> Result<Vec<u8>, Damage> {
        let manifest = self.manifest(id)?;
        self.read_checked(id, RESULT, manifest.result_json)
    }

    /// A succeeded job's `cycles.jsonl`, checked against its manifest. Blocking.
    pub fn read_cycles(&self, id: Uuid) -> Result<Vec<u8>, Damage> {
        let manifest = self.manifest(id)?;
        self.read_checked(id, CYCLES, manifest.cycles_jsonl)
    }

    /// Checks both files of a succeeded job against its manifest. Blocking.
    pub fn check_result(&self, id: Uuid) -> Result<(), Damage> {
        let manifest = self.manifest(id)?;
        self.read_checked(id, RESULT, manifest.result_json)?;
        self.read_checked(id, CYCLES, manifest.cycles_jsonl)?;
        Ok(())
    }

    /// The cycle log of a job that did not succeed, as far as it was written (nothing is
    /// promised of it: the run stopped). Blocking.
    pub fn read_partial_cycles(&self, id: Uuid) -> io::Result<Vec<u8>> {
        fs::read(self.dir(id).join(CYCLES))
    }

    /// A job's scene, read back. Blocking.
    pub fn read_scene(&self, id: Uuid) -> Result<Scene, Damage> {
        read_scene(&self.dir(id))
    }

    /// Starts a job's cycle log afresh (a re-run replaces what an interrupted run wrote).
    pub fn cycles_writer(&self, id: Uuid) -> io::Result<CyclesWriter> {
        let file = OpenOptions::new()
            .create(true)
            .write(true)
            .truncate(true)
            .open(self.dir(id).join(CYCLES))?;
        Ok(CyclesWriter {
            file: BufWriter::new(file),
            hasher: crc32fast::Hasher::new(),
            bytes: 0,
        })
    }

    /// Deletes a job's directory: renamed aside first, so a crash midway leaves no
    /// half-deleted job behind. Once renamed the job is gone; a directory that then cannot be
    /// removed is logged and swept at the next start.
    pub fn remove(&self, id: Uuid) -> io::Result<()> {
        let doomed = self.jobs_dir.join(format!("{id}{DELETED_SUFFIX}"));
        fs::rename(self.dir(id), &doomed)?;
        sync_dir(&self.jobs_dir)?;
        if let Err(e) = fs::remove_dir_all(&doomed) {
            tracing::error!(path = %doomed.display(), "cannot remove: {e}; swept at the next start");
        }
        Ok(())
    }

    /// Every job directory on disk, with interrupted writes' temporary files swept. Entries
    /// not named by a UUID are not jobs and are skipped. Nothing here fails the whole load:
    /// what cannot be read is reported in the job's `record` or `scene`.
    pub fn load(&self) -> io::Result<Vec<StoredJob>> {
        let mut jobs = Vec::new();
        for entry in fs::read_dir(&self.jobs_dir)? {
            let Ok(entry) = entry else { continue };
            let path = entry.path();
            let Some(id) = path
                .file_name()
                .and_then(|name| name.to_str())
                .and_then(|name| Uuid::parse_str(name).ok())
            else {
                continue;
            };
            if !path.is_dir() {
                continue;
            }
            if let Err(e) = sweep_temporaries(&path) {
                tracing::warn!(%id, "cannot sweep temporary files: {e}");
            }
            let modified = fs::metadata(&path)
                .and_then(|metadata| metadata.modified())
                .ok()
                .map(OffsetDateTime::from);
            let record = read_json::<JobRecord>(&path, STATUS).and_then(|record| {
                if record.id == id {
                    Ok(record)
                } else {
                    Err(Damage::Invalid {
                        file: STATUS,
                        message: format!("it names job {}", record.id),
                    })
                }
            });
            jobs.push(StoredJob {
                id,
                record,
                scene: read_scene(&path),
                modified,
            });
        }
        Ok(jobs)
    }
}

/// The scene stored in a job's directory `dir`. A name stored before names were bounded
/// (200 characters, no hidden characters) is tidied to pass the bound, so the job runs
/// (each run checks its scene again) instead of failing on a name that was accepted.
fn read_scene(dir: &Path) -> Result<Scene, Damage> {
    let mut scene: Scene = read_json(dir, SCENE)?;
    if crate::text::check(&scene.name, NAME_MAX_CHARS, Lines::One).is_err() {
        scene.name = crate::text::tidy(&scene.name, NAME_MAX_CHARS);
    }
    Ok(scene)
}

/// Removes a file or a directory tree.
fn remove_any(path: &Path) -> io::Result<()> {
    if fs::symlink_metadata(path)?.is_dir() {
        fs::remove_dir_all(path)
    } else {
        fs::remove_file(path)
    }
}

/// Appends cycle records to a job's `cycles.jsonl`, keeping the digest of what it wrote.
pub struct CyclesWriter {
    file: BufWriter<File>,
    hasher: crc32fast::Hasher,
    bytes: u64,
}

impl CyclesWriter {
    /// Appends one line. Flushed to the OS at once so a client replaying the file from disk
    /// sees every record the job has announced.
    pub fn append(&mut self, line: &str) -> io::Result<()> {
        self.file.write_all(line.as_bytes())?;
        self.file.write_all(b"\n")?;
        self.file.flush()?;
        self.hasher.update(line.as_bytes());
        self.hasher.update(b"\n");
        self.bytes += line.len() as u64 + 1;
        Ok(())
    }

    /// Makes every line durable; the digest of the whole log.
    pub fn finish(self) -> io::Result<Digest> {
        let file = self
            .file
            .into_inner()
            .map_err(io::IntoInnerError::into_error)?;
        file.sync_all()?;
        Ok(Digest::from_parts(self.bytes, self.hasher.finalize()))
    }
}
