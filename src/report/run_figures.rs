//! The figures of a run, those the page draws: wear volume (with Table 3 when the run is
//! the measured test, and the attached volumes), deepest point, potential, WAC volume,
//! profiles across the track (with the ball and an attached profile) and pressure maps.

use crate::scene::PAPER_TABLE3;
use crate::simulation::SimulationResult;

use super::figure::{FigureError, LineFigure, Series, Style, figure};
use super::pressure_map::{Map, pressure_svg};
use super::residuals::{Measured, column};
use super::scene::flatten;

/// The fields Table 3 was measured under, as the paper's preset holds them: a run that
/// differs in any is another experiment (the page's rule, `static/js/run-figures.js`).
const TABLE3_CONDITIONS: [&str; 5] = [
    "test.load_n",
    "test.speed_rpm",
    "test.track_radius_mm",
    "ball",
    "disc",
];

const CYCLES: &str = "cycles (passes of the ball)";

/// Whether Table 3 belongs beside a run of `result`'s scene.
fn table3_applies(result: &SimulationResult) -> bool {
    let (Ok(run), Ok(paper)) = (
        serde_json::to_value(&result.scene),
        serde_json::to_value(crate::scene::dalmau2018_316l()),
    ) else {
        return false;
    };
    let (run, paper) = (flatten(&run), flatten(&paper));
    let under =
        |path: &str, prefix: &str| path == prefix || path.starts_with(&format!("{prefix}."));
    TABLE3_CONDITIONS.iter().all(|prefix| {
        let pick = |fields: &std::collections::BTreeMap<String, serde_json::Value>| {
            fields
                .iter()
                .filter(|(path, _)| under(path, prefix))
                .map(|(path, value)| (path.clone(), value.clone()))
                .collect::<Vec<_>>()
        };
        pick(&run) == pick(&paper)
    })
}

/// The rubbing's cycles per second.
fn cycles_per_s(result: &SimulationResult) -> f64 {
    result.scene.test.cycles_per_second()
}

/// The measured wear volumes as `(cycle, mm^3, spread)`: at their cycles, or at their times
/// turned into cycles at the run's speed.
pub fn measured_volumes(
    result: &SimulationResult,
    measured: &Measured,
) -> Vec<(f64, f64, Option<f64>)> {
    let Some(table) = &measured.wear_volume else {
        return Vec::new();
    };
    let volumes = column(table, "volume_mm3");
    let (cycles, times, spread) = (
        column(table, "cycles"),
        column(table, "time_s"),
        column(table, "spread_mm3"),
    );
    (0..volumes.len())
        .map(|i| {
            let at = cycles
                .get(i)
                .copied()
                .or_else(|| times.get(i).map(|t| t * cycles_per_s(result)));
            (at.unwrap_or(f64::NAN), volumes[i], spread.get(i).copied())
        })
        .collect()
}

/// The model's volume Table 3 and an attached volume compare with: the total (wear and
/// WAC, what a profilometer measures) with corrosion, else the wear, from 0 at cycle 0.
pub fn model_volume(result: &SimulationResult) -> Vec<(f64, f64)> {
    std::iter::once((0.0, 0.0))
        .chain(result.cycles.iter().map(|c| {
            (
                c.cycle as f64,
                c.total_volume_mm3.unwrap_or(c.wear_volume_mm3),
            )
        }))
        .collect()
}

