//! `tribosim study STUDY.json --slurm DIR`: the member scenes, the manifest and the
//! job-array script, and optionally the submission.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::value::RawValue;

use super::{FORMAT, MANIFEST, Manifest, ManifestMember, SCRIPT, SlurmError, VERSION, scene_path};
use crate::study::Member;
use crate::study::command::read_members;

/// What `--slurm DIR` was asked to write.
#[derive(Debug, Clone)]
pub struct SlurmOptions {
    /// The study directory to create; it may exist if empty.
    pub dir: PathBuf,
    /// The `tribosim` the tasks run: an absolute path every node can reach.
    pub tribosim: PathBuf,
    /// `#SBATCH --partition`, when given.
    pub partition: Option<String>,
    /// `#SBATCH --time` (Slurm's format, as `10:00` or `1-00:00:00`), when given.
    pub time: Option<String>,
    /// `#SBATCH --cpus-per-task`, when given.
    pub cpus_per_task: Option<u32>,
    /// The member limit.
    pub max_members: usize,
    /// Submit the script with `sbatch` once written.
    pub submit: bool,
}

/// Writes the study directory for the study file `study` and, when asked, submits it.
/// Prints the `sbatch` command to standard output, or the array job's id once submitted.
pub fn write_dir(study: &Path, options: &SlurmOptions) -> Result<(), SlurmError> {
    for (option, value) in [("partition", &options.partition), ("time", &options.time)] {
        if let Some(value) = value {
            if value.is_empty()
                || value.contains(|c: char| c.is_whitespace() || "'\"\\".contains(c))
            {
                return Err(SlurmError::BadOption {
                    option,
                    value: value.clone(),
                });
            }
        }
    }
    let (text, members) = read_members(study, options.max_members)?;
    let dir = &options.dir;
    let occupied = std::fs::read_dir(dir).is_ok_and(|mut entries| entries.next().is_some());
    if occupied {
        return Err(SlurmError::NotEmpty(dir.clone()));
    }
    for sub in ["members", "logs"] {
        let path = dir.join(sub);
        std::fs::create_dir_all(&path).map_err(SlurmError::io(&path))?;
    }
    for member in &members {
        let json = serde_json::to_string_pretty(&member.scene).map_err(|e| SlurmError::Io {
            path: dir.join(scene_path(member.index)),
            source: e.into(),
        })?;
        write(&dir.join(scene_path(member.index)), &(json + "\n"))?;
    }
    write(&dir.join(SCRIPT), &script(members.len(), options))?;
    // Last: a directory with a manifest has every other file.
    write(&dir.join(MANIFEST), &manifest(&text, &members, dir)?)?;
    eprintln!(
        "wrote {} members to {}; collect with: tribosim study collect {}",
        members.len(),
        dir.display(),
        dir.display()
    );
    if options.submit {
        println!("{}", submit(dir)?);
    } else {
        println!(
            "cd {} && sbatch {SCRIPT}",
            shell_quote(&dir.to_string_lossy())
        );
    }
    Ok(())
}

fn manifest(text: &str, members: &[Member], dir: &Path) -> Result<String, SlurmError> {
    let failed = |e: serde_json::Error| SlurmError::Io {
        path: dir.join(MANIFEST),
        source: e.into(),
    };
    let manifest = Manifest {
        format: FORMAT.to_owned(),
        tribosim_version: VERSION.to_owned(),
        study: RawValue::from_string(text.trim().to_owned()).map_err(failed)?,
        members: members
            .iter()
            .map(|m| ManifestMember {
                index: m.index,
                values: m.values.iter().cloned().collect(),
            })
            .collect(),
    };
    Ok(serde_json::to_string_pretty(&manifest).map_err(failed)? + "\n")
}

/// The job-array script: task i runs member i. Relative paths are the study directory's,
/// which is where `sbatch` must be run (the job's working directory is the submission's).
fn script(members: usize, options: &SlurmOptions) -> String {
    let mut lines = vec![
        "#!/bin/bash".to_owned(),
        "# A tribosim study as a Slurm job array: task i runs members/NNNN.scene.json (NNNN = i,"
            .to_owned(),
        "# four digits) with `tribosim run` and writes members/NNNN.result.json. Submit from this"
            .to_owned(),
        format!(
            "# directory: sbatch {SCRIPT}. Options on sbatch's command line (--partition, --time,"
        ),
        "# --mem, --array=3,7 for some members only) override the lines below. TRIBOSIM in the"
            .to_owned(),
        "# environment overrides the binary. Then: tribosim study collect <this directory>."
            .to_owned(),
        "#SBATCH --job-name=tribosim-study".to_owned(),
        format!("#SBATCH --array=0-{}", members - 1),
        "#SBATCH --output=logs/%4a.out".to_owned(),
        "#SBATCH --error=logs/%4a.err".to_owned(),
    ];
    if let Some(partition) = &options.partition {
        lines.push(format!("#SBATCH --partition={partition}"));
    }
    if let Some(time) = &options.time {
        lines.push(format!("#SBATCH --time={time}"));
    }
    if let Some(cpus) = options.cpus_per_task {
        lines.push(format!("#SBATCH --cpus-per-task={cpus}"));
    }
    lines.extend([
        "set -euo pipefail".to_owned(),
        format!("if [ ! -f {MANIFEST} ]; then"),
        format!("    echo \"no {MANIFEST} in $PWD: run sbatch from the study directory\" >&2"),
        "    exit 1".to_owned(),
        "fi".to_owned(),
        format!(
            "tribosim=\"${{TRIBOSIM:-{}}}\"",
            shell_quote(&options.tribosim.to_string_lossy())
        ),
        "member=\"$(printf %04d \"$SLURM_ARRAY_TASK_ID\")\"".to_owned(),
        "exec \"$tribosim\" run \"members/$member.scene.json\" -o \"members/$member.result.json\""
            .to_owned(),
    ]);
    lines.join("\n") + "\n"
}

/// `sbatch --parsable` in the study directory; gives the array job's id.
fn submit(dir: &Path) -> Result<String, SlurmError> {
    let output = Command::new("sbatch")
        .args(["--parsable", SCRIPT])
        .current_dir(dir)
        .output()
        .map_err(|e| SlurmError::Sbatch(format!("cannot run it ({e}); is Slurm installed?")))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        return Err(SlurmError::Sbatch(format!(
            "{} ({})",
            String::from_utf8_lossy(&output.stderr).trim(),
            output.status
        )));
    }
    // `--parsable` prints `id` or `id;cluster`.
    let id = stdout.trim().split(';').next().unwrap_or_default();
    if id.is_empty() {
        return Err(SlurmError::Sbatch("printed no job id".into()));
    }
    eprintln!("submitted array job {id}");
    Ok(id.to_owned())
}

/// `text` as one word for the shell: single-quoted, with its single quotes escaped.
fn shell_quote(text: &str) -> String {
    if !text.is_empty()
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "/._-+".contains(c))
    {
        return text.to_owned();
    }
    format!("'{}'", text.replace('\'', r"'\''"))
}

fn write(path: &Path, text: &str) -> Result<(), SlurmError> {
    std::fs::write(path, text).map_err(SlurmError::io(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_with_spaces_and_quotes_stays_one_shell_word() {
        assert_eq!(shell_quote("/usr/bin/tribosim"), "/usr/bin/tribosim");
        assert_eq!(
            shell_quote("/opt/my tools/it's"),
            r"'/opt/my tools/it'\''s'"
        );
    }
}
