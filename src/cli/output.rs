//! Where the command line writes a result: the file asked for, standard output when it is
//! a pipe (scripts read the JSON there), or, when it is a terminal, a new file in the
//! current folder rather than a megabyte of JSON scrolling past.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::error::CliError;

/// Where a command's JSON goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Destination {
    /// The file given with `-o`, replaced if it exists.
    Asked(PathBuf),
    /// A new file chosen for the user (standard output is a terminal); never an existing
    /// one.
    Chosen(PathBuf),
    /// Standard output.
    Stdout,
}

/// Where a command given `output` writes, when standard output is a terminal or not; a
/// chosen file is `<kind>-<label>-<date>.json` in `folder`, numbered past any that exist.
pub fn destination(
    output: Option<&Path>,
    stdout_is_terminal: bool,
    folder: &Path,
    name: &FileName,
) -> Destination {
    match output {
        Some(path) => Destination::Asked(path.to_owned()),
        None if stdout_is_terminal => Destination::Chosen(free_path(folder, name)),
        None => Destination::Stdout,
    }
}

/// The parts of a chosen file's name.
pub struct FileName<'a> {
    /// What the file holds: `result`, `study`.
    pub kind: &'a str,
    /// What it is of: the scene's name, the study file's.
    pub label: &'a str,
    /// The day, `2025-11-26`.
    pub date: String,
}

/// Today's date in UTC, `2025-11-26`.
pub fn today() -> String {
    let now = time::OffsetDateTime::now_utc();
    format!(
        "{:04}-{:02}-{:02}",
        now.year(),
        u8::from(now.month()),
        now.day()
    )
}

/// `label` as a file name's part: letters, digits and dashes, at most 40 characters.
fn slug(label: &str) -> String {
    let mut slug = String::new();
    for c in label.chars() {
        if c.is_ascii_alphanumeric() {
            slug.push(c.to_ascii_lowercase());
        } else if !slug.ends_with('-') && !slug.is_empty() {
            slug.push('-');
        }
    }
    let slug: String = slug.chars().take(40).collect();
    let slug = slug.trim_end_matches('-');
    if slug.is_empty() {
        "untitled".to_owned()
    } else {
        slug.to_owned()
    }
}

/// The first of `<kind>-<label>-<date>.json`, `...-2.json`, `...-3.json` ... in `folder`
/// that does not exist.
fn free_path(folder: &Path, name: &FileName) -> PathBuf {
    let stem = format!("{}-{}-{}", name.kind, slug(name.label), name.date);
    (1..)
        .map(|n| match n {
            1 => folder.join(format!("{stem}.json")),
            n => folder.join(format!("{stem}-{n}.json")),
        })
        .find(|path| !path.exists())
        .unwrap_or_else(|| folder.join(format!("{stem}.json")))
}

/// Writes `value` as pretty JSON to `destination`; a chosen file is created new (never
/// replacing one that appeared meanwhile) and named on standard error.
pub fn write_json(
    value: &impl serde::Serialize,
    destination: &Destination,
) -> Result<(), CliError> {
    let text = serde_json::to_string_pretty(value)? + "\n";
    let unwritten = |path: &Path| {
        let path = path.to_owned();
        move |source| CliError::File {
            action: "write",
            path,
            source,
        }
    };
    match destination {
        Destination::Asked(path) => write_whole(path, &text).map_err(unwritten(path)),
        Destination::Chosen(path) => {
            let written = std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(path)
                .and_then(|mut file| file.write_all(text.as_bytes()));
            written.map_err(unwritten(path))?;
            eprintln!(
                "wrote {} (standard output is a terminal: `-o FILE` names the file, a pipe \
                 gets the JSON)",
                path.display()
            );
            Ok(())
        }
        Destination::Stdout => write!(std::io::stdout(), "{text}").map_err(CliError::Stdout),
    }
}

/// Writes `text` to a temporary file beside `path`, then renames it into place: a reader
/// (`tribosim study collect` while a cluster's tasks still run) sees the whole file or none.
/// A `path` that exists and is not a regular file (`/dev/null`, a pipe) is written into
/// instead: a rename would put a regular file in its place, and a `/dev/null` replaced so,
/// as root, fills with whatever later commands discard there and feeds it to every reader
/// (cargo's rustc probe, which reads it, then failed on compiler messages as its source).
fn write_whole(path: &Path, text: &str) -> std::io::Result<()> {
    let special = std::fs::metadata(path).is_ok_and(|m| !m.is_file());
    if special {
        return std::fs::OpenOptions::new()
            .write(true)
            .open(path)?
            .write_all(text.as_bytes());
    }
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(format!(".{}.tmp", std::process::id()));
    std::fs::write(&temporary, text)?;
    std::fs::rename(&temporary, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&temporary);
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name(label: &str) -> FileName<'_> {
        FileName {
            kind: "result",
            label,
            date: "2025-11-26".to_owned(),
        }
    }

    #[test]
    fn a_terminal_gets_a_new_file_a_pipe_the_json_and_an_asked_file_its_path() {
        let folder = std::env::temp_dir().join(format!("tribosim-cli-{}", std::process::id()));
        std::fs::create_dir_all(&folder).expect("a temporary folder");
        let label = name("316L vs alumina, 5 N");
        let first = folder.join("result-316l-vs-alumina-5-n-2025-11-26.json");
        assert_eq!(
            destination(None, true, &folder, &label),
            Destination::Chosen(first.clone())
        );
        std::fs::write(&first, "{}").expect("written");
        let second = folder.join("result-316l-vs-alumina-5-n-2025-11-26-2.json");
        assert_eq!(
            destination(None, true, &folder, &label),
            Destination::Chosen(second)
        );
        assert_eq!(
            destination(None, false, &folder, &label),
            Destination::Stdout
        );
        let asked = Path::new("out.json");
        assert_eq!(
            destination(Some(asked), true, &folder, &label),
            Destination::Asked(asked.to_owned())
        );
        std::fs::remove_dir_all(&folder).expect("removed");
    }

    #[test]
    fn labels_become_safe_file_names() {
        assert_eq!(slug("../etc/passwd"), "etc-passwd");
        assert_eq!(slug("  "), "untitled");
        assert_eq!(slug("A [test.load_n = 2]"), "a-test-load-n-2");
    }
}
