//! CSV cells as every CSV file tribosim writes has them (a result's cycles, a study's
//! summary): RFC 4180 quoting, and text that a spreadsheet would run as a formula
//! neutralised.
//!
//! A cell that starts with `=`, `+`, `-`, `@`, a tab or a carriage return is a formula to
//! Excel, LibreOffice and Google Sheets, so a value a client chose (a study axis's string,
//! an error quoting it) could run `=HYPERLINK(...)` in whoever opens the file. As OWASP's
//! "CSV Injection" page recommends, such a cell is prefixed with a single quote, which the
//! spreadsheets show as text. Numbers are left alone: `-0.35` is a number to a spreadsheet
//! and must stay one.

use std::borrow::Cow;

/// The characters that start a formula.
const FORMULA_STARTS: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// `text` as one CSV cell: a number as it is; text starting as a formula prefixed with `'`;
/// then quoted when it holds a comma, a quote or a line break.
pub fn cell(text: &str) -> Cow<'_, str> {
    let neutral: Cow<'_, str> =
        if text.starts_with(FORMULA_STARTS) && text.trim().parse::<f64>().is_err() {
            Cow::Owned(format!("'{text}"))
        } else {
            Cow::Borrowed(text)
        };
    if neutral.contains([',', '"', '\n', '\r']) {
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
        assert_eq!(cell("\t=1"), "'\t=1");
        assert_eq!(cell("\r=1"), "\"'\r=1\"");
        for number in ["-0.35", "+2", "-1.5e-7", "0", "-inf"] {
            assert_eq!(cell(number), number);
        }
        assert_eq!(cell("a, b"), "\"a, b\"");
        assert_eq!(cell("plain"), "plain");
        assert_eq!(line(&["1", "=2+3", "x"], "\r\n"), "1,'=2+3,x\r\n");
    }
}
