//! `tribosim bench`: speed against error, measured in one run on this machine. Times are
//! medians of repeated runs; speeds are reported as ratios to a baseline measured in the
//! same run (one padded FFT round trip), so they compare across machines.

mod auto;
mod contact;
mod fft_pair;
mod plot;
mod report;
mod wear;

use std::path::Path;
use std::time::Instant;

pub use auto::{AutoGrid, AutoStudies, CouplingRow, auto_studies};
pub use contact::{
    CAPPED_REFERENCE_N, CAPPED_YIELD_PRESSURE_PA, ContactCase, ContactRow, Measures, Reference,
    ToleranceRow, contact_rows, contact_rows_against, tolerance_rows,
};
pub use fft_pair::FftPair;
pub use plot::{LogAxis, LogLogPlot, Point, Series};
pub use report::{Machine, Measurements};
pub use wear::{WearRow, wear_rows};

/// Which tables to print.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchTarget {
    /// The Hertz and capped-Hertz contact: grid size and tolerance against error and time.
    Contact,
    /// The paper scene: cycle step, grid and tolerance against error and time.
    Wear,
    /// The measurements behind the auto choices: coupling, domain, plasticity.
    Auto,
    /// All three.
    All,
}

/// Median wall time of `reps` calls of `f`, s.
pub fn median_time(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// Runs the chosen benchmark and prints it as a table or as JSON lines; with `markdown`, also
/// writes the report there and its plots beside it.
pub fn print(target: BenchTarget, json: bool, markdown: Option<&Path>) -> Result<(), String> {
    let wanted = |t: BenchTarget| target == t || target == BenchTarget::All;
    let mut measured = Measurements::default();
    if wanted(BenchTarget::Contact) {
        let capped = Reference::capped(CAPPED_REFERENCE_N).map_err(|e| e.to_string())?;
        measured.contact =
            contact_rows_against(&[64, 128, 256, 512, 1024], &capped).map_err(|e| e.to_string())?;
        emit(&measured.contact, json, contact::table)?;
        measured.contact_tolerance =
            tolerance_rows(256, &[1e-4, 1e-6, 1e-8, 1e-10], &capped).map_err(|e| e.to_string())?;
        emit(&measured.contact_tolerance, json, contact::tolerance_table)?;
    }
    if wanted(BenchTarget::Wear) {
        measured.wear = wear_rows().map_err(|e| e.to_string())?;
        emit(&measured.wear, json, wear::table)?;
    }
    if wanted(BenchTarget::Auto) {
        let studies = auto_studies().map_err(|e| e.to_string())?;
        emit(&studies.coupling, json, auto::coupling_table)?;
        emit(&studies.wear, json, wear::table)?;
        if json {
            let facts = serde_json::json!({
                "grid": studies.grid,
                "domain_growth": studies.domain_growth,
                "plasticity": studies.plasticity,
            });
            println!("{facts}");
        } else {
            print!("{}", auto::facts(&studies));
        }
        measured.auto = Some(studies);
    }
    if let Some(path) = markdown {
        let name = clap::ValueEnum::to_possible_value(&target)
            .map_or_else(|| "all".to_owned(), |v| v.get_name().to_owned());
        let command = format!(
            "cargo run --release -- bench {name} --markdown {}",
            path.display()
        );
        let plots = report::write(path, &measured, &Machine::detect(path), &command)?;
        eprintln!("wrote {} and {plots} plots", path.display());
    }
    Ok(())
}

fn emit<R: serde::Serialize>(
    rows: &[R],
    json: bool,
    table: fn(&[R]) -> String,
) -> Result<(), String> {
    if json {
        for row in rows {
            println!("{}", serde_json::to_string(row).map_err(|e| e.to_string())?);
        }
    } else {
        print!("{}", table(rows));
    }
    Ok(())
}
