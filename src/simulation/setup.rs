//! From a checked scene to the numerical problem: the grid and domain, the disc's initial
//! roughness on it, the solver's settings, and the decisions of what to model, each recorded
//! with its reason.

use std::num::NonZeroUsize;

use crate::contact::{
    ContactSolver, CoupledSolver, DcFft, ElasticPair, Grid, Hertz, Kernel, NormalSolver,
    SINGLE_PRECISION_HEADROOM, SINGLE_PRECISION_MIN_TOLERANCE, SINGLE_PRECISION_ROUNDOFF,
    SolverOptions, split_threads,
};
use crate::hardness::TABOR_REPRESENTATIVE_STRAIN;
use crate::scene::{FieldWarning, Scene, SolverThreads, Switch};
use crate::surface::HeightMap;
use crate::wear::Groove;

use super::hardening::work_hardening_report;
use super::plan::Plan;
use super::result::{CycleRecord, Summary, SurfaceReport};
use super::roughness::{DiscSurface, build, wanted_cell_m};
use super::sizing::{GridPlan, LowestYield, cells_per_contact_radius, plan_grid};
use super::{Model, ModelChoice, SimulationError};

/// The coupling term changes the pressures by at least 1.2 |mu delta-nu| relative to p0
/// (measured on the paper's Hertz case: 1.21 to 1.26 at N = 64, 1.74 to 1.81 at N = 128, for
/// mu from 0.01 to 1). Below `tolerance / COUPLING_SENSITIVITY` it cannot matter.
pub const COUPLING_SENSITIVITY: f64 = 1.2;

/// What a run takes beside its plan.
#[derive(Debug, Clone, Copy)]
pub struct RunOptions<'a> {
    /// The height map of a scene whose `disc.surface` is measured.
    pub surface: Option<&'a HeightMap>,
    /// Runs solving at the same time as this one, among which its automatic thread counts
    /// (`numerics.threads: "auto"`) share the cores; the results do not depend on it.
    pub concurrent_runs: NonZeroUsize,
}

impl Default for RunOptions<'_> {
    /// No measured surface; the only run of the process.
    fn default() -> Self {
        Self {
            surface: None,
            concurrent_runs: NonZeroUsize::MIN,
        }
    }
}

/// A checked scene turned into numbers (SI) and modelling decisions.
#[derive(Debug, Clone)]
pub struct Setup {
    /// The checked scene and what the check derived from it: the elastic pair, the
    /// hardness law, Hertz's contact, the wear law.
    pub plan: Plan,
    /// The first cycle's grid.
    pub grid: Grid,
    /// Whether pressures are capped at Y (eq. 12).
    pub plasticity: bool,
    /// Whether the friction coupling term is modelled (eq. 7).
    pub coupling: bool,
    /// Whether the contact's transforms compute in f32 (the tolerance leaves room for its
    /// round-off, [`SINGLE_PRECISION_MIN_TOLERANCE`]).
    pub single_precision: bool,
    /// Contact solver settings.
    pub options: SolverOptions,
    /// The decisions, for the result's `models`.
    pub models: Vec<ModelChoice>,
    /// What in the scene looks wrong without being invalid, each with its field's path: the
    /// plan's, then the hardness points far off their law; for the result's `warnings`.
    pub warnings: Vec<FieldWarning>,
    /// The disc's initial roughness on the first grid; `None` for a smooth disc.
    pub surface: Option<DiscSurface>,
}

fn choice(name: Model, active: bool, reason: String) -> ModelChoice {
    ModelChoice {
        name,
        active,
        reason,
    }
}

/// Resolves an on/off/auto switch (auto: `needed`) and records it with its reason.
fn decide(
    models: &mut Vec<ModelChoice>,
    name: Model,
    switch: Switch,
    needed: bool,
    reason: String,
) -> bool {
    let (active, reason) = match switch {
        Switch::On => (true, format!("on by request; {reason}")),
        Switch::Off => (false, format!("off by request; {reason}")),
        Switch::Auto => (needed, reason),
    };
    models.push(choice(name, active, reason));
    active
}

impl Setup {
    /// What a result reports of the disc's initial roughness; `None` for a smooth disc.
    pub fn surface_report(&self) -> Option<SurfaceReport> {
        self.surface.as_ref().map(|s| SurfaceReport {
            on_grid: s.statistics.clone(),
            measured: s.source.clone(),
        })
    }

