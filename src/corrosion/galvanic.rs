//! The galvanic cell solved as a charge balance instead of eq. 18's closed form: the passive
//! film's own current kept, the bare metal's own corrosion potential as a floor, and an
//! ohmic drop between the anode and the cathode (`docs/corrosion.md`).
//!
//! At open circuit no current leaves the electrode, so what the bare spots (A_a) dissolve,
//! I, is what the passive area (A_c) reduces beyond its own passive balance:
//!
//! I = A_c (i_c(E) - i_0),  i_c(E) the cathodic Tafel line, i_0 = 10^(a_c / b_c) its current
//! at E_corr,
//!
//! so E = E_corr + a_c - b_c log10(i_0 + I / A_c): eq. 18 with the passive area's current
//! i_0 kept, which eq. 18 as printed drops. It equals E_corr at I = 0 and is below it for any
//! current, so the cap eq. 18 needs is not needed here. The anode sits at E - I R (R the
//! electrolyte's resistance between them) and passes i_a A_a, less the bare metal's own
//! cathodic reaction when a bare corrosion potential E_b is given: with the same Tafel slope
//! as the passive surface's (the one cathodic slope measured), the bare net current is
//! i_a (1 - 10^(-(E_an - E_b) / b_c)), zero at E_b. The potential then never falls below E_b
//! however large the anode: the bare metal's own potential bounds it.

use super::{CorrosionError, CorrosionModel};

/// What eq. 18 leaves out, given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Balance {
    /// The bare metal's own corrosion potential E_b, V (against E_corr's electrode); `None`:
    /// no floor, the bare metal passes i_a at any potential (as eq. 18 assumes).
    pub bare_corrosion_potential_v: Option<f64>,
    /// Electrolyte resistance between the bare spots and the passive area, ohm.
    pub ohmic_resistance_ohm: f64,
}

/// The balanced cell at one anodic area.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coupling {
    /// The electrode's potential, what the reference electrode reads near the passive
    /// surface, V.
    pub potential_v: f64,
    /// The bare spots' net anodic current, A.
    pub anodic_current_a: f64,
}

/// Bisection steps: the current's interval halves each step, so 200 steps reach the last
/// bit of any f64 interval.
const BISECTIONS: usize = 200;

