//! The command line without dead ends, against the built binary: a scene typed as an
//! argument points to standard input, near misses name what was meant, a unit slip is
//! refused with the slip named, warnings and a long run's estimate come before the run,
//! the result goes to a new file on a terminal and to a pipe as JSON, and `calibrate` and
//! `study` print readable summaries.

mod common;

use std::io::{BufRead, BufReader, ErrorKind, Write};
use std::path::Path;
use std::process::{Command, Output, Stdio};

use serde_json::Value;

use common::TempDir;

/// A run of a few cycles on a small grid: well under a second.
const QUICK: &str = r#"{"name": "quick one", "test": {"cycles": 2}, "numerics": {"grid": 32}}"#;

fn tribosim() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tribosim"))
}

/// `tribosim args...` in `dir` with `stdin` on standard input.
fn run_in(dir: &Path, args: &[&str], stdin: &str) -> Output {
    let mut child = tribosim()
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start tribosim");
    let written = child
        .stdin
        .take()
        .expect("stdin")
        .write_all(stdin.as_bytes());
    // A command refused before it reads its input (a mistyped flag, which clap refuses
    // first) may exit before the write: the closed pipe is then its answer, not a failure.
    if let Err(e) = written {
        assert_eq!(e.kind(), ErrorKind::BrokenPipe, "write stdin: {e}");
    }
    child.wait_with_output().expect("tribosim ends")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

#[test]
fn a_scene_typed_as_the_argument_points_to_standard_input() {
    let dir = TempDir::new("cli-text");
    let output = run_in(dir.path(), &["run", "{}"], "");
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("echo '{}' | tribosim run -"), "{message}");
}

