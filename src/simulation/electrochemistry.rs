//! Wear-accelerated corrosion over a run (paper Section 5.1): which area the sliding
//! depassivates, the potential during rubbing (eq. 18) and the dissolved volume by
//! Faraday's law, accumulated over the cycles each solve stands for.

use crate::corrosion::{CorrosionError, CorrosionModel, real_contact_area_m2};
use crate::scene::{AnodicArea, Corrosion};
use crate::wear::Groove;

/// The electrochemical cell of a run and the wear-accelerated corrosion volume so far.
#[derive(Debug)]
pub(super) struct Cell<'a> {
    model: CorrosionModel,
    settings: &'a Corrosion,
    wac_m3: f64,
}

/// What the surface offers the anodic reaction at one cycle.
pub(super) struct Surface<'a> {
    /// The groove after this cycle's wear.
    pub(super) groove: &'a Groove,
    /// The contact area of the solution, m^2.
    pub(super) contact_area_m2: f64,
    /// The load, N.
    pub(super) load_n: f64,
    /// The hardness at this cycle, Pa.
    pub(super) hardness_pa: f64,
    /// The length of the wear track, m.
    pub(super) track_length_m: f64,
}

/// One solved cycle's electrochemistry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reading {
    /// The depassivated area, m^2.
    pub(super) anodic_area_m2: f64,
    /// The potential during rubbing, V.
    pub(super) potential_v: f64,
    /// The wear-accelerated corrosion volume so far, m^3.
    pub(super) wac_m3: f64,
}

impl<'a> Cell<'a> {
    /// The cell of a scene's `corrosion` section.
    pub(super) fn new(settings: &'a Corrosion) -> Self {
        Self {
            model: settings.model(),
            settings,
            wac_m3: 0.0,
        }
    }

    /// The depassivated area the scene chose, times its factor.
    fn anodic_area_m2(&self, surface: &Surface) -> f64 {
        let area = match self.settings.anodic_area {
            AnodicArea::WearTrack => surface.groove.worn_width_m() * surface.track_length_m,
            AnodicArea::RealContact => real_contact_area_m2(surface.load_n, surface.hardness_pa),
            AnodicArea::BemContact => surface.contact_area_m2,
        };
        area * self.settings.anodic_area_factor
    }

    /// One solved cycle of `period_s`: the anodic area, the WAC volume it dissolves
    /// (Faraday) and the potential (eq. 18).
    pub(super) fn solved_cycle(
        &mut self,
        surface: &Surface,
        period_s: f64,
    ) -> Result<Reading, CorrosionError> {
        let area = self.anodic_area_m2(surface);
        self.wac_m3 += self.model.wac_volume_m3(area, period_s);
        Ok(Reading {
            anodic_area_m2: area,
            potential_v: self.model.potential_v(area)?,
            wac_m3: self.wac_m3,
        })
    }

    /// The cycles a solve stands for after its own, `duration_s` in all, at the area of
    /// its `reading`.
    pub(super) fn skipped(&mut self, reading: &Reading, duration_s: f64) {
        self.wac_m3 += self.model.wac_volume_m3(reading.anodic_area_m2, duration_s);
    }

    /// How the anodic area is chosen, for the `corrosion` model's reason.
    pub(super) fn describe(&self) -> String {
        let area = match self.settings.anodic_area {
            AnodicArea::WearTrack => "the wear track (worn width x track length)",
            AnodicArea::RealContact => "the real contact area F / H",
            AnodicArea::BemContact => {
                "the contact area of the solution (on a rough disc the real contact area of \
                 the asperities)"
            }
        };
        format!(
            "eq. 18 galvanic coupling and Faraday's law; anodic area: {area}, times {}",
            self.settings.anodic_area_factor
        )
    }
}
