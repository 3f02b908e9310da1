//! The ranges of the electrochemical cell's numbers that a real 316L test in chloride can
//! give, and the unit slip a number outside them most likely is. One home for these rules:
//! the scene's plausibility check ([`crate::simulation`]) and the Tafel fit's outputs
//! (`tribosim calibrate tafel`) both judge by them. Each rule warns outside what 316L in
//! chloride shows, and refuses only where no electrode of any metal in water could be.

/// What a rule found: a warning, or a refusal (no real cell gives it), with the words.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// Whether no real cell could give the value.
    pub refuse: bool,
    /// The value, the range and the likely slip.
    pub message: String,
}

impl Finding {
    fn warn(message: String) -> Option<Self> {
        Some(Self {
            refuse: false,
            message,
        })
    }

    fn refuse(message: String) -> Option<Self> {
        Some(Self {
            refuse: true,
            message,
        })
    }
}

/// `x` to four significant digits, without trailing zeros (0.1, 1.13e-6).
fn short(x: f64) -> String {
    let rounded: f64 = format!("{x:.3e}").parse().unwrap_or(x);
    format!("{rounded}")
}

/// 2.303 R T / F at 25 C, V: the Tafel slope of one electron at a transfer coefficient of 1.
const NERNST_SLOPE_V: f64 = 0.059_16;

/// Cathodic Tafel slopes measured on metals in water lie between about 0.03 V/decade
/// (hydrogen on platinum) and 1 V/decade (oxygen through a thick passive film; the paper's
/// 316L gives 0.56, Table 2).
const TAFEL_SLOPE_WARN_V_PER_DECADE: (f64, f64) = (0.03, 1.0);

/// No reaction's slope lies below 2.303 R T / (4 F) = 0.015 V/decade (four electrons at a
/// transfer coefficient of 1): the steepest a Tafel line can be.
pub const SMALLEST_TAFEL_SLOPE_V_PER_DECADE: f64 = NERNST_SLOPE_V / 4.0;

/// Outside [`SMALLEST_TAFEL_SLOPE_V_PER_DECADE`] and 10 V/decade (a transfer coefficient of
/// 0.006) a slope is a unit slip.
const TAFEL_SLOPE_REFUSE_V_PER_DECADE: (f64, f64) = (SMALLEST_TAFEL_SLOPE_V_PER_DECADE, 10.0);

/// Aqueous electrode potentials run from Li+/Li at -3.04 V to F2/F- at +2.87 V vs SHE; the
/// references offered sit within 0.25 V of SHE. A magnitude above this is a slip (mV as V).
const POTENTIAL_REFUSE_V: f64 = 3.5;

/// Water's stability window at pH 0 to 14 spans about -0.83 to +1.23 V vs SHE; a stainless
/// steel's E_corr in chloride lies well inside (-0.4 to +0.3 V vs Ag/AgCl is the usual).
const POTENTIAL_WARN_V: f64 = 1.5;

/// Corrosion current densities of passive 316L in chloride lie about 1e-9 to 1e-5 A/cm^2
/// (Table 2: 1.13e-6); a decade either side is still a stainless steel's. A current 1000
/// times off this lands outside it.
const CORROSION_CURRENT_WARN_A_CM2: (f64, f64) = (1e-10, 1e-4);

/// Above this no corrosion current is possible: 10 A/cm^2 exceeds the salt-film-limited
/// dissolution of any metal in water (pits reach a few A/cm^2).
const CURRENT_REFUSE_A_CM2: f64 = 10.0;

/// Bare 316L in chloride passes about 1e-4 to 1 A/cm^2 in scratch tests before it
/// repassivates (the paper takes 10 mA/cm^2, Section 5.1).
const ANODIC_CURRENT_WARN_A_CM2: (f64, f64) = (1e-4, 1.0);

/// The cathodic Tafel slope b_c, V/decade.
pub fn tafel_slope(b_c_v_per_decade: f64) -> Option<Finding> {
    let b = b_c_v_per_decade;
    let (warn_low, warn_high) = TAFEL_SLOPE_WARN_V_PER_DECADE;
    let (refuse_low, refuse_high) = TAFEL_SLOPE_REFUSE_V_PER_DECADE;
    let found = format!("b_c = {} V/decade", short(b));
    if b > refuse_high {
        return Finding::refuse(format!(
            "{found} would need a transfer coefficient below 0.006; no reaction is that slow \
             to respond: was it in mV/decade? {} mV/decade = {} V/decade",
            short(b),
            short(b * 1e-3)
        ));
    }
    if b < refuse_low {
        return Finding::refuse(format!(
            "{found} is below 2.303 RT / (4F) = {} V/decade, steeper than any reaction of up \
             to four electrons: was it in kV/decade, or ln-based in mV?",
            short(refuse_low)
        ));
    }
    (b < warn_low || b > warn_high).then(|| Finding {
        refuse: false,
        message: format!(
            "{found} is outside the {warn_low} to {warn_high} V/decade metals in water show \
             (Table 2: 0.56): check that it is in V per decade of A/cm^2"
        ),
    })
}

