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
use crate::scene::{FieldError, FieldWarning, MAX_RMS_HEIGHT_UM, Scene};
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
/// The smallest ball a tribometer holds: micro-tribometers use 0.5-1 mm balls, colloidal
/// probes reach 10 um. A smaller radius was typed in m (3 mm as 0.003), and a contact it
/// cannot hold names it rather than the load.
const SMALLEST_BALL_MM: f64 = 0.01;
/// Annealed pure aluminium, about the softest structural metal, has HV 20-25 (200-250 MPa)
/// and annealed copper HV 40-50; only lead and tin (HV about 5, 50 MPa) and indium (HB
/// about 1, 9 MPa) are softer. Below this a disc is of lead or tin, or its hardness in GPa
/// was typed as MPa (316L's 2.473 GPa as 2.473).
const WARN_HARDNESS_MPA: f64 = 100.0;
/// Softer than indium (about 9 MPa), the softest metal solid at room temperature: no metal
/// disc, so a unit slip.
const REFUSE_HARDNESS_MPA: f64 = 5.0;
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
    let before = verdict.refusals.len();
    hardness(&mut verdict, scene);
    // A hardness slip sets the contact too (the flat punch F / (pi Y)): named once, there.
    if verdict.refusals.len() == before {
        contact_size(&mut verdict, scene, derived);
    }
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
                     solid: was it in MPa? {} MPa = {} GPa",
                    num(gpa),
                    num(gpa),
                    sig(gpa * 1e-3)
                ),
            );
        }
    }
}

