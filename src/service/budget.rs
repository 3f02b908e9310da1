//! The budgets a request is held to before its work is built, each with its flag of
//! `tribosim serve` (`docs/operations.md`, "Limits and their flags", gives each one's
//! reason and the measurement behind its default). The resources receive the numbers; this
//! file knows none of them.

use std::num::NonZeroUsize;

/// The budgets of uploads and fits.
#[derive(Debug, Clone, clap::Args)]
pub struct Budgets {
    /// The most pixels a height-map upload may declare, counted before it is read (413
    /// beyond). The default is a 2048 x 2048 map, the contact grid's largest side.
    #[arg(long, default_value_t = Budgets::DEFAULT.max_surface_pixels)]
    pub max_surface_pixels: u64,
    /// Height-map uploads read at once; a further upload gets 429 before its body is read.
    #[arg(long, default_value_t = Budgets::DEFAULT.surface_parses)]
    pub surface_parses: NonZeroUsize,
    /// The most cells per side of a calibration's simulated runs (422 beyond).
    #[arg(long, default_value_t = Budgets::DEFAULT.calibration_max_grid)]
    pub calibration_max_grid: usize,
    /// The most cell-cycles one simulated run of a calibration may ask for: cells per side
    /// squared times the cycles the run goes to (422 beyond).
    #[arg(long, default_value_t = Budgets::DEFAULT.calibration_max_cell_cycles)]
    pub calibration_max_cell_cycles: u64,
    /// Bytes of finished calibrations' results kept in memory; the oldest are forgotten
    /// beyond it.
    #[arg(long, default_value_t = Budgets::DEFAULT.calibration_kept_bytes)]
    pub calibration_kept_bytes: usize,
}

impl Budgets {
    /// The defaults (`docs/operations.md` gives each one's reason).
    pub const DEFAULT: Self = Self {
        max_surface_pixels: 2048 * 2048,
        surface_parses: NonZeroUsize::new(2).expect("2 is not zero"),
        calibration_max_grid: 256,
        calibration_max_cell_cycles: 1 << 28,
        calibration_kept_bytes: 64 << 20,
    };
}

impl Default for Budgets {
    fn default() -> Self {
        Self::DEFAULT
    }
}