/// The corrosion current density a Tafel line gives at E_corr, 10^(a_c / b_c), A/cm^2:
/// what a_c says, judged against 316L in chloride. `what` names the number.
pub fn corrosion_current(what: &str, i_corr_a_cm2: f64) -> Option<Finding> {
    let (low, high) = CORROSION_CURRENT_WARN_A_CM2;
    let found = format!("{what} = {} A/cm^2", short(i_corr_a_cm2));
    if i_corr_a_cm2 > CURRENT_REFUSE_A_CM2 {
        return Finding::refuse(format!(
            "{found} exceeds any metal's dissolution current in water (about 10 A/cm^2 at \
             most): mA/cm^2 typed as A/cm^2, or A/m^2 read as A/cm^2?"
        ));
    }
    if i_corr_a_cm2 > high {
        return Finding::warn(format!(
            "{found} is above the {low:e} to {high:e} A/cm^2 of passive 316L in chloride \
             (Table 2: 1.13e-6): mA/cm^2 typed as A/cm^2? ({} mA/cm^2 is {} A/cm^2)",
            short(i_corr_a_cm2),
            short(i_corr_a_cm2 * 1e-3)
        ));
    }
    if i_corr_a_cm2 < low {
        return Finding::warn(format!(
            "{found} is below the {low:e} to {high:e} A/cm^2 of passive 316L in chloride \
             (Table 2: 1.13e-6): A/cm^2 typed as mA/cm^2 or uA/cm^2, or A/m^2 values under an \
             A/cm^2 name?"
        ));
    }
    None
}

/// E_corr, V against the scene's reference electrode.
pub fn corrosion_potential(e_corr_v: f64) -> Option<Finding> {
    let found = format!("E_corr = {} V", short(e_corr_v));
    if e_corr_v.abs() > POTENTIAL_REFUSE_V {
        return Finding::refuse(format!(
            "{found} lies beyond every aqueous electrode potential (-3.04 to +2.87 V vs SHE): \
             was it in mV? {} mV = {} V",
            short(e_corr_v),
            short(e_corr_v * 1e-3)
        ));
    }
    (e_corr_v.abs() > POTENTIAL_WARN_V).then(|| Finding {
        refuse: false,
        message: format!(
            "{found} is outside water's stability window (about -0.83 to +1.23 V vs SHE); a \
             stainless steel in chloride sits near -0.4 to +0.3 V: check the reference and \
             that it is in V"
        ),
    })
}

/// The anodic current density i_a on depassivated metal, A/cm^2.
pub fn anodic_current(i_a_a_cm2: f64) -> Option<Finding> {
    let (low, high) = ANODIC_CURRENT_WARN_A_CM2;
    let found = format!("i_a = {} A/cm^2", short(i_a_a_cm2));
    if i_a_a_cm2 > CURRENT_REFUSE_A_CM2 {
        return Finding::refuse(format!(
            "{found} exceeds any metal's dissolution current in water (about 10 A/cm^2 at \
             most, a salt film's limit): was it in mA/cm^2 ({} mA/cm^2 = {} A/cm^2) or A/m^2 \
             ({} A/m^2 = {} A/cm^2)?",
            short(i_a_a_cm2),
            short(i_a_a_cm2 * 1e-3),
            short(i_a_a_cm2),
            short(i_a_a_cm2 * 1e-4)
        ));
    }
    (i_a_a_cm2 < low || i_a_a_cm2 > high).then(|| Finding {
        refuse: false,
        message: format!(
            "{found} is outside the {low:e} to {high} A/cm^2 bare 316L passes in chloride (the \
             paper's 0.01): check that it is in A/cm^2"
        ),
    })
}

/// The numbers of a scene's `corrosion` section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cell {
    /// E_corr, V.
    pub corrosion_potential_v: f64,
    /// a_c, V.
    pub tafel_a_c_v: f64,
    /// b_c, V/decade.
    pub tafel_b_c_v_per_decade: f64,
    /// i_a, A/cm^2.
    pub anodic_current_density_a_cm2: f64,
}

