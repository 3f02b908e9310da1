//! The markdown of `docs/paper.md`: each of the paper's figures beside its statements, the
//! numbers side by side, and the reason for each difference.

use crate::bench::report::format::{sig, table};
use crate::simulation::{PressureMap, SimulationResult};

use super::caps;
use super::figures::last_map;
use super::numbers::CapNumbers;
use super::numbers::{EARLY, PaperNumbers, TABLE3, loaded_volume_mm3, plastic_gone, record};
use super::{PaperStudy, READING_CYCLES, Reading, Statement, Verdict, statements};

/// The command that writes the page.
pub const COMMAND: &str = "cargo run --release -- bench paper --markdown docs/paper.md";

/// The whole page.
pub fn markdown(study: &PaperStudy) -> String {
    let n = study.numbers();
    [
        header(study, &n),
        fig9(study),
        fig10(study),
        fig11(study, &n),
        fig12(study, &n),
        fig13(study),
        fig14(study),
        table3(study, &n),
        statement_table(study, &n),
        caps::section(study),
        readings(study),
    ]
    .join("\n")
}

fn header(study: &PaperStudy, n: &PaperNumbers) -> String {
    format!(
        "# The paper, figure by figure\n\n\
         Dalmau et al., Wear 394-395 (2018) 166-175, Section 4 and 5.2, against tribosim. Every \
         number and figure on this page is written by one command from the repository root:\n\n\
         ```sh\n{COMMAND}\n```\n\n\
         The runs: the paper's scene `{{}}` for its whole test (3600 cycles, auto grid and cycle \
         steps: Table 3, Figs. 9, 13, 14), and its first 300 cycles on the paper's own mesh \
         (Section 4.5: 0.256 x 0.256 mm in 256 x 256 cells of 1 um), every cycle solved, for \
         the elastic-perfectly-plastic (EPP, the default) and the perfectly elastic disc \
         (`wear.plasticity: \"off\"`) (Figs. 10-12). `tests/paper.rs` holds the numbers, with \
         tolerances from the same runs on 2 um cells.\n\n\
         Two depths are reported. The *groove* is what the wear model removes (eqs. 13-17): \
         the surface a profilometer sees after the test. The *loaded* surface is the disc under \
         the ball: the groove plus the disc's own elastic displacement, its share s = \
         [(1 - nu2^2) / E2] E* = {s:.3} of the pair's (eqs. 3-6; from the elastic constants \
         alone) times the solved displacement (`cycles[].loaded_max_depth_um`, \
         `profiles[].loaded_depth_um`). The page compares the groove. That the paper's Figs. \
         11-12 show the loaded surface is a conjecture, not something the paper states: the \
         loaded depths meet its Section 5.2 numbers, but the loaded surface holds an elastic \
         dent that exists only under the ball (the purely elastic disc's is {e1:.3} um at \
         cycle 1, with no yielding), so its numbers are reported as an output and are no \
         criterion.\n",
        s = study.disc_share,
        e1 = n.elastic_loaded_first_um,
    )
}

fn fig9(study: &PaperStudy) -> String {
    let law = |t: u64| record(&study.whole, t).hardness_mpa;
    let rows: Vec<Vec<String>> = TABLE3
        .iter()
        .map(|&(t, h, ..)| {
            vec![
                t.to_string(),
                format!("{h:.0}"),
                format!("{:.0}", law(t)),
                format!("{:+.0}", law(t) - h),
            ]
        })
        .collect();
    format!(
        "## Fig. 9: the hardness law\n\n\
         ![Fig. 9](paper/fig9_hardness.svg)\n\n\
         Section 4.5: \"a logarithmic expression is used to fit the experimental evolution of \
         the hardness\"; a fast rise over the first cycles, then a quasi-asymptotic trend. \
         The run fits H = a + b ln n by least squares through Table 3 and the bulk {bulk:.0} \
         MPa at n = 1 (the `work_hardening` model; the paper prints no coefficients):\n\n{}\n\
         The law and Table 3 differ by the fit's residuals; the yield pressure is Y = H / \
         {yf} (eq. 12).\n",
        table(
            &["time (s)", "Table 3 (MPa)", "law (MPa)", "difference (MPa)"],
            &rows
        ),
        bulk = study.whole.scene.disc.hardness_mpa,
        yf = study.whole.scene.disc.yield_factor,
    )
}

