//! The scene: the user's description of one ball-on-disc test (the contract's "Scene").
//!
//! Field names carry the user's units (`radius_mm`, `load_n`, ...); every field is optional on
//! input and defaults to the paper's value. [`parse_scene`] resolves presets, fills defaults and
//! validates, reporting every problem at once as [`FieldError`]s. The numerical core reads the
//! scene through the SI accessors (`ball_radius_m`, `sliding_speed_m_s`, ...).

mod parse;
mod preset;
mod validate;

use std::f64::consts::PI;
use std::fmt;

use serde::de::{DeserializeOwned, Error as _};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::corrosion::CorrosionModel;
use crate::hardness::{self, HardnessError, HardnessLaw};

pub use parse::{parse_scene, parse_scene_str};
pub use preset::{DALMAU2018_316L, Preset, presets};

/// Archard coefficient when a scene gives neither `archard_k` nor `archard_calibration`:
/// Table 3's 300 s point, k = V H / (F s) with V = 1.18e-3 mm^3, H = 2854 MPa, F = 5 N and
/// s = 300 s x 18.8 mm/s.
pub const DEFAULT_ARCHARD_K: f64 = 1.19e-4;

/// One ball-on-disc test, as the user describes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Scene {
    /// Free-form label.
    pub name: String,
    /// The counter body (alumina in the paper).
    pub ball: Ball,
    /// The worn disc (AISI 316L in the paper).
    pub disc: Disc,
    /// Load, kinematics and length of the test.
    pub test: TestConditions,
    /// Wear law settings.
    pub wear: Wear,
    /// Electrochemistry; absent means no corrosion estimate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub corrosion: Option<Corrosion>,
    /// Discretisation and solver settings.
    pub numerics: Numerics,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            name: "untitled".to_owned(),
            ball: Ball::default(),
            disc: Disc::default(),
            test: TestConditions::default(),
            wear: Wear::default(),
            corrosion: None,
            numerics: Numerics::default(),
        }
    }
}

/// The ball.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Ball {
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
    /// Young's modulus, GPa. (The paper prints "205 MPa", a typo for GPa.)
    pub youngs_modulus_gpa: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Bulk hardness, MPa: H at n = 1, and H throughout when there is no table.
    pub hardness_mpa: f64,
    /// Measured `(cycle, hardness_mpa)` pairs for the work-hardening fit H = A + B ln n.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hardness_table: Option<Vec<(f64, f64)>>,
    /// Y = H / `yield_factor` (2.8 after Johnson).
    pub yield_factor: f64,
}

