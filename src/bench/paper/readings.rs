//! The readings of eq. 13 that the paper's words allow, each cycled by the same small loop
//! on the paper's scene: the contact solved on the surface the reading leaves (the library's
//! solver, friction coupling as the scene has it), the reading's yield update, then one
//! Archard pass (eqs. 15-16). Section 3.2 leaves open what "the maximum of the wear profile
//! d_wear due to yielding for each y" accumulates, whether the yield groove enters the next
//! solve, and from which surface d_wear is measured; each [`Reading`] is one answer.
//!
//! Runs on 2 um cells over the paper's 0.256 mm window, [`CYCLES`] cycles: the readings
//! differ by factors at cycle 10, far more than the grid moves them. Measured on the
//! paper's 1 um cells, every row's depth at cycle 10 moves by under 2.5% ((b) 2.444 against
//! 2.386 um, (h) 1.014 against 1.012), except (d), whose sum over x doubles with the number
//! of cells; without friction, by under 0.2%.

use crate::contact::{ContactError, ContactProblem, ContactSolution, ContactSolver, Grid};
use crate::simulation::{RunOptions, Setup};

use crate::bench::BenchError;

#[cfg(doc)]
use super::COARSE_GRID;
use super::plan;

/// The cycles each reading is run for: the paper's first statements are at 10 s.
pub const CYCLES: u64 = 10;

/// One reading of eq. 13 and the profile update.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reading {
    /// (a) Each row cut by the largest interpenetration left at a capped cell, measured
    /// on the worn surface, accumulated: tribosim's model.
    WornSurface,
    /// (b) The interpenetration measured from the unworn surface, accumulated.
    UnwornAccumulated,
    /// (b2) As (b), on every row in contact while any cell is capped.
    UnwornEveryRow,
    /// (c) The interpenetration from the unworn surface replaces the yield groove.
    UnwornReplacing,
    /// (d) Eq. 16's sum over x applied to the interpenetration.
    SummedAlongTrack,
    /// (e1) The yield groove kept out of the next solve, maxima accumulated.
    OutOfSolveAccumulated,
    /// (e2) As (e1), a running maximum.
    OutOfSolveMaximum,
    /// (e3) Eq. 17 with its printed sign: the groove narrows the gap.
    PrintedSign,
    /// (g) The uncapped solve's approach against the capped pressures' displacement.
    UncappedApproach,
    /// (h) Rigid-perfectly-plastic: the whole load at Y on the overlap of the undeformed
    /// ball and the current groove, each row cut to the ball, no elastic displacement.
    RigidPlastic,
}

impl Reading {
    /// Every reading, in the table's order.
    pub const ALL: [Self; 10] = [
        Self::WornSurface,
        Self::UnwornAccumulated,
        Self::UnwornEveryRow,
        Self::UnwornReplacing,
        Self::SummedAlongTrack,
        Self::OutOfSolveAccumulated,
        Self::OutOfSolveMaximum,
        Self::PrintedSign,
        Self::UncappedApproach,
        Self::RigidPlastic,
    ];
}

impl Reading {
    /// The table's name of the reading: its letter and what it does.
    pub fn label(self) -> &'static str {
        match self {
            Self::WornSurface => {
                "(a) each row cut by the largest interpenetration at a capped cell, on the \
                 worn surface, accumulated (tribosim's model)"
            }
            Self::UnwornAccumulated => {
                "(b) d_wear measured from the unworn surface and accumulated"
            }
            Self::UnwornEveryRow => "(b2) as (b) on every contact row while any cell is capped",
            Self::UnwornReplacing => "(c) d_wear from the unworn surface, replacing the groove",
            Self::SummedAlongTrack => "(d) eq. 16's sum over x applied to the interpenetration",
            Self::OutOfSolveAccumulated => {
                "(e1) the yield groove kept out of the next solve, maxima accumulated"
            }
            Self::OutOfSolveMaximum => "(e2) as (e1), a running maximum",
            Self::PrintedSign => "(e3) eq. 17 with its printed sign (the groove narrows the gap)",
            Self::UncappedApproach => {
                "(g) the uncapped solve's approach with the capped pressures' displacement"
            }
            Self::RigidPlastic => {
                "(h) rigid-perfectly-plastic, cycled in its own groove: the whole load at Y on \
                 the overlap of the undeformed ball and the groove, each row cut to the ball"
            }
        }
    }
}

/// One reading cycled [`CYCLES`] times.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadingRun {
    /// The reading.
    pub reading: Reading,
    /// The groove's deepest point after each cycle (index 0 is cycle 1), um.
    pub depth_um: Vec<f64>,
    /// The groove's volume after each cycle, mm^3.
    pub volume_mm3: Vec<f64>,
    /// Whether some pressure sat at the cap in each cycle.
    pub capped: Vec<bool>,
    /// The cycle whose contact no longer fits the window, which ends the run.
    pub left_window_at: Option<u64>,
}

