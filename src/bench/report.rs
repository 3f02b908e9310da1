//! `tribosim bench ... --markdown PATH`: the measurements of one run as a markdown report,
//! with its log-log plots written beside it (`docs/accuracy.md` puts them in
//! `docs/accuracy/`). Every number is formatted here from the rows the same run measured, so
//! the report cannot drift from what the command printed. One renderer per row type: a new
//! study adds its table and its series without touching the others.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::simulation::{
    CELLS_PER_CONTACT_RADIUS, COUPLING_SENSITIVITY, DOMAIN_PER_CONTACT_RADIUS, MAX_STEP,
    STEP_CHANGE_BOUND,
};

use super::auto::{AutoStudies, CouplingRow, HERTZ_DOMAIN_M};
use super::contact::{CAPPED_REFERENCE_N, CAPPED_YIELD_PRESSURE_PA, paper_hertz};
use super::plot::{LogLogPlot, Point, Series};
use super::{ContactCase, ContactRow, ToleranceRow, WearRow};

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
}

/// Where and when the numbers were measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// UTC date, `YYYY-MM-DD`.
    pub date: String,
    /// CPU model name.
    pub cpu: String,
    /// Logical cores.
    pub cores: usize,
    /// Short commit hash, with ` + uncommitted changes` when tracked files other than the
    /// report's own differ from it.
    pub commit: Option<String>,
}

impl Machine {
    /// Reads `/proc/cpuinfo`, the clock and `git` (each optional); the report at `report`
    /// and its plots do not count as changes (a second run would see the first one's).
    pub fn detect(report: &Path) -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let (cpu, cores) = parse_cpuinfo(&cpuinfo);
        let cores = if cores > 0 {
            cores
        } else {
            std::thread::available_parallelism().map_or(1, usize::from)
        };
        Self {
            date: time::OffsetDateTime::now_utc().date().to_string(),
            cpu: cpu.unwrap_or_else(|| "unknown CPU".to_owned()),
            cores,
            commit: git_commit(report),
        }
    }
}

/// The first `model name` and the number of `processor` entries.
fn parse_cpuinfo(text: &str) -> (Option<String>, usize) {
    let field = |line: &str, key: &str| {
        let (name, value) = line.split_once(':')?;
        (name.trim() == key).then(|| value.trim().to_owned())
    };
    let model = text.lines().find_map(|l| field(l, "model name"));
    let cores = text
        .lines()
        .filter(|l| field(l, "processor").is_some())
        .count();
    (model, cores)
}

fn git(args: &[&str]) -> Option<String> {
    let out = std::process::Command::new("git").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

fn git_commit(report: &Path) -> Option<String> {
    let commit = git(&["rev-parse", "--short=10", "HEAD"]).filter(|c| !c.is_empty())?;
    let exclude = |p: &Path| format!(":(exclude){}", p.display());
    let (own, plots) = (exclude(report), exclude(&report.with_extension("")));
    let args = [
        "status",
        "--porcelain",
        "--untracked-files=no",
        "--",
        ".",
        &own,
        &plots,
    ];
    let dirty = git(&args).is_some_and(|s| !s.is_empty());
    Some(if dirty {
        format!("{commit} + uncommitted changes")
    } else {
        commit
    })
}

/// `v` to `digits` significant digits, fixed-point.
fn sig(v: f64, digits: i32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (digits - 1 - v.abs().log10().floor() as i32).max(0);
    format!("{v:.*}", decimals as usize)
}

/// A signed relative error, or `n/a` when there is none.
fn error(v: f64) -> String {
    if v.is_finite() {
        format!("{v:+.2e}")
    } else {
        "n/a".to_owned()
    }
}

/// A markdown table.
fn table(headers: &[&str], rows: &[Vec<String>]) -> String {
    let line = |cells: &[String]| {
        let escaped: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
        format!("| {} |\n", escaped.join(" | "))
    };
    let headers: Vec<String> = headers.iter().map(|h| (*h).to_owned()).collect();
    let mut out = line(&headers);
    out += &format!("|{}\n", "---|".repeat(headers.len()));
    for row in rows {
        out += &line(row);
    }
    out
}

/// Cells per Hertz contact radius on the contact benchmark's grid of `n` cells.
fn hertz_cells_per_radius(n: usize) -> f64 {
    paper_hertz().1.contact_radius_m() / (HERTZ_DOMAIN_M / n as f64)
}

const CONTACT_HEADERS: [&str; 10] = [
    "N",
    "cells per contact radius",
    "wall s",
    "build s",
    "solve s",
    "iterations",
    "iteration / FFT pair",
    "p_max error",
    "area error",
    "approach error",
];

fn contact_cells(r: &ContactRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        format!("{:.1}", hertz_cells_per_radius(r.n)),
        sig(r.wall_s, 3),
        sig(r.build_s, 3),
        sig(r.solve_s, 3),
        r.iterations.to_string(),
        format!("{:.2}", r.iteration_per_fft_pair),
        error(r.err_pmax),
        error(r.err_area),
        error(r.err_delta),
    ]
}

