//! The hard cases of the rough-disc wear run: the rough example of `docs/scene.md` past its
//! second cycle, and a matrix of rough discs (three seeds; short cut-offs of 1, 2 and 4 um;
//! rms heights from 0.05 to 0.3 um) with the friction coupling and the pressure cap on, each
//! for a few cycles. Their second and third cycles start from a surface the first cycle's
//! yielding cut, with most of the contact at the cap and thousands of cells leaving and
//! re-entering it at each step. With the free-set preconditioner alone (no fallback when
//! a solve stalls, `src/contact/solver.rs`, "Preconditioning") 5 of these 10 runs failed at
//! their second cycle with "no convergence after 2000 iterations", the rough example with
//! the residual 2.709e-1 the issue reported, and the file took 1447 s.
//!
//! Each run must finish (a stalled solve fails it with "no convergence"), carry the load,
//! keep every pressure at or under the cap and wear at least Archard's volume. The numbers in
//! the comments were measured with `cargo test --release --test hard_cases -- --nocapture`.

mod common {
    pub mod physics;
}

use std::sync::atomic::AtomicBool;

use common::physics::LOAD_CHECK;
use tribosim::simulation::{
    Model, PressureMap, RunOptions, Setup, SimulationResult, parse_scene_str, run_setup,
};

/// Cycles each rough disc runs: the first (a cold solve), then the two warm solves on
/// surfaces the cap cut, where the free-set preconditioner stalled.
const CYCLES: u64 = 3;

/// A pressure at the cap is the yield pressure itself, set by a clamp; the cap is computed
/// from the hardness again here, which may differ in its last bits.
const CAP_ROUNDOFF: f64 = 1e-12;

/// Archard's volume and the worn volume are sums over a few cycles and a few hundred rows;
/// their round-off is far below this (the same bound as the cycle loop's own test of the
/// volume's accounting, over 20 cycles).
const VOLUME_ROUNDOFF: f64 = 1e-9;

/// Runs the scene `text` and checks what any rough run must meet. Returns the result and the
/// setup it ran with.
fn run_checked(text: &str) -> (SimulationResult, Setup) {
    let scene = parse_scene_str(text).unwrap_or_else(|e| panic!("{text}: {e}"));
    let setup =
        Setup::new(&scene, &RunOptions::default()).unwrap_or_else(|e| panic!("{text}: {e}"));
    let started = std::time::Instant::now();
    let result = run_setup(&setup, &mut |_| {}, &AtomicBool::new(false))
        .unwrap_or_else(|e| panic!("{text}: {e}"));
    let cycles = setup.scene().test.cycles;
    assert_eq!(
        result.cycles.last().map(|c| c.cycle),
        Some(cycles),
        "{text}"
    );
    for map in &result.pressure_maps {
        let carried = carried_load_n(map);
        let load = setup.scene().load_n();
        assert!(
            (carried / load - 1.0).abs() < LOAD_CHECK,
            "{text}: cycle {} carries {carried} N of {load} N",
            map.cycle
        );
    }
    let yield_factor = setup.scene().disc.yield_factor;
    for record in &result.cycles {
        let cap_mpa = record.hardness_mpa / yield_factor;
        assert!(
            record.max_pressure_mpa <= cap_mpa * (1.0 + CAP_ROUNDOFF),
            "{text}: cycle {} reaches {} MPa over the cap {cap_mpa} MPa",
            record.cycle,
            record.max_pressure_mpa
        );
    }
    let plan = &setup.plan;
    let archard_mm3 = plan.wear().depth_scale(1..cycles + 1, plan.hardness())
        * plan.scene().load_n()
        * plan.scene().track_length_m()
        * 1e9;
    let worn_mm3 = result.summary.wear_volume_mm3;
    assert!(
        worn_mm3 >= archard_mm3 * (1.0 - VOLUME_ROUNDOFF),
        "{text}: worn {worn_mm3} mm^3 < Archard's {archard_mm3} mm^3"
    );
    let window = result
        .models
        .iter()
        .find(|m| m.name == Model::SolveWindow)
        .map_or("", |m| m.reason.as_str());
    if let Some((fell_back, solves)) = fallbacks(window) {
        assert!(
            (1..=solves).contains(&fell_back) && solves == result.summary.solves,
            "{text}: {window}"
        );
    }
    println!(
        "{text}\n  {:.1} s, {} solves, {} iterations ({:?} a cycle), {:.4e} mm^3; {window}",
        started.elapsed().as_secs_f64(),
        result.summary.solves,
        result.summary.iterations,
        result
            .cycles
            .iter()
            .map(|c| c.iterations)
            .collect::<Vec<_>>(),
        worn_mm3
    );
    (result, setup)
}

