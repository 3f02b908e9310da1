//! Plausibility: what a scene the simulation could run says that no real test does, as a
//! unit slip gives (a load in mN typed as N, a hardness in GPa typed as MPa, a height map
//! in um read as m). Each rule warns where the scene leaves a theory's range but may still
//! be meant, and refuses, naming the field and the likely slip, where no run could mean
//! anything. [`super::Plan`] judges every scene by them once the contact's limits hold; a
//! measured map is judged where the run receives it ([`check_map`]).

use super::estimate::{RunEstimate, describe_duration, describe_size};
use super::feasibility::Derived;
use super::sizing::sizing_radius_m;
use crate::contact::Hertz;
use crate::corrosion::plausible;
use crate::scene::format::{num, sig};
use crate::scene::{
    FieldError, FieldWarning, MAX_RMS_HEIGHT_UM, REFUSE_HARD_MPA, REFUSE_HARDNESS_MPA, Scene,
    WARN_HARD_MPA, WARN_HARDNESS_MPA, YieldCapLaw, hardness_slips,
};
use crate::surface::{HeightMap, rms_height};

/// Hertz's theory and the half-space of eqs. 5-10 assume a contact small against the ball,
/// a << R, and a/R = 0.1 is the usual bound of that assumption (Johnson, Contact
/// Mechanics, 1985, ch. 4). The paper's test has 44 um on 3 mm, a/R = 0.015.
const WARN_CONTACT_FRACTION: f64 = 0.1;
/// Above this no run means anything: Hertz's elastic strain p0 / E* = 2a / (pi R) would be
/// 19%, a hundred times a metal's elastic limit (316L: about 300 MPa over 205 GPa, 0.15%),
/// and the ball's surface at the contact's edge tilts by 17 degrees from the half-space's
/// plane. A load in mN typed as N lands here: a thousandfold load widens the paper's
/// contact tenfold (elastic, a ~ F^(1/3)) to 32-fold (at the cap, a ~ F^(1/2)), from a/R
/// = 0.015 to 0.15-0.45.
const REFUSE_CONTACT_FRACTION: f64 = 0.3;
/// The hardest metals, through-hardened tool and bearing steels, reach about HV 1000, 9.8
/// GPa (tungsten HV 350-450, 3.4-4.4 GPa): an unworn elastic peak pressure above this is
/// beyond any metal disc however the cap spreads it. The paper's is 1.22 GPa.
const WARN_PEAK_PRESSURE_PA: f64 = 10e9;
/// Diamond, the hardest solid, has HV 70-100 GPa: no pair of solids bears an elastic peak
/// pressure above it. A ball's radius in m typed as mm raises p0 a hundredfold (p0 ~
/// R^(-2/3)), to 122 GPa from the paper's 1.22.
const REFUSE_PEAK_PRESSURE_PA: f64 = 100e9;
/// Diamond's Young's modulus, 1050-1210 GPa, the stiffest solid's: a modulus above it was
/// typed in MPa (205 GPa as 205000), and is refused.
const DIAMOND_MODULUS_GPA: f64 = 1210.0;
/// Engineering polymers (PTFE about 0.5 GPa, PEEK 3.6 GPa) are the softest balls and
/// discs a tribometer runs; a modulus below this after a unit's conversion is no slip's.
const SOFTEST_MODULUS_GPA: f64 = 0.1;
/// The smallest ball a tribometer holds: micro-tribometers use 0.5-1 mm balls, colloidal
/// probes reach 10 um. A smaller radius was typed in m (3 mm as 0.003), and a contact it
/// cannot hold names it rather than the load.
const SMALLEST_BALL_MM: f64 = 0.01;
/// Indium, the softest metal, yields at about 1 MPa: a weaker disc is a strength in GPa
/// typed as MPa (annealed 316L's 0.29 GPa as 0.29).
const REFUSE_WEAK_YIELD_MPA: f64 = 1.0;
/// No solid's strength passes about a tenth of its modulus, diamond's about 100 GPa: a
/// stronger disc is a strength in Pa or kPa typed as MPa.
const REFUSE_STRONG_YIELD_MPA: f64 = 100e3;
/// MPa per ksi (1000 psi of 6894.757 Pa), the unit of US data sheets' strengths.
const MPA_PER_KSI: f64 = 6.894_757;
/// A run longer than this is worth a word before it starts: a hundred times the paper's
/// test (5.9 s).
const WARN_WALL_S: f64 = 600.0;
/// A result larger than this is worth a word before it starts: a hundred times the paper's
/// (1.0 MB), more than a browser page or a notebook loads comfortably.
const WARN_RESULT_BYTES: f64 = 100e6;

