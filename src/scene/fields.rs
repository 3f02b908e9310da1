//! Every field a scene accepts, one descriptor each: the one home of each field's unit and
//! allowed range. The range checks (`validate.rs`, `located.rs`) word their messages from
//! these, and `docs/scene.md`'s table is rendered from them (`reference.rs`); a test walks
//! the parser's accepted keys and fails on any key without a descriptor here. The
//! descriptors of `disc.surface`, `test.reciprocating` and `corrosion` are in their own files
//! under `fields/`, listed in [`FIELDS`] here.

mod corrosion;
mod material;
mod reciprocating;
mod surface;

pub(super) use corrosion::{
    ANODIC_AREA, ANODIC_AREA_FACTOR, ANODIC_CURRENT, APPLIED_POTENTIAL, BARE_CORROSION_POTENTIAL,
    CONTROL, CORROSION_POTENTIAL, DENSITY, EXPOSED_AREA, FARADAY, GALVANIC_CELL, MOLAR_MASS,
    OCP_AFTER, OCP_BEFORE, OHMIC_RESISTANCE, REFERENCE, REPASSIVATION_EXPONENT,
    REPASSIVATION_KINETICS, REPASSIVATION_TIME, TAFEL_A, TAFEL_B, TAFEL_ETA_MAX, TAFEL_ETA_MIN,
    VALENCE,
};

pub(super) use material::{BALL_MATERIAL, DISC_MATERIAL};

pub(super) use reciprocating::{FREQUENCY, RECIPROCATING, STROKE, VELOCITY_LAW};

pub(super) use surface::{
    SURFACE, SURFACE_HURST, SURFACE_ID, SURFACE_KIND, SURFACE_LONG_CUTOFF, SURFACE_REMOVE_TILT,
    SURFACE_RMS_HEIGHT, SURFACE_RMS_SLOPE, SURFACE_SEED, SURFACE_SHORT_CUTOFF,
};

use super::MAX_RECORD_CYCLES;
use super::field::{Field, Range};
use crate::contact::Grid;

/// Longest run accepted: a cap on run time and on the size of the result.
pub(super) const MAX_CYCLES: u64 = 1_000_000;

const POISSON_WHY: &str = "the bounds of an isotropic elastic solid";
const ELASTIC_FEEDS: &str = "E*, G*, nu*, delta-nu (eqs. 6, 8) in the influence coefficients \
                             (eqs. 7, 9)";

/// Free-form label.
pub(super) const NAME: Field = Field {
    path: "name",
    unit: "",
    range: Range::Text(crate::text::NAME_MAX_CHARS),
    why: "it is kept in every job record and list page, and names the downloads",
    meaning: "Free-form label, shown in the job list. A study's member is named after its \
              base's name and its values, cut to fit.",
    feeds: "",
};

/// `ball.radius_mm`.
pub(super) const BALL_RADIUS: Field = Field {
    path: "ball.radius_mm",
    unit: "mm",
    range: Range::Positive,
    why: "",
    meaning: "Radius of the ball (alumina in the paper).",
    feeds: "the separation d of the sphere from the disc (eqs. 2, 3, 17)",
};

/// `ball.youngs_modulus_gpa`.
pub(super) const BALL_MODULUS: Field = Field {
    path: "ball.youngs_modulus_gpa",
    unit: "GPa",
    range: Range::Positive,
    why: "",
    meaning: "Young's modulus of the ball.",
    feeds: ELASTIC_FEEDS,
};

/// `ball.poisson_ratio`.
pub(super) const BALL_POISSON: Field = Field {
    path: "ball.poisson_ratio",
    unit: "",
    range: Range::Open(-1.0, 0.5),
    why: POISSON_WHY,
    meaning: "Poisson's ratio of the ball.",
    feeds: ELASTIC_FEEDS,
};

/// `disc.youngs_modulus_gpa`.
pub(super) const DISC_MODULUS: Field = Field {
    path: "disc.youngs_modulus_gpa",
    unit: "GPa",
    range: Range::Positive,
    why: "",
    meaning: "Young's modulus of the disc (AISI 316L in the paper, which prints \"205 MPa\", \
              a typo for GPa).",
    feeds: ELASTIC_FEEDS,
};