impl Balance {
    /// The cell `model` balanced at the anodic (bare-equivalent) area `anodic_area_m2`.
    pub fn couple(
        &self,
        model: &CorrosionModel,
        anodic_area_m2: f64,
    ) -> Result<Coupling, CorrosionError> {
        let cathode_m2 = model.cathodic_area_m2(anodic_area_m2)?;
        let i_0 = model.line_corrosion_current_density_a_m2();
        let cathode_v = |current_a: f64| model.tafel_potential_v(i_0 + current_a / cathode_m2);
        let bare_a = |current_a: f64| {
            let anode_v = cathode_v(current_a) - current_a * self.ohmic_resistance_ohm;
            anodic_area_m2 * self.bare_current_density_a_m2(model, anode_v)
        };
        let full_a = model.anodic_current_a(anodic_area_m2);
        let current_a =
            if self.bare_corrosion_potential_v.is_none() && self.ohmic_resistance_ohm == 0.0 {
                full_a
            } else {
                // bare_a(I) - I falls as I rises (the anode's potential falls), from >= 0 at 0
                // to <= 0 at the full i_a A_a: one root between.
                let (mut low, mut high) = (0.0, full_a);
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (low + high);
                    if mid <= low || mid >= high {
                        break;
                    }
                    if bare_a(mid) > mid {
                        low = mid;
                    } else {
                        high = mid;
                    }
                }
                0.5 * (low + high)
            };
        Ok(Coupling {
            potential_v: cathode_v(current_a),
            anodic_current_a: current_a,
        })
    }

    /// The cell held at `applied_v` by a potentiostat: the bare spots of area
    /// `anodic_area_m2` dissolve at the bare metal's net current density there (the ohmic
    /// drop is the potentiostat's to compensate), `None` without a bare corrosion potential,
    /// below which the bare metal would otherwise dissolve at i_a whatever the potential.
    pub fn held(
        &self,
        model: &CorrosionModel,
        anodic_area_m2: f64,
        applied_v: f64,
    ) -> Option<Coupling> {
        self.bare_corrosion_potential_v?;
        Some(Coupling {
            potential_v: applied_v,
            anodic_current_a: anodic_area_m2 * self.bare_current_density_a_m2(model, applied_v),
        })
    }

    /// The current the passive area `cathode_m2` passes at `applied_v` beside the bare spots,
    /// its film's current less the cathodic reaction's, A: negative (cathodic) below E_corr.
    pub fn passive_current_a(model: &CorrosionModel, cathode_m2: f64, applied_v: f64) -> f64 {
        let i_0 = model.line_corrosion_current_density_a_m2();
        cathode_m2 * (i_0 - model.cathodic_current_density_a_m2(applied_v))
    }

    /// The bare metal's net anodic current density at `anode_v`, A/m^2.
    fn bare_current_density_a_m2(&self, model: &CorrosionModel, anode_v: f64) -> f64 {
        let i_a = model.anodic_current_density_a_m2;
        match self.bare_corrosion_potential_v {
            None => i_a,
            Some(floor) => {
                let own = 10f64.powf(-(anode_v - floor) / model.tafel_b_c_v_per_decade);
                (i_a * (1.0 - own)).max(0.0)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::corrosion::tests::paper_cell;

    const PLAIN: Balance = Balance {
        bare_corrosion_potential_v: None,
        ohmic_resistance_ohm: 0.0,
    };

    #[test]
    fn the_balance_keeps_the_passive_current_that_eq_18_drops() {
        let cell = paper_cell();
        // No anode: E_corr exactly (powf and log10 of one number).
        let none = PLAIN.couple(&cell, 0.0).expect("valid");
        assert!((none.potential_v + 0.10).abs() < 1e-13, "{none:?}");
        // Fig. 14's 0.1 mm^2: i_a A_a / A_c = 0.01 x 1e-3 / 2.559 = 3.908e-6 A/cm^2 against
        // the line's 1.228e-6 at E_corr: eq. 18 gives -3.41 - 0.56 log10(3.908e-6) =
        // -0.3815 V, the balance -3.41 - 0.56 log10(5.136e-6) = -0.4480 V (hand values to
        // four digits: 1e-4 V).
        let balanced = PLAIN.couple(&cell, 0.1e-6).expect("valid");
        let printed = cell.coupled_potential_v(0.1e-6).expect("valid");
        assert!((printed + 0.3815).abs() < 1e-4, "{printed}");
        assert!((balanced.potential_v + 0.4480).abs() < 1e-4, "{balanced:?}");
        // Far above the line's current the two agree: 10 mm^2 of bare metal.
        let large = PLAIN.couple(&cell, 10e-6).expect("valid").potential_v;
        let large_printed = cell.coupled_potential_v(10e-6).expect("valid");
        assert!(
            (large - large_printed).abs() < 1e-3,
            "{large} {large_printed}"
        );
        // Every anode lowers the potential, however small: no cap needed.
        let tiny = PLAIN.couple(&cell, 1e-12).expect("valid").potential_v;
        assert!(tiny < -0.10 && tiny > -0.1001, "{tiny}");
    }

    #[test]
    fn the_bare_metal_bounds_the_potential_and_its_current() {
        let cell = paper_cell();
        let floor = Balance {
            bare_corrosion_potential_v: Some(-0.45),
            ohmic_resistance_ohm: 0.0,
        };
        let mut last = -0.10;
        for area_mm2 in [1e-3, 0.1, 1.0, 10.0, 100.0, 250.0] {
            let c = floor.couple(&cell, area_mm2 * 1e-6).expect("valid");
            assert!(
                c.potential_v > -0.45 && c.potential_v < last,
                "{area_mm2}: {c:?}"
            );
            assert!(c.anodic_current_a <= cell.anodic_current_a(area_mm2 * 1e-6));
            last = c.potential_v;
        }
        // Far from the floor the bare metal passes i_a: 0.001 mm^2 couples at -0.1 V and
        // some, 0.35 V above -0.45 V, where 10^(-0.35 / 0.56) = 0.24 of i_a flows back.
        let small = floor.couple(&cell, 1e-9).expect("valid");
        let share = small.anodic_current_a / cell.anodic_current_a(1e-9);
        let expected = 1.0 - 10f64.powf(-(small.potential_v + 0.45) / 0.56);
        assert!((share - expected).abs() < 1e-9, "{share} {expected}");
    }

    #[test]
    fn held_below_the_bare_metals_potential_nothing_dissolves() {
        let cell = paper_cell();
        let floor = Balance {
            bare_corrosion_potential_v: Some(-0.45),
            ohmic_resistance_ohm: 0.0,
        };
        let area = 0.1e-6;
        // Cathodic protection: below -0.45 V the bare metal's own cathodic reaction wins.
        let protected = floor.held(&cell, area, -0.8).expect("a floor");
        assert!(protected.anodic_current_a.abs() < f64::MIN_POSITIVE);
        // Far above it, the full i_a: 1 - 10^(-1.05 / 0.56) = 0.9867 of it at +0.6 V.
        let anodic = floor.held(&cell, area, 0.6).expect("a floor");
        let share = anodic.anodic_current_a / cell.anodic_current_a(area);
        assert!(
            (share - (1.0 - 10f64.powf(-1.05 / 0.56))).abs() < 1e-12,
            "{share}"
        );
        assert!(PLAIN.held(&cell, area, -0.8).is_none());
        // At E_corr the passive area's net current is the line's offset from i_corr: 0 to
        // the rounding of 10^(a_c / b_c); below it, cathodic.
        let at_corr = Balance::passive_current_a(&cell, 2.5e-4, -0.10);
        assert!(at_corr.abs() < 1e-20, "{at_corr}");
        assert!(Balance::passive_current_a(&cell, 2.5e-4, -0.8) < 0.0);
    }

    #[test]
    fn an_ohmic_drop_raises_the_potential_the_reference_reads() {
        let cell = paper_cell();
        let plain = PLAIN.couple(&cell, 0.1e-6).expect("valid");
        let ohmic = Balance {
            bare_corrosion_potential_v: Some(-1.0),
            ohmic_resistance_ohm: 1e4,
        }
        .couple(&cell, 0.1e-6)
        .expect("valid");
        // The anode sits I R below the cathode, closer to its floor: it passes less, and
        // the cathode reads a potential nearer E_corr.
        assert!(ohmic.anodic_current_a < plain.anodic_current_a);
        assert!(ohmic.potential_v > plain.potential_v);
        // The balance holds: the bare net current at E - I R is the current.
        let anode = ohmic.potential_v - ohmic.anodic_current_a * 1e4;
        let bare = 0.1e-6 * 100.0 * (1.0 - 10f64.powf(-(anode + 1.0) / 0.56));
        assert!(
            ((bare - ohmic.anodic_current_a) / bare).abs() < 1e-9,
            "{bare} {ohmic:?}"
        );
    }
}
