//! The checked scene: a scene the simulation can run, with what checking it derived (the
//! elastic pair, the hardness law, the lowest yield pressure, Hertz's contact, the radius the
//! grid is sized by, the wear law). Only the check makes one ([`Plan::new`],
//! [`parse_scene`]), and [`super::Setup`] takes it without checking or deriving again.

use serde_json::Value;

use super::estimate::{RunEstimate, estimate};
use super::feasibility::{Derived, limits, resolution};
use super::plausibility::judge;
use super::sizing::{
    LowestYield, cells_per_contact_radius, elastic_pair, hertz, lowest_yield, plan_grid,
    sizing_radius_m,
};
use super::stroke_checks::{stroke_limits, stroke_warnings};
use crate::contact::{ElasticPair, Hertz};
use crate::hardness::{HardnessLaw, YieldCap};
use crate::scene::{self, FieldError, FieldWarning, Scene, SceneErrors, Switch};
use crate::wear::WearLaw;

/// A scene that passed every check (its fields, then the limits of the contact it
/// describes), and what the checks derived from it.
#[derive(Debug, Clone)]
pub struct Plan {
    scene: Scene,
    pair: ElasticPair,
    hardness: HardnessLaw,
    yield_cap: YieldCap,
    lowest: LowestYield,
    hertz: Hertz,
    sizing_radius_m: f64,
    wear: WearLaw,
    estimate: RunEstimate,
    warnings: Vec<FieldWarning>,
}

impl Plan {
    /// Checks `scene`: each field against its own range, then whether the simulation can
    /// run it. The errors' paths are the scene's (`test.load_n`); [`parse_scene`] gives them
    /// as they stand in the user's document.
    pub fn new(scene: Scene) -> Result<Self, SceneErrors> {
        scene.validate()?;
        derive(scene).map_err(SceneErrors)
    }

    /// The scene, defaults filled in.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene, to change and check again.
    pub fn into_scene(self) -> Scene {
        self.scene
    }

    /// The ball and the disc's combined elastic constants.
    pub fn pair(&self) -> &ElasticPair {
        &self.pair
    }

    /// The disc's hardness against cycles.
    pub fn hardness(&self) -> &HardnessLaw {
        &self.hardness
    }

    /// The pressure cap and how it hardens (eq. 12).
    pub fn yield_cap(&self) -> &YieldCap {
        &self.yield_cap
    }

    /// Hertz's contact of the unworn ball, the yardstick for sizing.
    pub fn hertz(&self) -> &Hertz {
        &self.hertz
    }

    /// The wear law.
    pub fn wear(&self) -> &WearLaw {
        &self.wear
    }

    /// What the run is expected to cost (solves, wall time, result size), extrapolated from
    /// the paper's scene.
    pub fn estimate(&self) -> &RunEstimate {
        &self.estimate
    }

    /// What in the scene looks wrong without being invalid (a contact wide against the
    /// ball, a soft disc, a long run), each with its field's path in the scene: printed
    /// before a run starts and carried into the result's `warnings`.
    pub fn warnings(&self) -> &[FieldWarning] {
        &self.warnings
    }

    /// Where and how low the yield pressure falls during the run.
    pub(super) fn lowest_yield(&self) -> &LowestYield {
        &self.lowest
    }

    /// The contact radius the first grid is sized by, m: Hertz's, or the flat punch at the
    /// lowest yield pressure where the cap may act and that is wider.
    pub(super) fn sizing_radius_m(&self) -> f64 {
        self.sizing_radius_m
    }
}

/// Parses a scene the simulation can run: [`scene::parse_scene`] with the checks of
/// [`Plan::new`], every error located in the user's document (`overrides.test.load_n`
/// under a preset). What the service and the command line accept.
pub fn parse_scene(json: &Value) -> Result<Plan, SceneErrors> {
    scene::parse_scene_with(json, derive)
}

/// [`parse_scene`] from JSON text.
pub fn parse_scene_str(text: &str) -> Result<Plan, SceneErrors> {
    scene::parse_scene_str_with(text, derive)
}

/// The plan of `scene`, whose fields each passed their own checks, or the limits of the
/// contact it describes that it breaks.
fn derive(scene: Scene) -> Result<Plan, Vec<FieldError>> {
    // The scene's own checks bound E, nu and the hardness table as the core does: neither
    // refusal can happen, and each would say what the core refused.
    let pair = elastic_pair(&scene).map_err(|e| {
        let message =
            format!("the contact core refused materials the scene's checks passed (a defect): {e}");
        vec![FieldError::new("", message)]
    })?;
    let hardness = scene
        .hardness_law()
        .map_err(|e| vec![FieldError::new("disc.hardness_table", e.to_string())])?;
    let yield_cap = scene.disc.yield_cap(hardness);
    let lowest = lowest_yield(&yield_cap, scene.test.cycles);
    let hertz = hertz(&scene, &pair);
    // Judged and sized wherever the cap may act (plasticity not "off"): under "auto" the
    // setup decides later, from the unworn contact's peak pressure, and where it leaves the
    // cap out Hertz's contact is wider than the punch (p0 < Y gives a punch radius below
    // sqrt(2/3) a), so the sizing radius is the same either way.
    let capped = scene.wear.plasticity != Switch::Off;
    let sizing_radius_m = sizing_radius_m(&hertz, lowest.yield_pa, capped);
    let derived = Derived {
        pair: &pair,
        lowest: &lowest,
        hertz: &hertz,
        capped,
        sizing_m: sizing_radius_m,
    };
    let density = cells_per_contact_radius(&scene);
    let first_grid = plan_grid(&scene.numerics, (sizing_radius_m, density), None);
    let estimate = estimate(&scene, &first_grid);
    let verdict = judge(&scene, &derived, &estimate);
    // A field the limits refuse keeps their message (its bound is exact); plausibility
    // names the slip of the others.
    let mut errors = limits(&scene, &derived);
    errors.extend(stroke_limits(&scene, sizing_radius_m, &first_grid));
    let refused = |path: &str, errors: &[FieldError]| errors.iter().any(|e| e.path == path);
    for refusal in verdict.refusals {
        if !refused(&refusal.path, &errors) {
            errors.push(refusal);
        }
    }
    if errors.is_empty() {
        errors = resolution(&scene, &derived);
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let wear = scene.wear.law(&scene.test, &hardness);
    let mut warnings = verdict.warnings;
    warnings.extend(stroke_warnings(&scene));
    Ok(Plan {
        scene,
        pair,
        hardness,
        yield_cap,
        lowest,
        hertz,
        sizing_radius_m,
        wear,
        estimate,
        warnings,
    })
}
