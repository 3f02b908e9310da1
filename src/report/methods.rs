//! The parts every report closes with: the methods paragraph citing the paper and the
//! models, and the provenance of the runs.

use time::format_description::well_known::Rfc3339;

use crate::simulation::{Build, ModelChoice, Provenance};

use super::html::{Cell, escape, heading, sized_table};

/// The paper the model follows.
pub const PAPER: &str = "A. Dalmau, A. Roda Buch, A. Rovira, J. Navarro-Laboulais, \
                         A. Igual Muñoz, \"Wear model for describing the time dependence of \
                         the material degradation mechanisms of the AISI 316L in a NaCl \
                         solution\", Wear 394-395 (2018) 166-175, \
                         doi:10.1016/j.wear.2017.10.015";

/// The methods paragraph: what was computed and how, with the models `models` names.
pub fn methods(models: &[ModelChoice]) -> String {
    // A model with several entries (a domain growth per growth) is named once.
    let mut active: Vec<String> = Vec::new();
    for name in models
        .iter()
        .filter(|m| m.active)
        .map(|m| crate::json::variant_name(m.name))
    {
        if !active.contains(&name) {
            active.push(name);
        }
    }
    let uses = |name: &str| active.iter().any(|a| a == name);
    let (rig, where_solved) = if uses("reciprocating") {
        (
            "reciprocating ball-on-flat",
            " at positions along the stroke wherever the track's depth changes along it",
        )
    } else {
        ("ball-on-disc", "")
    };
    let hardness = if uses("work_hardening") {
        "the work-hardened disc (eq. 12, hardness H = A + B ln n fitted to the scene's table, \
         Fig. 9)"
    } else {
        "the disc (eq. 12, at the scene's constant hardness)"
    };
    let mut html = heading(2, "Methods");
    html.push_str(&format!(
        "<p>The wear track of the {rig} test was computed with tribosim after {}. \
         Each solved cycle finds the contact pressure between the ball and the worn disc{where_solved} \
         by boundary elements on a regular grid (DC-FFT influence coefficients, bounded \
         conjugate gradients), capped at the yield pressure of {hardness}; the groove \
         grows by yielding (eq. 13) and by Archard's law, V = k F s / H (eqs. 14-16), and \
         one solve may stand for several cycles when the wear profile of a pass changes \
         little (the cycle loop of Fig. 4). With a corrosion section, the potential of the \
         disc during rubbing follows from the galvanic coupling of the depassivated wear \
         track with the passive rest of the electrode (eq. 18), and the wear-accelerated \
         corrosion volume from the anodic charge by Faraday's law. The models this run \
         used: {}. Each model's reason, with its numbers, is in the table of models.</p>\n",
        escape(PAPER),
        escape(&active.join(", ")),
    ));
    html
}

/// `build`'s rows: version, commit, date and cores.
fn build_rows(build: &Build) -> Vec<Vec<Cell>> {
    vec![
        vec![
            Cell::text("tribosim version"),
            Cell::text(&build.tribosim_version),
        ],
        vec![Cell::text("git commit"), Cell::text(&build.git_commit)],
        vec![
            Cell::text("computed at (UTC)"),
            Cell::text(build.computed_at.format(&Rfc3339).unwrap_or_default()),
        ],
        vec![Cell::text("cores"), Cell::text(build.cores.to_string())],
    ]
}

/// The provenance of a run: its build and its scene's SHA-256, or a note that the result
/// was written before provenance was recorded.
pub fn run_provenance(provenance: Option<&Provenance>) -> String {
    let Some(p) = provenance else {
        return "<p class=\"muted\">The result was written before tribosim recorded its \
                provenance.</p>\n"
            .to_owned();
    };
    let mut rows = build_rows(&p.build);
    rows.push(vec![
        Cell::text("scene SHA-256"),
        Cell::text(&p.scene_sha256),
    ]);
    sized_table("", &["", "value"], &rows, &[28, 72])
}

/// `build` as a table captioned `caption` (the report's own, a study summary's).
pub fn build_table(caption: &str, build: &Build) -> String {
    sized_table(caption, &["", "value"], &build_rows(build), &[28, 72])
}

/// The build that writes this report, now.
pub fn report_provenance() -> String {
    build_table("This report", &Build::now())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::Model;

    fn model(name: Model, active: bool) -> ModelChoice {
        ModelChoice {
            name,
            active,
            reason: String::new(),
        }
    }

    #[test]
    fn the_methods_name_the_rig_and_the_hardness_the_run_used() {
        let disc = methods(&[model(Model::WorkHardening, true)]);
        assert!(disc.contains("ball-on-disc test") && disc.contains("H = A + B ln n"));
        let constant = methods(&[
            model(Model::WorkHardening, false),
            model(Model::Reciprocating, true),
        ]);
        assert!(
            constant.contains("reciprocating ball-on-flat test"),
            "{constant}"
        );
        assert!(constant.contains("constant hardness") && !constant.contains("ln n"));
    }
}