/// `disc.poisson_ratio`.
pub(super) const DISC_POISSON: Field = Field {
    path: "disc.poisson_ratio",
    unit: "",
    range: Range::Open(-1.0, 0.5),
    why: POISSON_WHY,
    meaning: "Poisson's ratio of the disc.",
    feeds: ELASTIC_FEEDS,
};

/// `disc.hardness_mpa`.
pub(super) const DISC_HARDNESS: Field = Field {
    path: "disc.hardness_mpa",
    unit: "MPa",
    range: Range::Positive,
    why: "",
    meaning: "Bulk hardness: H at cycle 1, and H throughout when there is no \
              `hardness_table`.",
    feeds: "Y = H / yield_factor (eq. 12); H in Archard's law (eqs. 14-16); F / H for the \
            `real_contact` anodic area",
};

/// `disc.hardness_table`.
pub(super) const HARDNESS_TABLE: Field = Field {
    path: "disc.hardness_table",
    unit: "MPa",
    range: Range::HardnessTable,
    why: "",
    meaning: "Measured hardness of the worn surface against the cycle count, `[[cycles, \
              hardness_mpa], ...]` (the default is Table 3's five points). H(n) is the \
              least-squares fit H = A + B ln n through these points (and the bulk value at n = \
              1, see `hardness_fit_includes_bulk`). null: H stays at `hardness_mpa`.",
    feeds: "H(n) of Fig. 9 and Section 4.5, hence Y (eq. 12) and H (eqs. 14-16) at each cycle",
};

/// `disc.hardness_fit_includes_bulk`.
pub(super) const HARDNESS_FIT_INCLUDES_BULK: Field = Field {
    path: "disc.hardness_fit_includes_bulk",
    unit: "",
    range: Range::Bool,
    why: "",
    meaning: "Whether the bulk `hardness_mpa`, as the point n = 1, takes part in the fit with \
              the table. The result's `work_hardening` model gives A, B and each point's \
              residual, and warns of a point far off the law.",
    feeds: "H(n) of Fig. 9",
};

/// `disc.yield_factor`.
pub(super) const YIELD_FACTOR: Field = Field {
    path: "disc.yield_factor",
    unit: "",
    range: Range::Positive,
    why: "",
    meaning: "Ratio of hardness to yield pressure, Y = H / yield_factor (2.8 after Johnson).",
    feeds: "the pressure cap p <= Y (eq. 12)",
};

/// `disc.yield_cap`.
pub(super) const YIELD_CAP: Field = Field {
    path: "disc.yield_cap",
    unit: "",
    range: Range::OneOf(&["hardness", "strain_hardening"]),
    why: "",
    meaning: "How the cap Y follows the disc's hardening. `hardness`: Y = H(n) / \
              yield_factor from the first pass (the paper's eq. 12). `strain_hardening`: Y \
              starts at `initial_yield_strength_mpa` and rises, linearly in the surface's \
              plastic strain (Tabor's 0.2 a / R for each pass that yields), to H(n) / \
              yield_factor at Tabor's representative strain of 8%; the result's \
              `plasticity` model and each record's `yield_pressure_mpa` give the cap.",
    feeds: "the cap p <= Y (eq. 12) at each cycle",
};

/// `disc.initial_yield_strength_mpa`.
pub(super) const INITIAL_YIELD: Field = Field {
    path: "disc.initial_yield_strength_mpa",
    unit: "MPa",
    range: Range::Positive,
    why: "",
    meaning: "The unstrained disc's yield strength (0.2% proof stress); the default is \
              annealed 316L's typical 290 MPa (AK Steel's 316/316L data sheet). Used by \
              `yield_cap: \"strain_hardening\"`; a value above H / yield_factor leaves the \
              paper's cap.",
    feeds: "the first cycles' cap p <= Y (eq. 12)",
};

/// `test.load_n`.
pub(super) const LOAD: Field = Field {
    path: "test.load_n",
    unit: "N",
    range: Range::Positive,
    why: "",
    meaning: "Normal load on the ball.",
    feeds: "the load the pressures carry (eq. 11); F_N in eqs. 1 and 14",
};

