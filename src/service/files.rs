//! Durable files, the primitives every store of the service shares: atomic whole-file writes
//! (temporary file, fsync, rename, fsync of the directory, so a crash leaves either the old
//! or the new file, never a torn one), the length and CRC-32 that find damage done on disk,
//! what damage was found, and the quarantine where damaged files are moved, never deleted.

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::Path;

use serde::{Deserialize, Serialize};
use thiserror::Error;
use uuid::Uuid;

/// Why a stored file is not what was written to it.
#[derive(Debug, Error)]
pub enum Damage {
    /// The file is gone.
    #[error("{0} is missing")]
    Missing(&'static str),
    /// The file or its directory cannot be read.
    #[error("{file} cannot be read: {source}")]
    Unreadable {
        /// The file.
        file: &'static str,
        /// What failed.
        #[source]
        source: io::Error,
    },
    /// The file is longer or shorter than when it was written.
    #[error("{file} holds {found} bytes; {expected} were written")]
    Length {
        /// The file.
        file: &'static str,
        /// Its length now.
        found: u64,
        /// Its length when written.
        expected: u64,
    },
    /// The file has its length but other bytes.
    #[error("{0} does not match its checksum")]
    Checksum(&'static str),
    /// The file does not parse as what it should hold.
    #[error("{file} is not valid: {message}")]
    Invalid {
        /// The file.
        file: &'static str,
        /// The parser's complaint.
        message: String,
    },
}

impl Damage {
    /// Whether the file could not be read at all: possibly a fault of the machine (too
    /// many open files, an I/O error) rather than of the file, so a request that meets it
    /// fails and the next one tries again, instead of running the job again.
    pub fn is_read_failure(&self) -> bool {
        matches!(self, Self::Unreadable { .. })
    }

    pub(crate) fn reading(file: &'static str, source: io::Error) -> Self {
        if source.kind() == io::ErrorKind::NotFound {
            Self::Missing(file)
        } else {
            Self::Unreadable { file, source }
        }
    }
}

/// The length and CRC-32 of a file's bytes. CRC-32 finds every burst of damage up to 32 bits
/// and all but one in 2^32 of the others; a truncation is caught by the length already.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Digest {
    bytes: u64,
    crc32: u32,
}

impl Digest {
    pub(crate) fn of(bytes: &[u8]) -> Self {
        Self {
            bytes: bytes.len() as u64,
            crc32: crc32fast::hash(bytes),
        }
    }

    /// The digest of `bytes` counted as they were written (a log appended line by line).
    pub(crate) fn from_parts(bytes: u64, crc32: u32) -> Self {
        Self { bytes, crc32 }
    }

    pub(crate) fn check(self, file: &'static str, bytes: &[u8]) -> Result<(), Damage> {
        let found = Self::of(bytes);
        if found.bytes != self.bytes {
            return Err(Damage::Length {
                file,
                found: found.bytes,
                expected: self.bytes,
            });
        }
        if found.crc32 != self.crc32 {
            return Err(Damage::Checksum(file));
        }
        Ok(())
    }
}

/// `dir/file` parsed as JSON.
pub(crate) fn read_json<T: serde::de::DeserializeOwned>(
    dir: &Path,
    file: &'static str,
) -> Result<T, Damage> {
    let bytes = fs::read(dir.join(file)).map_err(|e| Damage::reading(file, e))?;
    serde_json::from_slice(&bytes).map_err(|e| Damage::Invalid {
        file,
        message: e.to_string(),
    })
}

/// Moves `path` into `quarantine_dir` under a unique name, logging where; logs if it cannot.
pub(crate) fn quarantine(quarantine_dir: &Path, path: &Path) {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let target = quarantine_dir.join(format!("{name}.{}", Uuid::new_v4().simple()));
    let parent = path.parent().unwrap_or(quarantine_dir);
    let moved = fs::create_dir_all(quarantine_dir)
        .and_then(|()| fs::rename(path, &target))
        .and_then(|()| sync_dir(parent));
    match moved {
        Ok(()) => tracing::warn!(from = %path.display(), to = %target.display(), "quarantined"),
        Err(e) => {
            tracing::error!(path = %path.display(), "cannot quarantine: {e}; left in place");
        }
    }
}

/// Removes the temporary files of writes a crash interrupted.
pub(crate) fn sweep_temporaries(job_dir: &Path) -> io::Result<()> {
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

/// Whether an error means the disk (or the user's quota) is full.
pub(crate) fn is_disk_full(error: &io::Error) -> bool {
    matches!(
        error.kind(),
        io::ErrorKind::StorageFull | io::ErrorKind::QuotaExceeded
    )
}

/// `value` as pretty JSON, the form every stored file has.
pub(crate) fn to_json(value: &impl serde::Serialize) -> io::Result<Vec<u8>> {
    serde_json::to_vec_pretty(value).map_err(io::Error::other)
}

/// Writes `dir/name` atomically and durably.
pub(crate) fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> io::Result<()> {
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
pub(crate) fn sync_dir(dir: &Path) -> io::Result<()> {
    File::open(dir)?.sync_all()
}
