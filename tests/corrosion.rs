//! The corrosion half of the paper's test against the paper's own data (Section 5.1, Figs. 6
//! and 14, Table 3): the default repassivation time is the fit to the paper's depassivated
//! area, `{}` reads the potential the paper infers, dissolves less than Table 3 measured in
//! all, and speed and load move the potential as the depassivated wake says. Also the OCP
//! trace, the reference electrodes and the warnings that replace silent clamps.

mod common {
    pub mod physics;
}

use std::path::PathBuf;

use common::physics::{scene, simulate};
use serde_json::json;
use tribosim::calibration::{OcpOptions, Table, fit_ocp};
use tribosim::scene::{PAPER_REPASSIVATION_TIME_S, Scene, TABLE3_TIMES_S};
use tribosim::simulation::{OcpPhase, SimulationResult};

/// Table 3's total volumes after each rubbing time, mm^3.
const TABLE3_TOTAL_MM3: [f64; 5] = [0.97e-3, 1.09e-3, 1.18e-3, 5.33e-3, 11.72e-3];

fn example(name: &str) -> Table {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("docs/calibration")
        .join(name);
    let text = std::fs::read_to_string(&path).expect("the example table is readable");
    Table::parse(&text).expect("a valid table")
}

fn run(json: &str) -> SimulationResult {
    simulate(&scene(json)).expect("runs")
}

/// The record of `result` at `cycle`, which the scene records exactly.
fn potential_at(result: &SimulationResult, cycle: u64) -> f64 {
    let record = result.cycles.iter().find(|r| r.cycle == cycle);
    record
        .and_then(|r| r.potential_v)
        .unwrap_or_else(|| panic!("no potential at cycle {cycle}"))
}

#[test]
fn the_default_repassivation_time_is_the_fit_to_the_papers_fig_14() {
    // docs/calibration/paper_ocp.csv: eq. 18 at A_a = 50 F / H at Table 3's times. Fitted on
    // the default run (the scene's own numerics), tau is the default constant to the three
    // digits it is written with: a change of the mechanics that moves the fit fails here.
    let fit = fit_ocp(
        &example("paper_ocp.csv"),
        &Scene::default(),
        OcpOptions::default(),
    )
    .expect("fits");
    let tau = fit.repassivation_time_s.expect("the wake's tau is fitted");
    println!(
        "tau = {:.5} +- {:.5} s, Q_p = {:?} mC/cm2, rms {:.4} V, A_a / (F/H) = {:.1}",
        tau.value,
        tau.standard_error,
        fit.repassivation_charge_mc_cm2,
        fit.rms_residual_v,
        fit.anodic_to_real_contact
    );
    for point in &fit.points {
        println!(
            "{:6} s: measured {:.4} V, model {:.4} V, residual {:+.4} V",
            point.time_s, point.potential_v, point.model_potential_v, point.residual_v
        );
    }
    assert!(
        (tau.value - PAPER_REPASSIVATION_TIME_S).abs() <= 0.5e-3,
        "fit {tau:?} against the default {PAPER_REPASSIVATION_TIME_S} s"
    );
    // The same potentials as a whole trace on the potentiostat's clock: the same run, the
    // same rubbing rows, so the same tau.
    let options = OcpOptions {
        rubbing_start_s: Some(3600.0),
        rubbing_stop_s: Some(7200.0),
    };
    let trace = fit_ocp(&example("paper_ocp_trace.csv"), &Scene::default(), options).expect("fits");
    let same = trace.repassivation_time_s.expect("fitted");
    assert!(
        (same.value - tau.value).abs() < 1e-12 * tau.value,
        "{same:?}"
    );
    assert!((trace.scene.test.ocp_before_s - 3600.0).abs() < 1e-12);
    assert_eq!(trace.scene.test.cycles, 3600);
}