/// The pressure at the cell nearest the contact's centre line and the sliding line, MPa.
fn centre(map: &PressureMap) -> f64 {
    let nearest = |v: &[f64]| {
        (0..v.len())
            .min_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
            .unwrap_or(0)
    };
    let (ix, iy) = (nearest(&map.x_um), nearest(&map.y_um));
    map.pressure_mpa
        .get(iy)
        .and_then(|row| row.get(ix))
        .copied()
        .unwrap_or(0.0)
}

/// The shape of a pressure map: length along x and width along y of the loaded cells (um),
/// the peak (MPa) and where it sits (x, y in um).
fn shape(map: &PressureMap) -> (f64, f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut peak = (0.0, 0.0, 0.0);
    for (&y, row) in map.y_um.iter().zip(&map.pressure_mpa) {
        for (&x, &p) in map.x_um.iter().zip(row) {
            if p > 0.0 {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
            if p > peak.0 {
                peak = (p, x, y);
            }
        }
    }
    let cell = map.x_um.get(1).map_or(1.0, |x| x - map.x_um[0]);
    (x1 - x0 + cell, y1 - y0 + cell, peak.0, peak.1, peak.2)
}

fn fig10(study: &PaperStudy) -> String {
    let describe = |result: &SimulationResult| {
        let (map, cap) = last_map(result);
        let (length, width, peak, px, py) = shape(map);
        let r = record(result, map.cycle);
        vec![
            map.cycle.to_string(),
            format!("{length:.0} x {width:.0}"),
            format!("{:.2}", width / length),
            format!("{peak:.0} (Y = {cap:.0})"),
            format!("{:.0}", centre(map)),
            format!(
                "x {px:+.0}, y {py:+.0} ({:.0}% of the half-width)",
                200.0 * py.abs() / width
            ),
            sig(r.plastic_area_mm2, 3),
        ]
    };
    let first = record(&study.epp, 1);
    let gone = plastic_gone(&study.epp);
    format!(
        "## Fig. 10: the pressure maps at 6 and 300 cycles\n\n\
         ![Fig. 10a](paper/fig10a_pressure_6.svg) ![Fig. 10b](paper/fig10b_pressure_300.svg)\n\n\
         Section 4.5: during the initial cycles the pressure \"reaches the yielding \
         condition\"; the contact changes \"from an initial circular or elliptical area to a \
         rectangular one with rounded corners\"; \"after those initial cycles (around 10 \
         cycles) all the contact pressures reduce below the yielding condition\"; then \"the \
         maximum contact pressure is located at the edges of the wear track groove\", and the \
         contact grows in width (y) and shortens in length (x).\n\n{}\n\
         Measured: the contact at cycle 1 is Hertz's circle (plastic area {p1:.2e} mm^2); the \
         cap holds until cycle {last}, and the plastic area is 0 from cycle {gone} on (the \
         paper: around 10). At 300 cycles the contact is wider than long (it widened in y \
         and shortened in x, as the paper says) with straight sides and rounded corners, and \
         its peak sits at the groove's edge, as the paper says, though only {edge:.1}% above \
         the centre: across the worn groove the pressure is nearly uniform, the conformity \
         Archard's wear drives towards. No difference to explain beyond the paper's \
         \"around\".\n",
        table(
            &[
                "cycle",
                "length x width (um)",
                "width / length",
                "peak (MPa)",
                "at the centre (MPa)",
                "peak at",
                "plastic area (mm^2)"
            ],
            &[describe(&study.first6), describe(&study.epp)],
        ),
        p1 = first.plastic_area_mm2,
        edge = {
            let (map, _) = last_map(&study.epp);
            100.0 * (shape(map).2 / centre(map) - 1.0)
        },
        last = gone.saturating_sub(1),
    )
}

fn fig11(study: &PaperStudy, n: &PaperNumbers) -> String {
    let rows: Vec<Vec<String>> = EARLY
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let measured = TABLE3.iter().find(|r| r.0 == t).map_or(0.0, |r| r.2);
            let pct = |v: f64| {
                format!(
                    "{} ({:+.0}%)",
                    sig(v * 1e3, 3),
                    100.0 * (v * 1e3 / measured - 1.0)
                )
            };
            vec![
                t.to_string(),
                format!("{measured:.2}"),
                pct(n.elastic_volume_mm3[i]),
                pct(n.epp.groove_volume_mm3[i]),
                pct(n.elastic_loaded_volume_mm3[i]),
                pct(n.loaded_volume_mm3[i]),
            ]
        })
        .collect();
    let first = loaded_volume_mm3(&study.epp, 1) * 1e3;
    let dent = (n.elastic_loaded_volume_mm3[2] - n.elastic_volume_mm3[2]) * 1e3;
    let over = |v: f64| 100.0 * (v * 1e3 / TABLE3[2].2 - 1.0);
    let (e300, p300) = (
        over(n.elastic_loaded_volume_mm3[2]),
        over(n.loaded_volume_mm3[2]),
    );
    format!(
        "## Fig. 11: wear volume over the first 300 cycles, elastic and EPP\n\n\
         ![Fig. 11](paper/fig11_volume.svg)\n\n\
         Section 4.5: the elastic material's volume \"follows a perfect linear evolution\"; \
         the EPP one \"shows a prominent increase at the first cycles followed by a linear \
         evolution parallel to the perfectly elastic behavior\"; the measurements lie between \
         the two: the elastic model \"underestimates wear at the beginning of the test, while \
         the EPP behaviour overestimates it\".\n\n\
         Volumes in 1e-3 mm^3, against Table 3; the loaded volume is the track length times \
         the loaded profile's area over the paper's 0.256 mm window:\n\n{}\n\
         The groove alone has the shape the paper describes (a step of yielding over the \
         first ~10 cycles, then Archard's line parallel to the elastic one) but lies *under* \
         the measurement at 10 and 60 s, where the paper's EPP curve lies over it. The \
         loaded columns are a conjecture about the paper's curves, not a volume of removed \
         material: they multiply a dent that exists only under the ball by the whole track \
         length. Read so, the curves follow the paper's order at 10 and 60 s, and the EPP \
         one its \"prominent increase at the first cycles\" ({first:.2} at cycle 1), but at \
         300 s both exceed Table 3, by {e300:+.0}% (elastic) and {p300:+.0}% (EPP), the \
         elastic dent alone being {dent:.2}: both would lie over the measurement, against two \
         of the paper's statements, that \"the experimental evolution of wear lies between \
         the numerical results\" and that \"at longer times, the results for the elastic \
         behaviour follow the experimental trend\". That volume also depends on the \
         window (the elastic dent still adds 0.06 um at +-128 um). Both models' grooves \
         exceed Table 3 at 300 s since k is fitted on the 3600 s point (Section 5.2: \"only \
         the final value of wear volume is used for determining the wear coefficient\").\n",
        table(
            &[
                "time (s)",
                "Table 3",
                "elastic, groove",
                "EPP, groove",
                "elastic, loaded",
                "EPP, loaded"
            ],
            &rows,
        ),
    )
}

