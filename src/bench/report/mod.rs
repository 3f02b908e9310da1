//! `tribosim bench ... --markdown PATH`: the measurements of one run as a markdown report,
//! with its log-log plots written beside it (`docs/accuracy.md` puts them in
//! `docs/accuracy/`). Every number is formatted from the rows the same run measured, and
//! every setting named in the prose from the constants the studies ran with, so the report
//! cannot drift from what the command printed. One file per section: a new study adds its
//! section without touching the others.

mod auto;
mod contact;
mod coupling;
pub(super) mod format;
mod machine;
mod rough;
mod speed;
mod splice;
mod wear;

use std::path::{Path, PathBuf};

pub use machine::Machine;

use super::BenchError;
use super::auto::AutoStudies;
use super::contact::{ContactRow, ToleranceRow};
use super::plot::{LogLogPlot, Series};
use super::rough::RoughRow;
use super::speed::SpeedStudies;
use super::wear::WearRow;

use self::wear::wear_series;

/// What one `bench` run measured; empty parts were not asked for.
#[derive(Debug, Default)]
pub struct Measurements {
    /// The contact grid study, Hertz and capped.
    pub contact: Vec<ContactRow>,
    /// The contact tolerance study.
    pub contact_tolerance: Vec<ToleranceRow>,
    /// The paper-scene studies.
    pub wear: Vec<WearRow>,
    /// The studies behind the auto choices.
    pub auto: Option<AutoStudies>,
    /// The solver's speed levers.
    pub speed: Option<SpeedStudies>,
    /// The rough-surface grid study.
    pub rough: Vec<RoughRow>,
}

/// The report being written: markdown text and the plots written so far.
struct Report {
    text: String,
    plot_dir: PathBuf,
    link_dir: String,
    plots: usize,
}

impl Report {
    /// An empty report for `path`, its plots to go in the folder of the same name (made
    /// here).
    fn beside(path: &Path) -> Result<Self, BenchError> {
        let stem = path
            .file_stem()
            .ok_or_else(|| BenchError::NotAFile(path.to_owned()))?
            .to_string_lossy()
            .into_owned();
        let plot_dir = path.parent().unwrap_or(Path::new("")).join(&stem);
        std::fs::create_dir_all(&plot_dir).map_err(|source| BenchError::Write {
            path: plot_dir.clone(),
            source,
        })?;
        Ok(Self {
            text: String::new(),
            plot_dir,
            link_dir: stem,
            plots: 0,
        })
    }

    /// Appends a block (paragraph, table, list, image), a blank line after it.
    fn push(&mut self, block: &str) {
        self.text += block.trim_end();
        self.text += "\n\n";
    }

    /// Writes `plot` as `NAME.svg` and links it.
    fn plot(&mut self, name: &str, plot: &LogLogPlot) -> Result<(), BenchError> {
        let file = format!("{name}.svg");
        plot.write_svg(&self.plot_dir.join(&file))?;
        self.plots += 1;
        let link = format!("![{}]({}/{file})\n", plot.title, self.link_dir);
        self.push(&link);
        Ok(())
    }

    fn time_plot(
        &mut self,
        name: &str,
        title: String,
        series: Vec<Series>,
    ) -> Result<(), BenchError> {
        self.plot(
            name,
            &LogLogPlot {
                title,
                x_label: "wall time, s".into(),
                y_label: "|relative error|".into(),
                series,
            },
        )
    }

    fn wear_plots(&mut self, prefix: &str, rows: &[&WearRow]) -> Result<(), BenchError> {
        self.time_plot(
            &format!("{prefix}-volume"),
            "Wear volume: |error| against wall time".into(),
            wear_series(rows, |r| r.err_volume),
        )?;
        self.time_plot(
            &format!("{prefix}-depth"),
            "Deepest point: |error| against wall time".into(),
            wear_series(rows, |r| r.err_depth),
        )
    }
}

