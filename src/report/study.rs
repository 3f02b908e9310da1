//! The report of a study: its table, a figure of each summary quantity against each axis,
//! the methods and the provenance.

use std::collections::BTreeMap;

use serde_json::Value;

use crate::simulation::Summary;
use crate::study::{MemberRow, StudySummary};

use super::figure::{FigureError, LineFigure, Series, Style, figure};
use super::html::{Cell, heading, page, paragraph, sized_table};
use super::methods::{PAPER, build_table, report_provenance};

/// A summary quantity: its name, its unit and where in a summary it is.
type Quantity = (&'static str, &'static str, fn(&Summary) -> Option<f64>);

/// The quantities drawn against each axis: the volume a profilometer measures, its
/// mechanical and corrosion parts, the depth and the potential.
const QUANTITIES: [Quantity; 5] = [
    ("total volume lost", "mm^3", |s| Some(s.wear_volume_mm3)),
    ("mechanical volume", "mm^3", |s| s.mechanical_volume_mm3),
    ("wear-accelerated corrosion volume", "mm^3", |s| {
        s.wac_volume_mm3
    }),
    ("maximum depth", "um", |s| Some(s.max_depth_um)),
    ("final potential", "V", |s| s.potential_v),
];

/// A value as text: strings without their quotes.
fn plain(value: Option<&Value>) -> String {
    match value {
        Some(Value::String(text)) => text.clone(),
        Some(other) => other.to_string(),
        None => String::new(),
    }
}

/// The study's table: a row per member, its axis values, its summary or why it has none.
fn members_table(study: &StudySummary) -> String {
    let rows: Vec<Vec<Cell>> = study
        .members
        .iter()
        .map(|m| {
            let mut row = vec![Cell::text(m.index.to_string())];
            row.extend(
                study
                    .axes
                    .iter()
                    .map(|a| Cell::text(plain(m.values.get(a)))),
            );
            match &m.summary {
                Some(s) => row.extend(
                    QUANTITIES
                        .iter()
                        .map(|(_, _, of)| Cell::optional(of(s)))
                        .chain([Cell::text(s.warnings.join("; "))]),
                ),
                None => {
                    row.extend(QUANTITIES.iter().map(|_| Cell::text("")));
                    let pending = m.pending.map(|p| format!("not finished ({})", p.name()));
                    row.push(Cell::text(m.error.clone().or(pending).unwrap_or_default()));
                }
            }
            row
        })
        .collect();
    let units: Vec<String> = QUANTITIES
        .iter()
        .map(|(name, unit, _)| format!("{name} ({unit})"))
        .collect();
    let axes: Vec<String> = study.axes.iter().map(|a| axis_words(a)).collect();
    let mut header: Vec<&str> = vec!["member"];
    header.extend(axes.iter().map(String::as_str));
    header.extend(units.iter().map(String::as_str));
    header.push("error, or the run's warnings");
    // The warnings column takes a quarter of the page: a warning is a sentence, and at an
    // equal share it wraps to a word per line.
    let numbers = header.len() - 2;
    let each = u8::try_from(67 / numbers.max(1)).unwrap_or(1);
    let mut widths = vec![8];
    widths.extend(std::iter::repeat_n(each, numbers));
    widths.push(25);
    sized_table(
        "One row per member; a member whose run warned (a potential capped at E_corr, one \
         outside the Tafel domain, ...) says so in the last column, and its points in the \
         figures carry the same caveat",
        &header,
        &rows,
        &widths,
    )
}

