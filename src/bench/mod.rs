//! `tribosim bench`: speed against error, measured in one run on this machine. Times are
//! medians of repeated runs; speeds are reported as ratios to a baseline measured in the
//! same run (one padded FFT round trip), so they compare across machines.

mod auto;
mod contact;
mod error;
mod fft_pair;
mod kappa;
mod paper;
mod plot;
mod report;
mod rough;
mod speed;
pub mod spots;
mod threads;
mod wear;

use std::path::Path;
use std::time::Instant;

pub use error::BenchError;
pub use kappa::{
    KappaRow, MeasuredMap, REDUCED_PRESSURES, generated_surface, kappa_rows, surface_rows,
};
pub use paper::{
    AROUND_10_CYCLES, COARSE_GRID, CapNumbers, CapRun, HALF_MICRON_UM, INITIAL_YIELDS_MPA,
    PAPER_GRID, PaperNumbers, PaperStudy, READING_CYCLES, Reading, ReadingRun, Statement, TABLE3,
    Verdict, markdown as paper_markdown, run_readings, statements, write as write_paper,
    write_figures as write_paper_figures,
};

use contact::{CAPPED_REFERENCE_N, GRID_STUDY_SIZES, Reference, TOLERANCE_STUDY};
use report::{Machine, Measurements};

/// Which tables to print.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum BenchTarget {
    /// The Hertz and capped-Hertz contact: grid size and tolerance against error and time.
    Contact,
    /// The paper scene: cycle step, grid and tolerance against error and time.
    Wear,
    /// The measurements behind the auto choices: coupling, domain, plasticity.
    Auto,
    /// The solver's speed levers: warm solves of the default scene, the coarse-to-fine
    /// start, the peak memory up to N = 2048, and the FFT passes split across threads.
    Speed,
    /// The thread study of `speed` alone (a table, never written to the report).
    Threads,
    /// A rough flat on a flat, periodic: one seeded self-affine surface on grids up to
    /// N = 2048, real contact area and mean gap against the finest grid.
    Rough,
    /// The area-load slope (Persson's kappa) of the generated rough surface, and of a
    /// measured map with `--map`, each on a periodic flat (a table, never written to the
    /// report).
    Kappa,
    /// The paper's Section 4 figure by figure: `--markdown docs/paper.md` writes the page
    /// and its SVG figures (never part of `all`).
    Paper,
    /// The depassivated area predicted from the solved contact's spots against the paper's
    /// Fig. 14 reading: `--markdown docs/corrosion.md` rewrites that page's section (never
    /// part of `all`).
    Spots,
    /// All five (the thread study within `speed`; `kappa` and `paper` apart).
    All,
}