const PLOT_NOTE: &str = "Log-log axes; each line is one study, its points labelled by their \
    setting; lower and further left is better. References are not plotted (their error is 0 by \
    definition); an open marker on the bottom edge is an error of exactly 0, which has no place \
    on a log axis.";

/// Writes the report at `path` and its plots in the folder of the same name; returns how
/// many plots were written.
pub fn write(
    path: &Path,
    measured: &Measurements,
    machine: &Machine,
    command: &str,
) -> Result<usize, BenchError> {
    let mut report = Report::beside(path)?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let peers = std::fs::read_to_string(folder.join("peers.md")).ok();
    render(&mut report, measured, machine, command, peers.as_deref())?;
    std::fs::write(path, report.text.trim_end().to_owned() + "\n").map_err(|source| {
        BenchError::Write {
            path: path.to_owned(),
            source,
        }
    })?;
    Ok(report.plots)
}

/// The speed studies' tables with their words, for the terminal.
pub fn speed_tables(studies: &SpeedStudies) -> String {
    let mut report = Report {
        text: String::new(),
        plot_dir: PathBuf::new(),
        link_dir: String::new(),
        plots: 0,
    };
    speed::body(&mut report, studies);
    report.text
}

/// Rewrites the speed section of the report at `path` alone (the file's other sections are
/// kept as another run wrote them); writes a report of that section alone if there is none.
pub fn write_speed_section(
    path: &Path,
    studies: &SpeedStudies,
    machine: &Machine,
    command: &str,
) -> Result<(), BenchError> {
    let existing = std::fs::read_to_string(path).unwrap_or_default();
    let mut report = Report {
        text: String::new(),
        plot_dir: PathBuf::new(),
        link_dir: String::new(),
        plots: 0,
    };
    speed::section(&mut report, studies, machine, command);
    let text = speed::splice(&existing, &report.text);
    std::fs::write(path, text).map_err(|source| BenchError::Write {
        path: path.to_owned(),
        source,
    })
}

/// Rewrites the rough-surface section of the report at `path` alone, its plots beside it
/// (the file's other sections are kept as another run wrote them).
pub fn write_rough_section(
    path: &Path,
    rows: &[RoughRow],
    machine: &Machine,
    command: &str,
) -> Result<(), BenchError> {
    let existing = std::fs::read_to_string(path).unwrap_or_default();
    let mut report = Report::beside(path)?;
    rough::section(&mut report, rows, machine, command)?;
    let text = splice::splice(&existing, rough::HEADING, &report.text);
    std::fs::write(path, text).map_err(|source| BenchError::Write {
        path: path.to_owned(),
        source,
    })
}

fn render(
    report: &mut Report,
    measured: &Measurements,
    machine: &Machine,
    command: &str,
    peers: Option<&str>,
) -> Result<(), BenchError> {
    report.push(&header(machine, command));
    if !measured.contact.is_empty() {
        contact::section(report, &measured.contact, &measured.contact_tolerance)?;
    }
    if !measured.wear.is_empty() {
        wear::section(report, &measured.wear)?;
    }
    if let Some(auto) = &measured.auto {
        auto::section(report, auto, measured)?;
    }
    if let Some(studies) = &measured.speed {
        speed::section(report, studies, machine, command);
    }
    if !measured.rough.is_empty() {
        rough::section(report, &measured.rough, machine, command)?;
    }
    if let Some(peers) = peers {
        // The fragment's own heading, if it has one, heads the section.
        let (heading, body) = match peers.split_once('\n') {
            Some((first, rest)) if first.starts_with("## ") => (first, rest),
            _ => ("## Peers", peers),
        };
        report.push(&format!("{heading}\n"));
        report.push(
            "Produced by `scripts/peers.sh` (a Python environment with the public solvers), not \
             by the command above; its `docs/peers.md` is included here verbatim.\n",
        );
        report.push(body.trim());
    }
    Ok(())
}

