//! Studies: the expansion of axes into member scenes, the refusals, and running members on
//! worker threads against running the same scenes one by one.

use std::sync::atomic::AtomicBool;

use serde_json::{Value, json};

use tribosim::simulation::{Plan, SimulationError, Summary, parse_scene, run};
use tribosim::study::{MAX_MEMBERS, Member, Study, StudyError, StudySummary, run_members};

/// The quick preset at the smallest grid and few cycles: a member runs in well under a
/// second, so a 2 x 2 study stays cheap on a shared machine.
fn tiny_base() -> Value {
    json!({
        "preset": "dalmau2018-316l",
        "overrides": {"test": {"cycles": 20}, "numerics": {"grid": 32}}
    })
}

/// A study of the tiny base over `axes`, given as text: a `Value` would sort them.
fn study(axes: &str) -> Result<Study, StudyError> {
    Study::parse(&format!(r#"{{"base": {}, "axes": {axes}}}"#, tiny_base()))
}

fn members(axes: &str) -> Result<Vec<Member>, StudyError> {
    study(axes)?.members(MAX_MEMBERS)
}

#[test]
fn the_first_axis_varies_slowest_and_a_range_includes_both_ends() {
    // Axes written out of alphabetical order: the file's order must win.
    let members = members(
        r#"{
        "test.speed_rpm": {"from": 30, "to": 60, "steps": 2},
        "test.load_n": [2, 5]
    }"#,
    )
    .expect("a valid study");
    let got: Vec<(f64, f64)> = members
        .iter()
        .map(|m| (m.scene.test.speed_rpm, m.scene.test.load_n))
        .collect();
    let want = [
        (30.0, 2.0),
        (30.0, 5.0),
        (45.0, 2.0),
        (45.0, 5.0),
        (60.0, 2.0),
        (60.0, 5.0),
    ];
    // Integers and their halves are exact in binary floating point, so equality is exact.
    assert_eq!(got, want);
    assert_eq!(
        members.iter().map(|m| m.index).collect::<Vec<_>>(),
        (0..6).collect::<Vec<_>>()
    );
    assert_eq!(
        members[3].values,
        vec![
            ("test.speed_rpm".to_owned(), json!(45)),
            ("test.load_n".to_owned(), json!(5))
        ]
    );
    // The preset's other overrides survive the axes being set beside them.
    assert!(members.iter().all(|m| m.scene.test.cycles == 20));
}

#[test]
fn an_integer_field_takes_a_range_with_integer_ends() {
    let members = members(r#"{"test.cycles": {"from": 10, "to": 30, "steps": 4}}"#)
        .expect("integer steps of 5 are integers");
    let cycles: Vec<u64> = members.iter().map(|m| m.scene.test.cycles).collect();
    assert_eq!(cycles, [10, 15, 20, 25, 30]);
}

#[test]
fn a_base_without_a_preset_is_set_at_the_path_itself() {
    let text = json!({
        "base": {"test": {"cycles": 20}, "numerics": {"grid": 32}},
        "axes": {"test.load_n": [3]}
    })
    .to_string();
    let members = Study::parse(&text)
        .and_then(|s| s.members(MAX_MEMBERS))
        .expect("valid");
    let mut direct =
        parse_scene(&json!({"test": {"cycles": 20, "load_n": 3}, "numerics": {"grid": 32}}))
            .expect("valid scene")
            .into_scene();
    // The member's name is the only difference: the base's name with the member's values.
    direct.name = format!("{} [test.load_n = 3]", direct.name);
    assert_eq!(members[0].scene, direct);
}

/// The refusal's message, which must name what is wrong.
fn refusal(axes: &str) -> String {
    match members(axes) {
        Ok(members) => panic!("accepted a bad study: {} members", members.len()),
        Err(error) => error.to_string(),
    }
}

#[test]
fn bad_axes_are_refused_naming_the_axis() {
    let empty = refusal(r#"{"test.load_n": [2], "test.speed_rpm": []}"#);
    assert!(
        empty.contains("test.speed_rpm") && empty.contains("no values"),
        "{empty}"
    );

    let no_steps = refusal(r#"{"test.speed_rpm": {"from": 30, "to": 60, "steps": 0}}"#);
    assert!(
        no_steps.contains("test.speed_rpm") && no_steps.contains("step"),
        "{no_steps}"
    );

    let not_values = refusal(r#"{"test.load_n": 5}"#);
    assert!(not_values.contains("test.load_n"), "{not_values}");

    let through_a_number = refusal(r#"{"test.cycles.x": [1]}"#);
    assert!(
        through_a_number.contains("test.cycles.x") && through_a_number.contains("not an object"),
        "{through_a_number}"
    );

    // An unknown field and an out-of-range value are the scene parser's to name, at their
    // place in the user's document (under `overrides` for a preset).
    let unknown = refusal(r#"{"test.lod_n": [2, 5]}"#);
    assert!(
        unknown.contains("overrides.test.lod_n") && unknown.contains("unknown field"),
        "{unknown}"
    );
    let out_of_range = refusal(r#"{"test.load_n": [5, -1]}"#);
    assert!(
        out_of_range.contains("overrides.test.load_n") && out_of_range.contains("member 1"),
        "{out_of_range}"
    );

    assert!(matches!(members(r#"{}"#), Err(StudyError::NoAxes)));
}

#[test]
fn a_study_over_the_member_limit_is_refused_before_any_member_is_built() {
    // 11^3 = 1331 members, over the default limit of 1000.
    let eleven = r#"{"from": 1, "to": 11, "steps": 10}"#;
    let big = study(&format!(
        r#"{{"test.load_n": {eleven}, "test.speed_rpm": {eleven}, "test.cycles": {eleven}}}"#
    ))
    .expect("well-formed");
    assert_eq!(big.member_count(), 1331);
    match big.members(MAX_MEMBERS) {
        Err(StudyError::TooManyMembers {
            members,
            sizes,
            limit,
        }) => {
            assert_eq!((members, limit), (1331, MAX_MEMBERS));
            assert_eq!(
                sizes,
                "test.load_n: 11 x test.speed_rpm: 11 x test.cycles: 11"
            );
        }
        other => panic!("expected the member limit, got {other:?}"),
    }
    // The limit is the caller's: the same 6-member study passes at 6 and fails at 5.
    let six = study(r#"{"test.load_n": [2, 5, 10], "test.speed_rpm": [30, 60]}"#).expect("ok");
    assert_eq!(six.members(6).map(|m| m.len()).ok(), Some(6));
    assert!(matches!(
        six.members(5),
        Err(StudyError::TooManyMembers { members: 6, .. })
    ));
}

#[test]
fn a_key_given_twice_and_a_malformed_file_are_refused() {
    let text = r#"{"base": {}, "axes": {"test.load_n": [2], "test.load_n": [5]}}"#;
    let error = Study::parse(text).expect_err("duplicate axis");
    assert!(error.to_string().contains("axes.test.load_n"), "{error}");

    let no_axes_key = Study::parse(r#"{"base": {}}"#).expect_err("no axes");
    assert!(no_axes_key.to_string().contains("axes"), "{no_axes_key}");
    let not_a_scene = Study::parse(r#"{"base": 5, "axes": {"test.load_n": [2]}}"#)
        .and_then(|s| s.members(MAX_MEMBERS))
        .expect_err("a number is no scene");
    assert!(matches!(not_a_scene, StudyError::BaseNotObject));
}

/// A summary without its wall time, the one number that differs between two runs.
fn without_wall_time(summary: &Summary) -> Summary {
    Summary {
        wall_s: 0.0,
        ..summary.clone()
    }
}

#[test]
fn a_two_by_two_study_on_two_workers_equals_its_members_run_one_by_one() {
    let members = members(r#"{"test.load_n": [2, 5], "test.speed_rpm": [30, 60]}"#).expect("valid");
    let outcomes = run_members(&members, 2, &AtomicBool::new(false), &mut |_, _| {});
    assert_eq!(outcomes.len(), 4);
    for (member, outcome) in members.iter().zip(&outcomes) {
        assert_eq!(outcome.index, member.index);
        let plan = Plan::new(member.scene.clone()).expect("valid");
        let alone = run(&plan, &mut |_| {}, &AtomicBool::new(false)).expect("runs");
        let in_study = outcome.result.as_ref().expect("runs in the study");
        // The same code on the same scene in one process takes the same floating-point
        // steps whichever thread runs it: equal to the last bit, no tolerance.
        assert_eq!(
            without_wall_time(&in_study.summary),
            without_wall_time(&alone.summary)
        );
        assert_eq!(in_study.cycles, alone.cycles);
        assert_eq!(in_study.profiles, alone.profiles);
    }
    let summary = StudySummary::new(&members, &outcomes, 2, 0.0);
    assert_eq!(summary.failed(), 0);
    assert_eq!(summary.axes, ["test.load_n", "test.speed_rpm"]);
    // A header and a separator, then one line per member.
    assert_eq!(summary.to_markdown().lines().count(), 2 + 4);
    assert_eq!(summary.to_csv().lines().count(), 1 + 4);
}

#[test]
fn a_failed_member_leaves_the_others_and_a_cancel_stops_those_not_started() {
    let mut members = members(r#"{"test.load_n": [2, 5, 10]}"#).expect("valid");
    // A scene the parser would refuse, given directly as a library caller could: the run
    // refuses it, the other two still run.
    members[1].scene.test.load_n = -1.0;
    let outcomes = run_members(&members, 2, &AtomicBool::new(false), &mut |_, _| {});
    assert!(outcomes[0].result.is_ok() && outcomes[2].result.is_ok());
    assert!(matches!(outcomes[1].result, Err(SimulationError::Scene(_))));
    let summary = StudySummary::new(&members, &outcomes, 2, 0.0);
    assert_eq!(summary.failed(), 1);
    assert!(summary.members[1].error.is_some() && summary.members[1].summary.is_none());

    // A cancel set before the study starts leaves every member unstarted; a cancel during
    // a member is the run's own (tested with the simulation), which the workers pass on.
    let cancel = AtomicBool::new(true);
    let outcomes = run_members(&members, 2, &cancel, &mut |_, _| {});
    assert_eq!(outcomes.len(), 3);
    for outcome in &outcomes {
        assert!(matches!(
            outcome.result,
            Err(SimulationError::Cancelled { cycles_done: 0 })
        ));
    }
}

#[test]
fn the_documented_example_expands_as_docs_study_md_says() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/study-load-speed.json");
    let text = std::fs::read_to_string(path).expect("the example is in scenes/");
    let members = Study::parse(&text)
        .and_then(|s| s.members(MAX_MEMBERS))
        .expect("the example is a valid study");
    let got: Vec<(f64, f64)> = members
        .iter()
        .map(|m| (m.scene.test.load_n, m.scene.test.speed_rpm))
        .collect();
    assert_eq!(
        got,
        [
            (2.0, 30.0),
            (2.0, 60.0),
            (5.0, 30.0),
            (5.0, 60.0),
            (10.0, 30.0),
            (10.0, 60.0)
        ]
    );
}

#[test]
fn the_command_writes_the_summary_and_names_the_flag_over_the_limit() {
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/study-load-speed.json");
    let output = std::env::temp_dir().join(format!("tribosim-study-{}.json", std::process::id()));
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["study", example, "--workers", "2", "-o"])
        .arg(&output)
        .stderr(std::process::Stdio::null())
        .status()
        .expect("the binary starts");
    let text = std::fs::read_to_string(&output).expect("the summary is written");
    let _ = std::fs::remove_file(&output);
    assert!(status.success());
    let summary: StudySummary = serde_json::from_str(&text).expect("the summary's JSON");
    assert_eq!(
        (summary.members.len(), summary.failed(), summary.workers),
        (6, 0, 2)
    );

    let refused = std::process::Command::new(env!("CARGO_BIN_EXE_tribosim"))
        .args(["study", example, "--max-members", "5"])
        .output()
        .expect("the binary starts");
    let message = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success());
    assert!(
        message.contains("6 members") && message.contains("--max-members"),
        "{message}"
    );
}

#[test]
fn a_study_and_its_members_are_named_after_the_study_and_their_own_values() {
    // The tiny base starts from the paper's preset and names nothing. The preset's name
    // states 5 N and 60 rpm, which a member at 2 N contradicts: the study is called after
    // the preset's id and its axes instead.
    let from_preset = study(r#"{"test.load_n": [2, 5]}"#).expect("a valid study");
    assert_eq!(from_preset.name(), "dalmau2018-316l varied in test.load_n");
    let members = from_preset.members(MAX_MEMBERS).expect("members");
    assert_eq!(
        members[0].scene.name,
        "dalmau2018-316l varied in test.load_n [test.load_n = 2]"
    );
    let named = Study::parse(
        r#"{"base": {"name": "a base", "test": {"cycles": 2}}, "axes": {"test.load_n": [2, 5]}}"#,
    )
    .expect("a valid study");
    assert_eq!(named.name(), "a base");
    let members = named.members(MAX_MEMBERS).expect("members");
    assert_eq!(members[1].scene.name, "a base [test.load_n = 5]");
    // A study's own name wins over its base's, in its members' names too.
    let own = Study::parse(
        r#"{"name": "loads", "base": {"preset": "dalmau2018-316l"},
            "axes": {"test.load_n": [2, 5], "test.speed_rpm": [30]}}"#,
    )
    .expect("a valid study");
    assert_eq!(own.name(), "loads");
    let members = own.members(MAX_MEMBERS).expect("members");
    assert_eq!(
        members[0].scene.name,
        "loads [test.load_n = 2, test.speed_rpm = 30]"
    );
    for member in &members {
        assert!(!member.scene.name.contains("5 N"), "{}", member.scene.name);
    }
}