/// What plausibility found in a scene: refusals (the run would mean nothing) and warnings.
#[derive(Debug, Default)]
pub(super) struct Verdict {
    /// Fields whose values no run could mean, with the likely slip.
    pub(super) refusals: Vec<FieldError>,
    /// Fields whose values leave a theory's range or cost much, with the numbers.
    pub(super) warnings: Vec<FieldWarning>,
}

impl Verdict {
    fn refuse(&mut self, path: &str, message: String) {
        self.refusals.push(FieldError::new(path, message));
    }

    fn warn(&mut self, path: &str, message: String) {
        self.warnings.push(FieldWarning::new(path, message));
    }
}

/// Judges `scene`, whose contact's limits hold, by every rule of this module; `estimate`
/// is what its run is expected to cost.
pub(super) fn judge(scene: &Scene, derived: &Derived, estimate: &RunEstimate) -> Verdict {
    let mut verdict = Verdict::default();
    moduli(&mut verdict, scene);
    // A modulus slip sets the peak pressure: named once, there.
    if verdict.refusals.is_empty() {
        peak_pressure(&mut verdict, scene, derived.hertz);
    }
    hardness(&mut verdict, scene);
    initial_yield(&mut verdict, scene);
    contact_size(&mut verdict, scene, derived);
    cost(&mut verdict, scene, estimate);
    if let Some(c) = &scene.corrosion {
        let cell = plausible::Cell {
            corrosion_potential_v: c.corrosion_potential_v,
            tafel_a_c_v: c.tafel_a_c_v,
            tafel_b_c_v_per_decade: c.tafel_b_c_v_per_decade,
            anodic_current_density_a_cm2: c.anodic_current_density_a_cm2,
        };
        for (path, finding) in plausible::judge_cell(cell) {
            let found = FieldError::new(path, finding.message);
            match finding.refuse {
                true => verdict.refusals.push(found),
                false => verdict
                    .warnings
                    .push(FieldWarning::new(found.path, found.message)),
            }
        }
    }
    verdict
}

/// The contact radius the plan expects (Hertz's, or the flat punch at the lowest cap)
/// against the ball's radius; see [`WARN_CONTACT_FRACTION`], [`REFUSE_CONTACT_FRACTION`].
fn contact_size(verdict: &mut Verdict, scene: &Scene, derived: &Derived) {
    let ball_m = scene.ball_radius_m();
    let fraction = derived.sizing_m / ball_m;
    if fraction <= WARN_CONTACT_FRACTION {
        return;
    }
    let load = scene.load_n();
    let found = format!(
        "{} N on a {} mm ball gives a contact radius of {} um, {:.0}% of the ball's",
        num(load),
        num(scene.ball.radius_mm),
        sig(derived.sizing_m * 1e6),
        100.0 * fraction
    );
    if fraction <= REFUSE_CONTACT_FRACTION {
        verdict.warn(
            "test.load_n",
            format!(
                "{found}: beyond Hertz's a << R (10% is the usual bound), which the half-space \
                 of eqs. 5-10 assumes; check that the load is in N and the radius in mm"
            ),
        );
        return;
    }
    let milli = Hertz {
        load_n: load * 1e-3,
        ..*derived.hertz
    };
    let slipped_m = sizing_radius_m(&milli, derived.lowest.yield_pa, derived.capped);
    if let Some((path, hint)) = radius_slip(scene) {
        verdict.refuse(path, format!("{found}: {hint}"));
        return;
    }
    let hint = if slipped_m / ball_m <= WARN_CONTACT_FRACTION {
        format!(
            "was the load in mN? {} mN = {} N gives a contact radius of {} um",
            num(load),
            sig(load * 1e-3),
            sig(slipped_m * 1e6)
        )
    } else {
        "check that the load is in N and the radius in mm".to_owned()
    };
    verdict.refuse(
        "test.load_n",
        format!(
            "{found}; above {:.0}% no contact model means anything (Hertz's elastic strain \
             2a / (pi R) would pass 19%): {hint}",
            100.0 * REFUSE_CONTACT_FRACTION
        ),
    );
}

