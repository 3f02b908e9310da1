//! Wear-accelerated corrosion over a run (paper Section 5.1): which area the sliding
//! depassivates, the potential during rubbing (eq. 18), the anodic current and the charge it
//! passes, and the dissolved volume by Faraday's law, accumulated over the cycles each solve
//! stands for; with what the run should say about it (the cap at E_corr, potentials outside
//! the Tafel line's fitted domain).

use crate::corrosion::galvanic::Balance;
use crate::corrosion::kinetics::Repassivation;
use crate::corrosion::spots::{Sliding, SpotRows, TrackAges};
use crate::corrosion::{
    AreaInputs, ContactGeometry, CorrosionError, CorrosionModel, real_contact_area_m2,
};
use crate::scene::{AnodicArea, Corrosion, FieldWarning, Scene};
use crate::wear::{Groove, VolumeBasis};

use super::CycleRecord;

/// The electrochemical cell of a run and the charge passed so far.
#[derive(Debug)]
pub(super) struct Cell<'a> {
    model: CorrosionModel,
    settings: &'a Corrosion,
    sliding_speed_m_s: f64,
    /// The unworn Hertz contact's width 2a, m: the band of `hertz_band`.
    hertz_width_m: f64,
    charge_c: f64,
    /// The first and the last solved cycle, for the model's reason.
    first: Option<Snapshot>,
    last: Option<Snapshot>,
    /// Solved cycles whose eq. 18 potential lay above E_corr and was capped there.
    capped: Tally,
    /// Solved cycles whose potential lay outside the Tafel line's fitted domain.
    outside: Tally,
    /// The spot models' state: each row of the track's age since it was last stripped.
    ages: TrackAges,
    /// The last solved cycle's spots, which the cycles it stands for repeat.
    last_spots: Option<SpotRows>,
    /// The sliding as the spots' kinetics see it.
    sliding: Sliding,
    /// What the `balanced` cell adds to eq. 18; `None` for eq. 18 as printed.
    balance: Option<Balance>,
    /// The largest share of the stripped rows' track that stayed bare over a solved cycle,
    /// and its cycle: near 1 the film has no time to regrow between passes.
    barest: Option<(f64, u64)>,
}

/// The bare share of the stripped track above which the run says the repassivation is
/// incomplete: half the track still bare a revolution after stripping.
const INCOMPLETE_REPASSIVATION: f64 = 0.5;

/// What the surface offers the anodic reaction at one cycle.
pub(super) struct Surface<'a> {
    /// The groove after this cycle's wear.
    pub(super) groove: &'a Groove,
    /// The solved contact: its area and the width it sweeps.
    pub(super) contact: ContactGeometry,
    /// The load, N.
    pub(super) load_n: f64,
    /// The hardness at this cycle, Pa.
    pub(super) hardness_pa: f64,
    /// The length of the wear track, m.
    pub(super) track_length_m: f64,
    /// The spots of the spot models (`None` for the other models).
    pub(super) spots: Option<SpotRows>,
}

/// One solved cycle's electrochemistry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Reading {
    /// The depassivated area, m^2.
    pub(super) anodic_area_m2: f64,
    /// The potential during rubbing, V against the scene's reference electrode.
    pub(super) potential_v: f64,
    /// The anodic current i_a A_a, A.
    pub(super) anodic_current_a: f64,
    /// The solved contact's mean chord along the sliding, m.
    pub(super) contact_chord_m: Option<f64>,
    /// The anodic charge passed so far, C.
    pub(super) charge_c: f64,
    /// The wear-accelerated corrosion volume so far, m^3.
    pub(super) wac_m3: f64,
}

