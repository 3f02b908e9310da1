//! The result of a run, as JSON: `docs/result.md` describes every field. Names carry units;
//! values are in those units (the core works in SI and converts here).

use serde::{Deserialize, Serialize};

use crate::contact::{Grid, Window};
use crate::corrosion::ReferenceElectrode;
use crate::scene::{FieldWarning, Scene};
use crate::surface::Statistics;
use crate::wear::{Groove, WearLaw, WearSummary};

use super::provenance::Provenance;
use super::stroke_report::StrokeReport;

/// A whole run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulationResult {
    /// Whether the run went to its last cycle. Only the service's result of a failed or
    /// cancelled job is incomplete: it holds the cycles solved before the stop.
    pub complete: bool,
    /// The scene as run, every default filled in.
    pub scene: Scene,
    /// The disc's initial roughness; absent for a smooth disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<SurfaceReport>,
    /// Which physical and numerical models the run used, and why.
    pub models: Vec<ModelChoice>,
    /// What in the scene looks wrong without being invalid (e.g. a hardness point far off
    /// its fitted law); absent when there is nothing to say.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Each of `warnings` with the dotted path in the scene of the field it is about
    /// (`test.load_n`), so a page can show it beside the field; absent when there is
    /// nothing to say.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub field_warnings: Vec<FieldWarning>,
    /// One record per solved cycle.
    pub cycles: Vec<CycleRecord>,
    /// Depth profiles across the track at chosen cycles.
    pub profiles: Vec<Profile>,
    /// Pressure maps at the first and the last solved cycle.
    pub pressure_maps: Vec<PressureMap>,
    /// The potential as the lab's potentiostat records it at open circuit: before, during
    /// and after the rubbing (Fig. 6); empty without corrosion.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub ocp_trace: Vec<OcpSample>,
    /// The reciprocating rig's wear map, axial profile and traces over a cycle; absent on
    /// the rotating disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stroke: Option<StrokeReport>,
    /// Totals.
    pub summary: Summary,
    /// Which build ran the scene, where and when, and the scene's SHA-256; absent from
    /// results written before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub provenance: Option<Provenance>,
}

/// One point of the open-circuit potential trace.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OcpSample {
    /// Time since the recording started (`test.ocp_before_s` before the rubbing), s.
    pub time_s: f64,
    /// The potential, V against `summary.potential_reference`.
    pub potential_v: f64,
    /// Which part of the test.
    pub phase: OcpPhase,
}

/// The parts of an open-circuit potential record, named in the JSON as `before`, `rubbing`
/// and `after`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OcpPhase {
    /// At open circuit before the ball moves.
    Before,
    /// While the ball slides.
    Rubbing,
    /// After the ball stops, while the bare metal repassivates.
    After,
}

/// One model switched on or off, with the reason in words and numbers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelChoice {
    /// Which model or numerical choice.
    pub name: Model,
    /// Whether the run uses it.
    pub active: bool,
    /// Why, e.g. `"p0 1221 MPa > Y 883 MPa"`.
    pub reason: String,
}

/// The physical models and numerical choices a run reports on, named in the JSON as
/// `plasticity`, `coupling`, `grid`, ...
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Model {
    /// The elastic-perfectly-plastic pressure cap (eq. 12).
    Plasticity,
    /// The friction coupling of normal and tangential tractions (eq. 7).
    Coupling,
    /// The first grid and domain.
    Grid,
    /// The hardness law (Fig. 9).
    WorkHardening,
    /// A growth of the auto domain during the run (one entry per growth).
    DomainGrowth,
    /// Cycle stepping: one solve standing for several cycles.
    CycleStep,
    /// Solving on a window around the contact.
    SolveWindow,
    /// Archard wear (eqs. 14-16).
    Archard,
    /// Wear-accelerated corrosion (eq. 18 and Faraday).
    Corrosion,
    /// What Faraday's law dissolves: its equivalent weight and density.
    Faraday,
    /// The disc's initial roughness and how the grid resolves it.
    Surface,
    /// The library's materials the scene names, and the values it gave instead.
    Materials,
    /// The reciprocating rig: the positions solved along the stroke.
    Reciprocating,
    /// The floating-point precision the contact's transforms compute in.
    Precision,
}