/// `test.track_radius_mm`.
pub(super) const TRACK_RADIUS: Field = Field {
    path: "test.track_radius_mm",
    unit: "mm",
    range: Range::Positive,
    why: "",
    meaning: "Radius R_c of the wear track on the disc.",
    feeds: "sliding distance 2 pi R_c per cycle (s in eqs. 1, 14, 15); the track length in \
            the result's volumes and in the `wear_track` anodic area (eq. 18)",
};

/// `test.speed_rpm`.
pub(super) const SPEED: Field = Field {
    path: "test.speed_rpm",
    unit: "rpm",
    range: Range::Positive,
    why: "",
    meaning: "Disc rotation speed, revolutions per minute; a cycle lasts 60 / rpm seconds.",
    feeds: "the time of each cycle (`time_s`), hence the WAC volume (Faraday's law) and the \
            sliding distance of a calibration point (eq. 1)",
};

/// `test.friction_coefficient`.
pub(super) const FRICTION: Field = Field {
    path: "test.friction_coefficient",
    unit: "",
    range: Range::Closed(0.0, 2.0),
    why: "2 is beyond any lubricated or dry metal-ceramic pair",
    meaning: "Coulomb friction coefficient mu between ball and disc.",
    feeds: "q_x = mu p (eq. 4) and the coupling term (eqs. 5, 7, 10)",
};

/// `test.cycles`.
pub(super) const CYCLES: Field = Field {
    path: "test.cycles",
    unit: "cycles",
    range: Range::Whole(1, MAX_CYCLES),
    why: "",
    meaning: "Passes of the ball over the track; at 60 rpm one cycle is one second.",
    feeds: "when the loop of Fig. 4 stops",
};

/// `wear.archard_k`.
pub(super) const ARCHARD_K: Field = Field {
    path: "wear.archard_k",
    unit: "",
    range: Range::Closed(0.0, 1.0),
    why: "0 is a run without wear",
    meaning: "Archard's wear coefficient k (dimensionless). Given, it replaces \
              `archard_calibration`; absent, k is derived from the calibration point. The k \
              used is in the result's `summary.archard_k`.",
    feeds: "k in Archard's law (eqs. 14-16)",
};

/// `wear.archard_k_basis`.
pub(super) const ARCHARD_K_BASIS: Field = Field {
    path: "wear.archard_k_basis",
    unit: "",
    range: Range::OneOf(&["total_loss", "mechanical"]),
    why: "",
    meaning: "The loss k was fitted on. `total_loss`: a profilometer's volume, corrosion \
              included (Table 3, and eq. 1 on it): the wear track is the total and the \
              mechanical part is the track less the WAC. `mechanical`: the loss without \
              corrosion (a cathodically protected test, or `tribosim calibrate archard`): the \
              total is the track plus the WAC. Without `corrosion` the two read the same.",
    feeds: "how the groove and the WAC make `total_volume_mm3` and `mechanical_volume_mm3` \
            (ASTM G119's balance); `wear_volume_mm3` is the total on either basis",
};

/// `wear.archard_calibration`.
pub(super) const CALIBRATION: Field = Field {
    path: "wear.archard_calibration",
    unit: "",
    range: Range::OptionalObject,
    why: "",
    meaning: "A measured point `{\"time_s\": ..., \"wear_volume_mm3\": ...}` from which k is \
              derived, in place of `archard_k`; by default Table 3's 3600 s point, as the \
              paper's Section 4.5 does. Its test conditions default to the scene's.",
    feeds: "k = V H / (F_N s) (eq. 1, which is eq. 14 solved for k), s = sliding speed x \
            time_s",
};

/// `wear.archard_calibration.time_s`.
pub(super) const CALIBRATION_TIME: Field = Field {
    path: "wear.archard_calibration.time_s",
    unit: "s",
    range: Range::Positive,
    why: "",
    meaning: "Rubbing time of the measured point (Table 3's last is 3600 s).",
    feeds: "s and the cycle of H in eq. 1",
};

/// `wear.archard_calibration.wear_volume_mm3`.
pub(super) const CALIBRATION_VOLUME: Field = Field {
    path: "wear.archard_calibration.wear_volume_mm3",
    unit: "mm^3",
    range: Range::AtLeast(0.0),
    why: "",
    meaning: "Wear volume measured after `time_s` (Table 3: 11.72e-3 mm^3 at 3600 s).",
    feeds: "V in eq. 1",
};