fn header(machine: &Machine, command: &str) -> String {
    let commit = machine
        .commit
        .as_ref()
        .map_or(String::new(), |c| format!(", commit `{c}`"));
    format!(
        "# Speed against accuracy\n\n\
         Generated by `{command}` (regenerate it with that command from the repository root) \
         on {}, on {} ({} cores){commit}. Every number below was measured and written by that \
         one run; the plots are beside this file in the folder of the same name. Times are \
         wall-clock on that machine: compare them with each other, not across machines.\n",
        machine.date, machine.cpu, machine.cores
    )
}

#[cfg(test)]
mod tests {
    use super::wear::tests::wear_row;
    use super::*;
    use crate::bench::auto::ELASTIC_LOAD_N;
    use crate::bench::contact::TOLERANCE_STUDY;
    use crate::bench::wear::WearStudy;
    use crate::bench::wear::paper_scene;

    #[test]
    fn the_report_has_its_header_tables_plots_and_peers() {
        let dir = std::env::temp_dir().join(format!("tribosim-report-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(
            dir.join("peers.md"),
            "| peer | s |\n|---|---|\n| tamaas | 1.0 |\n",
        )
        .expect("peers");
        let measured = Measurements {
            contact: Vec::new(),
            contact_tolerance: Vec::new(),
            wear: vec![
                wear_row(WearStudy::Grid, "256 cells, 0.52 um (reference)", 0.0, true),
                wear_row(WearStudy::Grid, "64 cells, 2.07 um", 1.3e-4, false),
                wear_row(WearStudy::Table3, "300 s: measured", 0.2, false),
            ],
            auto: None,
            speed: None,
            rough: Vec::new(),
        };
        let machine = Machine {
            date: "2026-11-22".into(),
            cpu: "AMD EPYC".into(),
            cores: 2,
            commit: Some("abc".into()),
        };
        let path = dir.join("accuracy.md");
        let plots = write(
            &path,
            &measured,
            &machine,
            "tribosim bench wear --markdown x.md",
        )
        .expect("written");
        let text = std::fs::read_to_string(&path).expect("readable");
        let volume = dir.join("accuracy").join("wear-volume.svg");
        let svg_exists = volume.is_file();
        std::fs::remove_dir_all(&dir).expect("cleaned up");
        assert_eq!(plots, 2);
        assert!(svg_exists);
        assert!(text.starts_with("# Speed against accuracy"));
        assert!(text.contains("`tribosim bench wear --markdown x.md`"));
        assert!(text.contains("on 2026-11-22, on AMD EPYC (2 cores), commit `abc`"));
        assert!(text.contains("| 64 cells, 2.07 um | 300 | 0.312 |"));
        assert!(
            text.contains("![Wear volume: |error| against wall time](accuracy/wear-volume.svg)")
        );
        assert!(text.contains("### Against the paper's Table 3"));
        assert!(text.contains("## Peers") && text.contains("| tamaas | 1.0 |"));
        assert!(
            !text.contains("## Contact"),
            "no contact rows, no contact section"
        );
    }

    /// The words the report generates from the studies' constants are those of the committed
    /// `docs/accuracy.md`: a changed setting fails here until the report is regenerated with
    /// `cargo run --release -- bench all --markdown docs/accuracy.md`.
    #[test]
    fn the_prose_from_the_constants_is_the_committed_reports() {
        let committed = include_str!("../../../docs/accuracy.md");
        let scene = paper_scene();
        let cycles = scene.test.cycles;
        let mut blocks = vec![
            contact::intro(),
            contact::capped_intro(),
            contact::tolerance_intro(TOLERANCE_STUDY.n),
            wear::intro(),
            wear::table3_intro(),
            auto::intro(cycles),
            auto::domain_intro(),
            auto::step_intro(),
            auto::plasticity_intro([scene.test.load_n, ELASTIC_LOAD_N]),
        ];
        for (_, heading) in wear::WEAR_STUDIES {
            blocks.push(heading(cycles));
        }
        for block in blocks {
            let block = block.trim_end();
            assert!(
                committed.contains(block),
                "not in docs/accuracy.md:\n{block}"
            );
        }
    }
}
