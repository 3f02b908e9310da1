//! Durable job storage: one directory per job, `<data-dir>/jobs/<uuid>/`, holding
//!
//! - `scene.json`: the scene as parsed (every default filled in), written once;
//! - `status.json`: the job record, rewritten at every transition;
//! - `cycles.jsonl`: one cycle record per line, appended while the job runs;
//! - `result.json`: the simulation result, written once when the job succeeds.
//!
//! Whole-file writes are atomic: temporary file, fsync, rename, fsync of the directory, so a
//! crash leaves either the old or the new file, never a torn one. A job directory is built
//! under `<uuid>.new` and renamed into place, so a job exists on disk completely or not at
//! all; it is removed by renaming it to `<uuid>.deleted` first. Leftovers of both are swept at
//! startup.
//!
//! `cycles.jsonl` is appended without an fsync per line: a job that was running when the
//! process died is run again from scratch (truncating the file), so only the lines of finished
//! jobs must be durable, and they are synced before `result.json` and the final status.

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use uuid::Uuid;

use super::job::JobRecord;
use crate::scene::Scene;

const SCENE: &str = "scene.json";
const STATUS: &str = "status.json";
const RESULT: &str = "result.json";
const CYCLES: &str = "cycles.jsonl";
const NEW_SUFFIX: &str = ".new";
const DELETED_SUFFIX: &str = ".deleted";

/// The job directories under one data directory.
#[derive(Debug)]
pub struct Store {
    jobs_dir: PathBuf,
}

/// A job as found on disk at startup.
pub struct StoredJob {
    /// Its last persisted record.
    pub record: JobRecord,
    /// Its scene, or why it could not be read back.
    pub scene: Result<Scene, String>,
}

impl Store {
    /// Opens (creating if needed) the store under `data_dir` and sweeps half-created and
    /// half-deleted job directories.
    pub fn open(data_dir: &Path) -> io::Result<Self> {
        let jobs_dir = data_dir.join("jobs");
        fs::create_dir_all(&jobs_dir)?;
        sync_dir(data_dir)?;
        let store = Self { jobs_dir };
        store.sweep()?;
        Ok(store)
    }

    fn sweep(&self) -> io::Result<()> {
        for entry in fs::read_dir(&self.jobs_dir)? {
            let entry = entry?;
            let name = entry.file_name();
            let name = name.to_string_lossy();
            if name.ends_with(NEW_SUFFIX) || name.ends_with(DELETED_SUFFIX) {
                tracing::info!(dir = %entry.path().display(), "removing incomplete job directory");
                fs::remove_dir_all(entry.path())?;
            }
        }
        Ok(())
    }

    fn dir(&self, id: Uuid) -> PathBuf {
        self.jobs_dir.join(id.to_string())
    }

    /// Persists a new job: its scene and first record. When this returns, the job survives a
    /// crash.
    pub fn create(&self, record: &JobRecord, scene: &Scene) -> io::Result<()> {
        let dir = self.dir(record.id);
        let staging = self.jobs_dir.join(format!("{}{NEW_SUFFIX}", record.id));
        fs::create_dir(&staging)?;
        write_atomic(&staging, SCENE, &to_json(scene)?)?;
        write_atomic(&staging, STATUS, &to_json(record)?)?;
        fs::rename(&staging, &dir)?;
        sync_dir(&self.jobs_dir)
    }

    /// Replaces a job's persisted record.
    pub fn write_status(&self, record: &JobRecord) -> io::Result<()> {
        write_atomic(&self.dir(record.id), STATUS, &to_json(record)?)
    }

    /// Persists a job's result.
    pub fn write_result(&self, id: Uuid, result: &[u8]) -> io::Result<()> {
        write_atomic(&self.dir(id), RESULT, result)
    }

    /// Where a job's result is (present once the job succeeded).
    pub fn result_path(&self, id: Uuid) -> PathBuf {
        self.dir(id).join(RESULT)
    }

    /// Where a job's cycle records are.
    pub fn cycles_path(&self, id: Uuid) -> PathBuf {
        self.dir(id).join(CYCLES)
    }

