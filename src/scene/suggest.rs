//! Near misses: the known name closest to a mistyped one (`test.load` for `test.load_n`,
//! `dalmau2018` for `dalmau2018-316l`), for the "did you mean" of a refusal.

use super::fields::FIELDS;

/// Edits (insertions, deletions, substitutions) from `a` to `b`, Levenshtein's distance.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substituted = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substituted.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// The candidate nearest to `typed`, if it is near enough to be meant: within a third of
/// the typed name's length in edits (at least 2), or starting with it (4 letters or more),
/// so `lod_n` finds `load_n` and `dalmau2018` finds `dalmau2018-316l` while an unrelated
/// word finds nothing.
pub fn nearest<'a>(typed: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let length = typed.chars().count();
    let allowed = (length / 3).max(2);
    let begins = |candidate: &str| length >= 4 && candidate.starts_with(typed);
    candidates
        .into_iter()
        .map(|candidate| (distance(typed, candidate), candidate))
        .filter(|(d, candidate)| *d <= allowed || begins(candidate))
        .min_by_key(|(d, _)| *d)
        .map(|(_, candidate)| candidate)
}

/// The scene field meant by the unknown dotted path `typed`: the field of the same object
/// whose name is nearest, or else a field of the same (or a near) name in another object
/// (`test.hardness_mpa` finds `disc.hardness_mpa`). Names are compared without their
/// object's path, so a long shared prefix does not make unrelated names look near.
pub fn field_path(typed: &str) -> Option<&'static str> {
    let (parent, key) = typed.rsplit_once('.').unwrap_or(("", typed));
    let split = |path: &'static str| path.rsplit_once('.').unwrap_or(("", path));
    let siblings: Vec<(&str, &str)> = FIELDS
        .iter()
        .map(|f| (split(f.path).1, f.path))
        .filter(|(_, path)| split(path).0 == parent)
        .collect();
    let elsewhere: Vec<(&str, &str)> = FIELDS.iter().map(|f| (split(f.path).1, f.path)).collect();
    [siblings, elsewhere].into_iter().find_map(|names| {
        let found = nearest(key, names.iter().map(|(name, _)| *name))?;
        names
            .iter()
            .find(|(name, _)| *name == found)
            .map(|(_, path)| *path)
    })
}

/// `; did you mean `x`?` for the unknown path `typed`, or "" when nothing is near.
pub fn did_you_mean_field(typed: &str) -> String {
    field_path(typed).map_or_else(String::new, |p| format!("; did you mean `{p}`?"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_misses_find_the_field_meant() {
        assert_eq!(distance("kitten", "sitting"), 3);
        assert_eq!(field_path("test.load"), Some("test.load_n"));
        assert_eq!(field_path("test.lod_n"), Some("test.load_n"));
        assert_eq!(field_path("test.load_mn"), Some("test.load_n"));
        assert_eq!(field_path("tset"), Some("test"));
        assert_eq!(field_path("test.hardness_mpa"), Some("disc.hardness_mpa"));
        assert_eq!(
            field_path("disc.surface.rms_heigth_um"),
            Some("disc.surface.rms_height_um")
        );
        assert_eq!(field_path("colour"), None);
        // A long shared path does not make an unrelated name near.
        assert_eq!(field_path("wear.archard_calibration.__probe__"), None);
    }

    #[test]
    fn a_preset_name_near_a_known_one_is_found() {
        assert_eq!(
            nearest("dalmau2018", ["dalmau2018-316l"]),
            Some("dalmau2018-316l")
        );
        assert_eq!(nearest("paper", ["dalmau2018-316l"]), None);
        assert_eq!(
            nearest("dalmau2018-316", ["dalmau2018-316l"]),
            Some("dalmau2018-316l")
        );
        assert_eq!(
            nearest("dalmau2019-316l", ["dalmau2018-316l"]),
            Some("dalmau2018-316l")
        );
    }
}
