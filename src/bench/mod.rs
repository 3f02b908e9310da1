//! `tribosim bench`: speed against error, measured in one run on this machine. Times are
//! medians of repeated runs; speeds are reported as ratios to a baseline measured in the
//! same run (one padded FFT round trip), so they compare across machines.

mod contact;
mod fft_pair;

use std::time::Instant;

pub use contact::{ContactRow, contact_rows};
pub use fft_pair::FftPair;

/// Which tables to print.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchTarget {
    /// The Hertz contact: grid size against error and time.
    Contact,
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
    match target {
        BenchTarget::Contact => {
            let rows = contact_rows(&[64, 128, 256, 512, 1024]).map_err(|e| e.to_string())?;
            if json {
                for row in &rows {
                    println!("{}", serde_json::to_string(row).map_err(|e| e.to_string())?);
                }
            } else {
                print!("{}", contact::table(&rows));
            }
        }
    }
    Ok(())
}
