//! The sections of a scene (ball, disc, test, wear, numerics; corrosion in
//! [`super::corrosion`]) with the paper's values as their defaults, and their conversions to
//! the core's SI types.

use serde::{Deserialize, Serialize};

use super::auto_or::{CycleStep, DomainSize, GridSize, SolverThreads, StepBound, Tolerance};
use super::materials::{BallMaterialName, DiscMaterialName};
use super::reciprocating::Reciprocating;
use super::record::RecordCycles;
use super::surface::SurfaceSpec;
use crate::hardness::{HardnessError, HardnessLaw, YieldCap};
use crate::wear::{Archard, ArchardK, ArchardRegimeChange, MeasuredPoint, VolumeBasis, WearLaw};

/// One row of the paper's Table 3, measured at 5 N and 60 rpm on the 2.992 mm track.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Table3Row {
    /// Rubbing time, s (cycles, at 60 rpm).
    pub time_s: u64,
    /// Hardness measured inside the wear track, MPa.
    pub hardness_mpa: f64,
    /// Its spread as the table gives it, MPa.
    pub hardness_spread_mpa: f64,
    /// Wear volume a profilometer measured, mm^3.
    pub wear_volume_mm3: f64,
    /// Its spread as the table gives it, mm^3.
    pub spread_mm3: f64,
}

/// The paper's Table 3: the one place its numbers are written; the hardness law's points,
/// the calibration point, the benchmarks and the page's overlay (through the preset's
/// `measured` points, `GET /api/v1/presets`) read them from here.
pub const PAPER_TABLE3: [Table3Row; 5] = [
    row(10, [2551.0, 90.0], [0.97e-3, 2.0e-3]),
    row(60, [2727.0, 90.0], [1.09e-3, 0.1e-3]),
    row(300, [2854.0, 10.0], [1.18e-3, 0.0]),
    row(1800, [2933.0, 90.0], [5.33e-3, 0.7e-3]),
    row(3600, [2953.0, 90.0], [11.72e-3, 0.2e-3]),
];

/// The spread of Table 3's bulk hardness, 2473 +- 110 MPa (the disc's `hardness_mpa`).
pub const PAPER_BULK_HARDNESS_SPREAD_MPA: f64 = 110.0;

/// A row from its time, its hardness and spread (MPa) and its volume and spread (mm^3).
const fn row(time_s: u64, hardness_mpa: [f64; 2], wear_volume_mm3: [f64; 2]) -> Table3Row {
    Table3Row {
        time_s,
        hardness_mpa: hardness_mpa[0],
        hardness_spread_mpa: hardness_mpa[1],
        wear_volume_mm3: wear_volume_mm3[0],
        spread_mm3: wear_volume_mm3[1],
    }
}

/// The calibration point when a scene gives neither `archard_k` nor `archard_calibration`:
/// the paper's own rule (Section 4.5), k by eq. 14 from the final measured time and wear
/// volume of Table 3 and the hardness measured there, k = V H / (F s) = 11.72e-3 mm^3 x
/// 2953 MPa / (5 N x 3600 s x 18.8 mm/s) = 1.02e-4. The test's conditions are part of the
/// point, so a scene at another load or speed keeps the paper's k.
pub const PAPER_ARCHARD_CALIBRATION: ArchardCalibration = {
    let last = PAPER_TABLE3[PAPER_TABLE3.len() - 1];
    ArchardCalibration {
        time_s: last.time_s as f64,
        wear_volume_mm3: last.wear_volume_mm3,
        hardness_mpa: Some(last.hardness_mpa),
        load_n: Some(5.0),
        speed_rpm: Some(60.0),
        track_radius_mm: Some(2.992),
    }
};

/// The paper's Table 3 hardness inside the wear track, `(cycles, MPa)` at 60 rpm (cycles =
/// seconds).
pub const PAPER_HARDNESS_TABLE: [(f64, f64); 5] = {
    let mut table = [(0.0, 0.0); 5];
    let mut i = 0;
    while i < table.len() {
        table[i] = (PAPER_TABLE3[i].time_s as f64, PAPER_TABLE3[i].hardness_mpa);
        i += 1;
    }
    table
};