impl Default for Disc {
    fn default() -> Self {
        Self {
            youngs_modulus_gpa: 205.0,
            poisson_ratio: 0.28,
            hardness_mpa: 2473.0,
            hardness_table: None,
            yield_factor: 2.8,
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
        match &self.hardness_table {
            None => Ok(HardnessLaw::constant(self.hardness_mpa * 1e6)),
            Some(table) => {
                let table_pa: Vec<(f64, f64)> = table.iter().map(|&(n, h)| (n, h * 1e6)).collect();
                HardnessLaw::fit(self.hardness_mpa * 1e6, &table_pa)
            }
        }
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
}

impl Default for TestConditions {
    fn default() -> Self {
        Self {
            load_n: 5.0,
            track_radius_mm: 2.992,
            speed_rpm: 60.0,
            friction_coefficient: 0.45,
            cycles: 300,
        }
    }
}

/// Wear law settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Wear {
    /// Archard coefficient k. Missing on input means "not given" (so a calibration may be
    /// used instead); [`parse_scene`] fills in [`DEFAULT_ARCHARD_K`] when neither is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_k: Option<f64>,
    /// A measured point from which k is derived, in place of `archard_k`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub archard_calibration: Option<ArchardCalibration>,
    /// Elastic-perfectly-plastic pressure cap.
    pub plasticity: Switch,
}

impl Default for Wear {
    fn default() -> Self {
        Self {
            archard_k: Some(DEFAULT_ARCHARD_K),
            archard_calibration: None,
            plasticity: Switch::Auto,
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
}

/// The electrochemical cell (paper Section 5.1); units in the names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Corrosion {
    /// Free corrosion potential E_corr, V.
    pub corrosion_potential_v: f64,
    /// Cathodic Tafel constant a_c, V (fitted with current densities in A/cm^2).
    pub tafel_a_c_v: f64,
    /// Cathodic Tafel slope b_c, V per decade.
    pub tafel_b_c_v_per_decade: f64,
    /// Anodic current density on depassivated metal, A/cm^2.
    pub anodic_current_density_a_cm2: f64,
    /// Electrode area exposed to the electrolyte, cm^2.
    pub exposed_area_cm2: f64,
    /// Which area depassivates.
    pub anodic_area: AnodicArea,
    /// Multiplier on the chosen anodic area.
    pub anodic_area_factor: f64,
    /// Molar mass of the dissolving metal, g/mol.
    pub molar_mass_g_mol: f64,
    /// Charge number of the dissolution reaction.
    pub valence: f64,
    /// Density of the metal, g/cm^3.
    pub density_g_cm3: f64,
}

impl Default for Corrosion {
    fn default() -> Self {
        Self {
            corrosion_potential_v: -0.10,
            tafel_a_c_v: -3.31,
            tafel_b_c_v_per_decade: 0.56,
            anodic_current_density_a_cm2: 0.01,
            exposed_area_cm2: 2.56,
            anodic_area: AnodicArea::WearTrack,
            anodic_area_factor: 1.0,
            molar_mass_g_mol: 55.85,
            valence: 2.0,
            density_g_cm3: 7.9,
        }
    }
}

impl Corrosion {
    /// The cell in SI units.
    pub fn model(&self) -> CorrosionModel {
        CorrosionModel {
            corrosion_potential_v: self.corrosion_potential_v,
            tafel_a_c_v: self.tafel_a_c_v,
            tafel_b_c_v_per_decade: self.tafel_b_c_v_per_decade,
            anodic_current_density_a_m2: self.anodic_current_density_a_cm2 * 1e4,
            exposed_area_m2: self.exposed_area_cm2 * 1e-4,
            molar_mass_kg_mol: self.molar_mass_g_mol * 1e-3,
            valence: self.valence,
            density_kg_m3: self.density_g_cm3 * 1e3,
        }
    }
}

/// Which area depassivates and carries the anodic current.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AnodicArea {
    /// Track width times track length.
    WearTrack,
    /// Real contact area of the asperities, F / H.
    RealContact,
    /// The contact area of the boundary-element solution.
    BemContact,
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
    /// Relative tolerance of the contact solver.
    pub tolerance: f64,
    /// Which cycles are solved.
    pub cycle_step: CycleStep,
    /// With `cycle_step: "auto"`, the largest relative (L1) change of the per-pass wear
    /// profile one step may span.
    pub cycle_step_bound: f64,
    /// The mu * delta-nu coupling of normal and tangential tractions (eq. 7).
    pub coupling: Switch,
}

impl Default for Numerics {
    fn default() -> Self {
        Self {
            grid: GridSize::Auto,
            domain_um: DomainSize::Auto,
            tolerance: 1e-8,
            cycle_step: CycleStep::Auto,
            cycle_step_bound: crate::simulation::STEP_CHANGE_BOUND,
            coupling: Switch::Auto,
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

/// Cells per side: `"auto"` or a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(from = "AutoOr<usize>", into = "AutoOr<usize>")]
pub enum GridSize {
    /// Sized to the contact by the simulation.
    Auto,
    /// This many cells per side.
    Cells(usize),
}

/// Domain side: `"auto"` or a number of micrometres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "AutoOr<f64>", into = "AutoOr<f64>")]
pub enum DomainSize {
    /// Sized to the contact by the simulation.
    Auto,
    /// This many micrometres per side.
    Micrometres(f64),
}

/// Which cycles are solved: `1` (every one) or `"auto"`.
///
/// Fixed strides n > 1 are rejected rather than supported: the contract names only 1 and
/// `"auto"`, and a stride would silently skip the fast plastic cycles at the start of a run,
/// which `"auto"` resolves under an error bound.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "AutoOr<u64>", into = "AutoOr<u64>")]
pub enum CycleStep {
    /// Steps chosen by the simulation under an error bound.
    Auto,
    /// Every cycle solved (JSON `1`).
    EveryCycle,
}

/// The JSON shape shared by the `"auto"`-or-number settings.
#[derive(Debug, Clone, Copy)]
enum AutoOr<T> {
    Auto,
    Value(T),
}

impl<T: Serialize> Serialize for AutoOr<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Auto => serializer.serialize_str("auto"),
            Self::Value(value) => value.serialize(serializer),
        }
    }
}

impl<'de, T: DeserializeOwned> Deserialize<'de> for AutoOr<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        // Buffering through a Value lets one message cover both accepted shapes instead of
        // serde's "did not match any variant".
        let value = serde_json::Value::deserialize(deserializer)?;
        if value.as_str() == Some("auto") {
            return Ok(Self::Auto);
        }
        T::deserialize(&value)
            .map(Self::Value)
            .map_err(|e| D::Error::custom(format!("expected \"auto\" or a number ({e})")))
    }
}