/// The unworn contact's elastic peak pressure against the hardest solids; see
/// [`WARN_PEAK_PRESSURE_PA`], [`REFUSE_PEAK_PRESSURE_PA`].
fn peak_pressure(verdict: &mut Verdict, scene: &Scene, hertz: &Hertz) {
    let p0 = hertz.peak_pressure_pa();
    if p0 <= WARN_PEAK_PRESSURE_PA {
        return;
    }
    let (path, hint) = radius_slip(scene).unwrap_or((
        "test.load_n",
        "check the load (N), the ball's radius (mm) and the moduli (GPa)".to_owned(),
    ));
    let found = format!(
        "the unworn contact's elastic peak pressure is {} GPa (Hertz's p0)",
        sig(p0 * 1e-9)
    );
    if p0 > REFUSE_PEAK_PRESSURE_PA {
        verdict.refuse(
            path,
            format!("{found}, above diamond's hardness (70-100 GPa), which no solid bears: {hint}"),
        );
    } else {
        verdict.warn(
            path,
            format!(
                "{found}, above the hardest metals' hardness (about 10 GPa, hardened steels): \
                 {hint}"
            ),
        );
    }
}

/// The ball's radius typed in m, if it is below [`SMALLEST_BALL_MM`]: its path and the
/// slip in words.
fn radius_slip(scene: &Scene) -> Option<(&'static str, String)> {
    let mm = scene.ball.radius_mm;
    (mm < SMALLEST_BALL_MM).then(|| {
        let hint = format!(
            "a ball of {} mm is smaller than any tribometer's (10 um and up): was the radius in \
             m? {} m = {} mm",
            num(mm),
            num(mm),
            sig(mm * 1e3)
        );
        ("ball.radius_mm", hint)
    })
}

/// Each modulus against diamond's; see [`DIAMOND_MODULUS_GPA`].
fn moduli(verdict: &mut Verdict, scene: &Scene) {
    let moduli = [
        ("ball.youngs_modulus_gpa", scene.ball.youngs_modulus_gpa),
        ("disc.youngs_modulus_gpa", scene.disc.youngs_modulus_gpa),
    ];
    for (path, gpa) in moduli {
        if gpa > DIAMOND_MODULUS_GPA {
            verdict.refuse(
                path,
                format!(
                    "{} GPa is stiffer than diamond ({DIAMOND_MODULUS_GPA} GPa), the stiffest \
                     solid: {}",
                    num(gpa),
                    modulus_slip(gpa)
                ),
            );
        }
    }
}

/// The unit a modulus above diamond's was likely typed in: the one (MPa, kPa or Pa) that
/// puts it between [`SOFTEST_MODULUS_GPA`] and diamond's, or a plea to check the unit.
fn modulus_slip(gpa: f64) -> String {
    let units = [("MPa", 1e-3), ("kPa", 1e-6), ("Pa", 1e-9)];
    units
        .iter()
        .find(|(_, to_gpa)| (SOFTEST_MODULUS_GPA..=DIAMOND_MODULUS_GPA).contains(&(gpa * to_gpa)))
        .map_or_else(
            || "check that it is in GPa".to_owned(),
            |(unit, to_gpa)| {
                format!(
                    "was it in {unit}? {} {unit} = {} GPa",
                    num(gpa),
                    sig(gpa * to_gpa)
                )
            },
        )
}

/// Each hardness the scene gives against the metals' ([`hardness_slips`]): the scene's
/// checks refuse the slips, so what reaches a plan is warned.
fn hardness(verdict: &mut Verdict, scene: &Scene) {
    for slip in hardness_slips(scene) {
        verdict.warn(&slip.path, slip.message);
    }
}