/// Fills `record`'s loss and corrosion columns: the groove `groove_m3` and the WAC of
/// `reading` split by `basis` (without corrosion the WAC is nil and either basis splits the
/// groove into itself), and the reading's potential, area, chord, current and charge.
pub(super) fn fill_corrosion(
    record: &mut CycleRecord,
    groove_m3: f64,
    basis: VolumeBasis,
    reading: Option<Reading>,
) {
    let loss = basis.split(groove_m3, reading.map_or(0.0, |r| r.wac_m3));
    record.wear_volume_mm3 = loss.total_m3 * 1e9;
    record.total_volume_mm3 = Some(loss.total_m3 * 1e9);
    record.mechanical_volume_mm3 = Some(loss.mechanical_m3 * 1e9);
    record.potential_v = reading.map(|r| r.potential_v);
    record.anodic_area_mm2 = reading.map(|r| r.anodic_area_m2 * 1e6);
    record.contact_chord_um = reading.and_then(|r| r.contact_chord_m).map(|c| c * 1e6);
    record.anodic_current_ma = reading.map(|r| r.anodic_current_a * 1e3);
    record.charge_c = reading.map(|r| r.charge_c);
    record.wac_volume_mm3 = reading.map(|r| r.wac_m3 * 1e9);
}

/// A solved cycle as the model's reason tells it.
#[derive(Debug, Clone, Copy)]
struct Snapshot {
    cycle: u64,
    /// A_a / (F / H).
    to_real_contact: f64,
    /// The solved contact's mean chord along the sliding, m.
    chord_m: Option<f64>,
}

/// How many solved cycles something happened at, the first of them and the extreme potential.
#[derive(Debug, Default)]
struct Tally {
    count: usize,
    first_cycle: Option<u64>,
    lowest_v: f64,
    highest_v: f64,
}

impl Tally {
    fn note(&mut self, cycle: u64, potential_v: f64) {
        if self.count == 0 {
            self.first_cycle = Some(cycle);
            self.lowest_v = potential_v;
            self.highest_v = potential_v;
        }
        self.count += 1;
        self.lowest_v = self.lowest_v.min(potential_v);
        self.highest_v = self.highest_v.max(potential_v);
    }
}

impl<'a> Cell<'a> {
    /// The cell of `scene`'s `corrosion` section, `None` without one; `hertz_radius_m` is
    /// the unworn Hertz contact's radius.
    pub(super) fn of(scene: &'a Scene, hertz_radius_m: f64) -> Option<Self> {
        let settings = scene.corrosion.as_ref()?;
        Some(Self {
            model: settings.model(),
            settings,
            sliding_speed_m_s: scene.sliding_speed_m_s(),
            hertz_width_m: 2.0 * hertz_radius_m,
            charge_c: 0.0,
            first: None,
            last: None,
            capped: Tally::default(),
            outside: Tally::default(),
            ages: TrackAges::default(),
            last_spots: None,
            sliding: Sliding {
                speed_m_s: scene.sliding_speed_m_s(),
                track_length_m: scene.track_length_m(),
            },
            balance: settings.balance(),
            barest: None,
        })
    }

    /// The potential at the anodic area `area_m2` and the anodic current it passes: eq. 18
    /// capped at E_corr with i_a A_a, or the balanced cell.
    pub(super) fn couple(&self, area_m2: f64) -> Result<(f64, f64), CorrosionError> {
        if let Some(applied_v) = self.settings.held_v() {
            self.model.cathodic_area_m2(area_m2)?;
            // Validation requires the bare corrosion potential with a potentiostat.
            let held = self
                .settings
                .bare_metal()
                .held(&self.model, area_m2, applied_v);
            return Ok(held.map_or((applied_v, 0.0), |c| (c.potential_v, c.anodic_current_a)));
        }
        match &self.balance {
            Some(balance) => {
                let coupling = balance.couple(&self.model, area_m2)?;
                Ok((coupling.potential_v, coupling.anodic_current_a))
            }
            None => Ok((
                self.model.potential_v(area_m2)?,
                self.model.anodic_current_a(area_m2),
            )),
        }
    }