/// The solves that fell back to the whole grid and all the solves, as the `solve_window`
/// model reports them when any did.
fn fallbacks(reason: &str) -> Option<(usize, usize)> {
    let (_, tail) = reason.split_once("fell back to the whole grid in ")?;
    let mut words = tail.split_whitespace();
    let fell_back = words.next()?.parse().ok()?;
    let solves = words.nth(1)?.parse().ok()?;
    Some((fell_back, solves))
}

/// The load a pressure map carries, N: its pressures times the cells' area.
fn carried_load_n(map: &PressureMap) -> f64 {
    let pitch_m = |centres_um: &[f64]| (centres_um[1] - centres_um[0]) * 1e-6;
    let cell_m2 = pitch_m(&map.x_um) * pitch_m(&map.y_um);
    let sum_mpa: f64 = map.pressure_mpa.iter().flatten().sum();
    sum_mpa * 1e6 * cell_m2
}

/// The rough example of `docs/scene.md` ("Rough and measured surfaces"), with the cycles
/// the issue ran it for cut to [`CYCLES`]: its second cycle did not converge in 2000
/// iterations (residual 0.27) with the free-set preconditioner alone.
#[test]
fn the_rough_example_of_the_scene_docs_runs_past_its_second_cycle() {
    let text = format!(
        r#"{{"disc": {{"surface": {{"kind": "synthetic", "rms_height_um": 0.1, "hurst": 0.8,
                "short_cutoff_um": 2, "long_cutoff_um": 50, "seed": 1}}}},
            "corrosion": {{"anodic_area": "bem_contact"}}, "test": {{"cycles": {CYCLES}}}}}"#
    );
    let (result, _) = run_checked(&text);
    assert!(result.cycles.iter().all(|c| c.contact_islands > 1));
}

/// A rough disc of the matrix.
struct Disc {
    seed: u64,
    short_cutoff_um: f64,
    rms_height_um: f64,
}

impl Disc {
    /// The load, N: the auto grid puts 8 cells across the short cut-off, so a 1 um cut-off
    /// under the paper's 5 N needs 1152 cells a side; 0.5 N (a contact 0.46 times as wide)
    /// keeps it to 512, 2 N to 432 cells at 2 um.
    fn load_n(&self) -> f64 {
        match self.short_cutoff_um {
            c if c < 2.0 => 0.5,
            c if c < 4.0 => 2.0,
            _ => 5.0,
        }
    }

    /// Runs the disc with the coupling and the cap on and checks that the cap acted.
    fn run(&self) {
        let text = format!(
            r#"{{"disc": {{"surface": {{"kind": "synthetic", "rms_height_um": {},
                    "hurst": 0.8, "short_cutoff_um": {}, "long_cutoff_um": 50, "seed": {}}}}},
                "test": {{"cycles": {CYCLES}, "load_n": {}}},
                "wear": {{"plasticity": "on"}}, "numerics": {{"coupling": "on"}}}}"#,
            self.rms_height_um,
            self.short_cutoff_um,
            self.seed,
            self.load_n()
        );
        let (result, setup) = run_checked(&text);
        assert!(setup.plasticity && setup.coupling, "{text}");
        // The hard part is the cap among many islands: each cycle has both.
        for record in &result.cycles {
            assert!(record.plastic_area_mm2 > 0.0, "{text}: no cell at the cap");
            assert!(record.contact_islands > 1, "{text}: one island");
        }
    }
}