fn volume(result: &SimulationResult, measured: &Measured) -> LineFigure {
    let c = &result.cycles;
    let milli = |points: Vec<(f64, f64)>| points.into_iter().map(|(x, y)| (x, y * 1e3)).collect();
    // The total is what a profilometer measures, the measurements' quantity; the
    // mechanical part is drawn beside it only where a corrosion volume tells them apart.
    let mut series = vec![Series::new(
        "model: total",
        milli(model_volume(result)),
        Style::Line,
    )];
    let mechanical: Vec<(f64, f64)> = c
        .iter()
        .filter(|r| r.wac_volume_mm3.is_some())
        .filter_map(|r| Some((r.cycle as f64, r.mechanical_volume_mm3?)))
        .collect();
    if !mechanical.is_empty() {
        series.push(Series::new(
            "model: mechanical",
            milli(mechanical),
            Style::Line,
        ));
    }
    if table3_applies(result) {
        let last = result.scene.test.cycles as f64;
        let points = PAPER_TABLE3
            .iter()
            .map(|r| {
                (
                    r.time_s as f64 * cycles_per_s(result),
                    r.wear_volume_mm3 * 1e3,
                    Some(r.spread_mm3 * 1e3),
                )
            })
            .filter(|(n, _, _)| *n <= last);
        series.push(Series::measured(
            "Table 3, measured (mean and spread)",
            points.collect(),
        ));
    }
    let attached = measured_volumes(result, measured)
        .into_iter()
        .map(|(n, v, spread)| (n, v * 1e3, spread.map(|s| s * 1e3)));
    series.push(Series::measured("attached measurement", attached.collect()));
    LineFigure {
        title: "Wear volume against cycles".into(),
        x_label: CYCLES.into(),
        y_label: "wear volume (10^-3 mm^3)".into(),
        series,
    }
}

fn depth(result: &SimulationResult) -> LineFigure {
    let points = result
        .cycles
        .iter()
        .map(|r| (r.cycle as f64, r.max_depth_um));
    LineFigure {
        title: "Maximum wear depth against cycles".into(),
        x_label: CYCLES.into(),
        y_label: "maximum wear depth (um)".into(),
        series: vec![Series::new("maximum depth", points.collect(), Style::Line)],
    }
}

/// The model's potential on the record's clock: the OCP trace, or the solved cycles of a
/// result without one.
pub fn model_potential(result: &SimulationResult) -> Vec<(f64, f64)> {
    if !result.ocp_trace.is_empty() {
        return result
            .ocp_trace
            .iter()
            .map(|p| (p.time_s, p.potential_v))
            .collect();
    }
    let start = result.scene.test.ocp_before_s;
    result
        .cycles
        .iter()
        .filter_map(|c| Some((start + c.time_s, c.potential_v?)))
        .collect()
}

fn potential(result: &SimulationResult, measured: &Measured) -> LineFigure {
    let model = model_potential(result);
    let reference = result
        .summary
        .potential_reference
        .map_or("the reference electrode", |r| r.label());
    let mut series = vec![Series::new("potential", model.clone(), Style::Line)];
    if let (Some(corrosion), Some(first), Some(last)) =
        (&result.scene.corrosion, model.first(), model.last())
    {
        let e = corrosion.corrosion_potential_v;
        series.push(Series::new(
            "E_corr, free corrosion potential",
            vec![(first.0, e), (last.0, e)],
            Style::Reference,
        ));
    }
    if let Some(table) = &measured.ocp {
        let points = column(table, "time_s")
            .iter()
            .zip(column(table, "potential_v"));
        series.push(Series::new(
            "attached measurement",
            points.map(|(t, v)| (*t, *v)).collect(),
            Style::Markers,
        ));
    }
    LineFigure {
        title: "Potential at open circuit, before, during and after the rubbing".into(),
        x_label: "time since the record started (s)".into(),
        y_label: format!("potential (V vs {reference})"),
        series,
    }
}

fn wac(result: &SimulationResult) -> LineFigure {
    let points = result
        .cycles
        .iter()
        .filter_map(|r| Some((r.time_s, r.wac_volume_mm3? * 1e3)));
    LineFigure {
        title: "Wear-accelerated corrosion volume against the rubbing time".into(),
        x_label: "time of rubbing (s)".into(),
        y_label: "WAC volume (10^-3 mm^3)".into(),
        series: vec![Series::new("WAC volume", points.collect(), Style::Line)],
    }
}