    /// The spot models' bare-equivalent area `since_stop_s` after the stop, times the
    /// factor, m^2; `None` for the other models.
    pub(super) fn spot_area_after_stop_m2(&self, since_stop_s: f64) -> Option<f64> {
        self.last_spots.as_ref()?;
        let kinetics = self.kinetics();
        let area = self
            .ages
            .area_after_stop_m2(since_stop_s, self.sliding, &kinetics);
        Some(area * self.settings.anodic_area_factor)
    }

    fn kinetics(&self) -> Repassivation {
        self.settings.repassivation()
    }

    /// The cell's model in SI units.
    pub(super) fn model(&self) -> &CorrosionModel {
        &self.model
    }

    /// The scene's `corrosion` section.
    pub(super) fn settings(&self) -> &Corrosion {
        self.settings
    }

    /// What `surface` offers the anodic area models; the spots advance the track's ages.
    fn inputs(&mut self, surface: &Surface) -> AreaInputs {
        let kinetics = self.kinetics();
        let spot_area_m2 = surface.spots.as_ref().map_or(0.0, |spots| {
            self.ages.cycle_area_m2(spots, self.sliding, &kinetics)
        });
        self.last_spots.clone_from(&surface.spots);
        AreaInputs {
            spot_area_m2,
            real_contact_m2: real_contact_area_m2(surface.load_n, surface.hardness_pa),
            contact_area_m2: surface.contact.area_m2,
            mean_chord_m: surface.contact.mean_chord_m(),
            wear_track_m2: surface.groove.worn_width_m() * surface.track_length_m,
            band_width_m: self.hertz_width_m,
            sliding_speed_m_s: self.sliding_speed_m_s,
        }
    }

    /// Solved cycle `cycle`, of `period_s`: the anodic area, the charge and the WAC volume it
    /// dissolves (Faraday) and the potential (eq. 18, capped at E_corr).
    pub(super) fn solved_cycle(
        &mut self,
        cycle: u64,
        surface: &Surface,
        period_s: f64,
    ) -> Result<Reading, CorrosionError> {
        let inputs = self.inputs(surface);
        if let Some(spots) = &surface.spots {
            let stripped_m2 = spots.stripped_width_m() * self.sliding.track_length_m;
            let share = if stripped_m2 > 0.0 {
                inputs.spot_area_m2 / stripped_m2
            } else {
                0.0
            };
            if self.barest.is_none_or(|(most, _)| share > most) {
                self.barest = Some((share, cycle));
            }
        }
        let area = self.settings.anodic_area_m2(&inputs);
        let contact = (inputs.real_contact_m2, inputs.mean_chord_m);
        self.book(cycle, area, contact, period_s)
    }

    /// A reciprocating cycle whose stroke leaves the bare-equivalent area `area_m2` on
    /// average over a cycle (before `anodic_area_factor`), over `duration_s` of rubbing (one
    /// cycle; those a step skips are [`Cell::skipped`]); `real_contact_m2` (F / H) and the
    /// contact's mean chord `chord_m` for the model's reason.
    pub(super) fn stroke_cycle(
        &mut self,
        cycle: u64,
        area_m2: f64,
        (real_contact_m2, chord_m): (f64, Option<f64>),
        duration_s: f64,
    ) -> Result<Reading, CorrosionError> {
        let area = area_m2 * self.settings.anodic_area_factor;
        self.book(cycle, area, (real_contact_m2, chord_m), duration_s)
    }

    /// The cell at the anodic area `area_m2` (the factor applied) over `duration_s` of
    /// `cycle`: its potential and current, the charge they pass, the tallies and the
    /// snapshot for the model's reason (`real_contact_m2`, `chord_m`).
    fn book(
        &mut self,
        cycle: u64,
        area_m2: f64,
        (real_contact_m2, chord_m): (f64, Option<f64>),
        duration_s: f64,
    ) -> Result<Reading, CorrosionError> {
        let (potential, current) = self.couple(area_m2)?;
        self.charge_c += current * duration_s;
        self.tally(cycle, area_m2, potential)?;
        let snapshot = Snapshot {
            cycle,
            to_real_contact: area_m2 / real_contact_m2,
            chord_m,
        };
        self.first.get_or_insert(snapshot);
        self.last = Some(snapshot);
        Ok(Reading {
            anodic_area_m2: area_m2,
            potential_v: potential,
            anodic_current_a: current,
            contact_chord_m: chord_m,
            charge_c: self.charge_c,
            wac_m3: self.model.dissolved_volume_m3(self.charge_c),
        })
    }