#[test]
fn the_papers_test_reads_the_papers_potential_and_dissolves_less_than_was_measured() {
    let result = run("{}");
    // Section 5.1: the potential of A_a = 50 F / H, -0.377 V at 10 s to -0.341 V at 3600 s
    // (docs/calibration/paper_ocp.csv), a few hundred mV below E_corr = -0.10 V; the issue
    // asks -0.30 to -0.40 V through the run. Measured: -0.326 to -0.397 V.
    for record in &result.cycles {
        let potential = record.potential_v.expect("corrosion on");
        assert!(
            (-0.40..=-0.30).contains(&potential),
            "cycle {}: {potential} V",
            record.cycle
        );
    }
    // Table 3's volumes are totals, corrosion included: the model's corrosion alone must
    // stay below each. Measured shares (316L, `corrosion.faraday`): 0.3, 1.5, 6.9, 10.2 and 9.9%.
    for (time, measured) in TABLE3_TIMES_S.iter().zip(TABLE3_TOTAL_MM3) {
        let record = result
            .cycles
            .iter()
            .find(|r| r.cycle == *time as u64)
            .expect("Table 3's times are recorded");
        let wac = record.wac_volume_mm3.expect("corrosion on");
        assert!(
            wac < measured,
            "{time} s: WAC {wac} against {measured} mm^3"
        );
    }
    // Nothing capped, nothing outside the Tafel line's domain, no WAC above the total.
    assert!(result.warnings.is_empty(), "{:?}", result.warnings);
    assert_eq!(
        result.ocp_trace.first().map(|s| (s.potential_v, s.phase)),
        Some((-0.10, OcpPhase::Before))
    );
}

#[test]
fn a_faster_disc_and_a_heavier_load_read_lower() {
    // The wake's area F / H (1 + v tau / L): v tau grows with the speed, and F / H / L with
    // the load (as F^(2/3) for a Hertz contact). At 300 s of rubbing on 48 cells.
    let at_300_s = |test: serde_json::Value| {
        let speed = test["speed_rpm"].as_f64().unwrap_or(60.0);
        let cycles = (300.0 * speed / 60.0) as u64;
        let mut test = test;
        test["cycles"] = json!(cycles);
        let document = json!({"test": test, "numerics": {"grid": 48}});
        potential_at(&run(&document.to_string()), cycles)
    };
    let slow = at_300_s(json!({"speed_rpm": 30}));
    let paper = at_300_s(json!({"speed_rpm": 60}));
    let fast = at_300_s(json!({"speed_rpm": 120}));
    println!("30, 60, 120 rpm: {slow:.4}, {paper:.4}, {fast:.4} V");
    assert!(fast < paper && paper < slow, "{slow} {paper} {fast}");
    let light = at_300_s(json!({"load_n": 2}));
    let heavy = at_300_s(json!({"load_n": 10}));
    println!("2, 5, 10 N: {light:.4}, {paper:.4}, {heavy:.4} V");
    assert!(heavy < paper && paper < light, "{light} {paper} {heavy}");
}

#[test]
fn the_whole_trace_holds_e_corr_drops_and_recovers() {
    let result = run(
        r#"{"test": {"cycles": 20, "ocp_before_s": 3600, "ocp_after_s": 1200},
        "numerics": {"grid": 48}}"#,
    );
    let trace = &result.ocp_trace;
    let first = trace[0];
    assert_eq!((first.time_s, first.phase), (0.0, OcpPhase::Before));
    // Whole seconds plus whole cycles of 1 s: exact in binary, compared as bits.
    assert_eq!(trace[1].time_s.to_bits(), 3600f64.to_bits());
    let rubbing: Vec<_> = trace
        .iter()
        .filter(|s| s.phase == OcpPhase::Rubbing)
        .collect();
    assert_eq!(rubbing.len(), result.cycles.len());
    // The first cycle ends 1 s after the start, at the record's potential.
    assert_eq!(rubbing[0].time_s.to_bits(), 3601f64.to_bits());
    assert!(rubbing.iter().all(|s| s.potential_v < -0.3));
    let after: Vec<_> = trace
        .iter()
        .filter(|s| s.phase == OcpPhase::After)
        .collect();
    // The potential rises monotonically back to E_corr, which the record ends at.
    assert!(
        after
            .windows(2)
            .all(|w| w[1].potential_v >= w[0].potential_v)
    );
    let last = after.last().expect("after points");
    assert_eq!((last.time_s, last.potential_v), (4820.0, -0.10));
    assert!(after[0].potential_v < -0.2, "{after:?}");
}

