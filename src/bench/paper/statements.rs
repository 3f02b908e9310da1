//! The paper's statements about its first cycles against tribosim's groove: what eq. 13
//! defines and what the confocal profiles measure after the test. Each verdict is the one
//! the numbers give, so a change that closes or widens a gap shows in the test of it.

use super::numbers::{CapNumbers, TABLE3};

/// Whether the groove meets a statement, or by how much it misses it (in the statement's
/// [`Statement::unit`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// The groove meets the statement.
    Met,
    /// The groove misses the statement by this much.
    Missed(f64),
}

/// One of the paper's statements and the groove's value against it.
#[derive(Debug, Clone, PartialEq)]
pub struct Statement {
    /// The statement, as the paper words it (Sections 4.5 and 5.2).
    pub claim: &'static str,
    /// What the statement asks of the groove, in numbers.
    pub test: String,
    /// tribosim's groove value, in [`Statement::unit`].
    pub value: f64,
    /// The unit of the value and of a miss, written straight after the number.
    pub unit: &'static str,
    /// The decimals the value is written with.
    pub decimals: usize,
    /// The verdict.
    pub verdict: Verdict,
}

/// How far from 10 cycles "around 10 cycles" reaches, cycles: half of it, a reading of
/// "around" and no more.
pub const AROUND_10_CYCLES: u64 = 5;

/// The depths the paper's "0.5 um" covers: the value printed to one significant figure
/// stands for the interval that rounds to it, so "reaches 0.5 um" is met from 0.45 um up to
/// 0.55 um, and a groove three times deeper does not meet it.
pub const HALF_MICRON_UM: (f64, f64) = (0.45, 0.55);

/// The statements, in the order of the page's table, for the groove of one EPP run `cap`
/// and the purely elastic groove volumes `elastic_volume_mm3` at 10, 60 and 300 cycles.
pub fn statements(cap: &CapNumbers, elastic_volume_mm3: &[f64; 3]) -> Vec<Statement> {
    let at_least = |value: f64, floor: f64| {
        if value >= floor {
            Verdict::Met
        } else {
            Verdict::Missed(floor - value)
        }
    };
    let below = |value: f64, ceiling: f64| {
        if value < ceiling {
            Verdict::Met
        } else {
            Verdict::Missed(value - ceiling)
        }
    };
    let measured = |i: usize| TABLE3[i].2;
    let volume = |v: f64| v * 1e3;
    let gone = cap.plastic_gone_cycle;
    let (low, high) = HALF_MICRON_UM;
    let depth10 = cap.groove_depth_um[0];
    let mut list = vec![Statement {
        claim: "the maximum depth in the wear track reaches rapidly 0.5 um at 10 s",
        test: format!("groove depth at 10 cycles in [{low}, {high}) um"),
        value: depth10,
        unit: " um",
        decimals: 3,
        verdict: match at_least(depth10, low) {
            Verdict::Met => below(depth10, high),
            missed => missed,
        },
    }];
    for (i, t) in [(0, 10), (1, 60)] {
        let epp = volume(cap.groove_volume_mm3[i]);
        list.push(Statement {
            claim: "the EPP behaviour overestimates [wear at the beginning of the test]",
            test: format!("EPP groove volume at {t} s >= Table 3's {:.2}", measured(i)),
            value: epp,
            unit: "e-3 mm^3",
            decimals: 3,
            verdict: at_least(epp, measured(i)),
        });
    }
    for (i, t) in [(0, 10), (1, 60)] {
        let elastic = volume(elastic_volume_mm3[i]);
        list.push(Statement {
            claim: "the elastic model underestimates wear at the beginning of the test",
            test: format!(
                "elastic groove volume at {t} s < Table 3's {:.2}",
                measured(i)
            ),
            value: elastic,
            unit: "e-3 mm^3",
            decimals: 3,
            verdict: below(elastic, measured(i)),
        });
    }
    list.push(Statement {
        claim: "after those initial cycles (around 10 cycles) all the contact pressures reduce \
                below the yielding condition",
        test: format!("plastic area 0 from a cycle within 10 +- {AROUND_10_CYCLES}"),
        value: gone as f64,
        unit: " cycles",
        decimals: 0,
        verdict: if gone.abs_diff(10) <= AROUND_10_CYCLES {
            Verdict::Met
        } else {
            Verdict::Missed((gone.abs_diff(10) - AROUND_10_CYCLES) as f64)
        },
    });
    list.push(Statement {
        claim: "the maximum (of the average) wear depth does not reach 1 um at 300 cycles",
        test: "groove depth at 300 cycles < 1 um".to_owned(),
        value: cap.groove_depth_um[1],
        unit: " um",
        decimals: 3,
        verdict: below(cap.groove_depth_um[1], 1.0),
    });
    list
}