/// The solution of one cycle's contact and the interpenetration
/// `delta - h - u` of each cell (m, positive where the bodies overlap).
struct Solved {
    solution: ContactSolution,
    overlap_m: Vec<f64>,
}

/// The loop's state: the scene's setup, its grid and solver, and the two parts of the groove
/// per row, m.
struct Cycler {
    setup: Setup,
    grid: Grid,
    solver: Box<dyn ContactSolver>,
    ball_m: Vec<f64>,
    archard_m: Vec<f64>,
    yield_m: Vec<f64>,
}

/// Runs every reading on the paper's scene with `numerics` (a scene's `"numerics"` member,
/// [`COARSE_GRID`] for the page).
pub fn run_all(numerics: &str) -> Result<Vec<ReadingRun>, BenchError> {
    // The readings are of eq. 13 under the paper's own cap, whatever the default's.
    let json = format!(
        r#"{{"test": {{"cycles": {CYCLES}}}, "disc": {{"yield_cap": "hardness"}}, {numerics}}}"#
    );
    let setup = Setup::new(&plan(&json)?, &RunOptions::default())?;
    Reading::ALL
        .iter()
        .map(|&reading| Cycler::new(setup.clone()).run(reading))
        .collect()
}

impl Cycler {
    fn new(setup: Setup) -> Self {
        let grid = setup.grid;
        let solver = setup.solver(&grid);
        let ball_m = setup.ball_separation(&grid);
        Self {
            setup,
            grid,
            solver,
            ball_m,
            archard_m: vec![0.0; grid.ny],
            yield_m: vec![0.0; grid.ny],
        }
    }

    fn run(mut self, reading: Reading) -> Result<ReadingRun, BenchError> {
        let mut out = ReadingRun {
            reading,
            depth_um: Vec::new(),
            volume_mm3: Vec::new(),
            capped: Vec::new(),
            left_window_at: None,
        };
        for cycle in 1..=CYCLES {
            match self.cycle(reading, cycle) {
                Ok(capped) => out.capped.push(capped),
                Err(ContactError::ContactAtEdge { .. }) => {
                    out.left_window_at = Some(cycle);
                    break;
                }
                Err(e) => return Err(e.into()),
            }
            let groove: Vec<f64> = self.groove_m().collect();
            out.depth_um
                .push(groove.iter().copied().fold(0.0, f64::max) * 1e6);
            let area_m2 = groove.iter().sum::<f64>() * self.grid.dy;
            out.volume_mm3
                .push(area_m2 * self.setup.scene().track_length_m() * 1e9);
        }
        Ok(out)
    }

