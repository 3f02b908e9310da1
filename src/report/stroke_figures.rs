//! The reciprocating rig's figures (`result.stroke`): the wear map, the depth along the
//! track's axis and the potential over a cycle at the traced cycles, as the page draws them.

use crate::simulation::{SimulationResult, StrokeReport};

use super::figure::{FigureError, LineFigure, Series, Style, figure};
use super::wear_map::wear_map_svg;

fn axial(stroke: &StrokeReport) -> LineFigure {
    let profile = &stroke.axial_profile;
    let points = profile
        .x_um
        .iter()
        .copied()
        .zip(profile.depth_um.iter().copied());
    LineFigure {
        title: "Wear depth along the stroke's axis at the end of the run".into(),
        x_label: "position along the stroke from its middle (um)".into(),
        y_label: "depth (um)".into(),
        series: vec![Series::new("depth", points.collect(), Style::Line)],
    }
}

/// The potential against the time into the cycle, one series per traced cycle, so the
/// oscillation at twice the frequency shows and the cycles overlay.
fn traces(stroke: &StrokeReport, period_s: f64) -> LineFigure {
    let series = stroke
        .traces
        .iter()
        .map(|trace| {
            let start = (trace.cycle - 1) as f64 * period_s;
            let points = trace
                .time_s
                .iter()
                .zip(&trace.potential_v)
                .map(|(t, e)| (t - start, *e));
            Series::new(
                format!("cycle {}", trace.cycle),
                points.collect(),
                Style::Line,
            )
        })
        .collect();
    LineFigure {
        title: "Potential over a cycle (the periodic state of each traced cycle)".into(),
        x_label: "time into the cycle (s)".into(),
        y_label: "potential (V)".into(),
        series,
    }
}

/// The figures of a reciprocating result as HTML `<figure>` elements; empty for a disc.
pub fn stroke_figures(result: &SimulationResult) -> Result<String, FigureError> {
    let Some(stroke) = &result.stroke else {
        return Ok(String::new());
    };
    let mut html = String::new();
    let caption = "Wear map along and across the stroke at the end of the run";
    let (svg, caption) = match wear_map_svg(&stroke.map) {
        Some((svg, scales)) => (Some(svg), format!("{caption}: {scales}")),
        None => (None, caption.to_owned()),
    };
    html.push_str(&figure(svg.as_deref(), &caption, "no wear"));
    let axial = axial(stroke);
    html.push_str(&figure(axial.svg()?.as_deref(), &axial.title, "no wear"));
    let traces = traces(stroke, result.scene.cycle_period_s());
    html.push_str(&figure(
        traces.svg()?.as_deref(),
        &traces.title,
        "this scene has no corrosion model: nothing to plot",
    ));
    Ok(html)
}