#[test]
fn another_reference_electrode_shifts_every_potential_and_names_itself() {
    let base = r#"{"test": {"cycles": 10}, "numerics": {"grid": 32}"#;
    let agcl = run(&format!("{base}}}"));
    let sce = run(&format!(
        r#"{base}, "corrosion": {{"reference_electrode": "sce"}}}}"#
    ));
    // Ag/AgCl (3 M KCl) is +0.205 V and SCE +0.241 V against SHE: every SCE potential is
    // 36 mV lower, to the rounding of the shifted E_corr.
    for (a, s) in agcl.cycles.iter().zip(&sce.cycles) {
        let shift = s.potential_v.expect("on") - a.potential_v.expect("on");
        assert!((shift + 0.036).abs() < 1e-12, "{shift}");
        assert_eq!(s.anodic_area_mm2, a.anodic_area_mm2);
    }
    let reference = serde_json::to_value(sce.summary.potential_reference).expect("serialises");
    assert_eq!(reference, json!("sce"));
    assert!(sce.summary.to_string().contains("V vs SCE"));
}

#[test]
fn a_clamped_potential_and_an_oversized_anode_are_said_not_hidden() {
    // The issue's silent clamp: F / H alone (factor 1) puts eq. 18 at +0.59 V, above
    // E_corr; the run reads E_corr and says why.
    let capped = run(r#"{"test": {"cycles": 5}, "numerics": {"grid": 32},
        "corrosion": {"anodic_area": "real_contact"}}"#);
    assert!(capped.cycles.iter().all(|r| r.potential_v == Some(-0.10)));
    assert!(
        capped
            .warnings
            .iter()
            .any(|w| w.contains("capped at E_corr")
                && w.contains("at 5 solved cycle(s), the first at cycle 1")),
        "{:?}",
        capped.warnings
    );
    let reason = &capped
        .models
        .iter()
        .find(|m| m.name == tribosim::simulation::Model::Corrosion)
        .expect("a corrosion model")
        .reason;
    assert!(reason.contains("capped at E_corr"), "{reason}");
    // The paper's Fig. 13 anode, the whole wear track: 4.7 times Table 3's measured total
    // dissolved by 3600 s, and below the -1.1 V end of Table 2's scan.
    let track = run(r#"{"numerics": {"grid": 48}, "corrosion": {"anodic_area": "wear_track"}}"#);
    let warnings = track.warnings.join("\n");
    assert!(
        warnings.contains("exceeds the total volume measured after 3600 s"),
        "{warnings}"
    );
    assert!(
        warnings.contains("outside the domain the Tafel line"),
        "{warnings}"
    );
}

#[test]
fn an_implausible_cell_is_refused_at_its_field_with_the_slip() {
    // The unit slips of the issue: each refused at its own path, naming the likely slip.
    let refused = |corrosion: serde_json::Value, path: &str, slip: &str| {
        let document = json!({"test": {"cycles": 5}, "corrosion": corrosion});
        let errors = tribosim::simulation::parse_scene(&document).expect_err("implausible");
        let found = errors.0.iter().find(|e| e.path == path);
        let message = found.map_or("", |e| e.message.as_str());
        assert!(message.contains(slip), "{path}: {errors}");
    };
    refused(
        json!({"tafel_b_c_v_per_decade": 100.0}),
        "corrosion.tafel_b_c_v_per_decade",
        "was it in mV/decade? 100 mV/decade = 0.1 V/decade",
    );
    refused(
        json!({"corrosion_potential_v": 1e300}),
        "corrosion.corrosion_potential_v",
        "was it in mV?",
    );
    refused(
        json!({"anodic_current_density_a_cm2": 1000.0}),
        "corrosion.anodic_current_density_a_cm2",
        "was it in mA/cm^2 (1000 mA/cm^2 = 1 A/cm^2)",
    );
    // a_c 1000 times Table 2's line current is a_c + 0.56 x 3 = -1.63 V: warned, not
    // refused (a current a real cell may give).
    let plan = tribosim::simulation::parse_scene(&json!({"corrosion": {"tafel_a_c_v": -1.63}}))
        .expect("a warning only");
    let warnings = plan
        .warnings()
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>();
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("mA/cm^2 typed as A/cm^2")),
        "{warnings:?}"
    );
}