/// The number of cycles of the paper's test: 3600 s at 60 rpm.
pub const PAPER_CYCLES: u64 = 3600;

/// The default largest relative (L1) change of the per-pass wear profile across one
/// automatic cycle step (`numerics.cycle_step_bound`). Measured on the paper scene at grid
/// 64 against every-cycle solving (`tribosim bench wear` gives the current numbers): 0.01
/// gives, at 300 cycles, 87 solves, volume exact and depth 6e-4; at 3600 cycles 326 solves
/// (8.6 times faster), volume 9e-5 and depth 1e-4. 0.03: depth 1.3e-3 and 3.3e-4 for no gain
/// at 3600 cycles, where the longest step (`simulation::MAX_STEP`) dominates; 0.1 skipped
/// the end of the yielding and erred by 1.6e-3 in volume at 300 cycles.
pub const STEP_CHANGE_BOUND: f64 = 0.01;

/// The default relative residual of the contact solves (`numerics.tolerance`): the loosest
/// whose error stays below the auto grid's own. On the Hertz case at the auto density
/// (N = 256, `tribosim bench contact`) 1e-6 leaves a pressure error of 2.0e-5 of p0 against
/// the grid's 1.1e-4 (peak pressure), area and approach unchanged; 1e-4 leaves 2.4e-3.
/// On the paper's 3600-cycle scene (`tribosim bench speed`) it changes the wear volume by
/// -1.7e-5, the depth by -1.7e-5 and the final potential by 0.001 mV against 1e-8, less
/// than the cycle step errs against solving every cycle (1.7e-4 in volume, `tribosim bench
/// wear`): the two runs step differently (464 against 470 solves); 4.7 instead of 6.7
/// iterations per solve. The contact core's own
/// default ([`crate::contact::SolverOptions`]) stays 1e-8, the tolerance its benchmarks and peers run at.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// The relative residual `numerics.tolerance: "auto"` solves a rough disc's contacts to,
/// every cycle solved ([`Numerics::solve_cycle_step`]): chosen by
/// `scripts/rough_default.py` (`docs/accuracy.md`, "Rough wear: the default by speed
/// against error"). On the 4 um cut-off disc over 600 cycles, against the same disc solved
/// every cycle at 1e-8: every cycle at 1e-4 took 3441 iterations and 0.88 of the CPU time
/// of automatic steps at 1e-5 (4230 iterations; medians of 3 alternating pairs, each
/// against the smooth disc's), and erred by -7.2e-5 in volume, +1.0e-5 in depth, -3.9e-3 in
/// the WAC and -1.1 mV in E, against -2.3e-4, -1.3e-4, -3.2e-3 and -1.6 mV: the steps'
/// skipped cuts cost more than the looser solves. The WAC's and E's errors sit at the floor
/// a 2e-5 change of load sets (up to 1e-3 and 1 mV), the volume's and depth's far below the
/// grid's 2-5%; automatic steps at 1e-4 erred by -1.8e-3 in volume. Over five seeds of
/// that disc (`scripts/rough_seeds.py`, "Rough wear: the tolerance over five discs"), 1e-4
/// is the loosest candidate within every target on all five: 2e-4, 5e-4 and 1e-3 each miss
/// on two, though on seed 1 alone 5e-4 meets them all.
pub const ROUGH_TOLERANCE: f64 = 1e-4;

/// The ball.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Ball {
    /// The library's ball whose values fill the fields not given; `None`: as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<BallMaterialName>,
    /// Ball radius, mm.
    pub radius_mm: f64,
    /// Young's modulus, GPa.
    pub youngs_modulus_gpa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
}

impl Default for Ball {
    fn default() -> Self {
        Self {
            material: None,
            radius_mm: 3.0,
            youngs_modulus_gpa: 300.0,
            poisson_ratio: 0.21,
        }
    }
}

impl Ball {
    /// Young's modulus, Pa.
    pub fn youngs_modulus_pa(&self) -> f64 {
        self.youngs_modulus_gpa * 1e9
    }
}