    /// Notes a potential eq. 18 would have put above E_corr, or one outside the Tafel line's
    /// fitted domain; a potentiostat's potential is neither eq. 18's nor the line's.
    fn tally(&mut self, cycle: u64, area: f64, potential: f64) -> Result<(), CorrosionError> {
        if self.settings.held_v().is_some() {
            return Ok(());
        }
        if self.balance.is_none() && area > 0.0 && self.model.coupled_potential_v(area)? > potential
        {
            self.capped.note(cycle, potential);
            return Ok(());
        }
        let overpotential = potential - self.model.corrosion_potential_v;
        let fitted =
            self.settings.tafel_overpotential_min_v..=self.settings.tafel_overpotential_max_v;
        if !fitted.contains(&overpotential) {
            self.outside.note(cycle, potential);
        }
        Ok(())
    }

    /// The cycles a solve stands for after its own, `duration_s` in all, at the current of
    /// its `reading`.
    pub(super) fn skipped(&mut self, reading: &Reading, duration_s: f64) {
        self.charge_c += reading.anodic_current_a * duration_s;
        if let Some(spots) = &self.last_spots {
            let cycles = (duration_s / self.sliding.period_s()).round() as u64;
            self.ages.repeat(spots, cycles, self.sliding);
        }
    }

    /// How the anodic area is chosen and what it came to, for the `corrosion` model's reason.
    pub(super) fn describe(&self) -> String {
        let settings = self.settings;
        let tau = settings.repassivation_time_s;
        let q_p = settings.repassivation_charge_mc_cm2();
        let area = match settings.anodic_area {
            AnodicArea::DepassivatedWake => format!(
                "the depassivated wake F / H (1 + v tau / L): the real contact stripped as it \
                 crosses the solved contact (mean chord L {}) and bare for tau = {tau} s after \
                 (Q_p = i_a tau = {q_p:.3} mC/cm^2)",
                self.chords()
            ),
            AnodicArea::HertzBand => format!(
                "the Hertz band F / H + 2a v tau: the real contact and a band {:.1} um wide \
                 bare for tau = {tau} s (Q_p = i_a tau = {q_p:.3} mC/cm^2)",
                self.hertz_width_m * 1e6
            ),
            AnodicArea::WearTrack => "the wear track (worn width x track length)".to_owned(),
            AnodicArea::RealContact => "the real contact area F / H".to_owned(),
            AnodicArea::BemContact => "the contact area of the solution (on a rough disc the \
                                       real contact area of the asperities)"
                .to_owned(),
            AnodicArea::AsperitySpots | AnodicArea::ContactSpots => format!(
                "the {} of the solved contact, island by island, each stripped as it enters \
                 the contact and repassivating until its row's next spot ({}; not fitted), \
                 each row of the track carrying its own age{}",
                if settings.anodic_area == AnodicArea::AsperitySpots {
                    "plastically deformed spots (cells at the cap)"
                } else {
                    "cells in contact"
                },
                self.kinetics().describe(),
                self.last_spots.as_ref().map_or(String::new(), |s| format!(
                    "; at the last solved cycle {} spot chord(s) on {:.1} um of stripped width, \
                     {:.3e} mm^2 of spots",
                    s.chords(),
                    s.stripped_width_m() * 1e6,
                    s.area_m2() * 1e6
                ))
            ),
        };
        let cell = self.cell_words();
        let mut reason = format!(
            "{cell} and Faraday's law; anodic area: {area}, times {}; \
             A_a / (F / H) {}; potentials against {}",
            settings.anodic_area_factor,
            self.ratios(),
            settings.reference_electrode.label()
        );
        for warning in self.warnings() {
            reason.push_str("; ");
            reason.push_str(&warning.message);
        }
        reason
    }