const fn condition(path: &'static str, unit: &'static str, meaning: &'static str) -> Field {
    Field {
        path,
        unit,
        range: Range::Positive,
        why: "",
        meaning,
        feeds: "eq. 1",
    }
}

/// `wear.archard_calibration.hardness_mpa`.
pub(super) const CALIBRATION_HARDNESS: Field = condition(
    "wear.archard_calibration.hardness_mpa",
    "MPa",
    "Hardness measured at `time_s` (H in eq. 1); absent, the hardness law's value there.",
);

/// `wear.archard_calibration.load_n`.
pub(super) const CALIBRATION_LOAD: Field = condition(
    "wear.archard_calibration.load_n",
    "N",
    "Load of the measured test; absent, the scene's `test.load_n`.",
);

/// `wear.archard_calibration.speed_rpm`.
pub(super) const CALIBRATION_SPEED: Field = condition(
    "wear.archard_calibration.speed_rpm",
    "rpm",
    "Rotation speed of the measured test; absent, the scene's `test.speed_rpm`. Given (or \
     `track_radius_mm` given), the point was measured on a disc, even for a reciprocating \
     scene; neither given, on the scene's own rig (a stroke's 2 L f).",
);

/// `wear.archard_calibration.track_radius_mm`.
pub(super) const CALIBRATION_TRACK_RADIUS: Field = condition(
    "wear.archard_calibration.track_radius_mm",
    "mm",
    "Wear track radius of the measured test; absent, the scene's `test.track_radius_mm`.",
);

/// `wear.archard_regime_change`.
pub(super) const REGIME_CHANGE: Field = Field {
    path: "wear.archard_regime_change",
    unit: "",
    range: Range::OptionalObject,
    why: "",
    meaning: "A change of wear regime, `{\"cycle\": 300, \"archard_k_before\": 2e-5}`: \
              cycles 1 to `cycle` wear with `archard_k_before`, the later ones with \
              `archard_k` (or the k of `archard_calibration`), as the paper's Section 5.2 reads \
              Table 3 (a low-wear period before about 300 cycles, Archard wear after). The \
              cycle stepping solves the first cycle after the change. Absent: one k \
              throughout. `tribosim calibrate archard --regime-change` fits it.",
    feeds: "k in Archard's law (eqs. 14-16), per cycle",
};

/// `wear.archard_regime_change.cycle`.
pub(super) const REGIME_CHANGE_CYCLE: Field = Field {
    path: "wear.archard_regime_change.cycle",
    unit: "cycles",
    range: Range::Whole(1, MAX_CYCLES - 1),
    why: "and below `test.cycles`, so that the second regime is part of the run",
    meaning: "The last cycle of the first regime.",
    feeds: "where k changes",
};

/// `wear.archard_regime_change.archard_k_before`.
pub(super) const REGIME_CHANGE_K_BEFORE: Field = Field {
    path: "wear.archard_regime_change.archard_k_before",
    unit: "",
    range: Range::Closed(0.0, 1.0),
    why: "0 is a first regime without Archard wear",
    meaning: "k of cycles 1 to `cycle` (dimensionless).",
    feeds: "k in Archard's law (eqs. 14-16) up to the change",
};

/// `wear.plasticity`.
pub(super) const PLASTICITY: Field = Field {
    path: "wear.plasticity",
    unit: "",
    range: Range::OneOf(&["auto", "on", "off"]),
    why: "",
    meaning: "The elastic-perfectly-plastic pressure cap: `auto` turns it on only where \
              pressures can reach Y (the result's `models` says why).",
    feeds: "the cap p <= Y (eq. 12) and the groove by yielding (eq. 13)",
};

/// `numerics.grid`.
pub(super) const GRID: Field = Field {
    path: "numerics.grid",
    unit: "cells",
    range: Range::AutoOrWhole(8, Grid::MAX_CELLS_PER_SIDE as u64),
    why: "below 8 a contact is not resolved; larger grids' padded 2N x 2N spectra need \
          gigabytes",
    meaning: "Cells per side of the square grid; `auto` sizes it to the contact.",
    feeds: "the cells dx, dy of the discretised eqs. 10-12",
};

