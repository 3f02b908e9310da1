//! Records the git commit tribosim is built from (`TRIBOSIM_GIT_COMMIT`), for the provenance
//! of every result: the environment's `TRIBOSIM_GIT_COMMIT` when set (a build without the
//! repository, as the Dockerfile's, is told it), else `git rev-parse HEAD`, else "unknown".

use std::path::{Path, PathBuf};
use std::process::Command;

/// `git rev-parse ARGS`, trimmed; `None` when git is missing or fails.
fn rev_parse(args: &[&str]) -> Option<String> {
    let output = Command::new("git")
        .arg("rev-parse")
        .args(args)
        .output()
        .ok()?;
    let text = String::from_utf8(output.stdout).ok()?;
    let text = text.trim();
    (output.status.success() && !text.is_empty()).then(|| text.to_owned())
}

/// Reruns this script when `path` changes; a path that does not exist is left out, as
/// cargo would rerun the script on every build for it.
fn watch(path: &Path) {
    if path.exists() {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=TRIBOSIM_GIT_COMMIT");
    let given = std::env::var("TRIBOSIM_GIT_COMMIT")
        .ok()
        .filter(|c| !c.trim().is_empty());
    let commit = given
        .or_else(|| rev_parse(&["HEAD"]))
        .unwrap_or_else(|| "unknown".to_owned());
    println!("cargo:rustc-env=TRIBOSIM_GIT_COMMIT={}", commit.trim());
    // A new commit moves HEAD (detached) or the branch's ref (loose, or packed).
    let Some(git_dir) = rev_parse(&["--absolute-git-dir"]).map(PathBuf::from) else {
        return;
    };
    watch(&git_dir.join("HEAD"));
    let common = rev_parse(&["--git-common-dir"]).map_or_else(|| git_dir.clone(), PathBuf::from);
    watch(&common.join("packed-refs"));
    if let Some(branch) = rev_parse(&["--symbolic-full-name", "HEAD"]) {
        watch(&common.join(branch));
    }
}
