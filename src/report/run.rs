//! The report of one run: the scene and its differences from its preset, the models and
//! warnings, the summary, the figures, the measurements against the model, the methods and
//! the provenance.

use crate::simulation::{SimulationResult, Summary, rms_residual};

use super::figure::FigureError;
use super::html::{Cell, escape, heading, number, page, paragraph, sized_table, table};
use super::methods::{methods, report_provenance, run_provenance};
use super::residuals::{Measured, Residual, column, residuals};
use super::run_figures::{measured_volumes, model_potential, model_volume, run_figures};
use super::scene::{closest_preset, flatten, shown};

/// The summary's quantities as rows: name, value, unit.
pub fn summary_rows(summary: &Summary) -> Vec<Vec<Cell>> {
    let mut rows = vec![
        ("cycles", Some(summary.cycles as f64), "cycles"),
        (
            "total volume lost (mechanical + WAC)",
            Some(summary.wear_volume_mm3),
            "mm^3",
        ),
        ("mechanical volume", summary.mechanical_volume_mm3, "mm^3"),
        ("WAC volume", summary.wac_volume_mm3, "mm^3"),
        ("maximum depth", Some(summary.max_depth_um), "um"),
        ("anodic charge", summary.charge_c, "C"),
        ("final potential", summary.potential_v, "V"),
        ("Archard k", Some(summary.wear.archard_k), "dimensionless"),
        ("wall-clock time", Some(summary.wall_s), "s"),
        ("contact solves", Some(summary.solves as f64), ""),
        ("solver iterations", Some(summary.iterations as f64), ""),
    ]
    .into_iter()
    .filter_map(|(name, value, unit)| {
        Some(vec![
            Cell::text(name),
            Cell::number(value?),
            Cell::text(unit),
        ])
    })
    .collect::<Vec<_>>();
    if let Some(reference) = summary.potential_reference {
        rows.push(vec![
            Cell::text("potentials against"),
            Cell::text(reference.label()),
            Cell::text(""),
        ]);
    }
    rows
}

/// The scene as run: its differences from the closest preset, then every field.
fn scene_section(result: &SimulationResult) -> String {
    let mut html = heading(2, "The scene as run");
    html.push_str(&paragraph("", &format!("Name: {}", result.scene.name)));
    match closest_preset(&result.scene) {
        Some((name, found)) if found.is_empty() => {
            html.push_str(&paragraph(
                "",
                &format!("The scene is the preset `{name}` unchanged."),
            ));
        }
        Some((name, found)) => {
            let rows: Vec<Vec<Cell>> = found
                .iter()
                .map(|d| {
                    vec![
                        Cell::text(&d.path),
                        Cell::text(shown(d.preset.as_ref())),
                        Cell::text(shown(d.run.as_ref())),
                    ]
                })
                .collect();
            let caption = format!("How the scene differs from the preset `{name}`");
            html.push_str(&table(&caption, &["field", name, "this run"], &rows));
        }
        None => {}
    }
    let fields = serde_json::to_value(&result.scene)
        .map(|v| flatten(&v))
        .unwrap_or_default();
    let rows: Vec<Vec<Cell>> = fields
        .iter()
        .map(|(path, value)| vec![Cell::text(path), Cell::text(shown(Some(value)))])
        .collect();
    html.push_str(&table(
        "Every field of the scene as run",
        &["field", "value"],
        &rows,
    ));
    html
}

/// The models with their reasons, and the warnings, under the heading `title`.
pub fn models_section(result: &SimulationResult, title: &str) -> String {
    let mut html = heading(2, title);
    let rows: Vec<Vec<Cell>> = result
        .models
        .iter()
        .map(|m| {
            let name = serde_json::to_value(m.name).ok();
            vec![
                Cell::text(name.as_ref().and_then(|v| v.as_str()).unwrap_or_default()),
                Cell::text(if m.active { "yes" } else { "no" }),
                Cell::text(&m.reason),
            ]
        })
        .collect();
    html.push_str(&sized_table(
        "The models the run used, and why",
        &["model", "active", "reason"],
        &rows,
        &[18, 9, 73],
    ));
    if result.warnings.is_empty() {
        html.push_str(&paragraph("muted", "No warnings."));
    } else {
        html.push_str("<ul>");
        for warning in &result.warnings {
            html.push_str(&format!("<li class=\"warning\">{}</li>", escape(warning)));
        }
        html.push_str("</ul>\n");
    }
    html
}