/// One Hertz error of a contact row.
type ContactMeasure = fn(&ContactRow) -> f64;

/// The Hertz errors, each plotted against wall time: file name, words, value.
const CONTACT_MEASURES: [(&str, &str, ContactMeasure); 3] = [
    ("pmax", "peak pressure", |r| r.err_pmax),
    ("area", "contact area", |r| r.err_area),
    ("approach", "approach", |r| r.err_delta),
];

/// One study's points for one Hertz error.
fn contact_series(study: &str, rows: &[ContactRow], measure: ContactMeasure) -> Series {
    Series {
        name: study.to_owned(),
        points: rows
            .iter()
            .map(|r| Point {
                x: r.wall_s,
                y: measure(r).abs(),
                label: format!("N={}", r.n),
            })
            .collect(),
    }
}

const WEAR_HEADERS: [&str; 7] = [
    "setting",
    "cycles",
    "wall s",
    "solves",
    "volume error",
    "depth error",
    "speed-up",
];

/// Added after `solves` where the cycle step is the question.
const STEP_HEADERS: [&str; 2] = ["longest step", "solves of MAX_STEP"];

/// Volume error, depth error and speed-up, or `reference`.
fn versus(r: &WearRow) -> [String; 3] {
    if r.reference {
        ["reference".into(), "reference".into(), "1".into()]
    } else {
        [
            error(r.err_volume),
            error(r.err_depth),
            format!("{:.1}", r.speedup),
        ]
    }
}

fn wear_cells(r: &WearRow, steps: bool) -> Vec<String> {
    let mut cells = vec![
        r.setting.clone(),
        r.cycles.to_string(),
        sig(r.wall_s, 3),
        r.solves.to_string(),
    ];
    if steps {
        cells.extend([r.longest_step.to_string(), r.steps_at_max.to_string()]);
    }
    cells.extend(versus(r));
    cells
}

fn wear_table(rows: &[&WearRow], steps: bool) -> String {
    let mut headers = WEAR_HEADERS.to_vec();
    if steps {
        headers.splice(4..4, STEP_HEADERS);
    }
    let cells: Vec<Vec<String>> = rows.iter().map(|r| wear_cells(r, steps)).collect();
    table(&headers, &cells)
}

/// A point's label: the setting up to its first qualifier.
fn short(setting: &str) -> &str {
    let end = [", ", " ("]
        .iter()
        .filter_map(|sep| setting.find(sep))
        .min()
        .unwrap_or(setting.len());
    &setting[..end]
}

/// One series per study (and cycle count, when a study has several references), the
/// references left out: their error is 0 by definition.
fn wear_series(rows: &[&WearRow], measure: fn(&WearRow) -> f64) -> Vec<Series> {
    let mut keys: Vec<(&str, u64)> = Vec::new();
    for r in rows {
        if !keys.contains(&(r.study, r.cycles)) {
            keys.push((r.study, r.cycles));
        }
    }
    keys.iter()
        .map(|&(study, cycles)| {
            let several = keys.iter().filter(|k| k.0 == study).count() > 1;
            Series {
                name: if several {
                    format!("{}, {cycles} cycles", study.replace('_', " "))
                } else {
                    study.replace('_', " ")
                },
                points: rows
                    .iter()
                    .filter(|r| r.study == study && r.cycles == cycles && !r.reference)
                    .map(|r| Point {
                        x: r.wall_s,
                        y: measure(r).abs(),
                        label: short(&r.setting).to_owned(),
                    })
                    .collect(),
            }
        })
        .filter(|s| !s.points.is_empty())
        .collect()
}