fn fig12(study: &PaperStudy, n: &PaperNumbers) -> String {
    let approach = |c: u64| record(&study.epp, c).approach_um;
    let rows = vec![
        vec![
            "10".to_owned(),
            "reaches rapidly 0.5 um".to_owned(),
            format!("{:.3}", n.epp.groove_depth_um[0]),
            format!("{:.3}", n.loaded_depth_um[0]),
            format!("{:.3}", n.formula_depth_um[0]),
            format!("{:.3}", approach(10)),
        ],
        vec![
            "300".to_owned(),
            "does not reach 1 um".to_owned(),
            format!("{:.3}", n.epp.groove_depth_um[1]),
            format!("{:.3}", n.loaded_depth_um[1]),
            format!("{:.3}", n.formula_depth_um[1]),
            format!("{:.3}", approach(300)),
        ],
    ];
    format!(
        "## Fig. 12: profiles at 10 and 300 cycles, with the ball\n\n\
         ![Fig. 12a](paper/fig12a_profile_10.svg) ![Fig. 12b](paper/fig12b_profile_300.svg)\n\n\
         Section 5.2: \"the maximum depth in the wear track reaches rapidly 0.5 um at 10 s\"; \
         \"the maximum (of the average) wear depth does not reach 1 um at 300 cycles\". The \
         caption plots the numerical profiles with \"the non-deformed profile of the alumina \
         ball\"; Section 4.5: \"the shape of the wear track almost matches the area occupied \
         by the ball\".\n\n\
         Deepest point, um (EPP, the paper's mesh):\n\n{}\n\
         The groove is {g10:.3} um at 10 cycles, not 0.5, and {g300:.3} um at 300 (< 1 um). \
         The loaded surface is {l10:.3} um at 10 cycles, of which {g10:.3} is groove and \
         {dent10:.3} the elastic dent under the ball, and {l300:.3} um at 300 (< 1 um): it \
         meets both of the paper's depths, but whether the paper's profiles are the loaded \
         surface is a conjecture, and the elastic disc's loaded surface is already \
         {e1:.3} um at cycle 1 without any yielding. The solved field and \
         the one-number formula D + s (delta - D) (s = {s:.3}) agree to {diff:.4} um at the \
         deepest point: the field is the surface under the cycle's pressure, before that \
         cycle's Archard pass, the formula takes the groove after it, so they differ by s \
         times one cycle's Archard depth. The \
         loaded profile is what lies under the ball in the figure, which the undeformed ball \
         drawn at the solved approach overlaps by the ball's own share (1 - s) of the \
         displacement.\n",
        table(
            &[
                "cycle",
                "the paper",
                "groove",
                "loaded (solved field)",
                "loaded (formula)",
                "approach delta"
            ],
            &rows,
        ),
        g10 = n.epp.groove_depth_um[0],
        g300 = n.epp.groove_depth_um[1],
        dent10 = n.loaded_depth_um[0] - n.epp.groove_depth_um[0],
        e1 = n.elastic_loaded_first_um,
        l10 = n.loaded_depth_um[0],
        l300 = n.loaded_depth_um[1],
        s = study.disc_share,
        diff = (n.loaded_depth_um[0] - n.formula_depth_um[0])
            .abs()
            .max((n.loaded_depth_um[1] - n.formula_depth_um[1]).abs()),
    )
}