/// Median wall time of `reps` calls of `f`, s.
fn median_time(reps: usize, mut f: impl FnMut()) -> f64 {
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

/// The median times of `a` and `b` run alternately `reps` times each, so that load from
/// other work falls on both alike.
fn median_times_alternating(reps: usize, mut a: impl FnMut(), mut b: impl FnMut()) -> (f64, f64) {
    let (mut first, mut second) = (Vec::new(), Vec::new());
    for _ in 0..reps.max(1) {
        let start = Instant::now();
        a();
        first.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        b();
        second.push(start.elapsed().as_secs_f64());
    }
    let median = |mut times: Vec<f64>| {
        times.sort_by(f64::total_cmp);
        times[times.len() / 2]
    };
    (median(first), median(second))
}

/// Runs the chosen benchmark and prints it as a table or as JSON lines; with `markdown`, also
/// writes the report there and its plots beside it; with `surfaces`, the rough study writes
/// the height array of each grid there; `map` is the measured map of the kappa study.
pub fn print(
    target: BenchTarget,
    json: bool,
    markdown: Option<&Path>,
    surfaces: Option<&Path>,
    map: Option<MeasuredMap>,
) -> Result<(), BenchError> {
    let wanted = |t: BenchTarget| target == t || target == BenchTarget::All;
    let mut measured = Measurements::default();
    if wanted(BenchTarget::Contact) {
        let capped = Reference::capped(CAPPED_REFERENCE_N)?;
        measured.contact = contact::grid_rows(&GRID_STUDY_SIZES, &capped)?;
        emit(&measured.contact, json, contact::table)?;
        measured.contact_tolerance = contact::tolerance_rows(&TOLERANCE_STUDY, &capped)?;
        emit(&measured.contact_tolerance, json, contact::tolerance_table)?;
    }
    if wanted(BenchTarget::Wear) {
        measured.wear = wear::wear_rows()?;
        emit(&measured.wear, json, wear::table)?;
    }
    if wanted(BenchTarget::Auto) {
        let studies = auto::auto_studies()?;
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
    if wanted(BenchTarget::Speed) {
        let studies = speed::SpeedStudies {
            warm: speed::warm_rows()?,
            coarse: speed::coarse_rows()?,
            threads: threads::thread_rows()?,
        };
        if json {
            speed::print_json(&studies)?;
        } else {
            print!("{}", report::speed_tables(&studies));
        }
        measured.speed = Some(studies);
    }
    if target == BenchTarget::Kappa {
        return emit(&kappa::kappa_rows(map)?, json, kappa::table);
    }
    if target == BenchTarget::Paper {
        return paper_only(markdown);
    }
    if target == BenchTarget::Spots {
        return spots::write(markdown);
    }
    if target == BenchTarget::Threads {
        emit(&threads::thread_rows()?, json, threads::threads_table)?;
        if markdown.is_some() {
            eprintln!("the thread study is written with the speed section: bench speed --markdown");
        }
        return Ok(());
    }
    if wanted(BenchTarget::Rough) {
        measured.rough = rough::rough_rows(surfaces)?;
        emit(&measured.rough, json, rough::table)?;
    }
    if let Some(path) = markdown {
        write_markdown(path, target, &measured)?;
    }
    Ok(())
}

/// Writes what was `measured` for `target` to the report at `path`: the whole report, or
/// only the section of a target that rewrites its own.
fn write_markdown(
    path: &Path,
    target: BenchTarget,
    measured: &Measurements,
) -> Result<(), BenchError> {
    let name = clap::ValueEnum::to_possible_value(&target)
        .map_or_else(|| "all".to_owned(), |v| v.get_name().to_owned());
    let command = format!(
        "cargo run --release -- bench {name} --markdown {}",
        path.display()
    );
    let machine = Machine::detect(path);
    match (&measured.speed, target) {
        (Some(studies), BenchTarget::Speed) => {
            report::write_speed_section(path, studies, &machine, &command)?;
            eprintln!("rewrote the speed section of {}", path.display());
        }
        (_, BenchTarget::Rough) => {
            report::write_rough_section(path, &measured.rough, &machine, &command)?;
            eprintln!("rewrote the rough-surface section of {}", path.display());
        }
        _ => {
            let plots = report::write(path, measured, &machine, &command)?;
            eprintln!("wrote {} and {plots} plots", path.display());
        }
    }
    Ok(())
}

/// `bench paper`: the page and its figures at `markdown`, or the reproduced numbers.
fn paper_only(markdown: Option<&Path>) -> Result<(), BenchError> {
    match markdown {
        Some(path) => {
            let figures = paper::write(path)?;
            eprintln!("wrote {} and {figures} figures", path.display());
        }
        None => println!("{:#?}", PaperStudy::run(PAPER_GRID)?.numbers()),
    }
    Ok(())
}

fn emit<R: serde::Serialize>(
    rows: &[R],
    json: bool,
    table: fn(&[R]) -> String,
) -> Result<(), BenchError> {
    if json {
        for row in rows {
            println!("{}", serde_json::to_string(row)?);
        }
    } else {
        print!("{}", table(rows));
    }
    Ok(())
}