    /// The groove, Archard's part and the yield part, per row, m.
    fn groove_m(&self) -> impl Iterator<Item = f64> + '_ {
        self.archard_m.iter().zip(&self.yield_m).map(|(a, y)| a + y)
    }

    /// One cycle: the contact, the reading's yield update, one Archard pass. Returns
    /// whether a pressure sat at the cap.
    fn cycle(&mut self, reading: Reading, cycle: u64) -> Result<bool, ContactError> {
        let cap = self.setup.yield_pressure_pa(cycle as f64, 0.0);
        // Which groove the solve sees: the whole one, Archard's part alone (the yield
        // groove kept out), or the whole one with eq. 17's printed sign.
        let groove: Vec<f64> = match reading {
            Reading::OutOfSolveAccumulated | Reading::OutOfSolveMaximum => self.archard_m.clone(),
            Reading::PrintedSign => self.groove_m().map(|d| -d).collect(),
            _ => self.groove_m().collect(),
        };
        let separation = self.separation(&groove);
        let solved = if reading == Reading::RigidPlastic {
            self.rigid_plastic(&separation, cap)
        } else {
            self.solve(&separation, cap)?
        };
        let capped = solved.solution.pressure.iter().any(|&p| p >= cap);
        let unworn: Vec<f64> = solved
            .overlap_m
            .iter()
            .zip(&separation)
            .zip(&self.ball_m)
            .map(|((t, h), b)| t + h - b)
            .collect();
        let p = &solved.solution.pressure;
        let at_cap = |i: usize| p[i] >= cap;
        match reading {
            Reading::WornSurface
            | Reading::OutOfSolveAccumulated
            | Reading::PrintedSign
            | Reading::RigidPlastic => self.accumulate(&solved.overlap_m, at_cap),
            Reading::UnwornAccumulated => self.accumulate(&unworn, at_cap),
            Reading::UnwornEveryRow if capped => self.accumulate(&unworn, |i| p[i] > 0.0),
            Reading::UnwornEveryRow => {}
            Reading::UnwornReplacing => {
                let deepest = self.row_maxima(&unworn, at_cap);
                for ((y, a), d) in self.yield_m.iter_mut().zip(&self.archard_m).zip(deepest) {
                    *y = y.max(d - a);
                }
            }
            Reading::SummedAlongTrack => {
                for (i, t) in solved.overlap_m.iter().enumerate() {
                    if at_cap(i) {
                        self.yield_m[i / self.grid.nx] += t.max(0.0);
                    }
                }
            }
            Reading::OutOfSolveMaximum => {
                let deepest = self.row_maxima(&solved.overlap_m, at_cap);
                for (y, d) in self.yield_m.iter_mut().zip(deepest) {
                    *y = y.max(d);
                }
            }
            Reading::UncappedApproach => {
                let uncapped = self.solve(&separation, f64::INFINITY)?.solution.approach_m;
                let shift = uncapped - solved.solution.approach_m;
                let overlap: Vec<f64> = solved.overlap_m.iter().map(|t| t + shift).collect();
                self.accumulate(&overlap, at_cap);
            }
        }
        self.archard(cycle, p);
        Ok(capped)
    }

    /// The separation of the ball and a disc worn by `groove_m` per row.
    fn separation(&self, groove_m: &[f64]) -> Vec<f64> {
        let nx = self.grid.nx;
        (0..self.grid.len())
            .map(|i| self.ball_m[i] + groove_m[i / nx])
            .collect()
    }

    fn solve(&mut self, separation: &[f64], cap: f64) -> Result<Solved, ContactError> {
        let problem = ContactProblem {
            grid: self.grid,
            separation,
            load_n: self.setup.scene().load_n(),
            yield_pressure_pa: cap,
            pass_wear_per_pa: 0.0,
        };
        let solution = self.solver.solve(&problem, &self.setup.options, None)?;
        let overlap_m = (0..self.grid.len())
            .map(|i| solution.approach_m - separation[i] - solution.displacement[i])
            .collect();
        Ok(Solved {
            solution,
            overlap_m,
        })
    }

    /// The rigid ball pressed into the rigid-plastic disc until the cells it overlaps carry
    /// the load at `cap`: the `ceil(F / (Y A_cell))` cells of least separation, and those
    /// tied with the last of them (the ball's symmetry makes ties), which carry a little
    /// more than F. The cut depends only on the approach, so the ties move only Archard's
    /// pass, itself a few hundredths of the cut (about 0.002 um a cycle).
    fn rigid_plastic(&self, separation: &[f64], cap: f64) -> Solved {
        let cells = (self.setup.scene().load_n() / (cap * self.grid.cell_area())).ceil() as usize;
        let mut sorted = separation.to_vec();
        sorted.sort_by(f64::total_cmp);
        let approach_m = sorted[cells.clamp(1, sorted.len()) - 1];
        let overlap_m: Vec<f64> = separation.iter().map(|h| approach_m - h).collect();
        let pressure = overlap_m
            .iter()
            .map(|&t| if t >= 0.0 { cap } else { 0.0 })
            .collect();
        let solution = ContactSolution {
            pressure,
            displacement: vec![0.0; self.grid.len()],
            approach_m,
            iterations: 0,
            operator_applies: 0,
            residual: 0.0,
            preconditioner_fallbacks: 0,
            uniform_restarts: 0,
        };
        Solved {
            solution,
            overlap_m,
        }
    }

    /// The largest positive `field` of each row over the cells `counted`, m.
    fn row_maxima(&self, field: &[f64], counted: impl Fn(usize) -> bool) -> Vec<f64> {
        let mut deepest = vec![0.0_f64; self.grid.ny];
        for (i, &t) in field.iter().enumerate() {
            if counted(i) {
                let row = &mut deepest[i / self.grid.nx];
                *row = row.max(t);
            }
        }
        deepest
    }

    /// Deepens the yield groove of each row by the row's largest positive `field` over the
    /// cells `counted`.
    fn accumulate(&mut self, field: &[f64], counted: impl Fn(usize) -> bool) {
        let deepest = self.row_maxima(field, counted);
        for (y, d) in self.yield_m.iter_mut().zip(deepest) {
            *y += d;
        }
    }

    /// One pass of Archard's wear at `cycle`'s hardness (eqs. 15-16).
    fn archard(&mut self, cycle: u64, pressure: &[f64]) {
        let wear = self.setup.plan.wear();
        let scale = wear.depth_scale(cycle..cycle + 1, self.setup.plan.hardness());
        for (a, d) in self
            .archard_m
            .iter_mut()
            .zip(wear.pass_profile(&self.grid, pressure))
        {
            *a += scale * d;
        }
    }
}