impl Model {
    /// The model of the wear law `law`.
    pub fn of_law(law: &WearLaw) -> Self {
        match law {
            WearLaw::Archard(_) => Self::Archard,
        }
    }
}

/// The state after one solved cycle (its default: cycle 0, nothing worn, no corrosion).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CycleRecord {
    /// Cycle number, from 1.
    pub cycle: u64,
    /// Time at the end of the cycle, s.
    pub time_s: f64,
    /// The volume lost so far, what a profilometer measures, mm^3: always the same as
    /// `total_volume_mm3`, whatever loss k was fitted on (`wear.archard_k_basis`).
    pub wear_volume_mm3: f64,
    /// Deepest point of the groove, um.
    pub max_depth_um: f64,
    /// Deepest point of the disc's surface under the ball, um: the groove's depth plus the
    /// disc's share of the elastic displacement (0 in results written before it was
    /// computed).
    #[serde(default)]
    pub loaded_max_depth_um: f64,
    /// Largest contact pressure, MPa.
    pub max_pressure_mpa: f64,
    /// Area in contact (cells with p > 0), mm^2: on a rough disc the real contact area at
    /// the asperity scale, resolved down to the cell.
    pub contact_area_mm2: f64,
    /// Contact islands: 4-connected groups of cells in contact (1 for a smooth contact; 0
    /// in results written before it was counted).
    #[serde(default)]
    pub contact_islands: usize,
    /// Area at the yield pressure, mm^2.
    pub plastic_area_mm2: f64,
    /// Disc hardness at this cycle, MPa.
    pub hardness_mpa: f64,
    /// The pressure cap Y of this cycle (eq. 12, `disc.yield_cap`), MPa; absent without
    /// plasticity (and in results written before it was recorded).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_pressure_mpa: Option<f64>,
    /// Rigid-body approach, um.
    pub approach_um: f64,
    /// Solver iterations for this cycle.
    pub iterations: usize,
    /// Potential during rubbing (eq. 18), V against the scene's
    /// `corrosion.reference_electrode` (the paper's Ag/AgCl by default); absent without
    /// `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential_v: Option<f64>,
    /// Anodic (depassivated) area, mm^2; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anodic_area_mm2: Option<f64>,
    /// The solved contact's mean chord along the sliding direction (its area over the width
    /// its chords sweep), um: the L of the depassivated wake; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_chord_um: Option<f64>,
    /// The anodic current i_a A_a, mA; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anodic_current_ma: Option<f64>,
    /// The anodic charge passed so far, C; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub charge_c: Option<f64>,
    /// Wear-accelerated corrosion volume so far, mm^3; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wac_volume_mm3: Option<f64>,
    /// The mechanical and the corrosion volume together, what a profilometer measures,
    /// mm^3: the groove when k was fitted on total losses (`wear.archard_k_basis`
    /// `total_loss`), the groove plus `wac_volume_mm3` when on the mechanical loss; the
    /// groove without `corrosion`. Absent only in results written before every run had it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_volume_mm3: Option<f64>,
    /// The mechanical loss, `total_volume_mm3 - wac_volume_mm3` (never below 0), mm^3; the
    /// groove without `corrosion`. Absent only in results written before every run had it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mechanical_volume_mm3: Option<f64>,
}

