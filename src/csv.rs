//! CSV cells as every CSV file tribosim writes has them (a result's cycles, a study's
//! summary): RFC 4180 quoting, and text that a spreadsheet would run as a formula
//! neutralised.
//!
//! The files are comma-separated, but a spreadsheet in a locale whose list separator is `;`
//! (most of Europe) splits unquoted lines at semicolons, and some split at tabs, so a cell
//! holding any of `,` `;` a tab, a quote or a line break is quoted: one cell in every
//! locale.
//!
//! A cell that starts with `=`, `+`, `-`, `@`, a tab or a carriage return is a formula to
//! Excel, LibreOffice and Google Sheets, so a value a client chose (a study axis's string,
//! an error quoting it) could run `=HYPERLINK(...)` in whoever opens the file. As OWASP's
//! "CSV Injection" page recommends, such a cell is prefixed with a single quote, which the
//! spreadsheets show as text. So is a cell any part of which, after a separator or a line
//! break, starts so: an importer that splits there after all (a "text to columns" at `;`,
//! a paste into Google Sheets) would otherwise make that part a formula cell. Numbers are
//! left alone: `-0.35` is a number to a spreadsheet and must stay one.

use std::borrow::Cow;

/// The characters that start a formula.
const FORMULA_STARTS: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// The characters at which some spreadsheet or importer starts a new cell or row.
const SPLITS: [char; 5] = [',', ';', '\t', '\r', '\n'];

/// The characters that make a cell quoted: the splits and the quote itself.
const QUOTED: [char; 6] = [',', ';', '\t', '\r', '\n', '"'];

/// Whether some spreadsheet could read `text`, or a part of it after a split, as a formula.
fn could_be_formula(text: &str) -> bool {
    text.starts_with(FORMULA_STARTS)
        || text
            .match_indices(SPLITS)
            .any(|(at, split)| text[at + split.len()..].starts_with(FORMULA_STARTS))
}

/// `text` as one CSV cell: a number as it is; text that could be a formula, at its start or
/// after a separator or line break, prefixed with `'`; then quoted when it holds a comma, a
/// semicolon, a tab, a quote or a line break.
pub fn cell(text: &str) -> Cow<'_, str> {
    let neutral: Cow<'_, str> = if could_be_formula(text) && text.trim().parse::<f64>().is_err() {
        Cow::Owned(format!("'{text}"))
    } else {
        Cow::Borrowed(text)
    };
    if neutral.contains(QUOTED) {
        Cow::Owned(format!("\"{}\"", neutral.replace('"', "\"\"")))
    } else {
        neutral
    }
}

/// One CSV line of `cells`, each through [`cell`], ended by `ending`.
pub fn line<S: AsRef<str>>(cells: &[S], ending: &str) -> String {
    let mut line = cells
        .iter()
        .map(|c| cell(c.as_ref()))
        .collect::<Vec<_>>()
        .join(",");
    line.push_str(ending);
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formulas_are_neutralised_and_numbers_kept() {
        assert_eq!(
            cell("=HYPERLINK(\"http://x\")"),
            "\"'=HYPERLINK(\"\"http://x\"\")\""
        );
        assert_eq!(cell("+1+2"), "'+1+2");
        assert_eq!(cell("-cmd"), "'-cmd");
        assert_eq!(cell("@SUM(A1)"), "'@SUM(A1)");
        assert_eq!(cell("\t=1"), "\"'\t=1\"");
        assert_eq!(cell("\r=1"), "\"'\r=1\"");
        for number in ["-0.35", "+2", "-1.5e-7", "0", "-inf"] {
            assert_eq!(cell(number), number);
        }
        assert_eq!(cell("a, b"), "\"a, b\"");
        assert_eq!(cell("plain"), "plain");
        assert_eq!(line(&["1", "=2+3", "x"], "\r\n"), "1,'=2+3,x\r\n");
    }

    /// The value: in a semicolon locale `1;=cmd|' /C calc'!A0` written as is was
    /// two cells, the second a formula.
    #[test]
    fn a_semicolon_is_quoted_and_a_formula_after_it_neutralised() {
        let attack = "1;=cmd|' /C calc'!A0";
        assert_eq!(cell(attack), "\"'1;=cmd|' /C calc'!A0\"");
        assert_eq!(cell("a;b"), "\"a;b\"");
        assert_eq!(cell("x;-1"), "\"'x;-1\"");
        assert_eq!(cell("a; =1"), "\"a; =1\"");
        assert_eq!(line(&["0", "a;b"], "\n"), "0,\"a;b\"\n");
    }

    #[test]
    fn a_tab_is_quoted_and_a_formula_after_it_neutralised() {
        assert_eq!(cell("a\tb"), "\"a\tb\"");
        assert_eq!(cell("a\t@SUM(A1)"), "\"'a\t@SUM(A1)\"");
        assert_eq!(cell("a\t\tb"), "\"'a\t\tb\"");
        assert_eq!(cell("load,+1"), "\"'load,+1\"");
        assert_eq!(cell("line\n=1"), "\"'line\n=1\"");
        assert_eq!(cell("line\r\nok"), "\"line\r\nok\"");
    }
}