/// Each hardness the scene gives against the softest metals; see [`WARN_HARDNESS_MPA`],
/// [`REFUSE_HARDNESS_MPA`].
fn hardness(verdict: &mut Verdict, scene: &Scene) {
    let table = scene.disc.hardness_table.iter().flatten().enumerate();
    let points = std::iter::once(("disc.hardness_mpa".to_owned(), scene.disc.hardness_mpa))
        .chain(table.map(|(i, &(_, mpa))| (format!("disc.hardness_table[{i}][1]"), mpa)));
    for (path, mpa) in points {
        if mpa >= WARN_HARDNESS_MPA {
            continue;
        }
        // Typed in GPa only if a thousand times it is a metal's hardness.
        let slip = if mpa * 1e3 <= WARN_PEAK_PRESSURE_PA * 1e-6 {
            format!("was it in GPa? {} GPa = {} MPa", num(mpa), sig(mpa * 1e3))
        } else {
            "check that it is in MPa".to_owned()
        };
        if mpa < REFUSE_HARDNESS_MPA {
            verdict.refuse(
                &path,
                format!(
                    "{} MPa is softer than any metal (indium, the softest, is about 9 MPa): \
                     {slip}",
                    num(mpa)
                ),
            );
        } else {
            verdict.warn(
                &path,
                format!(
                    "{} MPa is softer than annealed pure aluminium (about 200 MPa); only lead, \
                     tin and indium are softer: {slip}",
                    num(mpa)
                ),
            );
        }
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
            "{} cycles will take about {} and give a result of about {} ({} solves; estimated \
             from the paper's scene, within a factor of about 3)",
            scene.test.cycles,
            describe_duration(estimate.wall_s),
            describe_size(estimate.bytes),
            estimate.solves
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
            "stiffer than diamond (a modulus in MPa typed as GPa)".to_owned(),
        ],
        [
            "each hardness given".to_owned(),
            "`disc.hardness_mpa`, `disc.hardness_table[i][1]`".to_owned(),
            format!("< {WARN_HARDNESS_MPA} MPa"),
            format!("< {REFUSE_HARDNESS_MPA} MPa"),
            "softer than annealed pure aluminium (200 MPa); than indium (9 MPa), the softest \
             metal (a hardness in GPa typed as MPa)"
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
mod tests {
    use super::*;
    use crate::scene::{SceneErrors, Switch};
    use crate::simulation::Plan;

    fn refusals(scene: &Scene) -> Vec<FieldError> {
        Plan::new(scene.clone())
            .err()
            .map(|SceneErrors(e)| e)
            .unwrap_or_default()
    }

    fn warnings(scene: &Scene) -> Vec<FieldWarning> {
        Plan::new(scene.clone())
            .map(|plan| plan.warnings().to_vec())
            .unwrap_or_else(|e| panic!("refused: {e}"))
    }

    /// The messages at `path` among `items` (paths and messages), one a line; "" for none.
    fn at<'a>(items: impl IntoIterator<Item = (&'a str, &'a str)>, path: &str) -> String {
        items
            .into_iter()
            .filter(|(p, _)| *p == path)
            .map(|(_, m)| m)
            .collect::<Vec<_>>()
            .join("\n")
    }

    fn refused_at(scene: &Scene, path: &str) -> String {
        let found = refusals(scene);
        at(
            found.iter().map(|e| (e.path.as_str(), e.message.as_str())),
            path,
        )
    }

    fn warned_at(scene: &Scene, path: &str) -> String {
        let found = warnings(scene);
        at(
            found.iter().map(|w| (w.path.as_str(), w.message.as_str())),
            path,
        )
    }

    #[test]
    fn the_paper_scene_and_the_presets_give_no_warning() {
        assert_eq!(warnings(&Scene::default()), []);
        for preset in crate::scene::presets() {
            assert_eq!(warnings(&preset.scene), [], "{}", preset.name);
        }
    }

    #[test]
    fn a_load_in_mn_typed_as_n_is_refused_with_the_slip_named() {
        // The flat punch at the lowest cap (877 MPa at cycle 1): sqrt(5000 / (pi 877e6)) =
        // 1.347 mm, 45% of the 3 mm ball; at 5 N, 42.6 um.
        let mut scene = Scene::default();
        scene.test.load_n = 5000.0;
        let message = refused_at(&scene, "test.load_n");
        assert!(message.contains("1347 um, 45% of the ball's"), "{message}");
        assert!(
            message.contains("was the load in mN? 5000 mN = 5 N"),
            "{message}"
        );
    }

    #[test]
    fn a_contact_wide_against_the_ball_is_warned_below_the_refusal() {
        // sqrt(1000 / (pi 877e6)) = 0.602 mm: 20% of the ball's radius.
        let mut scene = Scene::default();
        scene.test.load_n = 1000.0;
        let message = warned_at(&scene, "test.load_n");
        assert!(message.contains("20% of the ball's"), "{message}");
        assert!(message.contains("Hertz's a << R"), "{message}");
        // 2600 N: sqrt(2600 / (pi 877e6)) = 0.971 mm, 32%: refused.
        scene.test.load_n = 2600.0;
        assert!(refused_at(&scene, "test.load_n").contains("32% of the ball's"));
    }

    #[test]
    fn a_modulus_or_a_radius_typed_in_another_unit_is_refused_with_the_slip_named() {
        // One modulus in MPa: E* stays near the ball's, p0 near the paper's; refused anyway.
        let mut scene = Scene::default();
        scene.disc.youngs_modulus_gpa = 205_000.0;
        let message = refused_at(&scene, "disc.youngs_modulus_gpa");
        assert!(message.contains("stiffer than diamond"), "{message}");
        assert!(
            message.contains("was it in MPa? 205000 MPa = 205 GPa"),
            "{message}"
        );
        // Both: p0 would be 122 GPa, named once, at the moduli.
        scene.ball.youngs_modulus_gpa = 300_000.0;
        let found = refusals(&scene);
        let paths: Vec<&str> = found.iter().map(|e| e.path.as_str()).collect();
        assert_eq!(
            paths,
            ["ball.youngs_modulus_gpa", "disc.youngs_modulus_gpa"]
        );
        // A 3 mm ball typed in m, without the cap (which refuses it as wider than the ball):
        // p0 = 1.2214 GPa x 1000^(2/3) = 122 GPa, beyond diamond's hardness.
        let mut scene = Scene::default();
        scene.ball.radius_mm = 0.003;
        scene.wear.plasticity = Switch::Off;
        let message = refused_at(&scene, "ball.radius_mm");
        assert!(message.contains("above diamond's hardness"), "{message}");
        assert!(
            message.contains("was the radius in m? 0.003 m = 3 mm"),
            "{message}"
        );
    }

    #[test]
    fn a_peak_pressure_beyond_the_hardest_metals_is_warned() {
        // A 0.1 mm ball without the cap: p0 ~ R^(-2/3), 30^(2/3) = 9.655 times the paper's
        // 1.2214 GPa = 11.79 GPa.
        let mut scene = Scene::default();
        scene.ball.radius_mm = 0.1;
        scene.wear.plasticity = Switch::Off;
        let message = warned_at(&scene, "test.load_n");
        assert!(
            message.contains("11.79 GPa") && message.contains("hardest metals"),
            "{message}"
        );
    }

    #[test]
    fn a_hardness_in_gpa_typed_as_mpa_is_refused_and_a_soft_one_warned() {
        let mut scene = Scene::default();
        scene.disc.hardness_mpa = 2.473;
        let message = refused_at(&scene, "disc.hardness_mpa");
        assert!(
            message.contains("was it in GPa? 2.473 GPa = 2473 MPa"),
            "{message}"
        );
        // A lead-like disc: warned, and not taken for a slip (50 GPa is no metal's).
        scene.disc.hardness_table = None;
        scene.disc.hardness_mpa = 50.0;
        let message = warned_at(&scene, "disc.hardness_mpa");
        assert!(
            message.contains("softer than annealed pure aluminium"),
            "{message}"
        );
        assert!(message.contains("check that it is in MPa"), "{message}");
        // A table point is judged too, at its own path.
        scene.disc.hardness_mpa = 2473.0;
        scene.disc.hardness_table = Some(vec![(10.0, 2551.0), (60.0, 2.5)]);
        scene.disc.hardness_fit_includes_bulk = false;
        scene.test.cycles = 60;
        let message = refused_at(&scene, "disc.hardness_table[1][1]");
        assert!(!message.is_empty(), "{:?}", refusals(&scene));
        // The punch of 5 N at 2.5 / 2.8 MPa is 1.3 mm wide: the hardness's slip, not the
        // load's, and not the grid's resolution of it.
        assert_eq!(refusals(&scene).len(), 1, "{:?}", refusals(&scene));
        assert!(
            message.contains("was it in GPa? 2.5 GPa = 2500 MPa"),
            "{message}"
        );
        assert_eq!(refused_at(&scene, "disc.hardness_mpa"), "");
    }

    #[test]
    fn a_long_run_is_warned_with_its_time_and_size() {
        let mut scene = Scene::default();
        scene.test.cycles = 1_000_000;
        let message = warned_at(&scene, "test.cycles");
        assert!(
            message.contains("1000000 cycles will take about"),
            "{message}"
        );
        assert!(
            message.contains(" min") || message.contains(" h"),
            "{message}"
        );
        assert!(message.contains(" MB"), "{message}");
        // Ten times the paper's test is no warning (59 s measured).
        scene.test.cycles = 36_000;
        assert_eq!(warned_at(&scene, "test.cycles"), "");
    }

    #[test]
    fn a_height_map_in_um_read_as_m_is_refused() {
        // A checkerboard of +-0.1 read as m: rms 0.1 m = 1e5 um.
        let heights: Vec<f64> = (0..64)
            .map(|i| if (i + i / 8) % 2 == 0 { 0.1 } else { -0.1 })
            .collect();
        let map = HeightMap::new(8, 8, 1e-6, 1e-6, heights.clone()).expect("a valid map");
        let error = check_map("disc.gsf", &map).expect_err("refused");
        assert_eq!(error.path, "disc.surface.id");
        assert!(
            error.message.contains("in um rather than m"),
            "{}",
            error.message
        );
        assert!(error.message.contains("1.000e5 um") || error.message.contains("100000 um"));
        let scaled: Vec<f64> = heights.iter().map(|h| h * 1e-6).collect();
        let map = HeightMap::new(8, 8, 1e-6, 1e-6, scaled).expect("a valid map");
        assert_eq!(check_map("disc.gsf", &map), Ok(()));
    }
}