fn fig13(study: &PaperStudy) -> String {
    let wac = |t: u64| record(&study.whole, t).wac_volume_mm3.unwrap_or(0.0);
    let total = |t: u64| {
        let r = record(&study.whole, t);
        r.total_volume_mm3.unwrap_or(r.wear_volume_mm3)
    };
    format!(
        "## Fig. 13: the wear-accelerated corrosion volume\n\n\
         ![Fig. 13](paper/fig13_wac.svg)\n\n\
         Section 5.1: \"a linear increase with time was observed because the depassivation of \
         the whole wear track was considered\"; the text gives no value. tribosim's default \
         anodic area is the depassivated wake (`corrosion.md`), not the whole track: V_WAC is \
         {w1800:.3e} mm^3 at 1800 s and {w3600:.3e} at 3600 s ({share:.1}% of the total loss, \
         the wear track's {t3600:.3e}); its ratio 3600 s / 1800 s is {ratio:.2} (2 for a straight line): the \
         depassivated wake grows as the contact's chord shortens (Fig. 14). The difference \
         from the paper's line is the anodic area chosen (a named model, \
         `corrosion.anodic_area`), not a fit.\n",
        w1800 = wac(1800),
        w3600 = wac(3600),
        share = 100.0 * wac(3600) / total(3600),
        t3600 = total(3600),
        ratio = wac(3600) / wac(1800),
    )
}

fn fig14(study: &PaperStudy) -> String {
    let load = study.whole.scene.load_n();
    let rows: Vec<Vec<String>> = TABLE3
        .iter()
        .map(|&(t, ..)| {
            let r = record(&study.whole, t);
            let real = load / r.hardness_mpa;
            let anodic = r.anodic_area_mm2.unwrap_or(0.0);
            vec![
                t.to_string(),
                format!("{real:.2e}"),
                format!("{anodic:.2e}"),
                format!("{:.0}", anodic / real),
                format!("{:.0}", r.contact_chord_um.unwrap_or(0.0)),
            ]
        })
        .collect();
    format!(
        "## Fig. 14: real and depassivated areas\n\n\
         ![Fig. 14](paper/fig14_areas.svg)\n\n\
         Section 5.1: the real area F / H falls as the disc hardens; the depassivated area \
         from eq. 18 at i_a = 10 mA/cm^2 is \"around 50 times higher\"; \"the Hertzian area of \
         contact lies between both values (6e-3 mm^2)\".\n\n{}\n\
         Hertz's area here is {hertz:.2e} mm^2, between the two as in the paper. The \
         ratio is near the paper's 50 but not constant: the wake is A_a = A_r (1 + v tau / \
         L) (`corrosion.md`), its length v tau fixed by the fitted `repassivation_time_s`, \
         while the contact's mean chord L shortens as the groove widens the contact (Fig. \
         10), so A_a grows while A_r falls. The paper derives A_a from its measured \
         potentials through eq. 18 and finds the ratio constant; a constant ratio would need \
         a chord that stays constant. This is a named difference of the wake model \
         (`corrosion.anodic_area`), not of the contact.\n",
        table(
            &[
                "time (s)",
                "A_r = F / H (mm^2)",
                "A_a (mm^2)",
                "A_a / A_r",
                "chord L (um)"
            ],
            &rows
        ),
        hertz = study.hertz_area_mm2,
    )
}

