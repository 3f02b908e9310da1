//! The result of a run: the contract's "Result" JSON. Names carry units; values are in
//! those units (the core works in SI and converts here).

use serde::{Deserialize, Serialize};

use crate::scene::Scene;

/// A whole run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulationResult {
    /// The scene as run, every default filled in.
    pub scene: Scene,
    /// Which physical and numerical models the run used, and why.
    pub models: Vec<ModelChoice>,
    /// One record per solved cycle.
    pub cycles: Vec<CycleRecord>,
    /// Depth profiles across the track at chosen cycles.
    pub profiles: Vec<Profile>,
    /// Pressure maps at the first and the last solved cycle.
    pub pressure_maps: Vec<PressureMap>,
    /// Totals.
    pub summary: Summary,
}

/// One model switched on or off, with the reason in words and numbers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelChoice {
    /// `plasticity`, `coupling`, `grid`, `cycle_step`, ...
    pub name: String,
    /// Whether the run uses it.
    pub active: bool,
    /// Why, e.g. `"p0 1221 MPa > Y 883 MPa"`.
    pub reason: String,
}

/// The state after one solved cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CycleRecord {
    /// Cycle number, from 1.
    pub cycle: u64,
    /// Time at the end of the cycle, s.
    pub time_s: f64,
    /// Wear track volume so far, mm^3.
    pub wear_volume_mm3: f64,
    /// Deepest point of the groove, um.
    pub max_depth_um: f64,
    /// Largest contact pressure, MPa.
    pub max_pressure_mpa: f64,
    /// Area in contact, mm^2.
    pub contact_area_mm2: f64,
    /// Area at the yield pressure, mm^2.
    pub plastic_area_mm2: f64,
    /// Disc hardness at this cycle, MPa.
    pub hardness_mpa: f64,
    /// Rigid-body approach, um.
    pub approach_um: f64,
    /// Solver iterations for this cycle.
    pub iterations: usize,
    /// Potential during rubbing (eq. 18), V; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential_v: Option<f64>,
    /// Anodic (depassivated) area, mm^2; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anodic_area_mm2: Option<f64>,
    /// Wear-accelerated corrosion volume so far, mm^3; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wac_volume_mm3: Option<f64>,
}

/// The groove depth across the track (y) at one cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Profile {
    /// Cycle number.
    pub cycle: u64,
    /// Positions across the track, um.
    pub y_um: Vec<f64>,
    /// Depth below the original surface, um (positive into the disc).
    pub depth_um: Vec<f64>,
}

/// The contact pressure over the grid at one cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PressureMap {
    /// Cycle number.
    pub cycle: u64,
    /// Cell centres along the sliding direction, um.
    pub x_um: Vec<f64>,
    /// Cell centres across the track, um.
    pub y_um: Vec<f64>,
    /// Pressure, MPa, indexed `[iy][ix]`.
    pub pressure_mpa: Vec<Vec<f64>>,
}

/// Totals of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Cycles simulated.
    pub cycles: u64,
    /// Final wear track volume, mm^3.
    pub wear_volume_mm3: f64,
    /// Final deepest point, um.
    pub max_depth_um: f64,
    /// Final wear-accelerated corrosion volume, mm^3; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wac_volume_mm3: Option<f64>,
    /// Wall-clock time of the run, s.
    pub wall_s: f64,
    /// Contact solves performed.
    pub solves: usize,
    /// Solver iterations over all solves.
    pub iterations: usize,
}
