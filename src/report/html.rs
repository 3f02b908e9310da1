//! The report's HTML: the page around the sections, with the print rules that fit it to A4
//! and Letter, and the pieces every section is made of (escaped text, tables, numbers).

use std::fmt::Write;

/// The print rules and the screen look. A4 is 210 mm wide and Letter 215.9 mm: with 15 mm
/// margins the narrower printable width is A4's 180 mm, so every block is at most the
/// page's width (`max-width: 100%`), figures scale to it, long words (hashes, field paths)
/// break anywhere, and tables lay out to the width given rather than their content's.
const STYLE: &str = r#"
@page { size: auto; margin: 15mm; }
* { box-sizing: border-box; }
html { font: 10.5pt/1.4 "DejaVu Sans", "Helvetica Neue", Arial, sans-serif; color: #111; }
body { margin: 0 auto; max-width: 180mm; padding: 4mm 0; }
h1 { font-size: 17pt; margin: 0 0 2mm; }
h2 { font-size: 13pt; margin: 7mm 0 2mm; border-bottom: 1px solid #999; break-after: avoid; page-break-after: avoid; }
h3 { font-size: 11pt; margin: 4mm 0 1mm; break-after: avoid; page-break-after: avoid; }
p, li { overflow-wrap: anywhere; }
.muted { color: #555; }
table { width: 100%; max-width: 100%; border-collapse: collapse; table-layout: fixed; margin: 2mm 0; font-size: 9pt; }
th, td { border: 1px solid #bbb; padding: 0.8mm 1.5mm; text-align: left; vertical-align: top; overflow-wrap: anywhere; word-break: break-word; }
th { background: #eee; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.dense { font-size: 7.5pt; }
table.dense th, table.dense td { padding: 0.5mm 0.8mm; }
tr { break-inside: avoid; page-break-inside: avoid; }
thead { display: table-header-group; }
figure { margin: 3mm 0; break-inside: avoid; page-break-inside: avoid; }
figure svg { display: block; width: 100%; max-width: 100%; height: auto; }
figcaption { font-size: 9pt; color: #333; }
code { font-size: 9pt; overflow-wrap: anywhere; }
.warning { color: #8a4b00; }
@media print { body { padding: 0; } a { color: inherit; text-decoration: none; } }
"#;

/// `text` with the characters HTML gives a meaning escaped, for text and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// A whole page titled `title` around `body` (already HTML).
pub fn page(title: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <meta name=\"generator\" content=\"tribosim {}\">\n<title>{}</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n{body}</body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        escape(title),
        escape(title),
    )
}

/// A cell of a [`table`]: text, or a number set right.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// Text, escaped when written.
    Text(String),
    /// A number already formatted, set right.
    Number(String),
}

impl Cell {
    /// A text cell.
    pub fn text(text: impl Into<String>) -> Self {
        Self::Text(text.into())
    }

    /// A number cell, written by [`number`].
    pub fn number(value: f64) -> Self {
        Self::Number(number(value))
    }

    /// A number cell when there is a value, else an empty text cell.
    pub fn optional(value: Option<f64>) -> Self {
        value.map_or_else(|| Self::text(""), Self::number)
    }
}

/// A table with `header` and `rows`, captioned by `caption` when it is not empty, its
/// columns of equal width.
pub fn table(caption: &str, header: &[&str], rows: &[Vec<Cell>]) -> String {
    sized_table(caption, header, rows, &[])
}

/// Columns past which a table is set dense: at 9 pt, ten columns leave 18 mm each, and a
/// number such as "4.444e-5" no longer fits on one line of a cell.
const DENSE_AFTER_COLUMNS: usize = 8;

/// A [`table`] whose columns take `widths`, percent of the page's width (equal when empty).
pub fn sized_table(caption: &str, header: &[&str], rows: &[Vec<Cell>], widths: &[u8]) -> String {
    let mut out = String::from(if header.len() > DENSE_AFTER_COLUMNS {
        "<table class=\"dense\">"
    } else {
        "<table>"
    });
    if !caption.is_empty() {
        let _ = write!(
            out,
            "<caption class=\"muted\">{}</caption>",
            escape(caption)
        );
    }
    if !widths.is_empty() {
        out.push_str("<colgroup>");
        for width in widths {
            let _ = write!(out, "<col style=\"width: {width}%\">");
        }
        out.push_str("</colgroup>");
    }
    out.push_str("<thead><tr>");
    for name in header {
        let _ = write!(out, "<th>{}</th>", escape(name));
    }
    out.push_str("</tr></thead><tbody>");
    for row in rows {
        out.push_str("<tr>");
        for cell in row {
            let _ = match cell {
                Cell::Text(text) => write!(out, "<td>{}</td>", escape(text)),
                Cell::Number(text) => write!(out, "<td class=\"num\">{}</td>", escape(text)),
            };
        }
        out.push_str("</tr>");
    }
    out.push_str("</tbody></table>\n");
    out
}

/// A heading and a paragraph, escaped.
pub fn heading(level: u8, text: &str) -> String {
    format!("<h{level}>{}</h{level}>\n", escape(text))
}

/// A paragraph of `text`, escaped, with `class` when it is not empty.
pub fn paragraph(class: &str, text: &str) -> String {
    if class.is_empty() {
        format!("<p>{}</p>\n", escape(text))
    } else {
        format!("<p class=\"{class}\">{}</p>\n", escape(text))
    }
}

/// `value` with four significant digits: plainly between 0.001 and 100 000, else in
/// scientific notation; integers as they are.
pub fn number(value: f64) -> String {
    if !value.is_finite() {
        return value.to_string();
    }
    let magnitude = value.abs();
    if value.fract() == 0.0 && magnitude < 1e9 {
        return format!("{value:.0}");
    }
    if (1e-3..1e5).contains(&magnitude) {
        let decimals = (3 - magnitude.log10().floor() as i32).max(0) as usize;
        return format!("{value:.decimals$}");
    }
    format!("{value:.3e}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(number(3600.0), "3600");
        assert_eq!(number(0.011_72), "0.01172");
        assert_eq!(number(12.3456), "12.35");
        assert_eq!(number(-0.543_21), "-0.5432");
        assert_eq!(number(1.0228e-4), "1.023e-4");
        assert_eq!(number(2.5e7), "25000000");
        assert_eq!(number(2.5e12), "2.500e12");
    }

    #[test]
    fn text_is_escaped_in_cells_and_headings() {
        let html = table("a < b", &["x & y"], &[vec![Cell::text("<script>")]]);
        assert!(html.contains("a &lt; b") && html.contains("x &amp; y"));
        assert!(html.contains("&lt;script&gt;") && !html.contains("<script>"));
        assert_eq!(heading(2, "\"q\""), "<h2>&quot;q&quot;</h2>\n");
    }
}
