//! The reciprocating rig as a scene (`test.reciprocating`): what it refuses, and what its
//! result holds, checked against the conservation of the wear and the stroke's kinematics.

use std::sync::atomic::AtomicBool;

use serde_json::{Value, json};
use tribosim::report::{Measured, run_report};
use tribosim::simulation::{SimulationResult, TRACE_SAMPLES, parse_scene, run};

/// A short stroke on a coarse grid: the paper's pair and cell at 1 Hz.
fn scene(extra: Value) -> Value {
    let mut scene = json!({
        "test": {"cycles": 6, "reciprocating": {"stroke_mm": 0.6, "frequency_hz": 1.0}},
        "numerics": {"grid": 32, "record_cycles": [3]}
    });
    merge(&mut scene, extra);
    scene
}

fn merge(into: &mut Value, from: Value) {
    match (into, from) {
        (Value::Object(a), Value::Object(b)) => {
            for (k, v) in b {
                merge(a.entry(k).or_insert(Value::Null), v);
            }
        }
        (slot, v) => *slot = v,
    }
}

fn result(scene: &Value) -> SimulationResult {
    let plan = parse_scene(scene).expect("a valid scene");
    run(&plan, &mut |_| {}, &AtomicBool::new(false)).expect("runs")
}

fn refused_at(scene: &Value) -> Vec<String> {
    match parse_scene(scene) {
        Ok(_) => Vec::new(),
        Err(errors) => errors.0.into_iter().map(|e| e.path).collect(),
    }
}

#[test]
fn the_map_holds_the_volume_and_the_ends_wear_less_than_the_middle() {
    let result = result(&scene(json!({})));
    let stroke = result.stroke.as_ref().expect("a reciprocating result");
    let map = &stroke.map;
    // The map's blocks are whole here (under 400 columns), so its sum times the cells is
    // the volume the records give: the same numbers summed in another order, 1e-12.
    assert!(map.x_um.len() < 400);
    let dx_um = map.x_um[1] - map.x_um[0];
    let dy_um = map.y_um[1] - map.y_um[0];
    let sum: f64 = map.depth_um.iter().flatten().sum();
    let volume_mm3 = sum * dx_um * dy_um * 1e-9;
    let recorded = result.summary.wear_volume_mm3;
    assert!(
        ((volume_mm3 - recorded) / recorded).abs() < 1e-12,
        "{volume_mm3} {recorded}"
    );
    // Along the axis: the middle is the deepest, and the points beyond the ball's reach
    // (a contact radius past the turning points) are unworn.
    let axis = &stroke.axial_profile;
    let middle = axis.depth_um[axis.depth_um.len() / 2];
    let deepest = axis.depth_um.iter().copied().fold(0.0, f64::max);
    assert!(
        (deepest - middle).abs() <= 1e-9 * deepest,
        "{deepest} {middle}"
    );
    assert_eq!(axis.depth_um[0].to_bits(), 0.0_f64.to_bits());
    // At a turning point the ball covers the track on one side of its centre only.
    let end = axis
        .x_um
        .iter()
        .position(|&x| x >= -300.0)
        .expect("the start of the stroke");
    assert!(axis.depth_um[end] > 0.0 && axis.depth_um[end] < 0.75 * middle);
    // The profile across the middle is the map's middle, and the records' deepest point
    // is the map's.
    let profile = result.profiles.last().expect("the last cycle's profile");
    assert_eq!(profile.cycle, 6);
    let across = profile.depth_um.iter().copied().fold(0.0, f64::max);
    assert!((across - result.summary.max_depth_um).abs() <= 1e-9 * across);
}

#[test]
fn the_potential_oscillates_at_twice_the_frequency_and_corrosion_stays_within_the_loss() {
    let result = result(&scene(json!({"corrosion": {"anodic_area": "contact_spots",
                                                     "repassivation_time_s": 0.05}})));
    let stroke = result.stroke.as_ref().expect("a reciprocating result");
    let cycles: Vec<u64> = stroke.traces.iter().map(|t| t.cycle).collect();
    assert_eq!(
        cycles,
        [1, 3, 6],
        "the first, the recorded and the last cycle"
    );
    let trace = stroke.traces.last().expect("a trace");
    assert_eq!(trace.time_s.len(), TRACE_SAMPLES);
    // Half a period apart the ball is at mirrored places going the mirrored way over a
    // mirrored history (the contact is symmetric without the coupling): the same area, so
    // the trace repeats at twice the frequency.
    let area = &trace.anodic_area_mm2;
    let (quarter, three_quarters) = (area[TRACE_SAMPLES / 4], area[3 * TRACE_SAMPLES / 4]);
    assert!(
        ((quarter - three_quarters) / quarter).abs() < 1e-9,
        "{quarter} {three_quarters}"
    );
    // Two maxima a cycle: the area is largest at the middle passes and smallest at the
    // turning points, where the crank rests and the track behind repassivates.
    let (low, high) = area
        .iter()
        .fold((f64::MAX, 0.0_f64), |(l, h), &a| (l.min(a), h.max(a)));
    assert!(area[0] < quarter && area[TRACE_SAMPLES / 2] < quarter);
    assert!(high > 1.2 * low, "an oscillation, {low} to {high}");
    // A trace that reaches E_corr (the paper's -0.1 V) is capped there, and the run says so.
    let capped = stroke
        .traces
        .iter()
        .any(|t| t.potential_v.iter().any(|&e| e >= -0.1));
    let said = result
        .field_warnings
        .iter()
        .any(|w| w.path == "corrosion.anodic_area" && w.message.contains("flat tops"));
    assert!(
        capped,
        "this short stroke's turning points leave too little bare area"
    );
    assert!(said);
    // The corrosion never exceeds the total loss it is part of (k on the total loss).
    let last = result.cycles.last().expect("records");
    let wac = last.wac_volume_mm3.expect("corrosion");
    assert!(wac > 0.0 && wac < last.total_volume_mm3.expect("a total"));
    // The report names the rig and draws the map, the axis and the traces.
    let report = run_report(&result, &Measured::default()).expect("a report");
    assert!(report.contains("reciprocating ball-on-flat test"));
    assert!(report.contains("Wear map along and across the stroke at the end of the run: x"));
    assert!(report.contains("depth (um)</text>"));
    assert!(report.contains("Wear depth along the stroke"));
    assert!(report.contains("Potential over a cycle"));
    assert!(report.contains("H = A + B ln n"));
}