/// The disc.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Disc {
    /// The library's disc whose values fill the fields not given; `None`: as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<DiscMaterialName>,
    /// Young's modulus, GPa. (The paper prints "205 MPa", a typo for GPa.)
    pub youngs_modulus_gpa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Bulk hardness, MPa: H at n = 1, and H throughout when there is no table.
    pub hardness_mpa: f64,
    /// Measured `(cycle, hardness_mpa)` pairs for the work-hardening fit H = A + B ln n;
    /// `null` for a constant hardness.
    pub hardness_table: Option<Vec<(f64, f64)>>,
    /// Whether the bulk hardness, as the point n = 1, takes part in the fit with the table.
    pub hardness_fit_includes_bulk: bool,
    /// Y = H / `yield_factor` (2.8 after Johnson).
    pub yield_factor: f64,
    /// How the cap Y follows the disc's hardening.
    pub yield_cap: YieldCapLaw,
    /// The unstrained disc's yield strength (0.2% proof stress), MPa: where the
    /// `strain_hardening` cap starts.
    pub initial_yield_strength_mpa: f64,
    /// The initial roughness; `None` for a smooth disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<SurfaceSpec>,
}

impl Default for Disc {
    fn default() -> Self {
        Self {
            material: None,
            youngs_modulus_gpa: 205.0,
            poisson_ratio: 0.28,
            hardness_mpa: 2473.0,
            hardness_table: Some(PAPER_HARDNESS_TABLE.to_vec()),
            hardness_fit_includes_bulk: true,
            yield_factor: 2.8,
            yield_cap: YieldCapLaw::Hardness,
            initial_yield_strength_mpa: ANNEALED_316L_PROOF_STRESS_MPA,
            surface: None,
        }
    }
}

impl Disc {
    /// Young's modulus, Pa.
    pub fn youngs_modulus_pa(&self) -> f64 {
        self.youngs_modulus_gpa * 1e9
    }

    /// The hardness law: the least-squares log fit when a table is given, else constant.
    pub fn hardness_law(&self) -> Result<HardnessLaw, HardnessError> {
        match self.hardness_fit_points() {
            None => Ok(HardnessLaw::constant(self.hardness_mpa * 1e6)),
            Some(points) => HardnessLaw::fit_points(&points),
        }
    }

    /// The pressure cap of the hardness law `law` (eq. 12), as `yield_cap` asks.
    pub fn yield_cap(&self, law: HardnessLaw) -> YieldCap {
        let yield_factor = self.yield_factor;
        match self.yield_cap {
            YieldCapLaw::Hardness => YieldCap::Hardness { law, yield_factor },
            YieldCapLaw::StrainHardening => YieldCap::StrainHardening {
                law,
                yield_factor,
                initial_pa: self.initial_yield_strength_mpa * 1e6,
            },
        }
    }

    /// The `(cycle, hardness_pa)` points the law is fitted to: the table, and the bulk value
    /// at n = 1 when `hardness_fit_includes_bulk`; `None` without a table.
    pub fn hardness_fit_points(&self) -> Option<Vec<(f64, f64)>> {
        let table = self.hardness_table.as_ref()?;
        let bulk = self
            .hardness_fit_includes_bulk
            .then_some((1.0, self.hardness_mpa));
        Some(
            bulk.into_iter()
                .chain(table.iter().copied())
                .map(|(n, h)| (n, h * 1e6))
                .collect(),
        )
    }
}

/// Load, kinematics and length of the test.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TestConditions {
    /// Normal load, N.
    pub load_n: f64,
    /// Radius of the wear track on the disc, mm.
    pub track_radius_mm: f64,
    /// Disc rotation speed, revolutions per minute.
    pub speed_rpm: f64,
    /// Coulomb friction coefficient mu.
    pub friction_coefficient: f64,
    /// Number of passes of the ball over the track.
    pub cycles: u64,
    /// Open-circuit time recorded before the rubbing starts, s.
    pub ocp_before_s: f64,
    /// Open-circuit time recorded after the rubbing stops, s.
    pub ocp_after_s: f64,
    /// The reciprocating rig's stroke; `None` for the ball on a rotating disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reciprocating: Option<Reciprocating>,
}

