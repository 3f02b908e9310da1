//! The tables of `docs/materials.md`, rendered from the library so the page cannot drift
//! from the values a scene gets.

use std::fmt::Write as _;

use super::{BALLS, DISCS, Property, REFERENCES, library};
use crate::json::variant_name;

/// The line before the generated tables in `docs/materials.md`.
pub const MATERIALS_BEGIN: &str = "<!-- The tables below are generated from \
                                   src/scene/materials: edit there, then run \
                                   TRIBOSIM_WRITE_DOCS=1 cargo test --release --test docs -->";
/// The line after the generated tables.
pub const MATERIALS_END: &str = "<!-- End of the generated materials tables. -->";

/// `value [source; note]`, or `not found (note)`; `digits` after the point, or as read.
fn cell(property: Property, digits: Option<usize>) -> String {
    let note = |n: &str| {
        if n.is_empty() {
            String::new()
        } else {
            format!("; {n}")
        }
    };
    match property.value {
        Some(value) => {
            let shown = digits.map_or_else(|| value.to_string(), |d| format!("{value:.d$}"));
            format!("{shown} [{}{}]", property.source, note(property.note))
        }
        None => format!("**not found** ({})", property.note),
    }
}

/// The discs' table, the balls' table, the electrochemistry and the references, between
/// [`MATERIALS_BEGIN`] and [`MATERIALS_END`] (both included).
pub fn materials_table() -> String {
    let mut out = format!("{MATERIALS_BEGIN}\n\n### Discs (`disc.material`)\n\n");
    discs_table(&mut out);
    out.push_str("\n### Electrochemistry in chloride\n\n");
    electrochemistry_table(&mut out);
    out.push_str("\n### Balls (`ball.material`)\n\n");
    balls_table(&mut out);
    out.push_str("\n### Sources\n\n");
    sources_list(&mut out);
    let _ = writeln!(out, "\n{MATERIALS_END}");
    out
}

/// The discs' mechanical and Faraday values, with their sources' keys.
fn discs_table(out: &mut String) {
    out.push_str(
        "| name | material | E (GPa) | nu | hardness (MPa, Vickers) | hardness law | 0.2% \
         yield (MPa) | density (g/cm^3) | EW (g/eq), `faraday` |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for d in &library().discs {
        let m = &d.material;
        let law = m.hardness_table.map_or_else(
            || "none read: constant".to_owned(),
            |t| format!("{} points [{}]", t.len(), m.hardness_law_source),
        );
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} | {law} | {} | {:.2} [{}] | {:.2}, `{}` [{}] |",
            variant_name(m.name),
            m.label,
            cell(m.youngs_modulus_gpa, None),
            cell(m.poisson_ratio, None),
            cell(m.hardness_mpa, Some(0)),
            cell(m.initial_yield_strength_mpa, None),
            d.density_g_cm3,
            d.composition_source,
            d.equivalent_weight_g_per_eq,
            d.faraday,
            d.equivalent_weight_source,
        );
    }
}

/// Each disc's electrochemical constants in chloride, or that none were found.
fn electrochemistry_table(out: &mut String) {
    out.push_str(
        "| disc | medium | E_corr (V) | a_c (V) | b_c (V/decade) | i_a (A/cm^2) | source |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for m in &DISCS {
        let _ = match m.electrochemistry {
            Some(e) => writeln!(
                out,
                "| `{}` | {} | {} vs {} | {} | {} | {} | [{}] |",
                variant_name(m.name),
                e.medium,
                e.corrosion_potential_v,
                e.reference_electrode.label(),
                e.tafel_a_c_v,
                e.tafel_b_c_v_per_decade,
                e.anodic_current_density_a_cm2,
                e.source
            ),
            None => writeln!(
                out,
                "| `{}` | **not found**: a scene with `corrosion` must give them | | | | | |",
                variant_name(m.name)
            ),
        };
    }
}

/// The balls' values, with their sources' keys.
fn balls_table(out: &mut String) {
    out.push_str(
        "| name | material | E (GPa) | nu | density (g/cm^3) | hardness |\n\
         |---|---|---|---|---|---|\n",
    );
    for b in &BALLS {
        let _ = writeln!(
            out,
            "| `{}` | {} | {} | {} | {} | {} [{}] |",
            variant_name(b.name),
            b.label,
            cell(b.youngs_modulus_gpa, None),
            cell(b.poisson_ratio, None),
            cell(b.density_g_cm3, None),
            b.hardness.0,
            b.hardness.1,
        );
    }
}

/// Every source the tables cite, primary or secondary.
fn sources_list(out: &mut String) {
    for r in REFERENCES {
        let kind = if r.primary { "primary" } else { "secondary" };
        let _ = writeln!(
            out,
            "- **[{}]** {} ({kind}). <{}>",
            r.key, r.citation, r.address
        );
    }
}
