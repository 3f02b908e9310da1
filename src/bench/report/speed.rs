//! The speed section: each lever of the solver against the code without it, measured in one
//! run. `tribosim bench speed --markdown PATH` rewrites only this section of an existing
//! report ([`splice`]), so it can be regenerated without the other studies.

use crate::bench::speed::{
    COARSE_STUDY_SIZES, CoarseRow, PREVIOUS_TOLERANCE, SpeedStudies, ThreadRow, WARM_ROUNDS,
    WarmRow, preconditioning_label,
};
use crate::bench::threads::THREAD_ROUNDS;
use crate::contact::{COARSE_TOLERANCE, COARSEST_CELLS, SPLIT_MIN_CELLS};
use crate::scene::DEFAULT_TOLERANCE;

use super::format::{error, sig, table};
use super::{Machine, Report};

/// The section's heading: where [`splice`] finds it.
pub(super) const HEADING: &str = "## Solver speed";

/// The section's opening words: what it measures, and which run measured it (the section
/// may be regenerated alone, so it names its own command, date and commit).
pub(super) fn intro(machine: &Machine, command: &str) -> String {
    let commit = machine
        .commit
        .as_ref()
        .map_or(String::new(), |c| format!(", commit `{c}`"));
    format!(
        "{HEADING}\n\n\
         Each lever of the solver against the code without it, timed in the same run: \
         `{command}` on {}, on {} ({} cores){commit}. The machine may be shared with other \
         work: compare the rows of one table with each other.\n",
        machine.date, machine.cpu, machine.cores
    )
}

fn warm_cells(r: &WarmRow) -> Vec<String> {
    let reference = r.tolerance == PREVIOUS_TOLERANCE;
    let change = |v: f64| {
        if reference {
            "reference".to_owned()
        } else {
            error(v)
        }
    };
    vec![
        format!("{:.0e}", r.tolerance),
        format!("`{}`", preconditioning_label(r.preconditioning)),
        r.solves.to_string(),
        r.iterations.to_string(),
        format!("{:.2}", r.iterations_per_solve),
        sig(r.wall_s, 3),
        r.cpu_s.map_or("n/a".to_owned(), |c| sig(c, 3)),
        change(r.err_volume),
        change(r.err_depth),
        if reference {
            "reference".to_owned()
        } else {
            format!("{:+.4}", r.potential_change_mv)
        },
    ]
}

fn coarse_cells(r: &CoarseRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        r.cold_iterations.to_string(),
        sig(r.cold_s, 3),
        r.fine_iterations.to_string(),
        sig(r.coarse_to_fine_s, 3),
        format!("{:.2}", r.speedup),
        r.whole_grid_iterations.to_string(),
        sig(r.whole_grid_s, 3),
        format!("{:.1e}", r.difference),
        r.peak_rss_bytes.map_or("n/a".to_owned(), |b| {
            format!("{:.0}", b as f64 / (r.n * r.n) as f64)
        }),
    ]
}

fn thread_cells(r: &ThreadRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        r.threads.to_string(),
        sig(r.one_thread_s, 3),
        sig(r.split_s, 3),
        format!("{:.2}", r.speedup),
        format!("{:.2}-{:.2}", r.speedup_range[0], r.speedup_range[1]),
        r.load_average
            .map_or("n/a".to_owned(), |l| format!("{l:.1}")),
    ]
}

/// The thread study's words and table.
fn threads(report: &mut Report, rows: &[ThreadRow]) {
    let auto = SPLIT_MIN_CELLS.map_or("never splits".to_owned(), |cells| {
        let side = (cells as f64).sqrt().round();
        format!("splits from {side} x {side} cells on")
    });
    report.push(&format!(
        "### Threads: the FFT passes of an apply split across cores\n\n\
         One apply of the Hertz case's operator on one thread against the same apply with \
         its row, column and row passes split across threads (bit-identical), \
         {THREAD_ROUNDS} alternating rounds per grid; times are the medians, the speed-up \
         the median of the rounds' ratios, with the lowest and highest round's. The load \
         average says how many of the cores other work held: a split only pays on free \
         cores. `numerics.threads: \"auto\"` {auto} (`contact::SPLIT_MIN_CELLS`), over the \
         cores the process may use divided among the service's workers.\n"
    ));
    report.push(&table(
        &[
            "N",
            "threads",
            "1 thread s",
            "split s",
            "speed-up",
            "rounds",
            "load average",
        ],
        &rows.iter().map(thread_cells).collect::<Vec<_>>(),
    ));
}