/// A name of a million characters was run and copied into the result; `tribosim run`
/// refuses it as the service does (`tests/strings_http.rs`), naming the field and its bound.
#[test]
fn a_name_past_its_bound_or_with_hidden_characters_is_refused() {
    let dir = TempDir::new("cli-name");
    let long = format!(r#"{{"name": "{}"}}"#, "x".repeat(201));
    let output = run_in(dir.path(), &["run", "-"], &long);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(
        message.contains("name: must be a string of at most 200 characters"),
        "{message}"
    );
    let output = run_in(dir.path(), &["run", "-"], r#"{"name": "a\u0000b"}"#);
    assert!(!output.status.success());
    assert!(stderr(&output).contains("U+0000"), "{}", stderr(&output));
}

#[test]
fn near_misses_name_the_field_the_preset_and_the_flag_meant() {
    let dir = TempDir::new("cli-near");
    let output = run_in(dir.path(), &["run", "-"], r#"{"test": {"load": 5}}"#);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("did you mean `test.load_n`?"),
        "{}",
        stderr(&output)
    );
    let output = run_in(dir.path(), &["run", "-"], r#"{"preset": "dalmau2018"}"#);
    assert!(
        stderr(&output).contains("did you mean `dalmau2018-316l`?"),
        "{}",
        stderr(&output)
    );
    // clap names the near flag itself.
    let output = run_in(dir.path(), &["run", "-", "--outptu", "x.json"], QUICK);
    assert!(
        stderr(&output).contains("'--output'"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn unit_slips_are_refused_with_the_slip_named() {
    let dir = TempDir::new("cli-slips");
    let output = run_in(dir.path(), &["run", "-"], r#"{"test": {"load_n": 5000}}"#);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("test.load_n"), "{message}");
    assert!(
        message.contains("was the load in mN? 5000 mN = 5 N"),
        "{message}"
    );

    let output = run_in(
        dir.path(),
        &["run", "-"],
        r#"{"disc": {"hardness_mpa": 2.473}}"#,
    );
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("disc.hardness_mpa"), "{message}");
    assert!(
        message.contains("was it in GPa? 2.473 GPa = 2473 MPa"),
        "{message}"
    );

    // A smooth 16 x 16 map of heights written in um but read as m.
    let rows: Vec<String> = (0..16)
        .map(|i| {
            (0..16)
                .map(|j| format!("{:.4}", 0.5 * ((i + j) as f64 * 0.4).sin()))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(dir.path().join("map.txt"), rows.join("\n") + "\n").expect("map");
    let args = ["run", "-", "--surface", "map.txt", "--pixel-um", "1"];
    let output = run_in(dir.path(), &args, QUICK);
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("disc.surface.id"), "{message}");
    assert!(message.contains("in um rather than m"), "{message}");
}

#[test]
fn warnings_come_before_the_run_and_with_their_paths_in_the_result() {
    // 1000 N: a flat-punch contact of 602 um on the 3 mm ball, 20% of its radius.
    let dir = TempDir::new("cli-warn");
    let scene = r#"{"test": {"load_n": 1000, "cycles": 2}, "numerics": {"grid": 32}}"#;
    let output = run_in(dir.path(), &["run", "-"], scene);
    assert!(output.status.success(), "{}", stderr(&output));
    let message = stderr(&output);
    let warned = message.find("warning: test.load_n:").expect("warned");
    let summary = message.find("cycles in").expect("the summary");
    assert!(warned < summary, "{message}");
    let result: Value = serde_json::from_slice(&output.stdout).expect("JSON on a pipe");
    let lines = result["warnings"].as_array().expect("warnings");
    let located = result["field_warnings"].as_array().expect("field_warnings");
    assert_eq!(lines.len(), located.len());
    assert_eq!(located[0]["path"], "test.load_n");
    assert_eq!(
        lines[0].as_str(),
        Some(
            format!(
                "test.load_n: {}",
                located[0]["message"].as_str().unwrap_or("")
            )
            .as_str()
        )
    );
}

#[test]
fn a_long_run_is_estimated_before_its_first_cycle() {
    let dir = TempDir::new("cli-long");
    let mut child = tribosim()
        .args(["run", "-", "-o", "long.json"])
        .current_dir(dir.path())
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start tribosim");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(br#"{"test": {"cycles": 1000000}}"#)
        .expect("write stdin");
    let mut lines = BufReader::new(child.stderr.take().expect("stderr")).lines();
    let first = lines.next().expect("a line").expect("text");
    // The run would take many minutes: the estimate is its first word, then it is stopped.
    child.kill().expect("stopped");
    child.wait().expect("ended");
    assert!(
        first.starts_with("warning: test.cycles: 1000000 cycles"),
        "{first}"
    );
    assert!(
        first.contains("will take about") && first.contains("MB"),
        "{first}"
    );
    assert!(!dir.path().join("long.json").exists());
}

#[test]
fn a_pipe_gets_the_json_and_a_terminal_a_new_file() {
    let dir = TempDir::new("cli-where");
    let output = run_in(dir.path(), &["run", "-"], QUICK);
    assert!(output.status.success(), "{}", stderr(&output));
    let result: Value = serde_json::from_slice(&output.stdout).expect("JSON on a pipe");
    assert_eq!(result["summary"]["cycles"], 2);

    // Under a pseudo-terminal (util-linux's `script`), twice: the second run does not
    // overwrite the first's file.
    std::fs::write(dir.path().join("quick.json"), QUICK).expect("scene");
    let command = format!("{} run quick.json", env!("CARGO_BIN_EXE_tribosim"));
    for _ in 0..2 {
        let status = Command::new("script")
            .args(["-qec", &command, "/dev/null"])
            .current_dir(dir.path())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .status()
            .expect("run script");
        assert!(status.success());
    }
    let mut written: Vec<String> = std::fs::read_dir(dir.path())
        .expect("list")
        .filter_map(|entry| entry.ok()?.file_name().into_string().ok())
        .filter(|name| name.starts_with("result-quick-one-"))
        .collect();
    // `-` sorts before `.`: the second run's `...-2.json` comes first.
    written.sort();
    assert_eq!(written.len(), 2, "{written:?}");
    assert!(written[0].ends_with("-2.json"), "{written:?}");
    let text = std::fs::read_to_string(dir.path().join(&written[1])).expect("read");
    let result: Value = serde_json::from_str(&text).expect("the result");
    assert_eq!(result["summary"]["cycles"], 2);
}

#[test]
fn calibrate_prints_the_fit_readably_and_writes_its_json() {
    let dir = TempDir::new("cli-calibrate");
    let table = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/calibration/table3_hardness.csv");
    let fit = dir.path().join("fit.json");
    let output = tribosim()
        .arg("calibrate")
        .arg("hardness")
        .arg(&table)
        .arg("-o")
        .arg(&fit)
        .output()
        .expect("run calibrate");
    assert!(output.status.success(), "{}", stderr(&output));
    let summary = stderr(&output);
    // Table 3's fit: A = 2455.0 +- 27.0 MPa, B = 63.38 +- 4.96 (tests/calibration.rs).
    assert!(
        summary.contains("a_mpa") && summary.contains("2455.0 +- 26.978"),
        "{summary}"
    );
    assert!(summary.contains("residuals:"), "{summary}");
    assert!(summary.contains("residual_mpa"), "{summary}");
    let json: Value = serde_json::from_slice(&std::fs::read(&fit).expect("fit")).expect("JSON");
    assert!(json["a_mpa"]["value"].is_number());
}

#[test]
fn study_names_itself_after_its_base_and_prints_a_table() {
    let dir = TempDir::new("cli-study");
    let study = r#"{"base": {"name": "tiny", "test": {"cycles": 2}, "numerics": {"grid": 32}},
                    "axes": {"test.load_n": [2, 5]}}"#;
    std::fs::write(dir.path().join("s.json"), study).expect("study");
    let output = run_in(dir.path(), &["study", "s.json", "-o", "summary.json"], "");
    assert!(output.status.success(), "{}", stderr(&output));
    let message = stderr(&output);
    assert!(message.contains("study `tiny`: 2 members"), "{message}");
    assert!(message.contains("| member | test.load_n |"), "{message}");
    let output = run_in(dir.path(), &["study", "s.json", "--max-members", "1"], "");
    assert!(!output.status.success());
    let message = stderr(&output);
    assert!(message.contains("over the limit of 1") && message.contains("--max-members"));
}

#[test]
fn contact_takes_a_measured_map_as_run_does() {
    // A 300 x 300 um map of 1 um pixels, a 0.05 um sine ridge pattern (period 15.7 px), in m.
    let dir = TempDir::new("cli-contact-surface");
    let rows: Vec<String> = (0..300)
        .map(|i| {
            (0..300)
                .map(|j| format!("{:.4e}", 0.05e-6 * ((i + j) as f64 * 0.4).sin()))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(dir.path().join("map.txt"), rows.join("\n") + "\n").expect("map");
    let scene = r#"{"numerics": {"grid": 64}}"#;
    let area = |output: &Output| -> (f64, Value) {
        assert!(output.status.success(), "{}", stderr(output));
        let contact: Value = serde_json::from_slice(&output.stdout).expect("JSON");
        let area = contact["contact_area_mm2"].as_f64().expect("an area");
        (area, contact)
    };
    let args = ["contact", "-", "--surface", "map.txt", "--pixel-um", "1"];
    let (rough, contact) = area(&run_in(dir.path(), &args, scene));
    // The same heights written in um, as a profiler exports them, and said to be: the
    // same contact (each height read as m agrees to the last bit or two, far below any
    // change of the cells in contact).
    let in_um: Vec<String> = rows
        .iter()
        .map(|row| {
            row.split(' ')
                .map(|h| format!("{:.4e}", h.parse::<f64>().expect("a height") * 1e6))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    std::fs::write(dir.path().join("map_um.txt"), in_um.join("\n") + "\n").expect("map");
    let args = [
        "contact",
        "-",
        "--surface",
        "map_um.txt",
        "--pixel-um",
        "1",
        "--height-unit",
        "um",
    ];
    let (from_um, _) = area(&run_in(dir.path(), &args, scene));
    assert!(
        (from_um / rough - 1.0).abs() < 1e-9,
        "{from_um} against {rough}"
    );
    let (smooth, _) = area(&run_in(dir.path(), &["contact", "-"], scene));
    let models = contact["models"].to_string();
    assert!(models.contains("measured `map.txt`"), "{models}");
    // The ridges hold the ball off the valleys: less of the apparent area touches (6.12e-3
    // against 6.58e-3 mm^2 here).
    assert!(rough < smooth, "rough {rough} against smooth {smooth}");
}

#[test]
fn an_output_that_is_not_a_regular_file_is_written_into_not_replaced() {
    // `-o /dev/null` once replaced the device with a regular file (the temporary file's
    // rename); a named pipe stands in for it here, since a failure on /dev/null itself
    // would break the machine the test runs on.
    use std::os::unix::fs::FileTypeExt;
    let dir = TempDir::new("cli-fifo");
    let fifo = dir.path().join("out.pipe");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).expect("read the pipe"))
    };
    let output = run_in(dir.path(), &["run", "-", "-o", "out.pipe"], QUICK);
    assert!(output.status.success(), "{}", stderr(&output));
    let result: Value = serde_json::from_str(&reader.join().expect("reader")).expect("JSON");
    assert_eq!(result["summary"]["cycles"], 2);
    let kind = std::fs::metadata(&fifo).expect("still there").file_type();
    assert!(kind.is_fifo(), "the pipe was replaced: {kind:?}");
}

/// The standard output of `tribosim ARGS`, which must succeed.
fn help_of(args: &[&str]) -> String {
    let output = tribosim().args(args).output().expect("start tribosim");
    assert!(output.status.success(), "tribosim {args:?}");
    String::from_utf8(output.stdout).expect("UTF-8")
}

#[test]
fn the_help_lists_the_verbs_first_and_each_verb_has_an_example() {
    let top = help_of(&["--help"]);
    let commands = top.find("Commands:").expect("the verbs are listed");
    // The server's options are behind `tribosim serve --help`, not before the verbs.
    assert!(!top.contains("--addr"), "{top}");
    assert!(top[commands..].contains("tribosim serve --help"), "{top}");
    assert!(help_of(&["serve", "--help"]).contains("--addr"));
    let verbs = [
        "serve",
        "run",
        "contact",
        "presets",
        "report",
        "calibrate",
        "study",
        "bench",
    ];
    for verb in verbs {
        let help = help_of(&[verb, "--help"]);
        let example = help
            .find("Example")
            .unwrap_or_else(|| panic!("{verb}: {help}"));
        assert!(
            help[example..].contains(&format!("tribosim {verb}")),
            "{verb}: {help}"
        );
    }
    assert!(help_of(&["study", "collect", "--help"]).contains("tribosim study collect"));
}