fn table3(study: &PaperStudy, n: &PaperNumbers) -> String {
    let rows: Vec<Vec<String>> = TABLE3
        .iter()
        .enumerate()
        .map(|(i, &(t, _, v, spread))| {
            let loaded = EARLY
                .iter()
                .position(|&c| c == t)
                .map_or("-".to_owned(), |j| sig(n.loaded_volume_mm3[j] * 1e3, 3));
            let wear = n.whole_volume_mm3[i] * 1e3;
            vec![
                t.to_string(),
                format!("{v:.2} ± {spread:.1}"),
                format!("{} ({:+.0}%)", sig(wear, 3), 100.0 * (wear / v - 1.0)),
                sig(n.whole_mechanical_mm3[i] * 1e3, 3),
                loaded,
            ]
        })
        .collect();
    format!(
        "## Table 3: each volume\n\n\
         `{{}}` (k = {k:.4e} from the 3600 s point by eq. 14, as Section 4.5 does), in 1e-3 \
         mm^3; the groove is the total loss, since k comes from a measured total, and \
         \"mechanical\" is the groove less the corrosion volume (`wear.archard_k_basis`); \
         \"loaded\" is Fig. 11's EPP loaded volume:\n\n{}\n\
         One k through the 3600 s point meets 300 s to {e300:+.0}% and 1800 s to \
         {e1800:+.0}%. At 10 and 60 s the groove is {u10:.0}% and {u60:.0}% under: the groove is \
         what the model removes, which in the first seconds is the yield groove of eq. 13 \
         and Archard's line; the measured volume there (whose spread at 10 s, ±2.0, exceeds \
         its value) is above it. \"loaded\" reads the paper's model as the loaded surface, a \
         conjecture (Fig. 11), and is no criterion. The readings study below gives the \
         groove of each reading of eq. 13 the paper's words allow.\n",
        table(
            &[
                "time (s)",
                "Table 3",
                "groove (total)",
                "mechanical",
                "loaded"
            ],
            &rows
        ),
        k = study.whole.summary.wear.archard_k,
        e300 = 100.0 * (n.whole_volume_mm3[2] * 1e3 / TABLE3[2].2 - 1.0),
        e1800 = 100.0 * (n.whole_volume_mm3[3] * 1e3 / TABLE3[3].2 - 1.0),
        u10 = 100.0 * (1.0 - n.whole_volume_mm3[0] * 1e3 / TABLE3[0].2),
        u60 = 100.0 * (1.0 - n.whole_volume_mm3[1] * 1e3 / TABLE3[1].2),
    )
}

fn statement_table(study: &PaperStudy, n: &PaperNumbers) -> String {
    let paper = statements(&n.epp, &n.elastic_volume_mm3);
    let sourced: &CapNumbers = &study.caps[0].numbers;
    let hardening = statements(sourced, &n.elastic_volume_mm3);
    let rows: Vec<Vec<String>> = paper
        .iter()
        .zip(&hardening)
        .map(|(st, hard)| {
            let [value, verdict] = value_and_verdict(st);
            let [hard_value, hard_verdict] = value_and_verdict(hard);
            vec![
                format!("\"{}\"", st.claim),
                st.test.clone(),
                value,
                verdict,
                hard_value,
                hard_verdict,
            ]
        })
        .collect();
    format!(
        "## The paper's first cycles against the groove\n\n\
         The groove is what eq. 13 and Archard's law remove and what the paper's confocal \
         profiles measure after the test, so it is the quantity compared (depths in um, \
         volumes against Table 3; the paper's mesh; `tests/paper.rs` holds each verdict). \
         Two caps: the paper's Y = H(n) / 2.8 (the default), and the cap that hardens from \
         annealed 316L's {y0} MPa (next section):\n\n{}\n\
         The paper's cap meets the statements about the elastic model, the end of yielding \
         and the depth at 300 cycles; it misses the depth of 0.5 um at 10 s and the EPP \
         volume above the measurements at 10 and 60 s: its cap from the first pass is \
         Tabor's flow stress of metal already strained 8%, so the fresh surface yields \
         less under it than the paper's profiles show. The hardening cap meets the EPP \
         volumes but overshoots both depths and yields for longer, so the paper's surface \
         yields between the two. The loaded surface meets \
         the two depths, but that it is what the paper's Figs. 11-12 plot is a conjecture, \
         and it is no criterion here (Fig. 12 above).\n",
        table(
            &[
                "the paper",
                "asked of the groove",
                "paper's cap",
                "verdict",
                "hardening cap",
                "verdict"
            ],
            &rows
        ),
        y0 = study.caps[0].initial_yield_mpa,
    )
}

