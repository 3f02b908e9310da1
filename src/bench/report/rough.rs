//! The rough-surface section: one seeded self-affine surface on grids up to N = 2048, error
//! against the finest grid and time. `tribosim bench rough --markdown PATH` rewrites only
//! this section of an existing report.

use crate::bench::BenchError;
use crate::bench::contact::DOMAIN_M;
use crate::bench::plot::{LogLogPlot, Point, Series};
use crate::bench::rough::{
    CELLS_PER_SHORT_CUTOFF, HURST, LONG_CUTOFF_REPEATS, REDUCED_PRESSURE, RMS_SLOPE, ROUGH_SIZES,
    RoughRow, SEED,
};

use super::format::{error, sig, table};
use super::{Machine, Report};

/// The section's heading: where [`super::splice::splice`] finds it.
pub(super) const HEADING: &str = "## Rough contact: grid study";

/// The section's opening words: the case, and which run measured it (the section may be
/// regenerated alone, so it names its own command, date and commit).
pub(super) fn intro(machine: &Machine, command: &str) -> String {
    let commit = machine
        .commit
        .as_ref()
        .map_or(String::new(), |c| format!(", commit `{c}`"));
    let finest = ROUGH_SIZES[ROUGH_SIZES.len() - 1];
    let sizes: Vec<String> = ROUGH_SIZES.iter().map(usize::to_string).collect();
    format!(
        "{HEADING}\n\n\
         A rough flat pressed by a rigid flat on the periodic elastic half-space (each Fourier \
         mode displaced by 2 p(q) / (E* |q|)), the paper's E*, with no pressure cap: one \
         self-affine surface (Hurst {HURST}, random phases of seed {SEED}, wavelengths from \
         {:.3} um, {CELLS_PER_SHORT_CUTOFF} cells at N = {finest}, to {:.1} um, a quarter of \
         the {:.3} mm square; rms slope {RMS_SLOPE} at N = {finest}) generated once at N = \
         {finest} and sampled bilinearly at the cell centres of each grid, N = {}, as the \
         simulation samples a map. The mean pressure is {REDUCED_PRESSURE} E* h' (h' the rms \
         slope), a few percent of real contact area. Real area counts the cells with p > 0; \
         the mean gap is the mean over all cells of K p + h - delta. Errors are against the \
         N = {finest} grid; times are operator construction plus solve (medians of up to 5 \
         cold runs, one at N >= 1024), \"threads\" those the operator's FFT passes are split over \
         (`numerics.threads` auto; \"solve CPU s\" is the calling thread's alone), \"apply\" \
         one application of the operator, \"per FFT pair\" an iteration's time in padded 2N x 2N FFT round trips (the contact study's \
         yardstick). Measured by `{command}` on {}, on {} ({} cores){commit}; the machine may \
         be shared with other work.\n",
        DOMAIN_M / (finest / CELLS_PER_SHORT_CUTOFF) as f64 * 1e6,
        DOMAIN_M / LONG_CUTOFF_REPEATS as f64 * 1e6,
        DOMAIN_M * 1e3,
        sizes.join(", "),
        machine.date,
        machine.cpu,
        machine.cores
    )
}

fn cells(r: &RoughRow, finest: usize) -> Vec<String> {
    let against = |v: f64| {
        if r.n == finest {
            "reference".to_owned()
        } else {
            error(v)
        }
    };
    vec![
        r.n.to_string(),
        format!("{:.2}", r.cells_per_short_cutoff),
        format!("{:.3}", 100.0 * r.area_fraction),
        sig(r.mean_gap_m * 1e6, 4),
        against(r.err_area),
        against(r.err_gap),
        r.iterations.to_string(),
        r.applies.to_string(),
        sig(r.wall_s, 3),
        r.threads.to_string(),
        r.solve_cpu_s.map_or("n/a".to_owned(), |c| sig(c, 3)),
        sig(r.apply_s * 1e3, 3),
        sig(r.applies as f64 * r.apply_s, 3),
        format!("{:.2}", r.iteration_per_fft_pair),
        r.peak_rss_bytes
            .map_or("n/a".to_owned(), |b| format!("{:.0}", b as f64 / 1e6)),
    ]
}

fn point(r: &RoughRow, y: f64) -> Point {
    Point {
        x: r.wall_s,
        y,
        label: format!("N = {}", r.n),
    }
}

