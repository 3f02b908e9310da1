//! The depassivated area predicted from the spots (`docs/corrosion.md`, "The depassivated
//! area predicted from the spots"): the page's generated table is what the runs give, and
//! what the page says of it holds.
//!
//! Every case of `bench spots` runs here in full (the two rough ones take about 2.5 minutes
//! each on 2 cores). Regenerate the table with
//! `cargo run --release -- bench spots --markdown docs/corrosion.md`, or
//! `TRIBOSIM_WRITE_DOCS=1 cargo test --release --test spots`.

use std::path::PathBuf;

use tribosim::bench::spots::{BEGIN, CASES, END, SMOOTH_CASES, SpotRow, markdown, run_case};

fn page_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/corrosion.md")
}

/// The table's rows without their last column, the run's wall time, which moves with the
/// machine.
fn without_wall_time(section: &str) -> Vec<String> {
    section
        .lines()
        .filter(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.trim_end_matches('|').split('|').collect();
            cells[..cells.len() - 1].join("|")
        })
        .collect()
}

fn rows() -> Vec<SpotRow> {
    let times = tribosim::bench::spots::table3_times_s();
    CASES
        .iter()
        .map(|case| run_case(case, &times).expect("the case runs"))
        .collect()
}

#[test]
fn the_pages_table_is_what_the_runs_give_and_its_reading_holds() {
    let rows = rows();
    let generated = markdown(&rows);
    let page = std::fs::read_to_string(page_path()).expect("docs/corrosion.md");
    let (begin, end) = (
        page.find(BEGIN).expect("begin marker"),
        page.find(END).expect("end marker") + END.len(),
    );
    let committed = &page[begin..end];
    if without_wall_time(committed) != without_wall_time(&generated) {
        if std::env::var_os("TRIBOSIM_WRITE_DOCS").is_some() {
            let updated = format!("{}{generated}{}", &page[..begin], &page[end..]);
            std::fs::write(page_path(), updated).expect("docs/corrosion.md is writable");
        } else {
            panic!(
                "docs/corrosion.md's spots table differs from the runs; regenerate it with \
                 `cargo run --release -- bench spots --markdown docs/corrosion.md`\n{generated}"
            );
        }
    }
    let (wake, smooth_spots, rough) = (&rows[0], &rows[1], &rows[SMOOTH_CASES..]);
    // The default is the only row within 60 mV rms of the paper (the page's "Default").
    assert!(wake.rms_v() < 0.060, "{}", wake.rms_v());
    for row in &rows[1..] {
        assert!(row.rms_v() > wake.rms_v(), "{}: {}", row.label, row.rms_v());
    }
    // The asperity spots of the paper's surface: a ratio far below 50, the potential capped
    // at E_corr (the page's "The goal was missed").
    let asperity = &rough[1];
    for p in &asperity.points {
        assert!(p.ratio < 20.0, "{p:?}");
        assert!((p.potential_v - -0.10).abs() < 1e-12, "{p:?}");
        // The balanced cell never rises above E_corr and stays below it with any anode.
        assert!(p.balanced_v < -0.10, "{p:?}");
    }
    // Every cell in contact as a spot: the ratio climbs as the groove widens.
    for row in [smooth_spots, &rough[0]] {
        let ratios: Vec<f64> = row.points.iter().map(|p| p.ratio).collect();
        assert!(
            ratios.windows(2).all(|w| w[1] > w[0]),
            "{}: {ratios:?}",
            row.label
        );
    }
    // Where A_a is near the paper's, keeping the passive current lowers the potential.
    for p in &wake.points {
        assert!(p.balanced_v < p.potential_v, "{p:?}");
    }
}