impl Default for TestConditions {
    fn default() -> Self {
        Self {
            load_n: 5.0,
            track_radius_mm: 2.992,
            speed_rpm: 60.0,
            friction_coefficient: 0.45,
            cycles: PAPER_CYCLES,
            ocp_before_s: 0.0,
            ocp_after_s: 0.0,
            reciprocating: None,
        }
    }
}

impl TestConditions {
    /// The mean sliding speed, m/s: 2 pi R_c rpm / 60 on the disc (18.8 mm/s in the
    /// paper), 2 L f on the reciprocating rig.
    pub fn sliding_speed_m_s(&self) -> f64 {
        match &self.reciprocating {
            Some(rig) => rig.stroke().mean_speed_m_s(),
            // The same order of operations as `Scene::track_length_m` times the turns per
            // second.
            None => {
                2.0 * std::f64::consts::PI * (self.track_radius_mm * 1e-3) * self.speed_rpm / 60.0
            }
        }
    }

    /// Cycles per second: rpm / 60 on the disc, the stroke's frequency on the
    /// reciprocating rig.
    pub fn cycles_per_second(&self) -> f64 {
        match &self.reciprocating {
            Some(rig) => rig.frequency_hz,
            None => self.speed_rpm / 60.0,
        }
    }

    /// Cycles completed after `time_s` of rubbing (fractional).
    pub fn cycles_at(&self, time_s: f64) -> f64 {
        match &self.reciprocating {
            Some(rig) => time_s * rig.frequency_hz,
            None => time_s * self.speed_rpm / 60.0,
        }
    }
}

/// Wear law settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Wear {
    /// Archard coefficient k, dimensionless. Missing on input means "not given" (so a
    /// calibration may be used instead); [`super::parse_scene`] fills in
    /// [`PAPER_ARCHARD_CALIBRATION`] when neither is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_k: Option<f64>,
    /// A measured point from which k is derived, in place of `archard_k`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_calibration: Option<ArchardCalibration>,
    /// A change of wear regime: another k up to a cycle; `archard_k` (or the calibration)
    /// gives k after it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_regime_change: Option<ArchardRegimeChange>,
    /// The loss k was fitted on, which decides how the groove and the corrosion add up.
    pub archard_k_basis: VolumeBasis,
    /// Elastic-perfectly-plastic pressure cap.
    pub plasticity: Switch,
}

impl Default for Wear {
    fn default() -> Self {
        Self {
            archard_k: None,
            archard_calibration: Some(PAPER_ARCHARD_CALIBRATION),
            archard_regime_change: None,
            archard_k_basis: VolumeBasis::TotalLoss,
            plasticity: Switch::Auto,
        }
    }
}

impl Wear {
    /// The wear law this section describes, in the scene's `test` with the disc's
    /// `hardness`: Archard's, of `archard_k` or else of the calibration point
    /// ([`PAPER_ARCHARD_CALIBRATION`] when neither is given), with the change of regime.
    pub fn law(&self, test: &TestConditions, hardness: &HardnessLaw) -> WearLaw {
        let k = match self.archard_k {
            Some(k) => ArchardK::Given(k),
            None => ArchardK::Measured(self.calibration_point(test, hardness)),
        };
        WearLaw::Archard(Archard::new(k, self.archard_regime_change))
    }

