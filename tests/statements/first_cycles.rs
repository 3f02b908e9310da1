//! The paper's statements about its first cycles against the groove, for the paper's cap
//! and the cap that hardens from annealed 316L's yield strength (`docs/paper.md`, "The
//! paper's first cycles against the groove" and "The yield cap of the first cycles").

use tribosim::bench::{CapNumbers, HALF_MICRON_UM, INITIAL_YIELDS_MPA, Verdict, statements};
use tribosim::scene::ANNEALED_316L_PROOF_STRESS_MPA;

use super::{near, study};

#[test]
fn the_papers_first_cycles_against_the_groove() {
    // The verdicts the groove of the paper's cap gets today, in the order of `statements`,
    // and by how much it misses (um, 1e-3 mm^3): the gaps are tracked here, so a change that
    // closes or widens one fails. The misses are the statements' bounds less the groove
    // values held above, so their tolerance is theirs (2.2e-4 um, 2.7e-7 mm^3 = 2.7e-4 of
    // 1e-3 mm^3).
    let expected = [
        (
            "depth 0.5 um at 10 s",
            Verdict::Missed(HALF_MICRON_UM.0 - 0.19725),
            2.2e-4,
        ),
        (
            "EPP over Table 3 at 10 s",
            Verdict::Missed(0.97 - 0.21716),
            2.7e-4,
        ),
        (
            "EPP over Table 3 at 60 s",
            Verdict::Missed(1.09 - 0.39697),
            2.7e-4,
        ),
        ("elastic under Table 3 at 10 s", Verdict::Met, 0.0),
        ("elastic under Table 3 at 60 s", Verdict::Met, 0.0),
        ("plastic area gone around cycle 10", Verdict::Met, 0.0),
        ("depth under 1 um at 300 cycles", Verdict::Met, 0.0),
    ];
    let n = study().numbers();
    check_verdicts(&n.epp, &expected);
}

#[test]
fn the_cap_hardening_from_annealed_316l_overshoots_the_first_cycles() {
    let study = study();
    let sourced = &study.caps[0];
    assert_eq!(
        sourced.initial_yield_mpa.to_bits(),
        ANNEALED_316L_PROOF_STRESS_MPA.to_bits()
    );
    let cap = &sourced.numbers;
    // 1 um against 2 um cells (`tribosim run` of the same scene, `numerics.grid` 128): depth
    // 1.431 / 1.429 um at 10 cycles, 1.707 / 1.705 at 300; volume 3.440 / 3.431, 3.619 /
    // 3.611 and 4.450 / 4.441 (1e-3 mm^3) at 10, 60 and 300; yielding ends at cycle 22 /
    // 24. Tolerances: those differences, rounded up.
    near("depth at 10", cap.groove_depth_um[0], 1.431, 3e-3);
    near("depth at 300", cap.groove_depth_um[1], 1.707, 3e-3);
    for (i, v) in [3.440, 3.619, 4.450].into_iter().enumerate() {
        near("volume", cap.groove_volume_mm3[i] * 1e3, v, 1e-2);
    }
    near("yielding ends", cap.plastic_gone_cycle as f64, 22.0, 2.0);
    // Its verdicts: the EPP volumes are over Table 3, the depths and the end of yielding
    // overshoot; the misses are the numbers above against the statements' bounds.
    let expected = [
        (
            "depth 0.5 um at 10 s",
            Verdict::Missed(1.431 - HALF_MICRON_UM.1),
            3e-3,
        ),
        ("EPP over Table 3 at 10 s", Verdict::Met, 0.0),
        ("EPP over Table 3 at 60 s", Verdict::Met, 0.0),
        ("elastic under Table 3 at 10 s", Verdict::Met, 0.0),
        ("elastic under Table 3 at 60 s", Verdict::Met, 0.0),
        (
            "plastic area gone around cycle 10",
            Verdict::Missed(22.0 - 15.0),
            2.0,
        ),
        (
            "depth under 1 um at 300 cycles",
            Verdict::Missed(1.707 - 1.0),
            3e-3,
        ),
    ];
    check_verdicts(cap, &expected);
    // The default is the cap that meets the most statements with sourced parameters: the
    // paper's, with as many as the sourced hardening cap and Table 3's 300 s volume kept
    // (the whole test's, held in `the_volumes_of_fig_11_and_table_3`).
    let met = |c: &CapNumbers| {
        statements(c, &study.numbers().elastic_volume_mm3)
            .iter()
            .filter(|s| s.verdict == Verdict::Met)
            .count()
    };
    assert!(met(&study.numbers().epp) >= met(cap));
    // Every strength of the sweep ran, in order, each from its own initial yield.
    let swept: Vec<f64> = study.caps.iter().map(|c| c.initial_yield_mpa).collect();
    assert_eq!(swept, INITIAL_YIELDS_MPA);
}

#[track_caller]
fn check_verdicts(cap: &CapNumbers, expected: &[(&str, Verdict, f64)]) {
    let found = statements(cap, &study().numbers().elastic_volume_mm3);
    assert_eq!(found.len(), expected.len());
    for (statement, &(what, verdict, tolerance)) in found.iter().zip(expected) {
        match (statement.verdict, verdict) {
            (Verdict::Met, Verdict::Met) => {}
            (Verdict::Missed(by), Verdict::Missed(expected)) => near(what, by, expected, tolerance),
            (found, _) => panic!("{what}: {found:?}, where the groove gave {verdict:?}"),
        }
    }
}