/// The hardening cap's starting strength against the metals' and against the cap it rises
/// to; see [`REFUSE_WEAK_YIELD_MPA`], [`REFUSE_STRONG_YIELD_MPA`].
fn initial_yield(verdict: &mut Verdict, scene: &Scene) {
    let disc = &scene.disc;
    if disc.yield_cap != YieldCapLaw::StrainHardening {
        return;
    }
    let path = "disc.initial_yield_strength_mpa";
    let mpa = disc.initial_yield_strength_mpa;
    let slip = |to_mpa: f64, unit: &str| {
        format!(
            "was it in {unit}? {} {unit} = {} MPa",
            num(mpa),
            sig(mpa * to_mpa)
        )
    };
    if mpa < REFUSE_WEAK_YIELD_MPA {
        let message = format!(
            "{} MPa yields below indium (about 1 MPa), the softest metal: {}",
            num(mpa),
            slip(1e3, "GPa")
        );
        verdict.refuse(path, message);
        return;
    }
    if mpa > REFUSE_STRONG_YIELD_MPA {
        let unit = if mpa * 1e-3 <= REFUSE_STRONG_YIELD_MPA {
            (1e-3, "kPa")
        } else {
            (1e-6, "Pa")
        };
        let message = format!(
            "{} MPa is stronger than any solid (diamond's ideal strength is about 100 GPa): {}",
            num(mpa),
            slip(unit.0, unit.1)
        );
        verdict.refuse(path, message);
        return;
    }
    let Ok(law) = disc.hardness_law() else {
        return;
    };
    let hardened_mpa = law.yield_pressure_pa(1.0, disc.yield_factor) * 1e-6;
    if mpa >= hardened_mpa {
        let message = format!(
            "{} MPa is at or above H(1) / yield_factor = {} MPa, the cap it would harden to: \
             the cap is the paper's from the first pass (`yield_cap: \"hardness\"`); check \
             that it is the 0.2% proof stress in MPa (ksi: {} ksi = {} MPa)",
            num(mpa),
            sig(hardened_mpa),
            num(mpa),
            sig(mpa * MPA_PER_KSI)
        );
        verdict.warn(path, message);
    }
}

/// The run's expected time and result size; see [`WARN_WALL_S`], [`WARN_RESULT_BYTES`].
fn cost(verdict: &mut Verdict, scene: &Scene, estimate: &RunEstimate) {
    if estimate.wall_s <= WARN_WALL_S && estimate.bytes <= WARN_RESULT_BYTES {
        return;
    }
    verdict.warn(
        "test.cycles",
        format!(
            "{} cycles will take about {} and give a result of about {} ({} solved cycles; \
             estimated from the {}, within a factor of about 3)",
            scene.test.cycles,
            describe_duration(estimate.wall_s),
            describe_size(estimate.bytes),
            estimate.solves,
            if scene.test.reciprocating.is_some() {
                "rig's default scene"
            } else {
                "paper's scene"
            }
        ),
    );
}

/// Refuses a measured map whose rms height is beyond what a synthetic surface may have
/// ([`MAX_RMS_HEIGHT_UM`]): heights in um read as m give a millionfold rms.
pub fn check_map(id: &str, map: &HeightMap) -> Result<(), FieldError> {
    let rms_um = rms_height(map) * 1e6;
    if rms_um <= MAX_RMS_HEIGHT_UM {
        return Ok(());
    }
    Err(FieldError::new(
        "disc.surface.id",
        format!(
            "the height map `{id}` has an rms height of {} um, beyond the {} um a surface may \
             have (a synthetic one is refused there too: beyond a ball-on-disc contact): were \
             its heights in um rather than m? Read as um they give {} um",
            sig(rms_um),
            num(MAX_RMS_HEIGHT_UM),
            sig(rms_um * 1e-6)
        ),
    ))
}

/// Where `docs/scene.md`'s plausibility table begins (the marker line).
pub const RULES_BEGIN: &str =
    "<!-- The plausibility table below is generated from src/simulation/plausibility.rs. -->";