/// The statistics of a rough disc's surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceReport {
    /// The surface as the contact sees it, on the first grid's cells.
    pub on_grid: Statistics,
    /// A measured map's own statistics before it was sampled onto the grid (after tilt
    /// removal when asked); absent for a synthetic surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<Statistics>,
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
    /// Depth of the disc's surface under the ball, um: `depth_um` plus the disc's share of
    /// the elastic displacement, the deepest along each row (empty in results written
    /// before it was computed).
    #[serde(default)]
    pub loaded_depth_um: Vec<f64>,
}

impl Profile {
    /// The depth of `groove` on `grid` at `cycle`, and the loaded depth `loaded_m` (m, per
    /// row).
    pub fn of(cycle: u64, grid: &Grid, groove: &Groove, loaded_m: &[f64]) -> Self {
        Self {
            cycle,
            y_um: (0..grid.ny).map(|iy| grid.y(iy) * 1e6).collect(),
            depth_um: groove.depth_m().iter().map(|d| d * 1e6).collect(),
            loaded_depth_um: loaded_m.iter().map(|d| d * 1e6).collect(),
        }
    }
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

impl PressureMap {
    /// `pressure` (Pa, on `grid`) over the contact's bounding box plus two cells, in MPa;
    /// empty when no cell is loaded.
    pub fn of(cycle: u64, grid: &Grid, pressure: &[f64]) -> Self {
        let Some(shown) = Window::loaded(grid, pressure).map(|w| w.padded(2, grid)) else {
            return Self {
                cycle,
                x_um: Vec::new(),
                y_um: Vec::new(),
                pressure_mpa: Vec::new(),
            };
        };
        let row = |iy: usize| {
            shown
                .columns()
                .map(|ix| pressure[iy * grid.nx + ix] / 1e6)
                .collect()
        };
        Self {
            cycle,
            x_um: shown.columns().map(|ix| grid.x(ix) * 1e6).collect(),
            y_um: shown.rows().map(|iy| grid.y(iy) * 1e6).collect(),
            pressure_mpa: shown.rows().map(row).collect(),
        }
    }
}

/// Totals of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Cycles simulated.
    pub cycles: u64,
    /// Final volume lost, what a profilometer measures, mm^3: the same as
    /// `total_volume_mm3`.
    pub wear_volume_mm3: f64,
    /// Final deepest point, um.
    pub max_depth_um: f64,
    /// Final wear-accelerated corrosion volume, mm^3; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wac_volume_mm3: Option<f64>,
    /// Final total volume, mechanical plus corrosion, mm^3 (as the cycle record's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_volume_mm3: Option<f64>,
    /// Final mechanical volume, the total less the corrosion, mm^3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mechanical_volume_mm3: Option<f64>,
    /// The anodic charge passed during the rubbing, C; absent without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub charge_c: Option<f64>,
    /// Potential during rubbing at the last cycle, V against `potential_reference`; absent
    /// without `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential_v: Option<f64>,
    /// The reference electrode of every potential of the result; absent without
    /// `corrosion`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub potential_reference: Option<ReferenceElectrode>,
    /// The wear law's fields (`archard_k`, `archard_regime_change`).
    #[serde(flatten)]
    pub wear: WearSummary,
    /// The run's warnings, each as its field's path and its first clause (the result's
    /// `field_warnings` hold them whole), so that a study's table can flag a member whose
    /// numbers come with a caveat (a potential capped at E_corr, for one); absent when the
    /// run warned of nothing.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Wall-clock time of the run, s.
    pub wall_s: f64,
    /// Contact solves performed.
    pub solves: usize,
    /// Solver iterations over all solves.
    pub iterations: usize,
}

impl Summary {
    /// The summary with the run's `warnings` as [`Summary::warnings`] holds them.
    #[must_use]
    pub fn with_warnings(mut self, warnings: &[FieldWarning]) -> Self {
        self.warnings = warnings.iter().map(FieldWarning::headline).collect();
        self
    }
}