#[test]
fn no_total_is_below_its_own_wac() {
    // 5 A/cm^2 on the whole wear track, a pit's current (warned, not refused): its WAC
    // outgrows the wear track k fitted on total losses makes the total. The total reads the
    // WAC, the mechanical part 0, and the run says so; once the total read the track.
    let result = run(r#"{"test": {"cycles": 20}, "numerics": {"grid": 32},
        "corrosion": {"anodic_area": "wear_track", "anodic_current_density_a_cm2": 5.0}}"#);
    let last = result.cycles.last().expect("records");
    let wac = last.wac_volume_mm3.expect("on");
    // The WAC outgrew the groove: the mechanical part reads 0, and the volume lost (the
    // total, `wear_volume_mm3` in every run) is the WAC itself.
    assert_eq!(last.mechanical_volume_mm3, Some(0.0));
    assert_eq!(last.wear_volume_mm3.to_bits(), wac.to_bits());
    for record in &result.cycles {
        let (total, wac) = (
            record.total_volume_mm3.expect("on"),
            record.wac_volume_mm3.expect("on"),
        );
        assert!(
            total >= wac,
            "cycle {}: total {total} below WAC {wac}",
            record.cycle
        );
    }
    assert!(
        result
            .warnings
            .iter()
            .any(|w| w.contains("the total reads the WAC")),
        "{:?}",
        result.warnings
    );
}

/// The spot models on 48 cells over `cycles` cycles, with `test` and `corrosion` merged in.
fn spots_run(test: &serde_json::Value, corrosion: &serde_json::Value) -> SimulationResult {
    let mut section = json!({"anodic_area": "contact_spots", "galvanic_cell": "balanced",
                             "bare_corrosion_potential_v": -0.6});
    if let (Some(s), Some(extra)) = (section.as_object_mut(), corrosion.as_object()) {
        s.extend(extra.clone());
    }
    let document = json!({"test": test, "corrosion": section, "numerics": {"grid": 48}});
    run(&document.to_string())
}

#[test]
fn spots_pass_into_incomplete_repassivation_at_speed_without_refusing() {
    let slow = spots_run(&json!({"cycles": 100}), &json!({}));
    // 6000 rpm: a revolution of 10 ms, one tau: the film cannot regrow between passes.
    let fast = spots_run(&json!({"cycles": 100, "speed_rpm": 6000}), &json!({}));
    let heavy = spots_run(&json!({"cycles": 100, "load_n": 10}), &json!({}));
    let (e_slow, e_fast, e_heavy) = (
        potential_at(&slow, 100),
        potential_at(&fast, 100),
        potential_at(&heavy, 100),
    );
    println!("60 rpm {e_slow:.4} V, 6000 rpm {e_fast:.4} V, 10 N {e_heavy:.4} V");
    assert!(
        e_fast < e_slow && e_heavy < e_slow,
        "{e_slow} {e_fast} {e_heavy}"
    );
    // The bare metal's own potential bounds every reading.
    for result in [&slow, &fast, &heavy] {
        assert!(result.cycles.iter().all(|r| r.potential_v > Some(-0.6)));
    }
    let incomplete = |r: &SimulationResult| {
        r.field_warnings
            .iter()
            .any(|w| w.message.starts_with("incomplete repassivation"))
    };
    assert!(incomplete(&fast) && !incomplete(&slow));
}