    /// The calibration point k is derived from when `archard_k` is not given, in the test
    /// it was measured in: the scene's `test`, with the point's own load, speed and track
    /// radius where it gives them; the hardness measured there, or `hardness`' at the
    /// point's cycle count.
    pub fn calibration_point(
        &self,
        test: &TestConditions,
        hardness: &HardnessLaw,
    ) -> MeasuredPoint {
        let point = self
            .archard_calibration
            .as_ref()
            .unwrap_or(&PAPER_ARCHARD_CALIBRATION);
        // A point that names a speed or a track radius was measured on a disc, whatever
        // rig the scene describes; one that names neither, on the scene's own rig.
        let on_disc = point.speed_rpm.is_some() || point.track_radius_mm.is_some();
        let test = TestConditions {
            load_n: point.load_n.unwrap_or(test.load_n),
            speed_rpm: point.speed_rpm.unwrap_or(test.speed_rpm),
            track_radius_mm: point.track_radius_mm.unwrap_or(test.track_radius_mm),
            reciprocating: test.reciprocating.clone().filter(|_| !on_disc),
            ..test.clone()
        };
        MeasuredPoint {
            time_s: point.time_s,
            wear_volume_mm3: point.wear_volume_mm3,
            load_n: test.load_n,
            speed_rpm: test.speed_rpm,
            track_radius_mm: test.track_radius_mm,
            measured_hardness_mpa: point.hardness_mpa,
            hardness_pa: match point.hardness_mpa {
                Some(mpa) => mpa * 1e6,
                None => hardness.hardness_pa(test.cycles_at(point.time_s)),
            },
            sliding_distance_m: test.sliding_speed_m_s() * point.time_s,
        }
    }
}

/// A measured wear volume after a rubbing time, from which k = V H / (F s) is derived.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArchardCalibration {
    /// Rubbing time, s.
    pub time_s: f64,
    /// Wear volume measured after `time_s`, mm^3.
    pub wear_volume_mm3: f64,
    /// Hardness measured at `time_s`, MPa; absent, the hardness law's value there.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hardness_mpa: Option<f64>,
    /// Load of the measured test, N; absent, the scene's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub load_n: Option<f64>,
    /// Rotation speed of the measured test, rpm; absent, the scene's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_rpm: Option<f64>,
    /// Wear track radius of the measured test, mm; absent, the scene's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub track_radius_mm: Option<f64>,
}

/// The typical 0.2% proof stress of annealed 316L, MPa: AK Steel's 316/316L product data
/// sheet (316/316L-S-08-01-07), 42 ksi. The paper's manufacturer measured its disc's by ASTM
/// A514 without printing the number (Section 2).
pub const ANNEALED_316L_PROOF_STRESS_MPA: f64 = 290.0;

/// How the pressure cap follows the disc's hardening ([`crate::hardness::YieldCap`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum YieldCapLaw {
    /// `Y = H(n) / yield_factor` from the first pass: the paper's eq. 12.
    Hardness,
    /// From `initial_yield_strength_mpa`, rising with the surface's plastic strain to
    /// `H(n) / yield_factor` at Tabor's representative strain.
    StrainHardening,
}

/// A model switch: decided by the simulation, forced on, or forced off.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Switch {
    /// The simulation decides.
    Auto,
    /// Always on.
    On,
    /// Always off.
    Off,
}

/// Discretisation and solver settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Numerics {
    /// Cells per side of the square grid.
    pub grid: GridSize,
    /// Side of the square domain.
    pub domain_um: DomainSize,
    /// Relative tolerance of the contact solver ([`Numerics::solve_tolerance`]).
    pub tolerance: Tolerance,
    /// Which cycles are solved.
    pub cycle_step: CycleStep,
    /// With `cycle_step: "auto"`, the largest relative (L1) change of the per-pass wear
    /// profile one step may span ([`Numerics::step_bound`]).
    pub cycle_step_bound: StepBound,
    /// The mu * delta-nu coupling of normal and tangential tractions (eq. 7).
    pub coupling: Switch,
    /// The cycles at which the state is recorded exactly: solved there, profile kept.
    pub record_cycles: RecordCycles,
    /// Threads of each contact solve's FFT passes.
    pub threads: SolverThreads,
}

impl Default for Numerics {
    fn default() -> Self {
        Self {
            grid: GridSize::Auto,
            domain_um: DomainSize::Auto,
            tolerance: Tolerance::Auto,
            cycle_step: CycleStep::Auto,
            cycle_step_bound: StepBound::Auto,
            coupling: Switch::Auto,
            record_cycles: RecordCycles::Auto,
            threads: SolverThreads::Auto,
        }
    }
}

impl Numerics {
    /// The domain side in m, or `None` when it is left to the simulation.
    pub fn domain_m(&self) -> Option<f64> {
        match self.domain_um {
            DomainSize::Auto => None,
            DomainSize::Micrometres(um) => Some(um * 1e-6),
        }
    }
}
