//! The contact core: influence coefficients, the DC-FFT operator and the bounded solver.
//!
//! The pieces are kept apart as in Tamaas and ContactMechanics: [`Grid`] and
//! [`ElasticPair`] describe the problem, [`Kernel`] holds the influence coefficients,
//! an [`Operator`] applies them ([`DcFft`] fast, [`DenseOperator`] by direct summation),
//! and the solver works on any operator.

pub mod check;
pub mod coupled;
mod error;
mod fft;
mod grid;
mod hertz;
pub mod influence;
mod material;
mod operator;
mod plans;
mod precondition;
pub mod solver;

pub use check::{Verification, verify};
pub use coupled::{CoupledSolver, solve_coupled};
pub use error::ContactError;
pub use fft::DcFft;
pub(crate) use fft::{BLOCK, STRIDE_PAD};
pub use grid::Grid;
pub use hertz::Hertz;
pub use influence::Kernel;
pub use material::{ElasticPair, Material};
pub use operator::{DenseOperator, Operator, Preconditioner, SumOperator};
pub(crate) use plans::Plans;
pub use precondition::FourierInverse;
pub use solver::{ContactProblem, ContactSolution, SolverOptions, solve};