    /// The totals of a run that recorded `cycles` (one record per solve) in `wall_s`: the
    /// state at the last record, so a run stopped early sums up what it did like a full one.
    pub fn summary(&self, cycles: &[CycleRecord], wall_s: f64) -> Summary {
        let last = cycles.last();
        Summary {
            cycles: last.map_or(0, |c| c.cycle),
            wear_volume_mm3: last.map_or(0.0, |c| c.wear_volume_mm3),
            max_depth_um: last.map_or(0.0, |c| c.max_depth_um),
            wac_volume_mm3: last.and_then(|c| c.wac_volume_mm3),
            total_volume_mm3: last.and_then(|c| c.total_volume_mm3),
            mechanical_volume_mm3: last.and_then(|c| c.mechanical_volume_mm3),
            charge_c: last.and_then(|c| c.charge_c),
            potential_v: last.and_then(|c| c.potential_v),
            potential_reference: self
                .scene()
                .corrosion
                .as_ref()
                .map(|c| c.reference_electrode),
            wear: self.plan.wear().summary(),
            warnings: Vec::new(),
            wall_s,
            solves: cycles.len(),
            iterations: cycles.iter().map(|c| c.iterations).sum(),
        }
    }

    /// Makes every decision for `plan`, with the measured surface and the cores' share of
    /// `options`.
    pub fn new(plan: &Plan, options: &RunOptions) -> Result<Self, SimulationError> {
        let scene = plan.scene();
        let solver = SolverOptions {
            tolerance: scene.numerics.solve_tolerance(scene.numerics_case()),
            concurrent_runs: options.concurrent_runs,
            ..SolverOptions::default()
        };
        let mut models = Vec::new();
        let plasticity = decide_plasticity(&mut models, scene, plan.hertz(), plan.lowest_yield());
        let coupling = decide_coupling(&mut models, scene, plan.pair(), &solver);
        let single_precision = decide_precision(&mut models, &solver);
        let radius = plan.sizing_radius_m();
        let spec = scene.disc.surface.as_ref();
        let surface_cell = spec.and_then(|s| wanted_cell_m(s, options.surface));
        let density = cells_per_contact_radius(scene);
        let grid_plan = plan_grid(&scene.numerics, (radius, density), surface_cell);
        let grid =
            Grid::square(grid_plan.cells, grid_plan.domain_m).map_err(SimulationError::Setup)?;
        models.push(grid_choice(&grid, &grid_plan, radius));
        let mut surface = spec.map(|s| build(s, options.surface, &grid)).transpose()?;
        if let Some(surface) = &mut surface {
            if plasticity {
                surface.model.reason.push_str(
                    "; yielding (eq. 13) truncates each row's asperities at the level its \
                     most-pressed capped cell was pressed to, so they flatten",
                );
            }
            models.push(surface.model.clone());
        }
        let (hardening, far_off) = work_hardening_report(&scene.disc, plan.hardness());
        models.push(hardening);
        if let Some(reason) = crate::scene::materials::describe(scene) {
            models.push(choice(Model::Materials, true, reason));
        }
        let warnings = plan.warnings().iter().cloned().chain(far_off).collect();
        Ok(Self {
            plan: plan.clone(),
            grid,
            plasticity,
            coupling,
            single_precision,
            options: solver,
            models,
            warnings,
            surface,
        })
    }

    /// The warnings as the result's `warnings` carries them, `path: message`.
    pub fn warning_lines(&self) -> Vec<String> {
        self.warnings.iter().map(ToString::to_string).collect()
    }

    /// The scene, defaults filled in.
    pub fn scene(&self) -> &Scene {
        self.plan.scene()
    }

    /// The pressure cap at `cycle` after the cumulative plastic strain `plastic_strain`
    /// ([`crate::hardness::YieldCap`]), or infinite without plasticity.
    pub fn yield_pressure_pa(&self, cycle: f64, plastic_strain: f64) -> f64 {
        if self.plasticity {
            self.plan.yield_cap().pressure_pa(cycle, plastic_strain)
        } else {
            f64::INFINITY
        }
    }

