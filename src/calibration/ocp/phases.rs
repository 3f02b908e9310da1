//! A measured open-circuit potential trace split at the rubbing's start and stop: which rows
//! are before, during and after the rubbing, refused (column and row named) unless the fit
//! can use them.

use super::super::{CalibrationError, Table, require_at_least, require_increasing, require_points};
use crate::scene::{Corrosion, Scene};
use crate::simulation::OcpPhase;

/// Where the rubbing lies in a trace whose times run on the potentiostat's clock.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OcpOptions {
    /// When the ball started, s on the table's clock; absent: every row is during the
    /// rubbing and `time_s` is the rubbing time.
    pub rubbing_start_s: Option<f64>,
    /// When the ball stopped, s on the table's clock; absent: at the table's end.
    pub rubbing_stop_s: Option<f64>,
}

/// The rows of a trace, each with its phase and, during the rubbing, its rubbing time.
pub(in crate::calibration) struct Trace<'a> {
    /// The table's times, s.
    pub(in crate::calibration) times: &'a [f64],
    /// The table's potentials, V.
    pub(in crate::calibration) potentials: &'a [f64],
    /// Each row's phase.
    pub(in crate::calibration) phases: Vec<OcpPhase>,
    /// When the ball started, s on the table's clock (0 without `rubbing_start_s`).
    pub(in crate::calibration) start_s: f64,
    /// When the ball stopped, s on the table's clock.
    pub(in crate::calibration) stop_s: f64,
    /// The scene's cell.
    pub(in crate::calibration) corrosion: &'a Corrosion,
}

/// Fewest rows during the rubbing: one parameter and at least two degrees of freedom for
/// the scatter its standard error is scaled by.
const MIN_RUBBING_ROWS: usize = 3;

impl Trace<'_> {
    /// The rubbing rows' indices.
    pub(in crate::calibration) fn rubbing(&self) -> Vec<usize> {
        (0..self.times.len())
            .filter(|&i| self.phases[i] == OcpPhase::Rubbing)
            .collect()
    }

    /// The rubbing time of row `i`, s.
    pub(in crate::calibration) fn rubbing_time_s(&self, i: usize) -> f64 {
        self.times[i] - self.start_s
    }
}

/// The table's trace in `scene`, refused unless the fit can use it: times increasing, a
/// start before a stop, at least [`MIN_RUBBING_ROWS`] rows during the rubbing, each below
/// E_corr.
pub(in crate::calibration) fn trace<'a>(
    table: &'a Table,
    scene: &'a Scene,
    options: OcpOptions,
) -> Result<Trace<'a>, CalibrationError> {
    let times = table.column("time_s")?;
    let potentials = table.column("potential_v")?;
    require_at_least("time_s", times, 0.0)?;
    require_increasing("time_s", times)?;
    let corrosion = scene
        .corrosion
        .as_ref()
        .ok_or(CalibrationError::MissingSection("corrosion"))?;
    let last = times[times.len() - 1];
    let start_s = options.rubbing_start_s.unwrap_or(0.0);
    let stop_s = match (options.rubbing_start_s, options.rubbing_stop_s) {
        (None, Some(_)) => return Err(CalibrationError::StopWithoutStart),
        (_, Some(stop)) if stop <= start_s => {
            return Err(CalibrationError::StopBeforeStart {
                start_s,
                stop_s: stop,
            });
        }
        (_, stop) => stop.unwrap_or(last),
    };
    let phases: Vec<OcpPhase> = times
        .iter()
        .map(|&t| {
            if options.rubbing_start_s.is_some() && t <= start_s {
                OcpPhase::Before
            } else if t <= stop_s {
                OcpPhase::Rubbing
            } else {
                OcpPhase::After
            }
        })
        .collect();
    let trace = Trace {
        times,
        potentials,
        phases,
        start_s,
        stop_s,
        corrosion,
    };
    let rubbing: Vec<f64> = trace.rubbing().iter().map(|&i| times[i]).collect();
    require_points("time_s", &rubbing, MIN_RUBBING_ROWS)?;
    let e_corr = corrosion.corrosion_potential_v;
    if let Some(&row) = trace.rubbing().iter().find(|&&i| potentials[i] >= e_corr) {
        return Err(CalibrationError::AboveCorrosionPotential {
            row: row + 1,
            value: potentials[row],
            corrosion_potential_v: e_corr,
        });
    }
    scene.hardness_law()?;
    Ok(trace)
}