/// `numerics.domain_um`.
pub(super) const DOMAIN: Field = Field {
    path: "numerics.domain_um",
    unit: "um",
    range: Range::AutoOrUpTo(100_000.0),
    why: "10 cm is far beyond any ball-on-disc contact",
    meaning: "Side of the square domain; `auto` sizes it to the contact and grows it as the \
              track widens.",
    feeds: "the domain of eqs. 10-12",
};

/// `numerics.tolerance`. The relative residual has a round-off floor of about machine
/// epsilon times the approach over the largest elastic displacement, so it rises as a groove
/// deepens. Wear runs stalled with NotConverged at residuals of 1.2e-13 to 1.5e-13 (paper
/// scene, 3600 cycles), 6e-13 (H falling to 300 MPa over 3600 cycles) and 1.3e-12 (to
/// 100 MPa over 1000 cycles, grid 32); all of them ran at 1e-11. 1e-10 is also the tightest
/// reference `tribosim bench wear` uses: 1e-8 already agrees with it to 4e-11 in volume.
pub(super) const TOLERANCE: Field = Field {
    path: "numerics.tolerance",
    unit: "",
    range: Range::AutoOrClosed(1e-10, 1e-2),
    why: "below 1e-10 the residual's round-off floor stalls long runs; above 1e-2 the \
          pressures are too rough to wear with",
    meaning: "Relative residual at which the contact solver stops; `auto` is 1e-6 on a \
              smooth disc, 1e-4 on a rough one and 1e-5 on the reciprocating rig \
              (`docs/accuracy.md`). From 1e-4 on, the contact's FFTs compute in single \
              precision (the result's `precision` model).",
    feeds: "the bounded solve of eqs. 10-12",
};

/// `numerics.cycle_step`.
pub(super) const CYCLE_STEP: Field = Field {
    path: "numerics.cycle_step",
    unit: "",
    range: Range::AutoOrOne,
    why: "",
    meaning: "Which cycles are solved: 1 solves every cycle (the paper's numerics; on the \
              reciprocating rig, both sweeps of each); `auto` lets one solve stand for several \
              cycles while the surface changes slowly (on the rig, a forward sweep for its \
              return too); on a rough disc it solves every cycle unless `cycle_step_bound` is \
              given (`docs/accuracy.md`).",
    feeds: "the loop of Fig. 4; the time step of eq. 15's s",
};

/// `numerics.cycle_step_bound`.
pub(super) const CYCLE_STEP_BOUND: Field = Field {
    path: "numerics.cycle_step_bound",
    unit: "",
    range: Range::AutoOrClosed(1e-4, 0.1),
    why: "above 0.1 a step skipped the end of the yielding phase (volume error 1.6e-3 at 300 \
          cycles); below 1e-4 no step is ever taken",
    meaning: "With `cycle_step: \"auto\"`, the largest relative (L1) change of the per-pass \
              wear profile one step may span; `auto` is 0.01 on a disc and 0.02 on the \
              reciprocating rig, and solves every cycle of a rough disc, where steps skip the \
              yield cuts of their cycles (`docs/accuracy.md` shows what each costs and buys).",
    feeds: "the time step of eq. 15's s",
};

/// `numerics.record_cycles`.
pub(super) const RECORD_CYCLES: Field = Field {
    path: "numerics.record_cycles",
    unit: "cycles",
    range: Range::AutoOrCycles(MAX_RECORD_CYCLES as u64),
    why: "each is a solve and a kept profile",
    meaning: "Cycles at which the state is recorded exactly: solved there (a cycle step never \
              passes one) and the profile kept. `auto`: Table 3's times at the scene's speed, \
              within the run.",
    feeds: "Table 3's times; the profiles of Fig. 12",
};

/// `numerics.coupling`.
pub(super) const COUPLING: Field = Field {
    path: "numerics.coupling",
    unit: "",
    range: Range::OneOf(&["auto", "on", "off"]),
    why: "",
    meaning: "The friction coupling of normal and tangential tractions (mu delta-nu): \
              `auto` keeps it only where it can move pressures beyond the tolerance.",
    feeds: "the mu C_zx term of eq. 10 (eq. 7)",
};