#[test]
fn a_power_law_transient_recovers_over_the_hold_after_the_stop() {
    let after = |kinetics: &str| -> Vec<(f64, f64)> {
        let result = spots_run(
            &json!({"cycles": 20, "ocp_after_s": 1200}),
            &json!({"repassivation_kinetics": kinetics, "repassivation_time_s": 0.001}),
        );
        result
            .ocp_trace
            .iter()
            .filter(|s| s.phase == OcpPhase::After)
            .map(|s| (s.time_s - 20.0, s.potential_v))
            .collect()
    };
    let (power, exponential) = (after("power_law"), after("exponential"));
    println!("power law {power:?}\nexponential {exponential:?}");
    // Rising all the way (Fig. 6's recovery).
    assert!(power.windows(2).all(|w| w[1].1 > w[0].1), "{power:?}");
    // The exponential of the same 1 ms is back at E_corr within a second: exp(-1000) of its
    // charge is left, which underflows to 0, and the balanced cell without an anode reads
    // E_corr to the rounding of a_c - b_c log10(10^(a_c / b_c)), about 1e-15 V.
    let second = |trace: &[(f64, f64)]| trace.iter().find(|(t, _)| *t >= 1.0).map(|p| p.1);
    assert!((second(&exponential).expect("sampled") + 0.10).abs() < 1e-9);
    // The t^-1/2 tail still holds the potential 20 mV below E_corr a minute after the stop
    // (measured: 46 mV at 64 s) and short of E_corr at the end of the hold (11.8 mV at 1200
    // s), as the paper's Fig. 6 recovers over its 1200 s.
    let minute = power.iter().find(|(t, _)| *t >= 60.0).expect("sampled");
    assert!(minute.1 < -0.12, "{minute:?}");
    let end = power.last().expect("sampled");
    assert!(end.1 < -0.10 - 1e-3, "{end:?}");
}

#[test]
fn a_potentiostat_below_the_bare_metals_potential_stops_the_wac() {
    let held = |volts: f64| {
        spots_run(
            &json!({"cycles": 20}),
            &json!({"control": "potentiostatic", "applied_potential_v": volts}),
        )
    };
    // Cathodic protection, 0.3 V below the bare metal's -0.6 V: nothing dissolves.
    let protected = held(-0.9);
    assert!(protected.ocp_trace.is_empty());
    for record in &protected.cycles {
        assert_eq!(record.potential_v, Some(-0.9));
        assert_eq!(record.wac_volume_mm3, Some(0.0));
    }
    // At -0.2 V the bare spots pass i_a (1 - 10^(-0.4 / 0.56)) = 0.8069 of i_a.
    let anodic = held(-0.2);
    let last = anodic.cycles.last().expect("records");
    let area_cm2 = last.anodic_area_mm2.expect("an area") * 1e-2;
    let share = last.anodic_current_ma.expect("a current") / (area_cm2 * 10.0);
    let expected = 1.0 - 10f64.powf(-0.4 / 0.56);
    // Products and one powf: 1e-12 relative.
    assert!(
        (share - expected).abs() < 1e-12,
        "{share} against {expected}"
    );
    assert!(last.wac_volume_mm3 > Some(0.0));
    // Without the bare metal's potential the potentiostat cannot say what dissolves.
    let errors = tribosim::scene::parse_scene_str(
        r#"{"corrosion": {"control": "potentiostatic", "applied_potential_v": -0.9}}"#,
    )
    .expect_err("refused");
    assert!(
        errors
            .to_string()
            .contains("corrosion.bare_corrosion_potential_v"),
        "{errors}"
    );
}