/// Appends the section.
pub(super) fn section(
    report: &mut Report,
    studies: &SpeedStudies,
    machine: &Machine,
    command: &str,
) {
    report.push(&intro(machine, command));
    body(report, studies);
}

/// The section's studies, each with its words and table.
pub(super) fn body(report: &mut Report, studies: &SpeedStudies) {
    report.push(&format!(
        "### Warm solves: the tolerance the error needs, the preconditioner's edges\n\n\
         The paper's 3600-cycle scene `{{}}` at the default tolerance ({DEFAULT_TOLERANCE:.0e}) \
         against the previous default ({PREVIOUS_TOLERANCE:.0e}), and at the default \
         tolerance with the preconditioner of the whole grid (`whole_grid`) instead of the \
         default one corrected at the free set's edges (`free_set`, \
         `src/contact/solver/free_set.rs`), run alternately {WARM_ROUNDS} times each; wall and CPU time (the run's thread alone, which other work \
         on the machine does not inflate as much) are the medians. The changes are those of \
         the final wear volume, deepest point and potential against the previous default's \
         run. Both warm-start each solve from the last two solves' `p - c g` extrapolated in \
         the cycle number (`src/simulation/warm.rs`, which gives that start's own gain).\n"
    ));
    report.push(&table(
        &[
            "tolerance",
            "preconditioner",
            "solves",
            "iterations",
            "iterations per solve",
            "wall s",
            "CPU s",
            "volume change",
            "depth change",
            "potential change mV",
        ],
        &studies.warm.iter().map(warm_cells).collect::<Vec<_>>(),
    ));
    let sizes: Vec<String> = COARSE_STUDY_SIZES.iter().map(usize::to_string).collect();
    report.push(&format!(
        "### Cold solves: a coarse-to-fine start\n\n\
         The Hertz case of the contact study at N = {}, at its tolerance, from the uniform \
         pressure (cold) and from the pressure of the same contact on half the cells per side \
         (solved to {COARSE_TOLERANCE:.0e}, itself started from the grid of half its cells, \
         down to {COARSEST_CELLS} cells), interpolated bilinearly. The coarse-to-fine time \
         includes the coarse operators and solves; the `whole_grid` columns repeat it with \
         the preconditioner of the whole grid (the warm study's). \"difference\" is \
         max |p - p_cold| / \
         max p_cold; \"peak bytes per cell\" is the process's peak resident memory during the \
         grid's solves (reset when the grid starts) over N^2.\n",
        sizes.join(", ")
    ));
    report.push(&table(
        &[
            "N",
            "cold iterations",
            "cold s",
            "fine iterations",
            "coarse-to-fine s",
            "speed-up",
            "`whole_grid` fine iterations",
            "`whole_grid` coarse-to-fine s",
            "difference",
            "peak bytes per cell",
        ],
        &studies.coarse.iter().map(coarse_cells).collect::<Vec<_>>(),
    ));
    threads(report, &studies.threads);
}

/// Rewrites only this section of the report `text` (the rest is another run's).
pub(super) fn splice(text: &str, section: &str) -> String {
    super::splice::splice(text, HEADING, section)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_section_is_replaced_where_it_is_or_put_before_the_peers() {
        let new = format!("{HEADING}\n\nnew words\n");
        let with = format!("# R\n\nhead\n\n## Wear\n\nw\n\n{HEADING}\n\nold\n\n## Peers\n\np\n");
        assert_eq!(
            splice(&with, &new),
            format!("# R\n\nhead\n\n## Wear\n\nw\n\n{HEADING}\n\nnew words\n\n## Peers\n\np\n")
        );
        let without = "# R\n\nhead\n\n## Peers\n\np\n";
        assert_eq!(
            splice(without, &new),
            format!("# R\n\nhead\n\n{HEADING}\n\nnew words\n\n## Peers\n\np\n")
        );
        let last = format!("# R\n\n{HEADING}\n\nold\n");
        assert_eq!(
            splice(&last, &new),
            format!("# R\n\n{HEADING}\n\nnew words\n")
        );
    }
}