    /// What sets the potential, in words.
    fn cell_words(&self) -> String {
        if let Some(applied_v) = self.settings.held_v() {
            let bare = self.settings.bare_metal();
            let share = bare.held(&self.model, 1.0, applied_v).map_or(0.0, |c| {
                c.anodic_current_a / self.model.anodic_current_density_a_m2
            });
            let passive_ma =
                Balance::passive_current_a(&self.model, self.model.exposed_area_m2, applied_v)
                    * 1e3;
            return format!(
                "held at {applied_v} V by a potentiostat: the bare spots dissolve at {share:.4} \
                 of i_a there (the bare metal's corrosion potential {} V); beside them the \
                 passive area passes a constant {passive_ma:.4e} mA (negative: cathodic), which \
                 the potentiostat's current adds to each record's anodic current;",
                bare.bare_corrosion_potential_v.unwrap_or(f64::NAN)
            );
        }
        match &self.balance {
            None => "eq. 18 galvanic coupling (capped at E_corr),".to_owned(),
            Some(b) => format!(
                "the galvanic cell balanced at open circuit (the passive area's own current \
                 kept{}, ohmic drop {} ohm),",
                b.bare_corrosion_potential_v
                    .map_or(", no bare-metal floor".to_owned(), |v| format!(
                        ", the bare metal's corrosion potential {v} V as the floor"
                    )),
                b.ohmic_resistance_ohm
            ),
        }
    }

    /// The solved contact's mean chord at the first and the last solved cycle, in words.
    fn chords(&self) -> String {
        let chord = |s: Option<Snapshot>| {
            s.and_then(|s| s.chord_m)
                .map_or("none".to_owned(), |c| format!("{:.1} um", c * 1e6))
        };
        let at = |s: Option<Snapshot>| s.map_or(0, |s| s.cycle);
        format!(
            "{} at cycle {}, {} at cycle {}",
            chord(self.first),
            at(self.first),
            chord(self.last),
            at(self.last)
        )
    }

    /// A_a / (F / H) at the first and the last solved cycle, in words.
    fn ratios(&self) -> String {
        match (self.first, self.last) {
            (Some(first), Some(last)) => format!(
                "{:.1} at cycle {}, {:.1} at cycle {}",
                first.to_real_contact, first.cycle, last.to_real_contact, last.cycle
            ),
            _ => "not computed (no cycle solved)".to_owned(),
        }
    }

