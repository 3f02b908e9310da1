//! The budgets a request is held to before its work is built, each with its flag of
//! `tribosim serve` (`docs/operations.md`, "Limits and their flags", gives each one's
//! reason and the measurement behind its default). The resources receive the numbers; this
//! file knows none of them.

use std::num::{NonZeroU64, NonZeroUsize};

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
    /// Memory the running jobs may take together, MiB, by each run's estimated peak: a job
    /// whose estimate exceeds it is refused at submit (422), and a job waits in the queue
    /// while the running ones leave too little. Half the machine's memory by default.
    #[arg(long, value_name = "MIB")]
    pub job_memory_mib: Option<NonZeroU64>,
}

impl Budgets {
    /// The defaults (`docs/operations.md` gives each one's reason).
    pub const DEFAULT: Self = Self {
        max_surface_pixels: 2048 * 2048,
        surface_parses: NonZeroUsize::new(2).expect("2 is not zero"),
        calibration_max_grid: 256,
        calibration_max_cell_cycles: 1 << 28,
        calibration_kept_bytes: 64 << 20,
        job_memory_mib: None,
    };

    /// The jobs' memory budget, bytes: `--job-memory-mib`, or half the machine's memory
    /// (`MemTotal` of `/proc/meminfo`), leaving the rest to the system, the server and
    /// other programs; 8 GiB where the machine's memory cannot be read.
    pub fn job_memory_bytes(&self) -> u64 {
        const MIB: u64 = 1 << 20;
        match self.job_memory_mib {
            Some(mib) => mib.get().saturating_mul(MIB),
            None => physical_memory_bytes().map_or(8 << 30, |bytes| bytes / 2),
        }
    }
}

impl Default for Budgets {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The machine's memory, bytes, from `/proc/meminfo` (Linux); `None` elsewhere.
fn physical_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|line| line.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
