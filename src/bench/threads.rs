//! The thread study: one DC-FFT apply on one thread against the same apply with its passes
//! split across threads ([`DcFft::threaded`]), on the Hertz case's grids. Rounds alternate
//! the two, so load from other work on the machine falls on both; each round's ratio is
//! reported with the median, and the load average, which says how many cores were free.

use std::time::Instant;

use serde::Serialize;

use super::contact::{DOMAIN_M, paper_hertz};
use super::error::BenchError;
use crate::contact::{DcFft, Grid, Kernel, Operator};

/// Grid sides of the thread study.
pub const THREAD_STUDY_SIZES: [usize; 4] = [256, 512, 1024, 2048];

/// Alternating rounds per grid.
pub const THREAD_ROUNDS: usize = 5;

/// Cells times applies per timing: about a tenth of a second of one-thread work per round.
const CELL_APPLIES: usize = 1 << 24;

/// One grid of the thread study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThreadRow {
    /// Always `speed_threads`.
    pub study: &'static str,
    /// Cells per side.
    pub n: usize,
    /// Threads of the split apply: the cores the process may use, at least 2.
    pub threads: usize,
    /// Applies per timing.
    pub applies: usize,
    /// Median one-thread time per apply, s.
    pub one_thread_s: f64,
    /// Median split time per apply, s.
    pub split_s: f64,
    /// Median over the rounds of the one-thread time over the split time.
    pub speedup: f64,
    /// The lowest and highest round's speed-up.
    pub speedup_range: [f64; 2],
    /// The one-minute load average when the grid's rounds ended (`None` where it cannot be
    /// read).
    pub load_average: Option<f64>,
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Time per apply of `applies` applies of `operator` to `input`, s.
fn per_apply(operator: &mut DcFft, input: &[f64], output: &mut [f64], applies: usize) -> f64 {
    let started = Instant::now();
    for _ in 0..applies {
        operator.apply(input, output);
        std::hint::black_box(&output);
    }
    started.elapsed().as_secs_f64() / applies as f64
}

/// The study at each of [`THREAD_STUDY_SIZES`].
pub fn thread_rows() -> Result<Vec<ThreadRow>, BenchError> {
    let (pair, hertz) = paper_hertz();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get().max(2));
    let mut rows = Vec::new();
    for n in THREAD_STUDY_SIZES {
        let grid = Grid::square(n, DOMAIN_M)?;
        let kernel = Kernel::normal(&grid, &pair);
        let mut one = DcFft::new(&kernel);
        let mut split = DcFft::new(&kernel).threaded(threads);
        // Any field will do: its values do not change the FFTs' work.
        let input = grid.sample(|x, y| hertz.separation_m(x, y));
        let mut output = vec![0.0; grid.len()];
        let applies = (CELL_APPLIES / grid.len()).max(2);
        let (mut ones, mut splits, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
        for _ in 0..THREAD_ROUNDS {
            let a = per_apply(&mut one, &input, &mut output, applies);
            let b = per_apply(&mut split, &input, &mut output, applies);
            ones.push(a);
            splits.push(b);
            ratios.push(a / b);
        }
        let lowest = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let highest = ratios.iter().copied().fold(0.0, f64::max);
        rows.push(ThreadRow {
            study: "speed_threads",
            n,
            threads,
            applies,
            one_thread_s: median(ones),
            split_s: median(splits),
            speedup: median(ratios),
            speedup_range: [lowest, highest],
            load_average: load_average(),
        });
    }
    Ok(rows)
}

/// The one-minute load average (Linux's `/proc/loadavg`).
fn load_average() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// The rows as a fixed-width table.
pub fn threads_table(rows: &[ThreadRow]) -> String {
    let mut out = String::from(
        "One DC-FFT apply on one thread against its passes split across threads\n\
         \x20    N threads  applies   1 thread s    split s  speed-up  (rounds)       load\n",
    );
    for r in rows {
        out += &format!(
            "{:>6} {:>7} {:>8} {:>12.3e} {:>10.3e} {:>9.2}  ({:.2}-{:.2}) {:>10}\n",
            r.n,
            r.threads,
            r.applies,
            r.one_thread_s,
            r.split_s,
            r.speedup,
            r.speedup_range[0],
            r.speedup_range[1],
            r.load_average
                .map_or("n/a".to_owned(), |l| format!("{l:.1}"))
        );
    }
    out
}