/// Where it ends (the marker line).
pub const RULES_END: &str = "<!-- End of the plausibility table. -->";

/// The plausibility rules as `docs/scene.md`'s table, from the thresholds above, between
/// [`RULES_BEGIN`] and [`RULES_END`] (both included).
pub fn rules_table() -> String {
    let rows = [
        [
            "contact radius (Hertz's, or the flat punch at the lowest cap) / ball radius"
                .to_owned(),
            "`test.load_n`, or `ball.radius_mm` below 0.01 mm".to_owned(),
            format!("> {WARN_CONTACT_FRACTION}"),
            format!("> {REFUSE_CONTACT_FRACTION}"),
            "Hertz's a << R; above 0.3 the elastic strain passes 19% (a load in mN typed as N)"
                .to_owned(),
        ],
        [
            "the unworn contact's elastic peak pressure (Hertz's p0)".to_owned(),
            "`test.load_n`, or `ball.radius_mm` below 0.01 mm".to_owned(),
            format!("> {} GPa", WARN_PEAK_PRESSURE_PA * 1e-9),
            format!("> {} GPa", REFUSE_PEAK_PRESSURE_PA * 1e-9),
            "the hardest metals (hardened steels, about 10 GPa); diamond (70-100 GPa), which no \
             solid passes (a radius in m typed as mm)"
                .to_owned(),
        ],
        [
            "each Young's modulus".to_owned(),
            "`ball.youngs_modulus_gpa`, `disc.youngs_modulus_gpa`".to_owned(),
            String::new(),
            format!("> {DIAMOND_MODULUS_GPA} GPa"),
            "stiffer than diamond (a modulus in MPa or Pa typed as GPa)".to_owned(),
        ],
        [
            "each hardness given".to_owned(),
            "`disc.hardness_mpa`, `disc.hardness_table[i][1]`".to_owned(),
            format!("< {WARN_HARDNESS_MPA} MPa or > {WARN_HARD_MPA} MPa"),
            format!("< {REFUSE_HARDNESS_MPA} MPa or > {REFUSE_HARD_MPA} MPa"),
            "softer than annealed pure aluminium (200 MPa); than indium (9 MPa), the softest \
             metal (a hardness in GPa typed as MPa); harder than hardened steels (about 10 GPa); \
             than diamond (70-100 GPa), the hardest solid (a hardness in Pa typed as MPa). \
             Refused by the scene's checks, before the hardness table's law is fitted"
                .to_owned(),
        ],
        [
            "the hardening cap's initial yield strength (`yield_cap: \"strain_hardening\"`)"
                .to_owned(),
            "`disc.initial_yield_strength_mpa`".to_owned(),
            ">= H(1) / yield_factor".to_owned(),
            format!("< {REFUSE_WEAK_YIELD_MPA} MPa or > {REFUSE_STRONG_YIELD_MPA} MPa"),
            "at or above the cap it hardens to, the cap is the paper's; below indium's (a \
             strength in GPa typed as MPa); above any solid's (in Pa or kPa)"
                .to_owned(),
        ],
        [
            "the rms height of a measured map".to_owned(),
            "`disc.surface.id`".to_owned(),
            String::new(),
            format!("> {MAX_RMS_HEIGHT_UM} um"),
            "the synthetic surface's own bound (heights in um read as m)".to_owned(),
        ],
        [
            "the run's estimated wall time or result size".to_owned(),
            "`test.cycles`".to_owned(),
            format!(
                "> {} or > {}",
                describe_duration(WARN_WALL_S),
                describe_size(WARN_RESULT_BYTES)
            ),
            String::new(),
            "a hundred times the paper's test (5.9 s, 1.0 MB); estimated from two runs of it"
                .to_owned(),
        ],
    ];
    let rows = rows.into_iter().chain(plausible::rules());
    let mut out = format!(
        "{RULES_BEGIN}\n\n| what | field | warned | refused | why |\n|---|---|---|---|---|\n"
    );
    for row in rows {
        out.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    out.push('\n');
    out.push_str(RULES_END);
    out.push('\n');
    out
}

#[cfg(test)]
mod tests;