/// The members that finished, grouped by their values on every axis but `axis` (a line per
/// group), as `(value on axis, summary)` in the axis's order; `None` when a value on
/// `axis` is not a number.
fn lines_along<'a>(
    study: &'a StudySummary,
    axis: &str,
) -> Option<BTreeMap<String, Vec<(f64, &'a Summary)>>> {
    let mut groups: BTreeMap<String, Vec<(f64, &Summary)>> = BTreeMap::new();
    for member in &study.members {
        let Some(summary) = &member.summary else {
            continue;
        };
        let x = member.values.get(axis)?.as_f64()?;
        groups
            .entry(others(study, member, axis))
            .or_default()
            .push((x, summary));
    }
    for points in groups.values_mut() {
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    Some(groups)
}

/// The member's values on the axes other than `axis`, as a legend reads them.
fn others(study: &StudySummary, member: &MemberRow, axis: &str) -> String {
    let parts: Vec<String> = study
        .axes
        .iter()
        .filter(|a| a.as_str() != axis)
        .map(|a| format!("{} = {}", axis_words(a), plain(member.values.get(a))))
        .collect();
    if parts.is_empty() {
        "members".to_owned()
    } else {
        parts.join(", ")
    }
}

/// Each quantity against each axis with numeric values.
fn figures(study: &StudySummary) -> Result<String, FigureError> {
    let mut html = String::new();
    for axis in &study.axes {
        let Some(groups) = lines_along(study, axis) else {
            html.push_str(&paragraph(
                "muted",
                &format!("`{axis}` takes values that are not numbers: no figure along it."),
            ));
            continue;
        };
        for (name, unit, of) in QUANTITIES {
            let mut series: Vec<Series> = groups
                .iter()
                .map(|(label, points)| {
                    let points = points
                        .iter()
                        .filter_map(|(x, s)| Some((*x, of(s)?)))
                        .collect();
                    Series::new(label.clone(), points, Style::Joined)
                })
                .collect();
            let warned = groups
                .values()
                .flatten()
                .filter(|(_, s)| !s.warnings.is_empty())
                .filter_map(|(x, s)| Some((*x, of(s)?)))
                .collect();
            series.push(Series::new(
                "the run warned: see the table",
                warned,
                Style::Flagged,
            ));
            let words = axis_words(axis);
            let f = LineFigure {
                title: format!("{name} against {words}"),
                x_label: words,
                y_label: format!("{name} ({unit})"),
                series,
            };
            html.push_str(&figure(
                f.svg()?.as_deref(),
                &f.title,
                "no finished member has this quantity",
            ));
        }
    }
    Ok(html)
}

/// An axis in words with its unit, from the scene's field table: the field's name without
/// its unit suffix, after the part for a ball's or a disc's (`test.load_n` is "load (N)",
/// `disc.hardness_mpa` "disc hardness (MPa)"); a path the table does not know, as it is.
fn axis_words(path: &str) -> String {
    let Some(field) = crate::scene::field(path) else {
        return path.to_owned();
    };
    let mut parts = path.split('.');
    let section = parts.next().unwrap_or_default();
    let name = parts.next_back().unwrap_or(path);
    let token = field.unit.to_lowercase().replace('/', "_").replace('^', "");
    let bare = name
        .strip_suffix(&format!("_{token}"))
        .filter(|_| !token.is_empty())
        .unwrap_or(name);
    let owner = if matches!(section, "ball" | "disc") {
        format!("{section} ")
    } else {
        String::new()
    };
    let words = format!("{owner}{}", bare.replace('_', " "));
    if field.unit.is_empty() {
        words
    } else {
        format!("{words} ({})", field.unit)
    }
}

/// The report of the study `name` summarised in `study`.
pub fn study_report(name: &str, study: &StudySummary) -> Result<String, FigureError> {
    let mut body = paragraph(
        "",
        &format!(
            "{} members over the axes {}; {} ended without a result. Each member is an \
             ordinary run of the model after {PAPER}; its own result holds its scene, its \
             models with their reasons and its provenance.",
            study.members.len(),
            study.axes.join(", "),
            study.failed()
        ),
    );
    body.push_str(&heading(2, "The members"));
    body.push_str(&members_table(study));
    body.push_str(&heading(2, "Figures against each axis"));
    body.push_str(&figures(study)?);
    body.push_str(&heading(2, "Provenance"));
    match &study.provenance {
        Some(build) => body.push_str(&build_table("The summary", build)),
        None => body.push_str(&paragraph(
            "muted",
            "The summary was written before tribosim recorded its provenance.",
        )),
    }
    body.push_str(&report_provenance());
    Ok(page(&format!("tribosim study report: {name}"), &body))
}

#[cfg(test)]
mod tests {
    use super::axis_words;

    #[test]
    fn an_axis_reads_in_words_with_its_unit() {
        assert_eq!(axis_words("test.load_n"), "load (N)");
        assert_eq!(axis_words("test.speed_rpm"), "speed (rpm)");
        assert_eq!(axis_words("disc.hardness_mpa"), "disc hardness (MPa)");
        assert_eq!(
            axis_words("test.friction_coefficient"),
            "friction coefficient"
        );
        assert_eq!(
            axis_words("corrosion.anodic_current_density_a_cm2"),
            "anodic current density (A/cm^2)"
        );
        assert_eq!(axis_words("no.such_field"), "no.such_field");
    }
}
