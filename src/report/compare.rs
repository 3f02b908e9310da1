//! The report of several runs side by side: their summaries, the scene fields where they
//! differ, their figures on shared axes, and each run's provenance.

use std::collections::{BTreeMap, BTreeSet};

use crate::simulation::SimulationResult;

use super::figure::{FigureError, LineFigure, Series, Style, figure};
use super::html::{Cell, heading, page, paragraph, table};
use super::methods::{methods, report_provenance};
use super::run::{models_section, summary_rows};
use super::scene::{flatten, shown};

/// One run of a comparison and the label it goes by (a file name, a job id).
#[derive(Debug, Clone, Copy)]
pub struct Labelled<'a> {
    /// The label.
    pub label: &'a str,
    /// The run's result.
    pub result: &'a SimulationResult,
}

/// The summaries side by side: a row per quantity, a column per run.
fn summaries(runs: &[Labelled<'_>]) -> String {
    let mut quantities: Vec<String> = Vec::new();
    let mut values: BTreeMap<String, Vec<Cell>> = BTreeMap::new();
    for (i, run) in runs.iter().enumerate() {
        for row in summary_rows(&run.result.summary) {
            let (Some(Cell::Text(name)), Some(value)) = (row.first(), row.get(1)) else {
                continue;
            };
            let unit = match row.get(2) {
                Some(Cell::Text(unit)) if !unit.is_empty() => format!(" ({unit})"),
                _ => String::new(),
            };
            let key = format!("{name}{unit}");
            if !values.contains_key(&key) {
                quantities.push(key.clone());
            }
            let cells = values
                .entry(key)
                .or_insert_with(|| vec![Cell::text(""); runs.len()]);
            cells[i] = value.clone();
        }
    }
    let rows: Vec<Vec<Cell>> = quantities
        .iter()
        .map(|q| {
            std::iter::once(Cell::text(q))
                .chain(values[q].iter().cloned())
                .collect()
        })
        .collect();
    let mut header = vec!["quantity"];
    header.extend(runs.iter().map(|r| r.label));
    table("", &header, &rows)
}

/// The scene fields where the runs differ, a column per run.
fn scene_differences(runs: &[Labelled<'_>]) -> String {
    let fields: Vec<BTreeMap<String, serde_json::Value>> = runs
        .iter()
        .map(|r| {
            serde_json::to_value(&r.result.scene)
                .map(|v| flatten(&v))
                .unwrap_or_default()
        })
        .collect();
    let paths: BTreeSet<&String> = fields.iter().flat_map(BTreeMap::keys).collect();
    let rows: Vec<Vec<Cell>> = paths
        .into_iter()
        .filter(|path| fields.iter().any(|f| f.get(*path) != fields[0].get(*path)))
        .map(|path| {
            std::iter::once(Cell::text(path))
                .chain(fields.iter().map(|f| Cell::text(shown(f.get(path)))))
                .collect()
        })
        .collect();
    if rows.is_empty() {
        return paragraph("", "The runs' scenes are the same in every field.");
    }
    let mut header = vec!["field"];
    header.extend(runs.iter().map(|r| r.label));
    table("The scene fields where the runs differ", &header, &rows)
}

/// One figure with a series per run, its points given by `points`.
fn per_run(
    runs: &[Labelled<'_>],
    title: &str,
    axes: (&str, &str),
    points: impl Fn(&SimulationResult) -> Vec<(f64, f64)>,
) -> LineFigure {
    LineFigure {
        title: title.to_owned(),
        x_label: axes.0.to_owned(),
        y_label: axes.1.to_owned(),
        series: runs
            .iter()
            .map(|r| Series::new(r.label, points(r.result), Style::Line))
            .collect(),
    }
}

/// The figures of the runs on shared axes.
fn figures(runs: &[Labelled<'_>]) -> Result<String, FigureError> {
    let cycles = "cycles (passes of the ball)";
    let list = [
        per_run(
            runs,
            "Wear volume against cycles",
            (cycles, "wear volume (10^-3 mm^3)"),
            |r| {
                r.cycles
                    .iter()
                    .map(|c| (c.cycle as f64, c.wear_volume_mm3 * 1e3))
                    .collect()
            },
        ),
        per_run(
            runs,
            "Maximum wear depth against cycles",
            (cycles, "maximum depth (um)"),
            |r| {
                r.cycles
                    .iter()
                    .map(|c| (c.cycle as f64, c.max_depth_um))
                    .collect()
            },
        ),
        per_run(
            runs,
            "Potential at open circuit",
            ("time since the record started (s)", "potential (V)"),
            |r| {
                r.ocp_trace
                    .iter()
                    .map(|p| (p.time_s, p.potential_v))
                    .collect()
            },
        ),
        per_run(
            runs,
            "Wear-accelerated corrosion volume",
            ("time of rubbing (s)", "WAC volume (10^-3 mm^3)"),
            |r| {
                r.cycles
                    .iter()
                    .filter_map(|c| Some((c.time_s, c.wac_volume_mm3? * 1e3)))
                    .collect()
            },
        ),
        per_run(
            runs,
            "Last profile across the track, surface height -D(y)",
            ("y across the track (um)", "surface height -D (um)"),
            |r| {
                r.profiles.last().map_or_else(Vec::new, |p| {
                    p.y_um
                        .iter()
                        .zip(&p.depth_um)
                        .map(|(y, d)| (*y, -d.abs()))
                        .collect()
                })
            },
        ),
    ];
    let mut html = String::new();
    for f in &list {
        html.push_str(&figure(
            f.svg()?.as_deref(),
            &f.title,
            "no run has points to plot",
        ));
    }
    Ok(html)
}

/// Each run's provenance, a row per run.
fn provenance(runs: &[Labelled<'_>]) -> String {
    let rows: Vec<Vec<Cell>> = runs
        .iter()
        .map(|r| {
            let Some(p) = &r.result.provenance else {
                return vec![
                    Cell::text(r.label),
                    Cell::text("not recorded"),
                    Cell::text(""),
                    Cell::text(""),
                    Cell::text(""),
                    Cell::text(""),
                ];
            };
            let at = p
                .build
                .computed_at
                .format(&time::format_description::well_known::Rfc3339)
                .unwrap_or_default();
            vec![
                Cell::text(r.label),
                Cell::text(&p.build.tribosim_version),
                Cell::text(&p.build.git_commit),
                Cell::text(&p.scene_sha256),
                Cell::text(at),
                Cell::text(p.build.cores.to_string()),
            ]
        })
        .collect();
    table(
        "",
        &[
            "run",
            "version",
            "git commit",
            "scene SHA-256",
            "computed at (UTC)",
            "cores",
        ],
        &rows,
    )
}

/// The report comparing `runs`.
pub fn comparison_report(runs: &[Labelled<'_>]) -> Result<String, FigureError> {
    let mut body = paragraph(
        "",
        &format!(
            "{} runs: {}.",
            runs.len(),
            runs.iter()
                .map(|r| format!("{} ({})", r.label, r.result.scene.name))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    );
    body.push_str(&heading(2, "Summaries"));
    body.push_str(&summaries(runs));
    body.push_str(&heading(2, "The scenes"));
    body.push_str(&scene_differences(runs));
    body.push_str(&heading(2, "Figures"));
    body.push_str(&figures(runs)?);
    for run in runs {
        let title = format!("Models and warnings: {}", run.label);
        body.push_str(&models_section(run.result, &title));
    }
    if let Some(first) = runs.first() {
        body.push_str(&methods(&first.result.models));
    }
    body.push_str(&heading(2, "Provenance"));
    body.push_str(&provenance(runs));
    body.push_str(&report_provenance());
    Ok(page(
        &format!("tribosim comparison of {} runs", runs.len()),
        &body,
    ))
}
