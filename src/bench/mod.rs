//! `tribosim bench`: speed against error, measured in one run on this machine. Times are
//! medians of repeated runs; speeds are reported as ratios to a baseline measured in the
//! same run (one padded FFT round trip), so they compare across machines.

mod contact;
mod fft_pair;
mod wear;

use std::time::Instant;

pub use contact::{
    CAPPED_REFERENCE_N, CAPPED_YIELD_PRESSURE_PA, ContactCase, ContactRow, Measures, Reference,
    ToleranceRow, contact_rows, contact_rows_against, tolerance_rows,
};
pub use fft_pair::FftPair;
pub use wear::{WearRow, wear_rows};

/// Which tables to print.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchTarget {
    /// The Hertz and capped-Hertz contact: grid size and tolerance against error and time.
    Contact,
    /// The paper scene: cycle step, grid and tolerance against error and time.
    Wear,
    /// Both.
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

/// Runs the chosen benchmark and prints it as a table or as JSON lines.
pub fn print(target: BenchTarget, json: bool) -> Result<(), String> {
    if matches!(target, BenchTarget::Contact | BenchTarget::All) {
        let capped = Reference::capped(CAPPED_REFERENCE_N).map_err(|e| e.to_string())?;
        let rows =
            contact_rows_against(&[64, 128, 256, 512, 1024], &capped).map_err(|e| e.to_string())?;
        emit(&rows, json, contact::table)?;
        let rows =
            tolerance_rows(256, &[1e-4, 1e-6, 1e-8, 1e-10], &capped).map_err(|e| e.to_string())?;
        emit(&rows, json, contact::tolerance_table)?;
    }
    if matches!(target, BenchTarget::Wear | BenchTarget::All) {
        let rows = wear_rows().map_err(|e| e.to_string())?;
        emit(&rows, json, wear::table)?;
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