/// The end-of-run summary a person reads: one quantity per line, with units.
impl std::fmt::Display for Summary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{} cycles in {:.1} s ({} solves, {} solver iterations)",
            self.cycles, self.wall_s, self.solves, self.iterations
        )?;
        writeln!(
            f,
            "  wear volume      {:.4e} mm^3 (the total a profilometer measures)",
            self.wear_volume_mm3
        )?;
        // The wear volume is the total: its two parts follow it, not the total again.
        if let Some(mechanical) = self.mechanical_volume_mm3 {
            writeln!(f, "    of which mechanical {mechanical:.4e} mm^3")?;
        }
        if let Some(wac) = self.wac_volume_mm3 {
            writeln!(f, "    of which WAC        {wac:.4e} mm^3")?;
        }
        writeln!(f, "  maximum depth    {:.3} um", self.max_depth_um)?;
        if let Some(charge) = self.charge_c {
            writeln!(f, "  anodic charge    {charge:.4e} C")?;
        }
        if let Some(potential) = self.potential_v {
            let reference = self
                .potential_reference
                .unwrap_or(ReferenceElectrode::AgAgCl3MKcl);
            writeln!(
                f,
                "  final potential  {potential:.4} V vs {}",
                reference.label()
            )?;
        }
        write!(f, "{}", self.wear)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_reads_with_units_and_the_reference_electrode() {
        let summary = Summary {
            cycles: 3600,
            wear_volume_mm3: 1.2e-2,
            max_depth_um: 12.5,
            wac_volume_mm3: Some(3.4e-4),
            total_volume_mm3: Some(1.2e-2),
            mechanical_volume_mm3: Some(1.166e-2),
            charge_c: Some(2.9e-2),
            potential_v: Some(-0.5432),
            potential_reference: Some(ReferenceElectrode::AgAgCl3MKcl),
            wear: WearSummary {
                archard_k: 1.0228e-4,
                archard_regime_change: None,
            },
            warnings: Vec::new(),
            wall_s: 6.31,
            solves: 326,
            iterations: 3400,
        };
        let text = summary.to_string();
        assert!(
            text.starts_with("3600 cycles in 6.3 s (326 solves"),
            "{text}"
        );
        assert!(text.contains("wear volume      1.2000e-2 mm^3"), "{text}");
        assert!(text.contains("-0.5432 V vs Ag/AgCl (3 M KCl)"), "{text}");
        assert!(!text.contains("total volume"), "{text}");
        assert!(
            text.contains("of which mechanical 1.1660e-2 mm^3"),
            "{text}"
        );
        let sce = Summary {
            potential_reference: Some(ReferenceElectrode::Sce),
            ..summary
        };
        assert!(sce.to_string().contains("V vs SCE"));
        let dry = Summary {
            wac_volume_mm3: None,
            total_volume_mm3: None,
            mechanical_volume_mm3: None,
            charge_c: None,
            potential_v: None,
            potential_reference: None,
            ..sce
        };
        assert!(!dry.to_string().contains("Ag/AgCl"));
    }

    #[test]
    fn models_are_named_in_the_json_as_before() {
        let names = [
            (Model::Plasticity, "plasticity"),
            (Model::Coupling, "coupling"),
            (Model::Grid, "grid"),
            (Model::WorkHardening, "work_hardening"),
            (Model::DomainGrowth, "domain_growth"),
            (Model::CycleStep, "cycle_step"),
            (Model::SolveWindow, "solve_window"),
            (Model::Archard, "archard"),
            (Model::Corrosion, "corrosion"),
            (Model::Faraday, "faraday"),
            (Model::Surface, "surface"),
            (Model::Materials, "materials"),
            (Model::Reciprocating, "reciprocating"),
            (Model::Precision, "precision"),
        ];
        for (model, name) in names {
            let json = serde_json::to_value(model).expect("serialises");
            assert_eq!(json, serde_json::json!(name));
            assert_eq!(
                serde_json::from_value::<Model>(json).expect("parses"),
                model
            );
        }
    }
}
