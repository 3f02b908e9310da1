//! `tribosim study --slurm DIR` and `tribosim study collect DIR` against the real binary,
//! without Slurm: the member scenes run by `tribosim run` (and by the job-array script with
//! the task's index set as Slurm sets it) give the local study's members, and collect
//! gives the local study's summary with a missing member marked. The same against a real
//! Slurm is `scripts/slurm-test.sh`.

mod common;

use std::path::Path;
use std::process::{Command, Output};
use std::sync::atomic::AtomicBool;

use serde_json::Value;

use common::TempDir;
use tribosim::simulation::{Plan, parse_scene_str, run};
use tribosim::study::{MAX_MEMBERS, Study};

/// The quick preset at the smallest grid and few cycles, 2 x 2: each member runs in well
/// under a second.
const STUDY: &str = r#"{
  "base": {
    "preset": "dalmau2018-316l",
    "overrides": { "test": { "cycles": 20 }, "numerics": { "grid": 32 } }
  },
  "axes": { "test.speed_rpm": [30, 60], "test.load_n": [2, 5] }
}"#;

fn tribosim(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run tribosim")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A temporary folder with the study file and its study directory `array/` written.
fn written() -> TempDir {
    let temp = TempDir::new("slurm");
    std::fs::write(temp.path().join("study.json"), STUDY).expect("write the study");
    let output = tribosim(&["study", "study.json", "--slurm", "array"], temp.path());
    assert!(output.status.success(), "{}", stderr(&output));
    temp
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).expect("read JSON");
    serde_json::from_str(&text).expect("parse JSON")
}

/// A summary without what depends on the machine and the moment: wall times, workers and
/// the provenance's date.
fn without_wall_times(mut summary: Value) -> Value {
    let object = summary.as_object_mut().expect("a summary object");
    object.remove("wall_s");
    object.remove("workers");
    if let Some(provenance) = object.get_mut("provenance").and_then(Value::as_object_mut) {
        provenance.remove("computed_at");
    }
    for member in object["members"].as_array_mut().expect("members") {
        if let Some(run) = member.get_mut("summary").and_then(Value::as_object_mut) {
            run.remove("wall_s");
        }
    }
    summary
}

#[test]
fn each_member_scene_runs_by_tribosim_run_to_the_local_members_result() {
    let temp = written();
    let array = temp.path().join("array");
    let members = Study::parse(STUDY)
        .and_then(|s| s.members(MAX_MEMBERS))
        .expect("a valid study");
    let scenes = std::fs::read_dir(array.join("members"))
        .expect("members/")
        .count();
    assert_eq!(scenes, members.len());
    let script = std::fs::read_to_string(array.join("study.sbatch")).expect("the script");
    assert!(script.contains("\n#SBATCH --array=0-3\n"), "{script}");
    for member in &members {
        let scene = format!("members/{:04}.scene.json", member.index);
        let text = std::fs::read_to_string(array.join(&scene)).expect("a member scene");
        assert_eq!(
            parse_scene_str(&text).expect("a valid scene").scene(),
            &member.scene
        );
        let result = format!("members/{:04}.result.json", member.index);
        let output = tribosim(&["run", &scene, "-o", &result], &array);
        assert!(output.status.success(), "{}", stderr(&output));
        let plan = Plan::new(member.scene.clone()).expect("a valid scene");
        let here = run(&plan, &mut |_| {}, &AtomicBool::new(false)).expect("a run");
        let mut there: tribosim::simulation::Summary =
            serde_json::from_value(read_json(&array.join(&result))["summary"].clone())
                .expect("a run summary");
        // Runs are deterministic and JSON numbers read back exactly (serde_json's
        // float_roundtrip), so every number but the wall time is equal.
        there.wall_s = here.summary.wall_s;
        assert_eq!(there, here.summary, "member {}", member.index);
    }
}

#[test]
fn collect_gives_the_local_summary_and_marks_a_member_without_result() {
    let temp = written();
    let array = temp.path().join("array");
    // Members 0 to 2 run by the script as Slurm runs a task; member 3's task was killed.
    for task in ["0", "1", "2"] {
        let output = Command::new("bash")
            .arg("study.sbatch")
            .env("SLURM_ARRAY_TASK_ID", task)
            .env("TRIBOSIM", env!("CARGO_BIN_EXE_tribosim"))
            .current_dir(&array)
            .output()
            .expect("run the script");
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let killed = "slurmstepd: error: *** JOB 8 ON n1 CANCELLED DUE TO TIME LIMIT ***";
    std::fs::write(array.join("logs/0003.err"), format!("\n{killed}\n")).expect("a log");

    let collected = tribosim(
        &["study", "collect", "array", "-o", "collected.json"],
        temp.path(),
    );
    assert!(
        !collected.status.success(),
        "a missing member fails the command"
    );
    assert!(
        stderr(&collected).contains("1 of 4 members have no result"),
        "{}",
        stderr(&collected)
    );
    let local = tribosim(&["study", "study.json", "-o", "local.json"], temp.path());
    assert!(local.status.success(), "{}", stderr(&local));

    let mut collected = without_wall_times(read_json(&temp.path().join("collected.json")));
    let local = without_wall_times(read_json(&temp.path().join("local.json")));
    let missing = collected["members"][3]
        .as_object_mut()
        .expect("member 3")
        .remove("error")
        .expect("member 3 has an error");
    assert!(
        missing.as_str().is_some_and(|e| e.contains(killed)),
        "{missing}"
    );
    for index in 0..3 {
        assert_eq!(collected["members"][index], local["members"][index]);
    }
    assert_eq!(collected["axes"], local["axes"]);
    assert!(collected["members"][3].get("summary").is_none());
}

#[test]
fn a_folder_that_is_not_a_study_directory_is_refused() {
    let temp = TempDir::new("slurm-refused");
    let output = tribosim(&["study", "collect", "."], temp.path());
    assert!(!output.status.success());
    assert!(output.stdout.is_empty());
    assert!(
        stderr(&output).contains("is not a study directory written by `tribosim study --slurm`"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn a_directory_in_use_is_not_written_over_and_the_options_reach_the_script() {
    let temp = written();
    let again = tribosim(&["study", "study.json", "--slurm", "array"], temp.path());
    assert!(!again.status.success());
    assert!(
        stderr(&again).contains("is not empty"),
        "{}",
        stderr(&again)
    );

    let options = [
        "study",
        "study.json",
        "--slurm",
        "other",
        "--tribosim",
        "bin/tribosim",
        "--partition",
        "short",
        "--time",
        "10:00",
        "--cpus-per-task",
        "2",
    ];
    let output = tribosim(&options, temp.path());
    assert!(output.status.success(), "{}", stderr(&output));
    let script = std::fs::read_to_string(temp.path().join("other/study.sbatch")).expect("a script");
    for line in [
        "#SBATCH --partition=short",
        "#SBATCH --time=10:00",
        "#SBATCH --cpus-per-task=2",
    ] {
        assert!(script.contains(line), "{line} in {script}");
    }
    // A relative --tribosim is made absolute: the tasks run in the study directory.
    let binary = temp.path().join("bin/tribosim");
    assert!(
        script.contains(&format!("${{TRIBOSIM:-{}}}", binary.display())),
        "{script}"
    );
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(
        printed.trim_end().ends_with("&& sbatch study.sbatch"),
        "{printed}"
    );
}
