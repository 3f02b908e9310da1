//! The reports' colours: a categorical palette for a few unordered series, and viridis for
//! ordered ones (profiles through the cycles, the pressure scale) or for more series than
//! the palette has colours, so no two series of a figure share a colour.

/// Colours distinct in print and to the colour-blind (Okabe and Ito, 2008), without their
/// black (kept for flags) and yellow (too pale on white paper).
pub const CATEGORICAL: [(u8, u8, u8); 6] = [
    (0, 114, 178),
    (213, 94, 0),
    (0, 158, 115),
    (204, 121, 167),
    (86, 180, 233),
    (230, 159, 0),
];

/// The viridis scale sampled at ten points (perceptually ordered, readable in grey).
const VIRIDIS: [(u8, u8, u8); 10] = [
    (68, 1, 84),
    (72, 40, 120),
    (62, 74, 137),
    (49, 104, 142),
    (38, 130, 142),
    (31, 158, 137),
    (53, 183, 121),
    (109, 205, 89),
    (180, 222, 44),
    (253, 231, 37),
];

/// Viridis at the fraction `f` of the scale (clamped to `[0, 1]`), interpolated.
pub fn viridis(f: f64) -> (u8, u8, u8) {
    let at = f.clamp(0.0, 1.0) * (VIRIDIS.len() - 1) as f64;
    let i = (at.floor() as usize).min(VIRIDIS.len() - 2);
    let u = at - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * u).round() as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The colour of each of `n` series: the categorical palette while it lasts, else viridis
/// from its dark end to 90% (its last tenth is too pale to see as a thin line).
pub fn series_colours(n: usize) -> Vec<(u8, u8, u8)> {
    if n <= CATEGORICAL.len() {
        return CATEGORICAL[..n].to_vec();
    }
    (0..n)
        .map(|i| viridis(0.9 * i as f64 / (n - 1) as f64))
        .collect()
}

/// `#rrggbb`.
pub fn hex((r, g, b): (u8, u8, u8)) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_two_series_share_a_colour_however_many_there_are() {
        for n in [1, 6, 7, 11, 30] {
            let colours = series_colours(n);
            let mut unique = colours.clone();
            unique.sort_unstable();
            unique.dedup();
            assert_eq!(unique.len(), n, "{n} series: {colours:?}");
        }
    }

    #[test]
    fn viridis_runs_from_dark_purple_to_yellow() {
        assert_eq!(hex(viridis(0.0)), "#440154");
        assert_eq!(hex(viridis(1.0)), "#fde725");
        assert_eq!(viridis(2.0), viridis(1.0));
    }
}