#[test]
fn what_the_rig_cannot_run_is_refused_at_its_field() {
    // A stroke within the contact (2a is about 0.09 mm here): 0.05 typed in cm or m.
    assert_eq!(
        refused_at(&scene(
            json!({"test": {"reciprocating": {"stroke_mm": 0.05}}})
        )),
        ["test.reciprocating.stroke_mm"]
    );
    assert_eq!(
        refused_at(&scene(
            json!({"test": {"reciprocating": {"frequency_hz": 500}}})
        )),
        ["test.reciprocating.frequency_hz"]
    );
    assert_eq!(
        refused_at(&scene(json!({"corrosion": {"anodic_area": "wear_track"}}))),
        ["corrosion.anodic_area"]
    );
    let rough = json!({"disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.1,
                       "short_cutoff_um": 5, "long_cutoff_um": 50}}});
    assert_eq!(refused_at(&scene(rough)), ["disc.surface"]);
    assert_eq!(
        refused_at(&scene(json!({"test": {"ocp_before_s": 10}}))),
        ["test.ocp_before_s"]
    );
    assert_eq!(
        refused_at(&scene(
            json!({"test": {"reciprocating": {"velocity_law": "triangle"}}})
        )),
        ["test.reciprocating.velocity_law"]
    );
    // Faster than the film regrows (0.5 / f below tau = 0.148 s): run, with a warning.
    let fast = parse_scene(&scene(
        json!({"test": {"reciprocating": {"frequency_hz": 5}}}),
    ))
    .expect("a warning, not a refusal");
    let paths: Vec<&str> = fast.warnings().iter().map(|w| w.path.as_str()).collect();
    assert!(
        paths.contains(&"test.reciprocating.frequency_hz"),
        "{paths:?}"
    );
}

#[test]
fn a_stepped_record_is_the_state_at_its_own_cycle() {
    // Archard's volume does not depend on the step (each pass removes k F 2L / H), so a
    // stepped run's record at cycle n holds the every-cycle run's volume at n: a record
    // that took in the cycles its solve stands for would be ahead by those cycles' wear.
    let stepped = result(&scene(json!({"test": {"cycles": 40}, "corrosion": null})));
    let every = result(&scene(
        json!({"test": {"cycles": 40}, "corrosion": null, "numerics": {"cycle_step": 1}}),
    ));
    assert!(stepped.cycles.len() < every.cycles.len(), "the run stepped");
    let mut worst = 0.0_f64;
    for record in &stepped.cycles {
        let same = &every.cycles[record.cycle as usize - 1];
        assert_eq!(same.cycle, record.cycle);
        let error = (record.wear_volume_mm3 - same.wear_volume_mm3).abs() / same.wear_volume_mm3;
        worst = worst.max(error);
    }
    // Measured 3.9e-7 (the runs' yielding differs in its last digits); a record a cycle
    // ahead of its own would be off by about 1 / n, at least 2.5e-2 in 40 cycles.
    assert!(worst < 1e-5, "{worst}");
}

/// A Ti-6Al-4V flat against zirconia at docs/materials.md's example k, 2e-4, grows its grid
/// from 64 x 64 to 64 x 96 cells near cycle 180. Run to 180 cycles, the last pressure map was
/// cut from the grown grid with the solve's smaller field (an index out of bounds); run on,
/// the grown grid's first solve, started cold, stayed at residual 0.54 for 2000 iterations.
/// The map now keeps the grid it was solved on, and a grown grid's first solve starts from
/// the last pressure.
#[test]
fn a_grown_grids_first_solve_converges_and_the_last_map_is_the_solves() {
    for cycles in [180, 184] {
        let run = result(&json!({
            "disc": {"material": "ti6al4v"},
            "ball": {"material": "zirconia"},
            "wear": {"archard_k": 2.0e-4},
            "corrosion": null,
            "test": {"cycles": cycles, "reciprocating": {}},
            "numerics": {"cycle_step_bound": 0.02, "tolerance": 1e-5}
        }));
        // At cycle 180 of 180 (the last solved cycle) and at 181 of 184 (before the last).
        let grown = run
            .models
            .iter()
            .any(|m| m.reason.contains("grown to 64 x 96 cells"));
        assert!(grown, "the grid grew to 64 x 96: {:?}", run.models);
        let last = run.pressure_maps.last().expect("a map");
        assert_eq!(last.cycle, cycles);
        assert!(
            last.pressure_mpa
                .iter()
                .all(|row| row.len() == last.x_um.len()),
            "every row spans the map's columns"
        );
        assert_eq!(last.pressure_mpa.len(), last.y_um.len());
    }
}