fn value_and_verdict(st: &Statement) -> [String; 2] {
    [
        format!("{:.*}{}", st.decimals, st.value, st.unit),
        match st.verdict {
            Verdict::Met => "met".to_owned(),
            Verdict::Missed(by) => format!("missed by {by:.*}{}", st.decimals, st.unit),
        },
    ]
}

fn readings(study: &PaperStudy) -> String {
    let at = |v: &[f64], cycle: u64| {
        v.get(cycle as usize - 1)
            .map_or("-".to_owned(), |x| sig(*x, 3))
    };
    let deepest = |r: Reading| study.reading(r).depth_um.last().copied().unwrap_or(0.0);
    let rows: Vec<Vec<String>> = study
        .readings
        .iter()
        .map(|run| {
            let capped_last = run.capped.iter().rposition(|&c| c).map(|i| i as u64 + 1);
            vec![
                run.reading.label().to_owned(),
                [1, 2, 5, 10].map(|c| at(&run.depth_um, c)).join(" / "),
                at(
                    &run.volume_mm3.iter().map(|v| v * 1e3).collect::<Vec<_>>(),
                    10,
                ),
                match run.depth_um.get(9).zip(run.depth_um.get(8)) {
                    Some((ten, nine)) => format!("{:.4}", ten - nine),
                    None => "-".to_owned(),
                },
                match (run.left_window_at, capped_last) {
                    (Some(c), _) => format!("contact leaves the window at cycle {c}"),
                    (None, Some(c)) if c == READING_CYCLES => "still capped".to_owned(),
                    (None, Some(c)) => format!("capped to cycle {c}"),
                    (None, None) => "never capped".to_owned(),
                },
            ]
        })
        .collect();
    format!(
        "## The early cycles: readings of eq. 13 and the profile update\n\n\
         Section 3.2 leaves open what \"the maximum of the wear profile d_wear due to yielding \
         for each y\" accumulates, whether the yield groove enters the next solve, and from \
         which surface d_wear is measured. Each reading the words allow is cycled by the same \
         loop (`src/bench/paper/readings.rs`): the scene's contact solver on the paper's \
         window in 2 um cells, the reading's yield update, one Archard pass, {cycles} cycles. \
         Depths in um, volumes in 1e-3 mm^3 (Table 3 at 10 s: 0.97):\n\n{}\n\
         (a) is tribosim's model (on 2 um cells; the paper's mesh gives {g10:.3} um at 10), \
         and (c) is the same on a smooth disc: the interpenetration from the unworn surface \
         less Archard's part is the yield groove plus the interpenetration on the worn one. \
         (h) is no bound on (a): cycled in its own groove the rigid-plastic rule keeps the \
         whole load at Y every cycle, since the ball's overlap with a groove it cut is a long \
         thin strip, and cuts deeper each cycle. By cycle 10 (a) has nearly stopped \
         cutting, and its plastic area is 0 from cycle {gone} (the paper's mesh). The \
         readings that cut a deeper groove by then either run away ((b) and (b2) are \
         {b:.0} and {b2:.0} times as deep as (a) at cycle 10; (d) and (e3) wear until the \
         contact leaves the window) or, (e1) and (h), still cut an order of magnitude more \
         per cycle than (a) at cycle 10, against Fig. 10's end of yielding around 10 \
         cycles. The \
         authors' thesis or a follow-up stating the implementation was not found (searched: \
         the A. Dalmau thesis, the BEM wear papers of the same group, the follow-up Section \
         5.1 announces).\n",
        table(
            &[
                "reading",
                "depth at cycles 1 / 2 / 5 / 10",
                "volume at 10",
                "cut in cycle 10",
                "cap"
            ],
            &rows
        ),
        cycles = READING_CYCLES,
        g10 = study.numbers().epp.groove_depth_um[0],
        gone = study.numbers().epp.plastic_gone_cycle,
        b = deepest(Reading::UnwornAccumulated) / deepest(Reading::WornSurface),
        b2 = deepest(Reading::UnwornEveryRow) / deepest(Reading::WornSurface),
    )
}