    /// The unworn ball's height above its apex at each cell of `grid` (the exact sphere),
    /// `rho^2 / (r + sqrt(r^2 - rho^2))`: equal to `r - sqrt(r^2 - rho^2)`, which loses the
    /// height to round-off once it nears `r` times machine epsilon (tiny contacts).
    pub fn ball_height(&self, grid: &Grid) -> Vec<f64> {
        let r = self.scene().ball_radius_m();
        grid.sample(|x, y| {
            let rho2 = x * x + y * y;
            if rho2 >= r * r {
                r
            } else {
                rho2 / (r + (r * r - rho2).sqrt())
            }
        })
    }

    /// The unworn disc on the first grid: smooth, or with its initial roughness.
    pub fn unworn_disc(&self) -> Groove {
        match &self.surface {
            Some(surface) => Groove::rough(&self.grid, surface.map.heights_m.clone()),
            None => Groove::new(&self.grid),
        }
    }

    /// The separation of the ball and the unworn disc at each cell of `grid`, the first grid
    /// or one grown from it: the ball's height less the roughness, which rises towards it.
    pub fn ball_separation(&self, grid: &Grid) -> Vec<f64> {
        self.unworn_disc()
            .widened(grid)
            .separation(&self.ball_height(grid), grid)
    }

    /// The threads the passes of a solve on `cells` cells split over ([`split_threads`] of
    /// the scene's `numerics.threads`).
    fn solve_threads(&self, cells: usize) -> usize {
        let requested = match self.scene().numerics.threads {
            SolverThreads::Auto => None,
            SolverThreads::Count(threads) => Some(threads),
        };
        split_threads(requested, cells, self.options.concurrent_runs)
    }

    /// Whether the run's cycle loop runs on one of the pool's threads, which then takes a
    /// share of each split pass itself: when the run is alone in the process and the solves
    /// of its first grid split. From outside the pool, the loop wakes the pool's threads for every pass
    /// and waits for them, and the idle ones spin on the cores it needs between passes. The
    /// 2 um example of `docs/scene.md`, on 2 cores: its first 300 cycles switched threads
    /// 1,164 times instead of 79,021 (median wall time of five alternating pairs, 0.934),
    /// and its 3600 cycles took 283.5 s against 303.5 s, the same to the bit. A pool thread
    /// waiting for its passes may take up other work queued on the pool, so a run sharing the
    /// process with others keeps its own thread: another run taken up would hold it.
    pub fn loop_on_pool(&self) -> bool {
        self.options.concurrent_runs == NonZeroUsize::MIN && self.solve_threads(self.grid.len()) > 1
    }

    /// The contact solver of `grid`: the normal operator alone, or with the coupling term.
    pub fn solver(&self, grid: &Grid) -> Box<dyn ContactSolver> {
        let normal = Kernel::normal(grid, self.plan.pair());
        let threads = self.solve_threads(grid.len());
        if self.coupling {
            let coupling = Kernel::coupling(
                grid,
                self.plan.pair(),
                self.scene().test.friction_coefficient,
            );
            if self.single_precision {
                Box::new(CoupledSolver::<f32>::of(&normal, &coupling).threaded(threads))
            } else {
                Box::new(CoupledSolver::<f64>::of(&normal, &coupling).threaded(threads))
            }
        } else if self.single_precision {
            Box::new(NormalSolver::new(
                DcFft::<f32>::of(&normal).threaded(threads),
            ))
        } else {
            Box::new(NormalSolver::new(
                DcFft::<f64>::of(&normal).threaded(threads),
            ))
        }
    }
}

/// Plasticity: pressures are highest on the unworn surface, so Hertz's p0 against the lowest
/// yield pressure of the run decides whether the cap can ever act.
fn decide_plasticity(
    models: &mut Vec<ModelChoice>,
    scene: &Scene,
    hertz: &Hertz,
    lowest: &LowestYield,
) -> bool {
    let p0 = hertz.peak_pressure_pa();
    let how = if lowest.from_initial {
        format!(
            "the initial yield strength, rising with plastic strain to H / {} at Tabor's {}%",
            scene.disc.yield_factor,
            TABOR_REPRESENTATIVE_STRAIN * 100.0
        )
    } else {
        format!("H / {}", scene.disc.yield_factor)
    };
    let reach = format!(
        "p0 {:.0} MPa {} lowest Y {:.0} MPa ({how})",
        p0 / 1e6,
        if p0 >= lowest.yield_pa { ">=" } else { "<" },
        lowest.yield_pa / 1e6
    );
    decide(
        models,
        Model::Plasticity,
        scene.wear.plasticity,
        p0 >= lowest.yield_pa,
        reach,
    )
}