const COUPLING_HEADERS: [&str; 8] = [
    "N",
    "mu",
    "abs(mu delta-nu)",
    "max abs(pressure change) / p0",
    "ratio",
    "auto",
    "solve s",
    "coupled solve s",
];

fn coupling_cells(r: &CouplingRow) -> Vec<String> {
    vec![
        r.n.to_string(),
        format!("{:.0e}", r.friction_coefficient),
        format!("{:.2e}", r.strength),
        format!("{:.2e}", r.change),
        format!("{:.3}", r.ratio),
        if r.auto_on { "on" } else { "off" }.to_owned(),
        sig(r.normal_s, 3),
        sig(r.coupled_s, 3),
    ]
}

/// The report being written: markdown text and the plots written so far.
struct Report {
    text: String,
    plot_dir: PathBuf,
    link_dir: String,
    plots: usize,
}

impl Report {
    /// Appends a block (paragraph, table, list, image), a blank line after it.
    fn push(&mut self, block: &str) {
        self.text += block.trim_end();
        self.text += "\n\n";
    }

    /// Writes `plot` as `NAME.svg` and links it.
    fn plot(&mut self, name: &str, plot: &LogLogPlot) -> Result<(), String> {
        let file = format!("{name}.svg");
        plot.write_svg(&self.plot_dir.join(&file))?;
        self.plots += 1;
        let link = format!("![{}]({}/{file})\n", plot.title, self.link_dir);
        self.push(&link);
        Ok(())
    }

