//! The markdown of `docs/paper.md`: each of the paper's figures beside its statements, the
//! numbers side by side, and the reason for each difference.

use crate::bench::report::format::{sig, table};
use crate::simulation::{PressureMap, SimulationResult};

use super::PaperStudy;
use super::figures::last_map;
use super::numbers::{EARLY, PaperNumbers, TABLE3, loaded_volume_mm3, plastic_gone, record};

/// The command that writes the page.
pub const COMMAND: &str = "cargo run --release -- bench paper --markdown docs/paper.md";

/// The whole page.
pub fn markdown(study: &PaperStudy) -> String {
    let n = study.numbers();
    [
        header(study),
        fig9(study),
        fig10(study),
        fig11(study, &n),
        fig12(study, &n),
        fig13(study),
        fig14(study),
        table3(study, &n),
        readings(&n),
    ]
    .join("\n")
}

fn header(study: &PaperStudy) -> String {
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
         `profiles[].loaded_depth_um`). The paper's depths in Section 5.2 match the loaded \
         ones, not the groove (Fig. 12, below).\n",
        s = study.disc_share
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
                pct(n.groove_volume_mm3[i]),
                pct(n.elastic_loaded_volume_mm3[i]),
                pct(n.loaded_volume_mm3[i]),
            ]
        })
        .collect();
    let first = loaded_volume_mm3(&study.epp, 1) * 1e3;
    let dent = (n.elastic_loaded_volume_mm3[2] - n.elastic_volume_mm3[2]) * 1e3;
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
         the measurement at 10 and 60 s, where the paper's EPP curve lies over it. The loaded \
         volume reproduces the paper's order (elastic under, EPP over the measurement early, \
         then parallel), and the EPP curve's \"prominent increase at the first cycles\": it \
         is {first:.2} at cycle 1. At 300 s both loaded volumes exceed Table 3 (by the \
         elastic dent, a constant {dent:.2} on the elastic run): the paper's text gives no \
         value of its curves there, so whether they also sit above 1.18 is a gap this page \
         cannot close. That volume depends on the window (the elastic dent still adds \
         0.06 um at +-128 um), so it is a weak quantity; the depths of Fig. 12 are the strong \
         evidence that the paper plots the loaded surface. Both models exceed Table 3 at 300 \
         s since k is fitted on the 3600 s point (Section 5.2: \"only the final value of wear \
         volume is used for determining the wear coefficient\").\n",
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
            format!("{:.3}", n.groove_depth_um[0]),
            format!("{:.3}", n.loaded_depth_um[0]),
            format!("{:.3}", n.formula_depth_um[0]),
            format!("{:.3}", approach(10)),
        ],
        vec![
            "300".to_owned(),
            "does not reach 1 um".to_owned(),
            format!("{:.3}", n.groove_depth_um[1]),
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
         The groove is {g10:.2} um at 10 cycles, not 0.5; the loaded surface is {l10:.2} um, \
         and {l300:.2} um at 300 (< 1 um): both of the paper's depths. The solved field and \
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
        g10 = n.groove_depth_um[0],
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
         its value) is above it, and the paper's own model, read as the loaded surface, is \
         above it too. The readings study below shows that no reading of eq. 13 the \
         paper's words allow gives a larger stable groove.\n",
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

fn readings(n: &PaperNumbers) -> String {
    format!(
        "## The early cycles: readings of eq. 13 and the profile update\n\n\
         Section 3.2 leaves open what \"the maximum of the wear profile d_wear due to yielding \
         for each y\" accumulates, whether the yield groove enters the next solve, and from \
         which surface d_wear is measured. Each reading the words allow was run in an \
         independent Python implementation of eqs. 12-17 (2 um cells, frictionless, the same \
         hardness law, k and Y = H / 2.8), written apart from this code; tribosim's own run \
         gives the two rows marked so. Depths in um, volumes in 1e-3 mm^3 (Table 3: 0.97, \
         1.09, 1.18):\n\n\
         | reading | depth at 10 | depth at 300 | volume 10 / 60 / 300 | plastic area 0 from | against the paper |\n\
         |---|---|---|---|---|---|\n\
         | (a) each row cut to the lowest level a capped cell was pressed to, on the worn surface (tribosim, this run) | {g10:.3} | {g300:.3} | {v0} / {v1} / {v2} | cycle {gone} | Fig. 10 and 12b hold; 0.5 um at 10 s and the early volumes do not |\n\
         | (b) d_wear measured from the unworn surface and accumulated | 2.39 | runaway | 4.41 at 10 | never | refuted: doubles each cycle, 4.5 x Table 3 at 10 s |\n\
         | (b2) as (b) on every contact row while any cell is capped | 3.24 | runaway | 5.87 at 10 | never | refuted |\n\
         | (c) d_wear from the unworn surface, replacing the groove | = (a) | | | | the same as (a) on a smooth disc |\n\
         | (d) eq. 16's sum over x applied to the yield profile | 330 | runaway | 1.75 at cycle 1 | never | refuted: mesh-dependent (doubles with 1 um cells), unstable |\n\
         | (e1) the yield groove kept out of the next solve, maxima accumulated | 0.79 | 3.33 | 0.667 / 2.04 / 2.97 | ~60-100 cycles | refuted by Fig. 10 (cap to ~10) and 12b (< 1 um) |\n\
         | (e2) as (e1), a running maximum | 0.125 | 0.71 | 0.121 / 0.301 / 1.132 | ~60-100 cycles | refuted by Fig. 10 |\n\
         | (e3) eq. 17 with its printed sign (wear narrows the gap) | | | | never | refuted: the groove draws load and deepens itself |\n\
         | (g) the uncapped solve's approach with the capped pressures' displacement | 0.11 at cycle 1 | | | | the same order as (a) |\n\
         | (h) rigid-perfectly-plastic bound: the whole load at Y, no elastic recovery | 0.29-0.30 | | | | even this bound on (a)'s mechanism is under 0.5 |\n\
         | (f) (a), the figures showing the loaded surface (tribosim, this run) | {l10:.3} | {l300:.3} | {w0} / {w1} / {w2} | cycle {gone} | all four: cap gone ~10, 0.5 um at 10 s, < 1 um at 300, EPP over Table 3 early |\n\n\
         Only (f) reproduces the four statements, and it changes no equation: s comes from the \
         elastic constants, not a fit. So reading (a) stays the model, and the result reports \
         both depths. The early shortfall of the groove against Table 3 is not explained by a \
         different eq. 13: the readings that give a deeper unloaded groove either run away or \
         keep the cap for tens of cycles against Fig. 10, and even the rigid-plastic bound \
         (h) gives 0.3 um. The authors' thesis or a follow-up stating the implementation was \
         not found (searched: the A. Dalmau thesis, the BEM wear papers of the same group, \
         the follow-up Section 5.1 announces).\n",
        g10 = n.groove_depth_um[0],
        g300 = n.groove_depth_um[1],
        l10 = n.loaded_depth_um[0],
        l300 = n.loaded_depth_um[1],
        v0 = sig(n.groove_volume_mm3[0] * 1e3, 3),
        v1 = sig(n.groove_volume_mm3[1] * 1e3, 3),
        v2 = sig(n.groove_volume_mm3[2] * 1e3, 3),
        w0 = sig(n.loaded_volume_mm3[0] * 1e3, 3),
        w1 = sig(n.loaded_volume_mm3[1] * 1e3, 3),
        w2 = sig(n.loaded_volume_mm3[2] * 1e3, 3),
        gone = n.plastic_gone_cycle,
    )
}
