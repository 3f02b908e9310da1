//! Number and markdown formatting shared by the report's sections.

/// `v` to `digits` significant digits, fixed-point.
pub(in crate::bench) fn sig(v: f64, digits: i32) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let decimals = (digits - 1 - v.abs().log10().floor() as i32).max(0);
    format!("{v:.*}", decimals as usize)
}

/// A signed relative error, or `n/a` when there is none.
pub(super) fn error(v: f64) -> String {
    if v.is_finite() {
        format!("{v:+.2e}")
    } else {
        "n/a".to_owned()
    }
}

/// A markdown table.
pub(in crate::bench) fn table(headers: &[&str], rows: &[Vec<String>]) -> String {
    let line = |cells: &[String]| {
        let escaped: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
        format!("| {} |\n", escaped.join(" | "))
    };
    let headers: Vec<String> = headers.iter().map(|h| (*h).to_owned()).collect();
    let mut out = line(&headers);
    out += &format!("|{}\n", "---|".repeat(headers.len()));
    for row in rows {
        out += &line(row);
    }
    out
}

/// A markdown list.
pub(super) fn bullets(items: &[String]) -> String {
    items.iter().map(|i| format!("- {i}\n")).collect()
}

/// A point's label: the setting up to its first qualifier.
pub(super) fn short(setting: &str) -> &str {
    let end = [", ", " ("]
        .iter()
        .filter_map(|sep| setting.find(sep))
        .min()
        .unwrap_or(setting.len());
    &setting[..end]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pipes_in_a_cell_are_escaped() {
        let text = table(&["a"], &[vec!["x | y".into()]]);
        assert!(text.ends_with("| x \\| y |\n"), "{text}");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(sig(0.002_957, 3), "0.00296");
        assert_eq!(sig(3.7725, 3), "3.77");
        assert_eq!(sig(106.17, 3), "106");
        assert_eq!(sig(0.0, 3), "0");
    }
}