    fn time_plot(&mut self, name: &str, title: String, series: Vec<Series>) -> Result<(), String> {
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

    fn wear_plots(&mut self, prefix: &str, rows: &[&WearRow]) -> Result<(), String> {
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
) -> Result<usize, String> {
    let stem = path
        .file_stem()
        .ok_or_else(|| format!("{}: not a file name", path.display()))?
        .to_string_lossy()
        .into_owned();
    let folder = path.parent().unwrap_or(Path::new(""));
    let plot_dir = folder.join(&stem);
    std::fs::create_dir_all(&plot_dir)
        .map_err(|e| format!("cannot create {}: {e}", plot_dir.display()))?;
    let peers = std::fs::read_to_string(folder.join("peers.md")).ok();
    let mut report = Report {
        text: String::new(),
        plot_dir,
        link_dir: stem,
        plots: 0,
    };
    render(&mut report, measured, machine, command, peers.as_deref())?;
    std::fs::write(path, report.text.trim_end().to_owned() + "\n")
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(report.plots)
}

fn render(
    report: &mut Report,
    measured: &Measurements,
    machine: &Machine,
    command: &str,
    peers: Option<&str>,
) -> Result<(), String> {
    report.push(&header(machine, command));
    if !measured.contact.is_empty() {
        contact_section(report, &measured.contact, &measured.contact_tolerance)?;
    }
    if !measured.wear.is_empty() {
        wear_section(report, &measured.wear)?;
    }
    if let Some(auto) = &measured.auto {
        auto_section(report, auto, measured)?;
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

fn contact_section(
    report: &mut Report,
    rows: &[ContactRow],
    tolerance: &[ToleranceRow],
) -> Result<(), String> {
    let (_, hertz) = paper_hertz();
    report.push(&format!(
        "## Contact: the Hertz case\n\n\
         The paper's case (R {} mm, F {} N, E* {:.2} GPa, domain {} mm, apex on a cell corner, \
         tolerance 1e-8) against Hertz's solution. Wall time is the kernel and operator \
         construction plus the solve (medians of repeated runs); \"FFT pair\" is one forward and \
         inverse real FFT of the padded 2N x 2N grid, timed in the same run.\n\n\
         ### Grid\n",
        hertz.radius_m * 1e3,
        hertz.load_n,
        hertz.reduced_modulus_pa / 1e9,
        HERTZ_DOMAIN_M * 1e3
    ));
    let of = |case: ContactCase| -> Vec<ContactRow> {
        rows.iter().filter(|r| r.case == case).cloned().collect()
    };
    let (elastic, capped) = (of(ContactCase::Hertz), of(ContactCase::Capped));
    let cells: Vec<Vec<String>> = elastic.iter().map(contact_cells).collect();
    report.push(&table(&CONTACT_HEADERS, &cells));
    if !capped.is_empty() {
        report.push(&format!(
            "### Capped at Y = {:.1} MPa\n\n\
             The same case with the pressure cap (the paper's H(10 cycles) / 2.8). No analytic \
             answer exists: the errors are against our own N = {CAPPED_REFERENCE_N} solution \
             solved to 1e-12, and \"p_max / Y - 1\" checks that the cap is reached and held.",
            CAPPED_YIELD_PRESSURE_PA / 1e6
        ));
        let cells: Vec<Vec<String>> = capped
            .iter()
            .map(|r| {
                vec![
                    r.n.to_string(),
                    sig(r.wall_s, 3),
                    r.iterations.to_string(),
                    error(r.err_pmax),
                    error(r.err_area),
                    error(r.err_delta),
                    r.err_plastic_area.map_or_else(String::new, error),
                ]
            })
            .collect();
        report.push(&table(
            &[
                "N",
                "wall s",
                "iterations",
                "p_max / Y - 1",
                "area error",
                "approach error",
                "capped area error",
            ],
            &cells,
        ));
    }
    report.push(PLOT_NOTE);
    for (name, what, measure) in CONTACT_MEASURES {
        let mut series = vec![contact_series("Hertz", &elastic, measure)];
        // The capped p_max is the cap itself, not an error of the grid.
        if name != "pmax" && !capped.is_empty() {
            series.push(contact_series("capped", &capped, measure));
        }
        report.time_plot(
            &format!("contact-{name}"),
            format!("Contact {what}: |error| against wall time"),
            series,
        )?;
    }
    if !tolerance.is_empty() {
        tolerance_section(report, tolerance)?;
    }
    Ok(())
}

fn tolerance_section(report: &mut Report, rows: &[ToleranceRow]) -> Result<(), String> {
    report.push(
        "### Solver tolerance\n\n\
         The grid held at N = 256; \"solve error\" is max |p - p*| / max p* against the same \
         grid solved to 1e-12, the part of the error the tolerance alone leaves. The other \
         errors are those of the grid table (against Hertz, or the capped reference).",
    );
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.case.name().to_owned(),
                format!("{:.0e}", r.tolerance),
                sig(r.solve_s, 3),
                r.iterations.to_string(),
                format!("{:.1e}", r.residual),
                error(r.err_solve),
                error(r.err_area),
                error(r.err_delta),
            ]
        })
        .collect();
    report.push(&table(
        &[
            "case",
            "tolerance",
            "solve s",
            "iterations",
            "residual",
            "solve error",
            "area error",
            "approach error",
        ],
        &cells,
    ));
    let series: Vec<Series> = ContactCase::ALL
        .iter()
        .map(|&case| Series {
            name: case.name().to_owned(),
            points: rows
                .iter()
                .filter(|r| r.case == case)
                .map(|r| Point {
                    x: r.solve_s,
                    y: r.err_solve.abs(),
                    label: format!("{:.0e}", r.tolerance),
                })
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    report.time_plot(
        "contact-tolerance",
        "Contact solve error against solve time, by tolerance (N = 256)".to_owned(),
        series,
    )
}

/// The wear studies in report order, with their headings.
const WEAR_STUDIES: [(&str, &str); 4] = [
    (
        "grid",
        "### Grid\n\nCells across the first domain (3 contact radii, grown with the track), 300 \
         cycles; errors against the finest grid.",
    ),
    (
        "tolerance",
        "### Solver tolerance\n\nGrid 64, 300 cycles; errors against the tightest tolerance.",
    ),
    (
        "cycle_step",
        "### Cycle step\n\nThe auto grid; errors against solving every cycle, at the same cycle \
         count.",
    ),
    (
        "paper_numerics",
        "### The paper's numerics against all auto\n\n300 cycles.",
    ),
];

fn wear_section(report: &mut Report, rows: &[WearRow]) -> Result<(), String> {
    report.push(
        "## Wear: the paper scene\n\n\
         The `dalmau2018-316l` preset; errors are those of the final wear volume and deepest \
         point, relative to each study's reference; speed-up is the reference's wall time over \
         the row's.\n",
    );
    let mut plotted = Vec::new();
    for (study, heading) in WEAR_STUDIES {
        let of: Vec<&WearRow> = rows.iter().filter(|r| r.study == study).collect();
        if of.is_empty() {
            continue;
        }
        report.push(heading);
        report.push(&wear_table(&of, study == "cycle_step"));
        plotted.extend(of);
    }
    report.push(&format!(
        "The grid, tolerance and cycle-step studies on one pair of axes. {PLOT_NOTE}\n"
    ));
    report.wear_plots("wear", &plotted)?;

    let measured: Vec<Vec<String>> = rows
        .iter()
        .filter(|r| r.study == "table3")
        .map(|r| {
            vec![
                r.setting.clone(),
                r.cycles.to_string(),
                format!("{:.3e}", r.wear_volume_mm3),
                error(r.err_volume),
            ]
        })
        .collect();
    if !measured.is_empty() {
        report.push(
            "### Against the paper's Table 3\n\n\
             Archard's k calibrated on the 3600 s volume, grid 64; errors against the measured \
             volumes (the last solved cycle at or before each time). One run, so no time axis: \
             this is the model's accuracy, not a numerical setting's.\n",
        );
        report.push(&table(
            &["measurement", "solved cycle", "volume mm3", "error"],
            &measured,
        ));
    }
    Ok(())
}

/// The contact row nearest the auto cell density, and the one at half of it.
fn nearest_density(rows: &[ContactRow]) -> Option<(&ContactRow, Option<&ContactRow>)> {
    let distance = |r: &ContactRow| {
        (hertz_cells_per_radius(r.n) / CELLS_PER_CONTACT_RADIUS)
            .ln()
            .abs()
    };
    let hertz = || rows.iter().filter(|r| r.case == ContactCase::Hertz);
    let best = hertz().min_by(|a, b| distance(a).total_cmp(&distance(b)))?;
    let coarser = hertz().find(|r| 2 * r.n == best.n);
    Some((best, coarser))
}

fn auto_section(
    report: &mut Report,
    auto: &AutoStudies,
    measured: &Measurements,
) -> Result<(), String> {
    report.push(
        "## The auto choices and the numbers behind them\n\n\
         What `\"auto\"` decides for each scene (`src/simulation/setup.rs`, `stepping.rs`) and \
         what each threshold buys, measured in this run. The wear runs of this section use grid \
         64 (300 cycles) where the grid is not the question, to keep the whole command to a few \
         minutes.",
    );
    grid_choice(report, auto, measured);
    let of =
        |study: &str| -> Vec<&WearRow> { auto.wear.iter().filter(|r| r.study == study).collect() };
    domain_choice(report, auto, &of("domain"));
    step_choice(report, measured);
    coupling_section(report, auto)?;
    report.push("In the paper scene (grid 64, 300 cycles):");
    report.push(&wear_table(&of("coupling"), false));
    plasticity_choice(
        report,
        auto,
        &[of("plasticity"), of("elastic_load")].concat(),
    );
    report.push(&format!(
        "The domain, coupling and plasticity alternatives against wall time. {PLOT_NOTE}"
    ));
    let everything: Vec<&WearRow> = auto.wear.iter().collect();
    report.wear_plots("auto", &everything)
}

/// A markdown list.
fn bullets(items: &[String]) -> String {
    items.iter().map(|i| format!("- {i}\n")).collect()
}

fn grid_choice(report: &mut Report, auto: &AutoStudies, measured: &Measurements) {
    let g = &auto.grid;
    let mut text = format!(
        "### Grid: `CELLS_PER_CONTACT_RADIUS` = {CELLS_PER_CONTACT_RADIUS}\n\n\
         The paper scene gets {} x {} cells of {:.3} um: {:.1} cells per contact radius of \
         {:.1} um (the side rounds up to a fast FFT size).",
        g.cells, g.cells, g.cell_um, g.cells_per_radius, g.contact_radius_um
    );
    if let Some((best, coarser)) = nearest_density(&measured.contact) {
        let _ = write!(
            text,
            " On the Hertz case the nearest grid, N = {} ({:.1} cells per radius), errs by {} \
             (peak pressure), {} (area) and {} (approach) in {} s",
            best.n,
            hertz_cells_per_radius(best.n),
            error(best.err_pmax),
            error(best.err_area),
            error(best.err_delta),
            sig(best.wall_s, 3)
        );
        if let Some(c) = coarser {
            let _ = write!(
                text,
                "; half the density (N = {}) is {:.1} times faster and errs {:.1} times more in \
                 peak pressure and {:.1} times more in area",
                c.n,
                best.wall_s / c.wall_s,
                (c.err_pmax / best.err_pmax).abs(),
                (c.err_area / best.err_area).abs()
            );
        }
        text += ". The contact table above has every density.";
    }
    report.push(&text);
    let rows: Vec<Vec<String>> = measured
        .wear
        .iter()
        .filter(|r| r.study == "grid")
        .map(|r| {
            let [volume, depth, _] = versus(r);
            vec![
                format!("{:.1}", r.grid as f64 / DOMAIN_PER_CONTACT_RADIUS),
                r.setting.clone(),
                sig(r.wall_s, 3),
                volume,
                depth,
            ]
        })
        .collect();
    if !rows.is_empty() {
        report.push(&format!(
            "On the paper scene (the wear grid study; its domain is auto, so the first grid \
             spans {DOMAIN_PER_CONTACT_RADIUS} contact radii):"
        ));
        let headers = [
            "cells per contact radius",
            "grid",
            "wall s",
            "volume error",
            "depth error",
        ];
        report.push(&table(&headers, &rows));
    }
}

fn domain_choice(report: &mut Report, auto: &AutoStudies, rows: &[&WearRow]) {
    report.push(&format!(
        "### Domain: `DOMAIN_PER_CONTACT_RADIUS` = {DOMAIN_PER_CONTACT_RADIUS}, grown near the \
         edge\n\n\
         DC-FFT convolves without wrap-around, so any domain holding the contact gives the same \
         answer: the run starts at {DOMAIN_PER_CONTACT_RADIUS} contact radii and grows the \
         domain when pressure nears its edge. The paper scene at the cells of grid 64, against \
         fixed domains:"
    ));
    report.push(&wear_table(rows, false));
    if auto.domain_growth.is_empty() {
        report.push("The auto-domain run did not grow.");
    } else {
        report.push("The auto-domain run grew as follows (the run's own words):");
        report.push(&bullets(&auto.domain_growth));
    }
}

fn step_choice(report: &mut Report, measured: &Measurements) {
    report.push(&format!(
        "### Cycle step: `STEP_CHANGE_BOUND` = {STEP_CHANGE_BOUND}, `MAX_STEP` = {MAX_STEP}\n\n\
         A solve stands for the next cycles while the per-pass wear profile changes by less than \
         the bound (relative, L1) per step, the step at most doubling each time and never \
         beyond `MAX_STEP`. The bound is the scene's `numerics.cycle_step_bound` (default \
         {STEP_CHANGE_BOUND}); the cycle-step study above sweeps it against solving every \
         cycle:"
    ));
    let steps: Vec<&WearRow> = measured
        .wear
        .iter()
        .filter(|r| r.study == "cycle_step")
        .collect();
    if steps.is_empty() {
        report.push("(Measured by `bench wear`; not part of this run.)");
        return;
    }
    let lines: Vec<String> = steps
        .iter()
        .filter(|r| !r.reference)
        .map(|r| {
            format!(
                "{} cycles, {}: {} solves, the longest step {} cycles; {} solves stood for `MAX_STEP` \
                 cycles ({:.0}% of the cycles), the bound, the doubling limit or yielding (steps \
                 of 1 while pressures sit at Y) set the others.",
                r.cycles,
                short(&r.setting),
                r.solves,
                r.longest_step,
                r.steps_at_max,
                100.0 * (r.steps_at_max as u64 * MAX_STEP) as f64 / r.cycles as f64
            )
        })
        .collect();
    report.push(&bullets(&lines));
    if steps.iter().all(|r| r.longest_step < MAX_STEP) {
        report.push(
            "No step reached `MAX_STEP` here: in the paper scene it only bounds how rarely a \
             cycle is recorded, so the accuracy above is the bound's.",
        );
    }
}

fn plasticity_choice(report: &mut Report, auto: &AutoStudies, rows: &[&WearRow]) {
    report.push(
        "### Plasticity: Hertz's p0 against the lowest yield pressure\n\n\
         Pressures are highest on the unworn surface, so `auto` caps them at Y only when \
         Hertz's peak pressure reaches the lowest Y of the run. The decisions at 5 N and 1.5 N, \
         in the runs' own words:",
    );
    report.push(&bullets(&auto.plasticity));
    report.push("What the other choice would change (grid 64, 300 cycles):");
    report.push(&wear_table(rows, false));
}

fn coupling_section(report: &mut Report, auto: &AutoStudies) -> Result<(), String> {
    let mut sizes: Vec<usize> = auto.coupling.iter().map(|r| r.n).collect();
    sizes.dedup();
    let lowest: Vec<String> = sizes
        .iter()
        .map(|&n| {
            let ratio = auto
                .coupling
                .iter()
                .filter(|r| r.n == n && r.auto_on)
                .map(|r| r.ratio)
                .fold(f64::INFINITY, f64::min);
            format!("{ratio:.3} at N = {n}")
        })
        .collect();
    let noise = auto
        .coupling
        .iter()
        .filter(|r| !r.auto_on)
        .map(|r| r.change)
        .fold(0.0, f64::max);
    report.push(&format!(
        "### Coupling: `COUPLING_SENSITIVITY` = {COUPLING_SENSITIVITY}\n\n\
         `auto` models the friction coupling term when {COUPLING_SENSITIVITY} |mu delta-nu| \
         reaches the solver tolerance ({:.0e}). On the Hertz case, solved with and without the \
         term at that tolerance, the largest pressure change relative to p0 is at least {} \
         times |mu delta-nu| (over the rows `auto` models). The ratio grows with the grid (the \
         change peaks at the contact edge), so {COUPLING_SENSITIVITY} is the coarsest grid's: \
         the side that models the term more often. Below the threshold the change measured (up \
         to {noise:.1e} of p0) is the two solves' own disagreement at this tolerance rather than \
         the term's effect.\n",
        auto.tolerance,
        lowest.join(", ")
    ));
    let cells: Vec<Vec<String>> = auto.coupling.iter().map(coupling_cells).collect();
    report.push(&table(&COUPLING_HEADERS, &cells));
    let mut series: Vec<Series> = sizes
        .iter()
        .enumerate()
        .map(|(i, &n)| Series {
            name: format!("N = {n}"),
            points: auto
                .coupling
                .iter()
                .filter(|r| r.n == n)
                .map(|r| Point {
                    x: r.strength,
                    y: r.change,
                    // The same mu at every N: labelled once.
                    label: if i == 0 {
                        format!("mu={:.0e}", r.friction_coefficient)
                    } else {
                        String::new()
                    },
                })
                .collect(),
        })
        .collect();
    let mut strengths: Vec<f64> = auto.coupling.iter().map(|r| r.strength).collect();
    strengths.sort_by(f64::total_cmp);
    strengths.dedup();
    let threshold = Series {
        name: format!("{COUPLING_SENSITIVITY} |mu delta-nu|"),
        points: strengths
            .iter()
            .map(|&s| Point {
                x: s,
                y: COUPLING_SENSITIVITY * s,
                label: String::new(),
            })
            .collect(),
    };
    // Drawn first so the measured lines lie on top of it.
    series.insert(0, threshold);
    report.plot(
        "coupling",
        &LogLogPlot {
            title: "Coupling term: pressure change against |mu delta-nu|".into(),
            x_label: "|mu delta-nu|".into(),
            y_label: "max |pressure change| / p0".into(),
            series,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::Reference;

    fn wear_row(study: &'static str, setting: &str, err: f64, reference: bool) -> WearRow {
        WearRow {
            study,
            setting: setting.to_owned(),
            cycles: 300,
            grid: 64,
            wall_s: 0.3125,
            solves: 87,
            iterations: 900,
            wear_volume_mm3: 1.2e-3,
            max_depth_um: 0.76,
            err_volume: err,
            err_depth: -err,
            speedup: 3.0,
            reference,
            longest_step: 16,
            steps_at_max: 0,
        }
    }

    #[test]
    fn a_contact_row_formats_as_one_markdown_line() {
        let row = ContactRow {
            study: "contact_grid",
            case: ContactCase::Hertz,
            n: 256,
            runs: 9,
            residual: 9.7e-9,
            err_plastic_area: None,
            measures: Reference::hertz().measures,
            reference: Reference::hertz(),
            wall_s: 0.083_91,
            build_s: 0.0142,
            solve_s: 0.0697,
            iterations: 42,
            applies: 53,
            fft_pair_s: 1.5e-3,
            iteration_per_fft_pair: 1.181,
            err_pmax: -1.0751e-4,
            err_area: 6.3666e-3,
            err_delta: -2.2598e-5,
        };
        let text = table(&CONTACT_HEADERS, &[contact_cells(&row)]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[1], "|---|---|---|---|---|---|---|---|---|---|");
        assert_eq!(
            lines[2],
            "| 256 | 44.2 | 0.0839 | 0.0142 | 0.0697 | 42 | 1.18 | -1.08e-4 | +6.37e-3 | -2.26e-5 |"
        );
    }

    #[test]
    fn a_wear_row_shows_its_errors_and_a_reference_says_so() {
        let cells = wear_cells(&wear_row("grid", "64 cells, 2.07 um", 1.3e-4, false), true);
        assert_eq!(
            cells,
            [
                "64 cells, 2.07 um",
                "300",
                "0.312",
                "87",
                "16",
                "0",
                "+1.30e-4",
                "-1.30e-4",
                "3.0"
            ]
        );
        let cells = wear_cells(&wear_row("grid", "256 cells", 0.0, true), false);
        assert_eq!(&cells[4..], ["reference", "reference", "1"]);
        assert_eq!(error(f64::NAN), "n/a");
    }

    #[test]
    fn pipes_in_a_cell_are_escaped() {
        let text = table(&["a"], &[vec!["x | y".into()]]);
        assert!(text.ends_with("| x \\| y |\n"), "{text}");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(0.002_957, 3), "0.00296");
        assert_eq!(sig(3.7725, 3), "3.77");
        assert_eq!(sig(106.17, 3), "106");
        assert_eq!(sig(0.0, 3), "0");
    }

    #[test]
    fn series_leave_references_out_and_split_studies_by_cycle_count() {
        let mut long = wear_row("cycle_step", "auto", 2e-4, false);
        long.cycles = 3600;
        let rows = [
            wear_row("cycle_step", "every cycle (reference)", 0.0, true),
            wear_row("cycle_step", "auto", 0.0, false),
            long,
            wear_row("grid", "128 cells, 1.04 um", -3e-5, false),
        ];
        let refs: Vec<&WearRow> = rows.iter().collect();
        let series = wear_series(&refs, |r| r.err_volume);
        let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(
            names,
            ["cycle step, 300 cycles", "cycle step, 3600 cycles", "grid"]
        );
        assert_eq!(series[0].points.len(), 1, "the reference is left out");
        assert!(
            series[0].points[0].y == 0.0,
            "an exact zero is kept for the plot"
        );
        assert_eq!(series[2].points[0].label, "128 cells");
        assert!(series[2].points[0].y > 0.0, "|error|");
    }

    #[test]
    fn cpuinfo_gives_the_model_and_the_processor_count() {
        let text = "processor\t: 0\nmodel name\t: AMD EPYC 7B13\nflags\t: fpu\n\n\
                    processor\t: 1\nmodel name\t: AMD EPYC 7B13\n";
        assert_eq!(parse_cpuinfo(text), (Some("AMD EPYC 7B13".to_owned()), 2));
        assert_eq!(parse_cpuinfo(""), (None, 0));
    }

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
                wear_row("grid", "256 cells, 0.52 um (reference)", 0.0, true),
                wear_row("grid", "64 cells, 2.07 um", 1.3e-4, false),
                wear_row("table3", "300 s: measured", 0.2, false),
            ],
            auto: None,
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
}