#[test]
fn seed_1_cut_off_1_um_rms_0_05_um() {
    Disc {
        seed: 1,
        short_cutoff_um: 1.0,
        rms_height_um: 0.05,
    }
    .run();
}

#[test]
fn seed_2_cut_off_1_um_rms_0_1_um() {
    Disc {
        seed: 2,
        short_cutoff_um: 1.0,
        rms_height_um: 0.1,
    }
    .run();
}

#[test]
fn seed_3_cut_off_1_um_rms_0_3_um() {
    Disc {
        seed: 3,
        short_cutoff_um: 1.0,
        rms_height_um: 0.3,
    }
    .run();
}

#[test]
fn seed_1_cut_off_2_um_rms_0_1_um() {
    Disc {
        seed: 1,
        short_cutoff_um: 2.0,
        rms_height_um: 0.1,
    }
    .run();
}

#[test]
fn seed_2_cut_off_2_um_rms_0_3_um() {
    Disc {
        seed: 2,
        short_cutoff_um: 2.0,
        rms_height_um: 0.3,
    }
    .run();
}

#[test]
fn seed_3_cut_off_2_um_rms_0_05_um() {
    Disc {
        seed: 3,
        short_cutoff_um: 2.0,
        rms_height_um: 0.05,
    }
    .run();
}

#[test]
fn seed_1_cut_off_4_um_rms_0_3_um() {
    Disc {
        seed: 1,
        short_cutoff_um: 4.0,
        rms_height_um: 0.3,
    }
    .run();
}

#[test]
fn seed_2_cut_off_4_um_rms_0_05_um() {
    Disc {
        seed: 2,
        short_cutoff_um: 4.0,
        rms_height_um: 0.05,
    }
    .run();
}

#[test]
fn seed_3_cut_off_4_um_rms_0_1_um() {
    Disc {
        seed: 3,
        short_cutoff_um: 4.0,
        rms_height_um: 0.1,
    }
    .run();
}

/// A rough disc under long cycle steps, where warm starts are far from the solution: the 4
/// um cut-off disc of `docs/accuracy.md` (seed 2, rms 0.1 um) at `cycle_step_bound` 0.1. Its
/// 27th cycle's warm start cycled on the whole grid for 2000 iterations (residual 0.29)
/// until a stalled warm start began again from the uniform pressure
/// (`src/contact/solver/progress.rs`).
#[test]
fn long_steps_on_a_rough_disc_converge_from_their_warm_starts() {
    run_checked(
        r#"{"disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.1, "hurst": 0.8,
                "short_cutoff_um": 4, "long_cutoff_um": 50, "seed": 2}},
            "test": {"cycles": 30}, "numerics": {"cycle_step_bound": 0.1}}"#,
    );
}

/// The same disc with seed 1 at `cycle_step_bound` 0.05 over 492 cycles: its last solve,
/// warm-started after a 5-cycle step, cycled between 250 and 18,000 capped cells for 2000
/// iterations while the load was restored by scaling; it converges with the shift of
/// `rescale_to_load` (`src/contact/solver/bounds.rs`). About 17 s in release.
#[test]
fn a_late_warm_start_under_the_cap_converges() {
    run_checked(
        r#"{"disc": {"surface": {"kind": "synthetic", "rms_height_um": 0.1, "hurst": 0.8,
                "short_cutoff_um": 4, "long_cutoff_um": 50, "seed": 1}},
            "test": {"cycles": 492}, "numerics": {"cycle_step_bound": 0.05}}"#,
    );
}