impl From<AutoOr<usize>> for GridSize {
    fn from(value: AutoOr<usize>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(cells) => Self::Cells(cells),
        }
    }
}

impl From<GridSize> for AutoOr<usize> {
    fn from(value: GridSize) -> Self {
        match value {
            GridSize::Auto => Self::Auto,
            GridSize::Cells(cells) => Self::Value(cells),
        }
    }
}

impl From<AutoOr<f64>> for DomainSize {
    fn from(value: AutoOr<f64>) -> Self {
        match value {
            AutoOr::Auto => Self::Auto,
            AutoOr::Value(um) => Self::Micrometres(um),
        }
    }
}

impl From<DomainSize> for AutoOr<f64> {
    fn from(value: DomainSize) -> Self {
        match value {
            DomainSize::Auto => Self::Auto,
            DomainSize::Micrometres(um) => Self::Value(um),
        }
    }
}

impl TryFrom<AutoOr<u64>> for CycleStep {
    type Error = String;

    fn try_from(value: AutoOr<u64>) -> Result<Self, Self::Error> {
        match value {
            AutoOr::Auto => Ok(Self::Auto),
            AutoOr::Value(1) => Ok(Self::EveryCycle),
            AutoOr::Value(n) => Err(format!(
                "must be 1 (every cycle solved) or \"auto\" (steps chosen under an error \
                 bound); fixed strides are not supported, got {n}"
            )),
        }
    }
}

impl From<CycleStep> for AutoOr<u64> {
    fn from(value: CycleStep) -> Self {
        match value {
            CycleStep::Auto => Self::Auto,
            CycleStep::EveryCycle => Self::Value(1),
        }
    }
}

impl Scene {
    /// Ball radius, m.
    pub fn ball_radius_m(&self) -> f64 {
        self.ball.radius_mm * 1e-3
    }

    /// Normal load, N.
    pub fn load_n(&self) -> f64 {
        self.test.load_n
    }

    /// Wear track radius R_c, m.
    pub fn track_radius_m(&self) -> f64 {
        self.test.track_radius_mm * 1e-3
    }

    /// Track length 2 pi R_c, m: the sliding distance of one cycle.
    pub fn track_length_m(&self) -> f64 {
        2.0 * PI * self.track_radius_m()
    }

    /// Sliding speed 2 pi R_c rpm / 60, m/s (18.8 mm/s in the paper).
    pub fn sliding_speed_m_s(&self) -> f64 {
        self.track_length_m() * self.test.speed_rpm / 60.0
    }

    /// Duration of one cycle, 60 / rpm, s.
    pub fn cycle_period_s(&self) -> f64 {
        60.0 / self.test.speed_rpm
    }

    /// Cycles completed after `time_s` of rubbing (fractional).
    pub fn cycles_at(&self, time_s: f64) -> f64 {
        time_s * self.test.speed_rpm / 60.0
    }

    /// The disc's hardness law (Pa against cycle count).
    pub fn hardness_law(&self) -> Result<HardnessLaw, HardnessError> {
        self.disc.hardness_law()
    }

    /// The Archard coefficient: `wear.archard_k` if given; else derived from
    /// `wear.archard_calibration` by eq. 1 with the hardness law at the calibration's cycle
    /// count; else [`DEFAULT_ARCHARD_K`].
    pub fn archard_k(&self) -> Result<f64, HardnessError> {
        match (self.wear.archard_k, &self.wear.archard_calibration) {
            (Some(k), _) => Ok(k),
            (None, Some(calibration)) => {
                let hardness_pa = self
                    .hardness_law()?
                    .hardness_pa(self.cycles_at(calibration.time_s));
                Ok(hardness::archard_k_from_measurement(
                    calibration.wear_volume_mm3 * 1e-9,
                    hardness_pa,
                    self.load_n(),
                    self.sliding_speed_m_s() * calibration.time_s,
                ))
            }
            (None, None) => Ok(DEFAULT_ARCHARD_K),
        }
    }