/// Every rule applied to a scene's cell, with the path of the field each finding is about.
pub fn judge_cell(cell: Cell) -> Vec<(&'static str, Finding)> {
    let slope = tafel_slope(cell.tafel_b_c_v_per_decade);
    // A slope already named sets the line's current too: judged once, there.
    let line = match slope {
        Some(_) => None,
        None => corrosion_current(
            "the Tafel line's current at E_corr, 10^(a_c / b_c)",
            10f64.powf(cell.tafel_a_c_v / cell.tafel_b_c_v_per_decade),
        ),
    };
    [
        (
            "corrosion.corrosion_potential_v",
            corrosion_potential(cell.corrosion_potential_v),
        ),
        ("corrosion.tafel_b_c_v_per_decade", slope),
        ("corrosion.tafel_a_c_v", line),
        (
            "corrosion.anodic_current_density_a_cm2",
            anodic_current(cell.anodic_current_density_a_cm2),
        ),
    ]
    .into_iter()
    .filter_map(|(path, finding)| finding.map(|f| (path, f)))
    .collect()
}

/// The rules as rows of `docs/scene.md`'s plausibility table: what, field, warned, refused,
/// why.
pub fn rules() -> [[String; 5]; 4] {
    let (slope_low, slope_high) = TAFEL_SLOPE_WARN_V_PER_DECADE;
    let (slope_min, slope_max) = TAFEL_SLOPE_REFUSE_V_PER_DECADE;
    let (i_low, i_high) = CORROSION_CURRENT_WARN_A_CM2;
    let (a_low, a_high) = ANODIC_CURRENT_WARN_A_CM2;
    [
        [
            "E_corr".to_owned(),
            "`corrosion.corrosion_potential_v`".to_owned(),
            format!("beyond +-{POTENTIAL_WARN_V} V"),
            format!("beyond +-{POTENTIAL_REFUSE_V} V"),
            "water's stability window; every aqueous electrode potential (-3.04 to +2.87 V vs \
             SHE) (mV typed as V)"
                .to_owned(),
        ],
        [
            "the cathodic Tafel slope b_c".to_owned(),
            "`corrosion.tafel_b_c_v_per_decade`, and the Tafel fit's".to_owned(),
            format!("outside {slope_low} to {slope_high} V/decade"),
            format!("outside {} to {slope_max} V/decade", short(slope_min)),
            "metals in water; 2.303 RT / (4F) and a transfer coefficient of 0.006 (mV/decade \
             typed as V/decade)"
                .to_owned(),
        ],
        [
            "the Tafel line's current at E_corr, 10^(a_c / b_c)".to_owned(),
            "`corrosion.tafel_a_c_v`, and the Tafel fit's".to_owned(),
            format!("outside {i_low:e} to {i_high:e} A/cm^2"),
            format!("> {CURRENT_REFUSE_A_CM2} A/cm^2"),
            "passive 316L in chloride; any metal's dissolution (mA/cm^2 typed as A/cm^2)"
                .to_owned(),
        ],
        [
            "the anodic current density i_a".to_owned(),
            "`corrosion.anodic_current_density_a_cm2`".to_owned(),
            format!("outside {a_low:e} to {a_high} A/cm^2"),
            format!("> {CURRENT_REFUSE_A_CM2} A/cm^2"),
            "bare 316L in scratch tests; any metal's dissolution (mA/cm^2 or A/m^2 typed as \
             A/cm^2)"
                .to_owned(),
        ],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_rule_names_the_slip_at_a_thousandfold_and_passes_the_papers_values() {
        assert_eq!(tafel_slope(0.56), None);
        assert_eq!(corrosion_current("i_corr", 1.13e-6), None);
        assert_eq!(corrosion_potential(-0.10), None);
        assert_eq!(anodic_current(0.01), None);
        let slope = tafel_slope(100.0).expect("100 V/decade");
        assert!(
            slope.refuse && slope.message.contains("mV/decade"),
            "{slope:?}"
        );
        let current = corrosion_current("i_corr", 1.13e-3).expect("1000 times Table 2's");
        assert!(!current.refuse, "{current:?}");
        assert!(current.message.contains("mA/cm^2 typed as A/cm^2"));
        let potential = corrosion_potential(1e300).expect("1e300 V");
        assert!(potential.refuse && potential.message.contains("mV"));
        let potential = corrosion_potential(-100.0).expect("-100 V");
        assert!(potential.message.contains("-0.1 V"), "{potential:?}");
        let anodic = anodic_current(1000.0).expect("1000 A/cm^2");
        assert!(anodic.refuse && anodic.message.contains("mA/cm^2"));
        // Warnings, not refusals, where a real cell may still be meant.
        assert!(!tafel_slope(0.02).expect("steep").refuse);
        assert!(!anodic_current(5.0).expect("a pit's").refuse);
        assert!(!corrosion_potential(-2.0).expect("outside water").refuse);
    }
}
