//! Where and when the report's numbers were measured: CPU, cores, date and commit.

use std::path::Path;

/// Where and when the numbers were measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// UTC date, `YYYY-MM-DD`.
    pub date: String,
    /// CPU model name.
    pub cpu: String,
    /// Logical cores.
    pub cores: usize,
    /// Short commit hash, with ` + uncommitted changes` when tracked files other than the
    /// report's own differ from it.
    pub commit: Option<String>,
}

impl Machine {
    /// Reads `/proc/cpuinfo`, the clock and `git` (each optional); the report at `report`
    /// and its plots do not count as changes (a second run would see the first one's).
    pub fn detect(report: &Path) -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let (cpu, cores) = parse_cpuinfo(&cpuinfo);
        let cores = if cores > 0 {
            cores
        } else {
            std::thread::available_parallelism().map_or(1, usize::from)
        };
        Self {
            date: time::OffsetDateTime::now_utc().date().to_string(),
            cpu: cpu.unwrap_or_else(|| "unknown CPU".to_owned()),
            cores,
            commit: git_commit(report),
        }
    }
}

/// The first `model name` and the number of `processor` entries.
fn parse_cpuinfo(text: &str) -> (Option<String>, usize) {
    let field = |line: &str, key: &str| {
        let (name, value) = line.split_once(':')?;
        (name.trim() == key).then(|| value.trim().to_owned())
    };
    let model = text.lines().find_map(|l| field(l, "model name"));
    let cores = text
        .lines()
        .filter(|l| field(l, "processor").is_some())
        .count();
    (model, cores)
}

fn git(args: &[&str]) -> Option<String> {
    let out = std::process::Command::new("git").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

fn git_commit(report: &Path) -> Option<String> {
    let commit = git(&["rev-parse", "--short=10", "HEAD"]).filter(|c| !c.is_empty())?;
    let exclude = |p: &Path| format!(":(exclude){}", p.display());
    let (own, plots) = (exclude(report), exclude(&report.with_extension("")));
    let args = [
        "status",
        "--porcelain",
        "--untracked-files=no",
        "--",
        ".",
        &own,
        &plots,
    ];
    let dirty = git(&args).is_some_and(|s| !s.is_empty());
    Some(if dirty {
        format!("{commit} + uncommitted changes")
    } else {
        commit
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpuinfo_gives_the_model_and_the_processor_count() {
        let text = "processor\t: 0\nmodel name\t: AMD EPYC 7B13\nflags\t: fpu\n\n\
                    processor\t: 1\nmodel name\t: AMD EPYC 7B13\n";
        assert_eq!(parse_cpuinfo(text), (Some("AMD EPYC 7B13".to_owned()), 2));
        assert_eq!(parse_cpuinfo(""), (None, 0));
    }
}