/// One kind's residuals as a table, with their root mean square.
fn residual_table(caption: &str, at: &str, unit: &str, points: &[Residual]) -> String {
    let rows: Vec<Vec<Cell>> = points
        .iter()
        .map(|p| {
            vec![
                Cell::number(p.x),
                Cell::number(p.measured),
                Cell::optional(p.model),
                Cell::optional(p.residual),
                Cell::optional(p.z_score),
            ]
        })
        .collect();
    let rms = rms_residual(points).map_or_else(
        || "no point within the run".to_owned(),
        |r| format!("{} {unit}", number(r)),
    );
    let caption = format!("{caption}; root mean square residual {rms}");
    let header = [
        at,
        &format!("measured ({unit})"),
        &format!("model ({unit})"),
        "residual",
        "z",
    ];
    table(&caption, &header, &rows)
}

/// The attached measurements against the model.
fn measurements_section(result: &SimulationResult, measured: &Measured) -> String {
    let mut html = heading(2, "Measurements against the model");
    if measured.is_empty() {
        html.push_str(&paragraph(
            "muted",
            "No measurements are attached to this run.",
        ));
        return html;
    }
    html.push_str(&paragraph(
        "",
        "Each measured point beside the model's value there (linear interpolation between \
         the result's points; none outside the run), the residual (measured minus model) \
         and, where the measurement gives its spread, the residual in spreads (z).",
    ));
    if measured.wear_volume.is_some() {
        let points = residuals(&model_volume(result), &measured_volumes(result, measured));
        let of = if result.scene.corrosion.is_some() {
            "total volume, what a profilometer measures"
        } else {
            "wear"
        };
        html.push_str(&residual_table(
            &format!("Wear volume against the model's {of}"),
            "cycle",
            "mm^3",
            &points,
        ));
    }
    if let (Some(table_of), Some(last)) = (&measured.profile, result.profiles.last()) {
        let curve: Vec<(f64, f64)> = last
            .y_um
            .iter()
            .copied()
            .zip(last.depth_um.iter().copied())
            .collect();
        let at: Vec<(f64, f64, Option<f64>)> = column(table_of, "y_mm")
            .iter()
            .zip(column(table_of, "depth_um"))
            .map(|(y, d)| (y * 1e3, *d, None))
            .collect();
        let caption = format!("Depth profile against the model's at cycle {}", last.cycle);
        html.push_str(&residual_table(
            &caption,
            "y (um)",
            "um",
            &residuals(&curve, &at),
        ));
    }
    if let Some(table_of) = &measured.ocp {
        let at: Vec<(f64, f64, Option<f64>)> = column(table_of, "time_s")
            .iter()
            .zip(column(table_of, "potential_v"))
            .map(|(t, v)| (*t, *v, None))
            .collect();
        let points = residuals(&model_potential(result), &at);
        html.push_str(&residual_table(
            "Potential against the model's, on the record's clock",
            "time (s)",
            "V",
            &points,
        ));
    }
    html
}

/// The whole report of `result`, with the `measured` points attached to it.
pub fn run_report(result: &SimulationResult, measured: &Measured) -> Result<String, FigureError> {
    let mut body = String::new();
    if !result.complete {
        body.push_str(&paragraph(
            "warning",
            "This run stopped before its last cycle: the report holds the cycles solved before the stop.",
        ));
    }
    body.push_str(&heading(2, "Summary"));
    body.push_str(&table(
        "",
        &["quantity", "value", "unit"],
        &summary_rows(&result.summary),
    ));
    body.push_str(&scene_section(result));
    body.push_str(&models_section(result, "Models and warnings"));
    body.push_str(&heading(2, "Figures"));
    body.push_str(&run_figures(result, measured)?);
    body.push_str(&measurements_section(result, measured));
    body.push_str(&methods(&result.models));
    body.push_str(&heading(2, "Provenance"));
    body.push_str(&run_provenance(result.provenance.as_ref()));
    body.push_str(&report_provenance());
    Ok(page(
        &format!("tribosim report: {}", result.scene.name),
        &body,
    ))
}
