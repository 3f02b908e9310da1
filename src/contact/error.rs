//! The ways a contact solve can fail. Each is a value the caller can match on and report;
//! none is a panic.

use std::fmt;

use thiserror::Error;

/// One of the two elastic constants of an isotropic material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElasticConstant {
    /// Young's modulus `E`, Pa.
    YoungsModulus,
    /// Poisson's ratio `nu`.
    PoissonRatio,
}

impl fmt::Display for ElasticConstant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::YoungsModulus => "Young's modulus (Pa)",
            Self::PoissonRatio => "Poisson's ratio",
        })
    }
}

/// Why a contact problem could not be solved.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContactError {
    /// A material constant is outside its physical range.
    #[error("invalid material: {constant} = {value} (allowed: {allowed})")]
    InvalidMaterial {
        /// Which constant.
        constant: ElasticConstant,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// The grid or one of the problem's arrays is malformed.
    #[error("invalid problem: {0}")]
    InvalidProblem(String),
    /// Even with every cell of the domain at the yield pressure the load cannot be carried:
    /// the elastic-perfectly-plastic problem has no solution.
    #[error(
        "load {load_n} N exceeds what the domain can carry at the yield pressure ({capacity_n} N = Y x domain area); enlarge the domain or check the hardness"
    )]
    LoadExceedsCapacity {
        /// The requested load.
        load_n: f64,
        /// Yield pressure times domain area.
        capacity_n: f64,
    },
    /// Pressure reached the outermost ring of cells: the contact does not fit in the domain,
    /// so the truncated half-space answer would be wrong.
    #[error(
        "contact reaches the domain edge: {edge_cells} edge cells carry {edge_load_fraction:.3e} of the load; enlarge the domain"
    )]
    ContactAtEdge {
        /// Number of edge cells with positive pressure.
        edge_cells: usize,
        /// Fraction of the load those cells carry.
        edge_load_fraction: f64,
    },
    /// The iteration limit was reached before the stopping test was met.
    #[error(
        "no convergence after {iterations} iterations: residual {residual:.3e} > tolerance {tolerance:.3e}"
    )]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// The relative residual reached (see [`crate::contact::solver`]).
        residual: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
}
