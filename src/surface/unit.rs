//! The unit a text map's heights are written in. A profiler's export is often in um or nm,
//! which read as m would be a million or a billion times too rough; a `.gsf` file states
//! its own unit (m).

use super::{Format, HeightMap, SurfaceError};

/// The unit of a text map's heights, `m`, `um` or `nm`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum HeightUnit {
    /// Metres, as a map's heights are read without a unit.
    M,
    /// Micrometres.
    Um,
    /// Nanometres.
    Nm,
}

impl HeightUnit {
    /// Every unit, with its name.
    pub const ALL: [(Self, &'static str); 3] = [(Self::M, "m"), (Self::Um, "um"), (Self::Nm, "nm")];

    /// The unit called `name` (`m`, `um`, `nm`).
    pub fn named(name: &str) -> Option<Self> {
        Self::ALL
            .iter()
            .find(|(_, n)| *n == name)
            .map(|&(unit, _)| unit)
    }

    /// The unit's size, m.
    pub fn metres(self) -> f64 {
        match self {
            Self::M => 1.0,
            Self::Um => 1e-6,
            Self::Nm => 1e-9,
        }
    }

    /// `map`'s heights, written in this unit, converted to m. A `.gsf` map is refused
    /// unless the unit is m: the file states its own unit.
    pub fn apply(self, map: &mut HeightMap, format: Format) -> Result<(), SurfaceError> {
        if self == Self::M {
            return Ok(());
        }
        if format == Format::Gsf {
            return Err(SurfaceError::Invalid(
                "a .gsf file states its own units (in m); a height unit is for text maps".into(),
            ));
        }
        let size = self.metres();
        map.heights_m.iter_mut().for_each(|h| *h *= size);
        Ok(())
    }
}