    /// Checks every range and consistency rule, returning all problems at once.
    pub fn validate(&self) -> Result<(), SceneErrors> {
        let errors = validate::check(self);
        if errors.is_empty() {
            Ok(())
        } else {
            Err(SceneErrors(errors))
        }
    }
}

/// One problem in a scene, located by a dotted path such as `test.load_n` or
/// `disc.hardness_table[2][0]` (empty for the document as a whole).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct FieldError {
    /// Where the problem is.
    pub path: String,
    /// What is wrong, with the allowed range.
    pub message: String,
}

impl FieldError {
    /// A problem at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{}: {}", self.path, self.message)
        }
    }
}

/// Every problem found in a scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct SceneErrors(pub Vec<FieldError>);

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0.as_slice() {
            [single] => write!(f, "invalid scene: {single}"),
            errors => {
                write!(f, "invalid scene, {} problems:", errors.len())?;
                for error in errors {
                    write!(f, "\n  {error}")?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for SceneErrors {}

#[cfg(test)]
mod tests {
    use super::*;

    fn relative_error(got: f64, want: f64) -> f64 {
        ((got - want) / want).abs()
    }

    #[test]
    fn si_accessors_of_the_paper_scene() {
        let scene = Scene::default();
        // The paper prints 18.8 mm/s for 60 rpm on the 2.992 mm track: half a unit in the last
        // printed digit is 0.05 mm/s.
        assert!((scene.sliding_speed_m_s() - 18.8e-3).abs() < 0.05e-3);
        // 60 / 60 rpm and unit conversions: exact or one rounding (1e-15 relative).
        assert!(relative_error(scene.cycle_period_s(), 1.0) < 1e-15);
        assert!(relative_error(scene.cycles_at(300.0), 300.0) < 1e-15);
        assert!(relative_error(scene.ball_radius_m(), 3e-3) < 1e-15);
        assert!(relative_error(scene.track_radius_m(), 2.992e-3) < 1e-15);
        assert!(relative_error(scene.load_n(), 5.0) < 1e-15);
        assert!(relative_error(scene.ball.youngs_modulus_pa(), 300e9) < 1e-15);
        assert!(relative_error(scene.disc.youngs_modulus_pa(), 205e9) < 1e-15);
        assert_eq!(scene.numerics.domain_m(), None);
        let numerics = Numerics {
            domain_um: DomainSize::Micrometres(256.0),
            ..Numerics::default()
        };
        let side = numerics.domain_m().expect("a fixed domain");
        assert!(relative_error(side, 256e-6) < 1e-15);
    }

    #[test]
    fn corrosion_model_is_in_si_units() {
        let model = Corrosion::default().model();
        // Each is one multiplication by a power of ten: one rounding (1e-15 relative).
        assert!(relative_error(model.anodic_current_density_a_m2, 100.0) < 1e-15);
        assert!(relative_error(model.exposed_area_m2, 2.56e-4) < 1e-15);
        assert!(relative_error(model.molar_mass_kg_mol, 55.85e-3) < 1e-15);
        assert!(relative_error(model.density_kg_m3, 7900.0) < 1e-15);
    }

    #[test]
    fn hardness_law_follows_the_table_or_stays_constant() {
        let constant = Scene::default().hardness_law().expect("no table");
        assert_eq!(constant, HardnessLaw::constant(2473e6));
        let preset = presets().remove(0).scene;
        let law = preset.hardness_law().expect("paper table fits");
        // Fit of Table 3 (see hardness tests): H(300) = 2454.99 + 63.383 ln 300 = 2816.5 MPa,
        // 37.5 MPa below the measured 2854; 1e-4 relative covers the 5 digits carried.
        assert!(relative_error(law.hardness_pa(300.0), 2816.5e6) < 1e-4);
        assert!(relative_error(preset.archard_k().expect("k given"), 1.19e-4) < 1e-15);
    }
}