/// Appends the section: words, table, the two plots.
pub(super) fn section(
    report: &mut Report,
    rows: &[RoughRow],
    machine: &Machine,
    command: &str,
) -> Result<(), BenchError> {
    report.push(&intro(machine, command));
    let Some(finest) = rows.last() else {
        return Ok(());
    };
    report.push(&table(
        &[
            "N",
            "cells per short cut-off",
            "real area %",
            "mean gap um",
            "err area",
            "err gap",
            "iterations",
            "applies",
            "wall s",
            "threads",
            "solve CPU s",
            "apply ms",
            "applies x apply s",
            "iteration per FFT pair",
            "peak MB",
        ],
        &rows.iter().map(|r| cells(r, finest.n)).collect::<Vec<_>>(),
    ));
    report.push(&format!(
        "At N = {}: {} s for the contact ({} s of CPU for the solve; {} iterations, {} operator \
         applications of {} ms: {} s of them; the preconditioner, at about the same cost an \
         application, takes two per iteration, three when many cells entered or left the \
         free set), the process's peak resident memory {:.0} MB; \
         \"peak MB\" is the process's during each grid's solves (reset when the grid starts; \
         the N = {} surface, generated first, is held throughout).\n",
        finest.n,
        sig(finest.wall_s, 3),
        finest.solve_cpu_s.map_or("n/a".to_owned(), |c| sig(c, 3)),
        finest.iterations,
        finest.applies,
        sig(finest.apply_s * 1e3, 3),
        sig(finest.applies as f64 * finest.apply_s, 3),
        finest.peak_rss_bytes.map_or(f64::NAN, |b| b as f64 / 1e6),
        finest.n,
    ));
    plots(report, rows, finest.n)
}

/// The log-log plots: each coarser grid's error against its time, and time against N.
fn plots(report: &mut Report, rows: &[RoughRow], finest: usize) -> Result<(), BenchError> {
    let coarser: Vec<&RoughRow> = rows.iter().filter(|r| r.n != finest).collect();
    report.plot(
        "rough-error",
        &LogLogPlot {
            title: "Rough contact: |error| against the finest grid, against wall time".into(),
            x_label: "wall time, s".into(),
            y_label: "|relative error|".into(),
            series: vec![
                Series {
                    name: "real contact area".into(),
                    points: coarser.iter().map(|r| point(r, r.err_area.abs())).collect(),
                },
                Series {
                    name: "mean gap".into(),
                    points: coarser.iter().map(|r| point(r, r.err_gap.abs())).collect(),
                },
            ],
        },
    )?;
    report.plot(
        "rough-time",
        &LogLogPlot {
            title: "Rough contact: wall time against cells per side".into(),
            x_label: "cells per side N".into(),
            y_label: "wall time, s".into(),
            series: vec![Series {
                name: "construction + solve".into(),
                points: rows
                    .iter()
                    .map(|r| Point {
                        x: r.n as f64,
                        y: r.wall_s,
                        label: format!("{} it.", r.iterations),
                    })
                    .collect(),
            }],
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::report::splice::splice;

    fn row(n: usize, err: f64) -> RoughRow {
        RoughRow {
            study: "rough_grid",
            n,
            pixel_m: 1e-7,
            cells_per_short_cutoff: 8.0 * n as f64 / 2048.0,
            reduced_modulus_pa: 1.3e11,
            mean_pressure_pa: 2e8,
            tolerance: 1e-8,
            area_fraction: 0.032 * (1.0 + err),
            mean_gap_m: 3.5e-7 * (1.0 - err),
            iterations: 60,
            applies: 120,
            residual: 5e-9,
            wall_s: n as f64 / 100.0,
            solve_s: n as f64 / 100.0,
            solve_cpu_s: None,
            threads: 2,
            runs: 1,
            apply_s: 0.1,
            fft_pair_s: 0.2,
            iteration_per_fft_pair: 1.0,
            peak_rss_bytes: Some(446_000_000),
            err_area: err,
            err_gap: -err,
            surface_file: None,
        }
    }

    #[test]
    fn the_section_has_its_table_plots_and_the_finest_grid_in_words() {
        let dir = std::env::temp_dir().join(format!("tribosim-rough-{}", std::process::id()));
        let path = dir.join("accuracy.md");
        let machine = Machine {
            date: "2026-11-23".into(),
            cpu: "AMD EPYC".into(),
            cores: 2,
            commit: None,
        };
        let mut report = Report::beside(&path).expect("plot folder");
        let rows = [row(1024, 0.05), row(2048, 0.0)];
        section(&mut report, &rows, &machine, "bench rough").expect("written");
        let plots = ["rough-error.svg", "rough-time.svg"].map(|f| dir.join("accuracy").join(f));
        let drawn = plots.iter().all(|p| p.is_file());
        std::fs::remove_dir_all(&dir).expect("cleaned up");
        assert!(drawn && report.plots == 2);
        let text = &report.text;
        assert!(text.starts_with(HEADING), "{text}");
        assert!(text.contains("| 1024 | 4.00 | 3.360 | 0.3325 | +5.00e-2 | -5.00e-2 |"));
        assert!(text.contains("| 2048 | 8.00 | 3.200 | 0.3500 | reference | reference |"));
        assert!(text.contains("At N = 2048: 20.5 s for the contact"));
        assert!(text.contains("peak resident memory 446 MB"));
        // Rewritten alone, before the peers.
        let spliced = splice("# R\n\n## Peers\n\np\n", HEADING, text);
        assert!(
            spliced.starts_with(&format!("# R\n\n{HEADING}"))
                && spliced.ends_with("## Peers\n\np\n")
        );
    }
}