    /// What the run should say about its potentials, at the anodic area that gave them: the
    /// records capped at E_corr and those outside the Tafel line's fitted domain.
    pub(super) fn warnings(&self) -> Vec<FieldWarning> {
        const AREA: &str = "corrosion.anodic_area";
        let mut warnings = Vec::new();
        if let Some((share, cycle)) = self.barest.filter(|(s, _)| *s > INCOMPLETE_REPASSIVATION) {
            warnings.push(FieldWarning::new(
                "corrosion.repassivation_time_s",
                format!(
                    "incomplete repassivation: at cycle {cycle} {:.0}% of the stripped track was \
                     still bare over the revolution (a revolution of {} s against the \
                     transient's {} s): the film has no time to regrow between passes, and the \
                     anodic area tends to the stripped width times the track",
                    share * 100.0,
                    self.sliding.period_s(),
                    self.settings.repassivation_time_s
                ),
            ));
        }
        if let Some(first) = self.capped.first_cycle {
            warnings.push(FieldWarning::new(
                AREA,
                format!(
                    "eq. 18 put the potential above E_corr at {} solved cycle(s), the first at \
                 cycle {first}: the coupled current density i_a A_a / A_c was below the Tafel \
                 line's own current at E_corr ({:.3e} A/cm^2), where eq. 18 does not hold, \
                 and the potential was capped at E_corr ({} V)",
                    self.capped.count,
                    self.model.line_corrosion_current_density_a_m2() * 1e-4,
                    self.model.corrosion_potential_v
                ),
            ));
        }
        if let Some(first) = self.outside.first_cycle {
            let e_corr = self.model.corrosion_potential_v;
            warnings.push(FieldWarning::new(
                AREA,
                format!(
                    "the potential during rubbing lay outside the domain the Tafel line was \
                 fitted on ({:.3} to {:.3} V) at {} solved cycle(s), the first at cycle \
                 {first} ({:.3} to {:.3} V): a_c and b_c are extrapolated there",
                    e_corr + self.settings.tafel_overpotential_min_v,
                    e_corr + self.settings.tafel_overpotential_max_v,
                    self.outside.count,
                    self.outside.lowest_v,
                    self.outside.highest_v
                ),
            ));
        }
        warnings
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::Grid;

    fn surface<'a>(groove: &'a Groove, contact: ContactGeometry) -> Surface<'a> {
        Surface {
            groove,
            contact,
            load_n: 5.0,
            hardness_pa: 2.5e9,
            track_length_m: 0.0188,
            spots: None,
        }
    }

    #[test]
    fn a_capped_record_and_one_outside_the_tafel_domain_are_said() {
        let mut scene = Scene::default();
        let grid = Grid::square(16, 160e-6).expect("a grid");
        let groove = Groove::new(&grid);
        let contact = ContactGeometry {
            area_m2: 6.5e-9,
            swept_width_m: 90e-6,
        };
        if let Some(c) = scene.corrosion.as_mut() {
            // F / H = 2e-9 m^2 alone is below the cap's 3.1e-8 m^2 (corrosion's tests).
            c.anodic_area = AnodicArea::RealContact;
        }
        let mut cell = Cell::of(&scene, 44e-6).expect("corrosion");
        let reading = cell
            .solved_cycle(1, &surface(&groove, contact), 1.0)
            .expect("valid area");
        assert!((reading.potential_v - -0.10).abs() < 1e-15);
        assert_eq!(cell.capped.count, 1);
        assert_eq!(cell.outside.count, 0);
        // 1e5 F / H = 2e-4 m^2 of the 2.56e-4 m^2 electrode: i_a A_a / A_c = 3.57e-2 A/cm^2
        // and eq. 18 gives -3.41 + 0.56 x 1.447 = -2.60 V, below the scan's -1.1 V.
        if let Some(c) = scene.corrosion.as_mut() {
            c.anodic_area_factor = 1e5;
        }
        let mut cell = Cell::of(&scene, 44e-6).expect("corrosion");
        let reading = cell
            .solved_cycle(3, &surface(&groove, contact), 1.0)
            .expect("valid area");
        assert!(reading.potential_v < -1.1, "{}", reading.potential_v);
        let warnings = cell.warnings();
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(
            warnings[0].message.contains("first at cycle 3"),
            "{warnings:?}"
        );
        assert_eq!(warnings[0].path, "corrosion.anodic_area");
    }

    #[test]
    fn charge_and_wac_follow_the_current_over_skipped_cycles() {
        let scene = Scene::default();
        let grid = Grid::square(16, 160e-6).expect("a grid");
        let groove = Groove::new(&grid);
        let contact = ContactGeometry {
            area_m2: 6.5e-9,
            swept_width_m: 90e-6,
        };
        let mut cell = Cell::of(&scene, 44e-6).expect("corrosion");
        let reading = cell
            .solved_cycle(1, &surface(&groove, contact), 1.0)
            .expect("valid area");
        cell.skipped(&reading, 9.0);
        let after = cell
            .solved_cycle(11, &surface(&groove, contact), 1.0)
            .expect("valid area");
        // The same current for 11 s in all: 11 times the first second, a few roundings.
        let ratio = after.charge_c / reading.charge_c;
        assert!((ratio - 11.0).abs() < 1e-12, "{ratio}");
        let faraday = cell.model().dissolved_volume_m3(after.charge_c);
        assert!((after.wac_m3 - faraday).abs() <= f64::EPSILON * faraday);
    }
}