/// The friction coupling term (eq. 7): modelled when it can move the pressures by more than
/// the solver's tolerance (see [`COUPLING_SENSITIVITY`]).
fn decide_coupling(
    models: &mut Vec<ModelChoice>,
    scene: &Scene,
    pair: &ElasticPair,
    options: &SolverOptions,
) -> bool {
    let mu = scene.test.friction_coefficient;
    let strength = (mu * pair.delta_nu).abs();
    let measured = format!(
        "|mu delta-nu| = {strength:.3e}; it moves pressures by >= {COUPLING_SENSITIVITY} times that, against tolerance {:.0e}",
        options.tolerance
    );
    decide(
        models,
        Model::Coupling,
        scene.numerics.coupling,
        COUPLING_SENSITIVITY * strength >= options.tolerance,
        measured,
    )
}

/// The transforms' precision: f32 where the solver's tolerance is at least
/// [`SINGLE_PRECISION_MIN_TOLERANCE`], f64 below.
fn decide_precision(models: &mut Vec<ModelChoice>, options: &SolverOptions) -> bool {
    let single = options.tolerance >= SINGLE_PRECISION_MIN_TOLERANCE;
    let reason = format!(
        "the contact's FFTs in {}: tolerance {:.0e} {} {SINGLE_PRECISION_MIN_TOLERANCE:.0e}, \
         where the f32 apply's round-off ({SINGLE_PRECISION_ROUNDOFF:.0e} of the largest displacement) stays below \
         1/{SINGLE_PRECISION_HEADROOM} of the tolerance; fields, sums and the wear stay in f64",
        if single {
            "single precision (f32)"
        } else {
            "double precision (f64)"
        },
        options.tolerance,
        if single { ">=" } else { "<" },
    );
    models.push(choice(Model::Precision, single, reason));
    single
}

/// The first grid, as planned for the sizing radius `radius`.
fn grid_choice(grid: &Grid, plan: &GridPlan, radius: f64) -> ModelChoice {
    choice(
        Model::Grid,
        true,
        format!(
            "{} x {} cells of {:.3} um over {:.1} um ({}); contact radius {:.1} um",
            plan.cells,
            plan.cells,
            grid.dx * 1e6,
            plan.domain_m * 1e6,
            plan.how,
            radius * 1e6
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulation::parse_scene_str;

    /// The setup of the scene `json`, without a measured surface.
    fn setup(json: &str) -> Setup {
        let plan = parse_scene_str(json).expect("valid");
        Setup::new(&plan, &RunOptions::default()).expect("valid")
    }

    #[test]
    fn paper_scene_gets_the_paper_cells_and_both_models() {
        let setup = setup(r#"{"preset": "dalmau2018-316l"}"#);
        // 3 radii of 44.2 um in 1 um cells is 133 cells, rounded up to 2^4 x 3^2.
        assert_eq!(setup.grid.nx, 144);
        assert!(
            (setup.grid.dx * 1e6 - 1.0).abs() < 0.01,
            "1 um cells like the paper"
        );
        assert!(setup.plasticity, "p0 1221 MPa > Y 883 MPa");
        assert!(setup.coupling, "|mu delta-nu| = 1.8e-2");
    }

    #[test]
    fn identical_materials_or_no_friction_leave_the_coupling_out() {
        let same = setup(
            r#"{"ball": {"youngs_modulus_gpa": 205, "poisson_ratio": 0.28},
                "test": {"friction_coefficient": 0.45}}"#,
        );
        assert!(!same.coupling);
        assert!(!setup(r#"{"test": {"friction_coefficient": 0}}"#).coupling);
    }

    #[test]
    fn light_load_on_hard_disc_is_elastic() {
        let light = setup(r#"{"test": {"load_n": 0.1}}"#);
        assert!(!light.plasticity);
        assert!(light.yield_pressure_pa(1.0, 0.0).is_infinite());
    }
}
