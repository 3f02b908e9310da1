//! A job's measured tables on disk: `measured_<kind>.json` in the job's directory (its home,
//! so a table goes when its job does), holding the columns and the length and CRC-32 of
//! their compact JSON (which serde_json writes the same for the same numbers, so it can be
//! recomputed), so that damage done on disk is found when the table is read. Every access
//! holds the job's disk lock (`Jobs::with_files`).

use std::fs;
use std::io;
use std::path::Path;

use serde::{Deserialize, Serialize};
use uuid::Uuid;

use super::table::{Columns, MeasurementKind, Measurements};
use crate::service::files::{Damage, Digest, read_json, sync_dir, to_json, write_atomic};
use crate::service::jobs::{JobError, Jobs};

/// What a `measured_<kind>.json` holds.
#[derive(Debug, Serialize, Deserialize)]
struct StoredTable {
    digest: Digest,
    columns: Columns,
}

/// Why a job's measurements could not be read or changed.
#[derive(Debug)]
pub enum MeasuredError {
    /// The job is unknown, or damaged (so nothing is attached to it).
    Job(JobError),
    /// A stored table does not match its digest; replacing or deleting it mends it.
    Damaged(Damage),
    /// A file could not be written.
    Storage(io::Error),
}

impl From<JobError> for MeasuredError {
    fn from(error: JobError) -> Self {
        Self::Job(error)
    }
}

/// Applies `change` to the tables in job `id`'s directory, then reads every table back.
/// Blocking (files).
pub fn measured(
    jobs: &Jobs,
    id: Uuid,
    change: impl FnOnce(&Path) -> io::Result<()>,
) -> Result<Measurements, MeasuredError> {
    jobs.with_files(id, |dir| {
        change(dir).map_err(MeasuredError::Storage)?;
        read(dir).map_err(MeasuredError::Damaged)
    })?
}

/// Every table of job `id`, unchanged (a report's). Blocking (files).
pub fn read_of(jobs: &Jobs, id: Uuid) -> Result<Measurements, MeasuredError> {
    measured(jobs, id, |_| Ok(()))
}

/// Replaces the table of `kind` in a job's directory.
pub fn write(dir: &Path, kind: MeasurementKind, columns: Columns) -> io::Result<()> {
    let compact = serde_json::to_vec(&columns).map_err(io::Error::other)?;
    let stored = StoredTable {
        digest: Digest::of(&compact),
        columns,
    };
    write_atomic(dir, kind.file(), &to_json(&stored)?)
}

/// Removes the table of `kind` from a job's directory, if it has one.
pub fn remove(dir: &Path, kind: MeasurementKind) -> io::Result<()> {
    match fs::remove_file(dir.join(kind.file())) {
        Ok(()) => sync_dir(dir),
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
    }
}

/// Every table in a job's directory, each checked against its digest.
fn read(dir: &Path) -> Result<Measurements, Damage> {
    let mut measurements = Measurements::default();
    for kind in MeasurementKind::ALL {
        let stored: StoredTable = match read_json(dir, kind.file()) {
            Ok(stored) => stored,
            Err(Damage::Missing(_)) => continue,
            Err(damage) => return Err(damage),
        };
        let compact = serde_json::to_vec(&stored.columns).map_err(|e| Damage::Invalid {
            file: kind.file(),
            message: e.to_string(),
        })?;
        stored.digest.check(kind.file(), &compact)?;
        *measurements.slot(kind) = Some(stored.columns);
    }
    Ok(measurements)
}