/// The ball's section, radius `radius_um`, with its lowest point at the deepest point of
/// `y_um`, `depth_um`, up to half the depth above the surface (the page's view).
fn ball(y_um: &[f64], depth_um: &[f64], radius_um: f64) -> Vec<(f64, f64)> {
    let Some((k, deepest)) = depth_um
        .iter()
        .map(|d| d.abs())
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
    else {
        return Vec::new();
    };
    let y0 = y_um[k];
    y_um.iter()
        .filter(|y| (*y - y0).abs() < radius_um)
        .map(|y| {
            (
                *y,
                -deepest + radius_um - (radius_um * radius_um - (y - y0) * (y - y0)).sqrt(),
            )
        })
        .filter(|(_, z)| *z <= 0.5 * deepest.max(0.01))
        .collect()
}

fn profiles(result: &SimulationResult, measured: &Measured) -> LineFigure {
    let mut series: Vec<Series> = result
        .profiles
        .iter()
        .map(|p| {
            let points = p.y_um.iter().zip(&p.depth_um).map(|(y, d)| (*y, -d.abs()));
            Series::new(
                format!("-D at cycle {}", p.cycle),
                points.collect(),
                Style::Line,
            )
        })
        .collect();
    if let Some(last) = result.profiles.last() {
        let radius_um = result.scene.ball.radius_mm * 1e3;
        series.push(Series::new(
            "ball",
            ball(&last.y_um, &last.depth_um, radius_um),
            Style::Reference,
        ));
    }
    if let Some(table) = &measured.profile {
        let points = column(table, "y_mm").iter().zip(column(table, "depth_um"));
        series.push(Series::new(
            "attached measurement",
            points.map(|(y, d)| (y * 1e3, -d.abs())).collect(),
            Style::Markers,
        ));
    }
    LineFigure {
        title: "Profiles across the track: the surface height -D(y), with the ball touching the deepest point of the last".into(),
        x_label: "y across the track (um)".into(),
        y_label: "surface height -D (um)".into(),
        series,
    }
}

/// Every figure of the run, as HTML `<figure>` elements, in the page's order.
pub fn run_figures(result: &SimulationResult, measured: &Measured) -> Result<String, FigureError> {
    let no_corrosion = "this scene has no corrosion model: nothing to plot";
    let lines = [
        (volume(result, measured), "no solved cycle"),
        (depth(result), "no solved cycle"),
        (potential(result, measured), no_corrosion),
        (wac(result), no_corrosion),
        (
            profiles(result, measured),
            "the result has no profiles (a stopped run keeps none)",
        ),
    ];
    let mut html = String::new();
    for (figure_of, empty) in &lines {
        html.push_str(&figure(
            figure_of.svg()?.as_deref(),
            &figure_of.title,
            empty,
        ));
    }
    let maps = &result.pressure_maps;
    let shown: Vec<Map<'_>> = maps
        .first()
        .into_iter()
        .chain(maps.last().filter(|_| maps.len() > 1))
        .map(|m| Map {
            cycle: m.cycle,
            x_um: &m.x_um,
            y_um: &m.y_um,
            pressure_mpa: &m.pressure_mpa,
        })
        .collect();
    let caption = "Contact pressure at the first and the last solved cycle, one length scale and one colour scale";
    let (svg, caption) = match pressure_svg(&shown) {
        Some((svg, scales)) => (Some(svg), format!("{caption}: {scales}")),
        None => (None, caption.to_owned()),
    };
    let empty = "the result has no pressure maps (a stopped run keeps none)";
    html.push_str(&figure(svg.as_deref(), &caption, empty));
    html.push_str(&super::stroke_figures::stroke_figures(result)?);
    Ok(html)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ball_touches_the_deepest_point_and_rises_away_from_it() {
        let y = [-20.0, -10.0, 0.0, 10.0, 20.0];
        let d = [0.0, 0.5, 2.0, 0.5, 0.0];
        let section = ball(&y, &d, 3000.0);
        let at = |y0: f64| {
            section
                .iter()
                .find(|p| (p.0 - y0).abs() < 1e-9)
                .map(|p| p.1)
        };
        assert_eq!(at(0.0), Some(-2.0));
        let up = at(20.0).expect("in view");
        // R - sqrt(R^2 - 20^2) = 400 / (2 R) to first order: 0.0667 um above the bottom.
        assert!((up - (-2.0 + 400.0 / 6000.0)).abs() < 1e-5, "{up}");
    }
}