/// `numerics.threads`.
pub(super) const THREADS: Field = Field {
    path: "numerics.threads",
    unit: "threads",
    range: Range::AutoOrWhole(1, crate::contact::MAX_SPLIT_THREADS as u64),
    why: "more threads than cores only wait for each other",
    meaning: "Threads of each contact solve's FFT passes and of the solver's passes over \
              the grid; the results do not depend on it. `auto`: one below 384 x 384 \
              cells, where the split does not pay, else the cores the process may use \
              divided among the service's workers (`docs/operations.md`).",
    feeds: "the apply of K in eqs. 10-12 (no value changes)",
};

/// A section of the scene: an object of the fields under its name.
const fn section(path: &'static str, meaning: &'static str, range: Range) -> Field {
    Field {
        path,
        unit: "",
        range,
        why: "",
        meaning,
        feeds: "",
    }
}

/// Every field a scene accepts, sections first in each group, in the order of the
/// reference. Add a field here and in its section's struct; the docs test then asks for
/// `docs/scene.md` to be regenerated.
pub const FIELDS: &[Field] = &[
    NAME,
    section("ball", "The counter body.", Range::Object),
    BALL_MATERIAL,
    BALL_RADIUS,
    BALL_MODULUS,
    BALL_POISSON,
    section("disc", "The worn disc.", Range::Object),
    DISC_MATERIAL,
    DISC_MODULUS,
    DISC_POISSON,
    DISC_HARDNESS,
    HARDNESS_TABLE,
    HARDNESS_FIT_INCLUDES_BULK,
    YIELD_FACTOR,
    YIELD_CAP,
    INITIAL_YIELD,
    SURFACE,
    SURFACE_KIND,
    SURFACE_RMS_HEIGHT,
    SURFACE_RMS_SLOPE,
    SURFACE_HURST,
    SURFACE_SHORT_CUTOFF,
    SURFACE_LONG_CUTOFF,
    SURFACE_SEED,
    SURFACE_ID,
    SURFACE_REMOVE_TILT,
    section(
        "test",
        "Load, kinematics and length of the test.",
        Range::Object,
    ),
    LOAD,
    TRACK_RADIUS,
    SPEED,
    FRICTION,
    CYCLES,
    OCP_BEFORE,
    OCP_AFTER,
    RECIPROCATING,
    STROKE,
    FREQUENCY,
    VELOCITY_LAW,
    section("wear", "The wear law.", Range::Object),
    ARCHARD_K,
    CALIBRATION,
    CALIBRATION_TIME,
    CALIBRATION_VOLUME,
    CALIBRATION_HARDNESS,
    CALIBRATION_LOAD,
    CALIBRATION_SPEED,
    CALIBRATION_TRACK_RADIUS,
    REGIME_CHANGE,
    REGIME_CHANGE_CYCLE,
    REGIME_CHANGE_K_BEFORE,
    ARCHARD_K_BASIS,
    PLASTICITY,
    section(
        "corrosion",
        "The electrochemical cell (Section 5.1), the paper's Table 2 by default; null: no \
         corrosion estimate.",
        Range::OptionalObject,
    ),
    CORROSION_POTENTIAL,
    REFERENCE,
    TAFEL_A,
    TAFEL_B,
    TAFEL_ETA_MIN,
    TAFEL_ETA_MAX,
    ANODIC_CURRENT,
    EXPOSED_AREA,
    ANODIC_AREA,
    REPASSIVATION_TIME,
    REPASSIVATION_KINETICS,
    REPASSIVATION_EXPONENT,
    GALVANIC_CELL,
    BARE_CORROSION_POTENTIAL,
    OHMIC_RESISTANCE,
    CONTROL,
    APPLIED_POTENTIAL,
    ANODIC_AREA_FACTOR,
    FARADAY,
    MOLAR_MASS,
    VALENCE,
    DENSITY,
    section(
        "numerics",
        "Discretisation and solver settings.",
        Range::Object,
    ),
    GRID,
    DOMAIN,
    TOLERANCE,
    CYCLE_STEP,
    CYCLE_STEP_BOUND,
    RECORD_CYCLES,
    COUPLING,
    THREADS,
];

/// The descriptor of the field at `path`, if the scene has one.
pub fn field(path: &str) -> Option<&'static Field> {
    FIELDS.iter().find(|f| f.path == path)
}
