//! The contact core: influence coefficients, the DC-FFT operator and the bounded solvers.
//!
//! The pieces are kept apart as in Tamaas and ContactMechanics: [`Grid`] and
//! [`ElasticPair`] describe the problem, [`Kernel`] holds the influence coefficients,
//! an [`Operator`] applies them ([`DcFft`] fast, [`DenseOperator`] by direct summation)
//! and may offer a [`Preconditioner`], and a [`ContactSolver`] solves a [`ContactProblem`]:
//! [`NormalSolver`] (preconditioned Polonsky-Keer on any operator), [`CoupledSolver`] (with
//! the friction coupling term) and [`WindowedSolver`] (on a window around the contact,
//! checked on every cell whose gap could close); [`WornRows`] adds the wear a solve's own pass
//! wears (the implicit update of [`worn_rows`]). [`residual`] holds the complementarity conditions they all
//! meet, and [`verify`] checks a solution against them independently.

mod blocks;
pub mod check;
mod coarse;
pub mod coupled;
mod error;
mod fft;
mod grid;
mod hertz;
pub mod influence;
mod material;
mod operator;
mod periodic;
mod precondition;
mod problem;
pub mod residual;
pub mod solver;
mod sums;
mod transform;
mod window;
pub mod worn_rows;

pub use check::{Verification, verify};
pub use coarse::{COARSE_TOLERANCE, COARSEST_CELLS, coarse_start, cold_start};
pub use coupled::{CoupledSolver, solve_coupled};
pub use error::{ContactError, ElasticConstant};
pub use fft::{
    DcFft, SINGLE_PRECISION_HEADROOM, SINGLE_PRECISION_MIN_TOLERANCE, SINGLE_PRECISION_ROUNDOFF,
};
pub use grid::{Grid, Window};
pub use hertz::Hertz;
pub use influence::Kernel;
pub use material::{ElasticPair, Material};
pub use operator::{DenseOperator, NEAR_REACH, Operator, Preconditioner, SumOperator};
pub use periodic::PeriodicHalfSpace;
pub use precondition::FourierInverse;
pub use problem::{
    ContactProblem, ContactSolution, ContactSolver, KnownStart, Preconditioning, SolverOptions,
};
pub use residual::complementarity_residual;
pub use solver::{NormalSolver, UPDATE_ROUNDOFF, solve, solve_known};
pub use transform::Real;
pub(crate) use transform::{BLOCK, Plans, column_stride, each_value, pack, packed_len, transpose};
pub use transform::{MAX_SPLIT_THREADS, SPLIT_MIN_CELLS, fft_friendly, split_threads};
pub use window::{KEPT_SHAPES, MARGIN_FRACTION, MIN_MARGIN, WindowFractions, WindowedSolver};
pub use worn_rows::{WornRows, add_worn_rows, worn_row_depths_m};