    /// Starts a job's cycle log afresh (a re-run replaces what an interrupted run wrote).
    pub fn cycles_writer(&self, id: Uuid) -> io::Result<CyclesWriter> {
        let file = OpenOptions::new()
            .create(true)
            .write(true)
            .truncate(true)
            .open(self.cycles_path(id))?;
        Ok(CyclesWriter {
            file: BufWriter::new(file),
        })
    }

    /// Deletes a job's directory: renamed aside first, so a crash midway leaves no
    /// half-deleted job behind.
    pub fn remove(&self, id: Uuid) -> io::Result<()> {
        let doomed = self.jobs_dir.join(format!("{id}{DELETED_SUFFIX}"));
        fs::rename(self.dir(id), &doomed)?;
        sync_dir(&self.jobs_dir)?;
        fs::remove_dir_all(doomed)
    }

    /// Every job on disk, with interrupted writes' temporary files swept. Entries that are not
    /// directories named by a UUID are not jobs and are skipped; a job whose record cannot be
    /// read is logged and skipped (the record is written atomically, so this means outside
    /// damage).
    pub fn load(&self) -> io::Result<Vec<StoredJob>> {
        let mut jobs = Vec::new();
        for entry in fs::read_dir(&self.jobs_dir)? {
            let path = entry?.path();
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
            sweep_temporaries(&path)?;
            let record = fs::read(path.join(STATUS)).and_then(|bytes| {
                serde_json::from_slice::<JobRecord>(&bytes).map_err(io::Error::other)
            });
            let record = match record {
                Ok(record) if record.id == id => record,
                Ok(_) => {
                    tracing::error!(%id, "status.json names another job; skipped");
                    continue;
                }
                Err(e) => {
                    tracing::error!(%id, "unreadable status.json: {e}; skipped");
                    continue;
                }
            };
            let scene = fs::read(path.join(SCENE))
                .map_err(|e| e.to_string())
                .and_then(|bytes| serde_json::from_slice(&bytes).map_err(|e| e.to_string()));
            jobs.push(StoredJob { record, scene });
        }
        Ok(jobs)
    }
}

/// Removes the temporary files of writes a crash interrupted.
fn sweep_temporaries(job_dir: &Path) -> io::Result<()> {
    for entry in fs::read_dir(job_dir)? {
        let entry = entry?;
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.') && name.ends_with(".tmp") {
            fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

/// Appends cycle records to a job's `cycles.jsonl`.
pub struct CyclesWriter {
    file: BufWriter<File>,
}

impl CyclesWriter {
    /// Appends one line. Flushed to the OS at once so a client replaying the file from disk
    /// sees every record the job has announced.
    pub fn append(&mut self, line: &str) -> io::Result<()> {
        self.file.write_all(line.as_bytes())?;
        self.file.write_all(b"\n")?;
        self.file.flush()
    }

    /// Makes every line durable.
    pub fn finish(self) -> io::Result<()> {
        let file = self
            .file
            .into_inner()
            .map_err(io::IntoInnerError::into_error)?;
        file.sync_all()
    }
}

fn to_json(value: &impl serde::Serialize) -> io::Result<Vec<u8>> {
    serde_json::to_vec_pretty(value).map_err(io::Error::other)
}

/// Writes `dir/name` atomically and durably.
fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> io::Result<()> {
    // A unique temporary name, so two writers can never interleave in one temporary file.
    let temporary = dir.join(format!(".{name}.{}.tmp", Uuid::new_v4()));
    let written = (|| {
        let mut file = File::create(&temporary)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        fs::rename(&temporary, dir.join(name))
    })();
    if written.is_err() {
        // Best effort: the write already failed, and a leftover temporary file is harmless.
        let _ = fs::remove_file(&temporary);
    }
    written?;
    sync_dir(dir)
}

/// Makes a directory's entries (creations, renames) durable.
fn sync_dir(dir: &Path) -> io::Result<()> {
    File::open(dir)?.sync_all()
}
