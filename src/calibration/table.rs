//! A measurement table: named numeric columns, read from CSV (a header row, then one row
//! per point; blank lines and lines starting with `#` skipped) or JSON (an array of row
//! objects, or an object of equal-length column arrays). The one reader of every table a
//! lab sends: the calibration's and the measurements attached to a job.
//!
//! Units live in the column names, in lower case (a header's `Potential_mV` is
//! `potential_mv`); a name in another unit of a known quantity ([`UNITS`]: `time_min`,
//! `potential_mv`, `volume_um3`, ...) is converted to the unit the fits use (`time_s`,
//! `potential_v`, `volume_mm3`, ...).
//!
//! Lab software writes the unit beside the quantity (`Time (s)`, `Volume [mm³]`,
//! `time/s`, `E (V vs SCE)`): such a header is read as the quantity and the unit joined by
//! `_` (`time_s`, `volume_mm3`, `e_v`), `³` and `²` as `3` and `2`, `µ` as `u`, a potential's
//! reference dropped (the scene's `corrosion.reference_electrode` says it), and the short
//! names potentiostats use for the potential (`E`, `Ewe`, `Vf`) as `potential`
//! ([`column_name`]); [`Table::renamed`] lists what was read so.
//!
//! A CSV's delimiter is a tab when its header holds one (potentiostat and tribometer
//! software's text exports), else `;` when the header holds one, `,` otherwise: European
//! spreadsheets save `;` because their decimal mark is the comma, so with `;` or a tab a
//! decimal comma is read as a decimal point (`0,5` is 0.5). Cells may be quoted
//! (`"time_s"`), a quote inside written twice.

use serde_json::Value;
use thiserror::Error;

/// The most columns a table may have: a fit reads at most four, and a header of 100,000
/// names would cost a comparison of every pair in the check for names given twice.
pub const MAX_COLUMNS: usize = 32;

/// The longest column name, in characters: a quantity and its unit (`current_density_a_cm2`).
pub const COLUMN_NAME_MAX_CHARS: usize = 64;

/// How much of a cell that is not a number an error echoes, in characters.
const ECHOED_CELL_CHARS: usize = 40;

/// Why a table could not be read, or lacks what a fit needs.
#[derive(Debug, Error)]
pub enum TableError {
    /// No header or no rows.
    #[error("the table is empty: it needs a header row and at least one data row")]
    Empty,
    /// A CSV row with a different number of fields than the header.
    #[error("row {row} has {got} fields, the header has {expected} (fields separated by {}){}",
        delimiter_name(*delimiter),
        if *delimiter == ',' { "; a decimal comma needs `;` between the fields" } else { "" })]
    Ragged {
        /// The data row, from 1.
        row: usize,
        /// Fields in the header.
        expected: usize,
        /// Fields in the row.
        got: usize,
        /// The delimiter the header showed.
        delimiter: char,
    },
    /// A quote opened in a CSV cell and not closed on its line.
    #[error("row {row}: a quote is not closed")]
    Unclosed {
        /// The row, from 0 for the header.
        row: usize,
    },
    /// More columns than `MAX_COLUMNS` (32), counted from the header before any cell is read.
    #[error("the table has {0} columns; at most {MAX_COLUMNS}")]
    TooManyColumns(usize),
    /// A column name past `COLUMN_NAME_MAX_CHARS` (64; its start echoed).
    #[error("column `{column}`: the name has {chars} characters; at most {COLUMN_NAME_MAX_CHARS}")]
    LongName {
        /// The name's first characters.
        column: String,
        /// Its length.
        chars: usize,
    },
    /// A cell that is not a finite number.
    #[error("column `{column}`: row {row} is `{text}`, not a finite number")]
    NotANumber {
        /// The column.
        column: String,
        /// The data row, from 1.
        row: usize,
        /// What the cell holds (its first 40 characters).
        text: String,
    },
    /// A column named twice or more in the header (after trimming): which one a fit would
    /// read is not the table's to leave open.
    #[error("the header names {} more than once; each column needs its own name", .0.iter().map(|c| format!("`{c}`")).collect::<Vec<_>>().join(", "))]
    DuplicateColumns(Vec<String>),
    /// A column the fit needs is absent.
    #[error(
        "no column {}; {}; the table has {}",
        quoted(wanted, " or "),
        accepted(wanted),
        quoted(found, ", ")
    )]
    MissingColumn {
        /// The column (or alternatives) wanted, as the fits name them.
        wanted: Vec<String>,
        /// The columns present.
        found: Vec<String>,
    },
    /// JSON that is not an array of row objects or an object of columns.
    #[error("a JSON table must be an array of row objects or an object of column arrays: {0}")]
    JsonShape(String),
    /// Malformed JSON.
    #[error("invalid JSON: {0}")]
    Json(#[from] serde_json::Error),
}

/// Named numeric columns of equal length.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    names: Vec<String>,
    columns: Vec<Vec<f64>>,
    renamed: Vec<(String, String)>,
}

impl Table {
    /// Reads CSV or JSON text (JSON when it starts with `[` or `{`).
    pub fn parse(text: &str) -> Result<Self, TableError> {
        match text.trim_start().chars().next() {
            Some('[' | '{') => Self::from_json(&serde_json::from_str(text)?),
            _ => Self::from_csv(text),
        }
    }

    /// Builds a table from named columns (for callers that hold their data in memory),
    /// refusing empty or unequal columns and cells that are not finite.
    pub fn from_columns(columns: &[(&str, &[f64])]) -> Result<Self, TableError> {
        for (name, values) in columns {
            for (i, &v) in values.iter().enumerate() {
                number(name, i + 1, Some(v), &v.to_string())?;
            }
        }
        let names: Vec<String> = columns.iter().map(|(n, _)| (*n).to_owned()).collect();
        Self::checked(&names, columns.iter().map(|(_, v)| v.to_vec()).collect())
    }

    /// Reads CSV text: a header row, then one row per point, delimited by `,` or `;`.
    pub fn from_csv(text: &str) -> Result<Self, TableError> {
        let mut lines = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'));
        let header = lines.next().ok_or(TableError::Empty)?;
        let delimiter = ['\t', ';']
            .into_iter()
            .find(|d| header.contains(*d))
            .unwrap_or(',');
        let names = fields(header, delimiter).ok_or(TableError::Unclosed { row: 0 })?;
        check_header(&names)?;
        let mut columns = vec![Vec::new(); names.len()];
        for (index, line) in lines.enumerate() {
            let row = index + 1;
            let fields = fields(line, delimiter).ok_or(TableError::Unclosed { row })?;
            if fields.len() != names.len() {
                return Err(TableError::Ragged {
                    row,
                    expected: names.len(),
                    got: fields.len(),
                    delimiter,
                });
            }
            for ((column, name), text) in columns.iter_mut().zip(&names).zip(fields) {
                let decimal = if delimiter != ',' {
                    text.replace(',', ".")
                } else {
                    text.clone()
                };
                column.push(number(name, row, decimal.parse().ok(), &text)?);
            }
        }
        Self::checked(&names, columns)
    }

    /// Reads a JSON table: an array of row objects, or an object of column arrays.
    pub fn from_json(value: &Value) -> Result<Self, TableError> {
        match value {
            Value::Array(rows) => {
                let first = rows.first().and_then(Value::as_object);
                let names: Vec<String> = first.ok_or(TableError::Empty)?.keys().cloned().collect();
                check_header(&names)?;
                let mut columns = vec![Vec::new(); names.len()];
                for (index, row) in rows.iter().enumerate() {
                    let object = row.as_object().ok_or_else(|| {
                        TableError::JsonShape(format!("row {} is not an object", index + 1))
                    })?;
                    for (column, name) in columns.iter_mut().zip(&names) {
                        let cell = object.get(name).unwrap_or(&Value::Null);
                        column.push(number(name, index + 1, cell.as_f64(), &cell.to_string())?);
                    }
                }
                Self::checked(&names, columns)
            }
            Value::Object(map) => {
                check_header(&map.keys().collect::<Vec<_>>())?;
                let mut names = Vec::new();
                let mut columns = Vec::new();
                for (name, cells) in map {
                    let cells = cells.as_array().ok_or_else(|| {
                        TableError::JsonShape(format!("column `{name}` is not an array"))
                    })?;
                    let column = cells
                        .iter()
                        .enumerate()
                        .map(|(i, c)| number(name, i + 1, c.as_f64(), &c.to_string()))
                        .collect::<Result<Vec<f64>, _>>()?;
                    names.push(name.clone());
                    columns.push(column);
                }
                Self::checked(&names, columns)
            }
            other => Err(TableError::JsonShape(format!("got {other}"))),
        }
    }

    /// Refuses a table without rows, with columns of different lengths or with a column
    /// named twice (once its name is in the fits' unit); converts the columns in other units.
    fn checked(given: &[String], mut columns: Vec<Vec<f64>>) -> Result<Self, TableError> {
        let mut names: Vec<String> = given.iter().map(|n| column_name(n)).collect();
        for (name, column) in names.iter_mut().zip(&mut columns) {
            if let Some(&(_, fits, factor)) = UNITS.iter().find(|(other, ..)| other == name) {
                *name = fits.to_owned();
                column.iter_mut().for_each(|v| *v *= factor);
            }
        }
        let renamed = given
            .iter()
            .zip(&names)
            .filter(|(given, name)| given.trim().to_lowercase() != **name)
            .map(|(given, name)| (given.trim().to_owned(), name.clone()))
            .collect();
        let mut repeated: Vec<String> = Vec::new();
        for (i, name) in names.iter().enumerate() {
            if names[..i].contains(name) && !repeated.contains(name) {
                repeated.push(name.clone());
            }
        }
        if !repeated.is_empty() {
            return Err(TableError::DuplicateColumns(repeated));
        }
        let rows = columns.first().map_or(0, Vec::len);
        if rows == 0 {
            return Err(TableError::Empty);
        }
        if let Some(i) = columns.iter().position(|c| c.len() != rows) {
            return Err(TableError::JsonShape(format!(
                "column `{}` has {} values, `{}` has {rows}",
                names[i],
                columns[i].len(),
                names[0]
            )));
        }
        Ok(Self {
            names,
            columns,
            renamed,
        })
    }

    /// The headers read under another name, as (the header, the column it became, in the
    /// fits' unit): `("Time (s)", "time_s")`, `("Time (min)", "time_s")`; empty when every
    /// header was a name in the fits' unit already.
    pub fn renamed(&self) -> &[(String, String)] {
        &self.renamed
    }

    /// The column names, in the table's order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The column called `name`, if present.
    pub fn optional(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| self.columns[i].as_slice())
    }

    /// The column called `name`.
    pub fn column(&self, name: &str) -> Result<&[f64], TableError> {
        self.optional(name).ok_or_else(|| self.missing(&[name]))
    }

    /// The error for a missing column, `wanted` the alternatives looked for.
    pub fn missing(&self, wanted: &[&str]) -> TableError {
        TableError::MissingColumn {
            wanted: wanted.iter().map(|w| (*w).to_owned()).collect(),
            found: self.names.clone(),
        }
    }
}

/// Column names in another unit of a quantity the fits read: the name, the fits' name, and
/// the factor from the one to the other.
pub const UNITS: &[(&str, &str, f64)] = &[
    ("time_ms", "time_s", 1e-3),
    ("time_min", "time_s", 60.0),
    ("time_h", "time_s", 3600.0),
    ("potential_mv", "potential_v", 1e-3),
    ("volume_um3", "volume_mm3", 1e-9),
    ("spread_um3", "spread_mm3", 1e-9),
    ("depth_nm", "depth_um", 1e-3),
    ("depth_mm", "depth_um", 1e3),
    ("y_um", "y_mm", 1e-3),
    ("hardness_gpa", "hardness_mpa", 1e3),
];

/// Every accepted spelling of the column `name` of the fits (`volume_mm3`: `volume_mm3`,
/// `volume_um3`), for an error to list.
pub fn spellings(name: &str) -> Vec<String> {
    std::iter::once(name.to_owned())
        .chain(
            UNITS
                .iter()
                .filter(|(_, fits, _)| *fits == name)
                .map(|(other, ..)| (*other).to_owned()),
        )
        .collect()
}

/// Every accepted spelling of the columns `wanted`, and the forms with the unit apart, in
/// words that follow "no column ...;" in an error.
fn accepted(wanted: &[String]) -> String {
    let all: Vec<String> = wanted.iter().flat_map(|w| spellings(w)).collect();
    format!(
        "accepted: {}, also with the unit in brackets, parentheses or after `/` (`Time (s)`, \
         `Volume [mm3]`, `time/s`)",
        quoted(&all, ", ")
    )
}

/// Each name in backticks, joined by `separator`: how a refusal lists names.
pub fn quoted(names: &[String], separator: &str) -> String {
    names
        .iter()
        .map(|name| format!("`{name}`"))
        .collect::<Vec<_>>()
        .join(separator)
}

/// The short names potentiostats give the potential: Gamry's `Vf`, EC-Lab's `Ewe`, and `E`.
const POTENTIAL_NAMES: [&str; 3] = ["e", "ewe", "vf"];

/// The name a header stands for: lower case, trimmed; `Quantity (unit)`, `Quantity [unit]`
/// and `Quantity/unit` as `quantity_unit` (spaces in the quantity as `_`, a potential's
/// `vs ...` dropped from its unit); `³`, `²` and `µ` as `3`, `2` and `u`.
pub fn column_name(header: &str) -> String {
    let plain: String = header
        .trim()
        .to_lowercase()
        .chars()
        .map(|c| match c {
            '³' => '3',
            '²' => '2',
            'µ' | 'μ' => 'u',
            c => c,
        })
        .collect();
    let split = plain
        .strip_suffix([')', ']'])
        .and_then(|inner| inner.rsplit_once(['(', '[']))
        .or_else(|| plain.rsplit_once('/'));
    let Some((quantity, unit)) = split else {
        return plain;
    };
    let quantity = quantity.split_whitespace().collect::<Vec<_>>().join("_");
    let quantity = if POTENTIAL_NAMES.contains(&quantity.as_str()) {
        "potential".to_owned()
    } else {
        quantity
    };
    let unit = unit.split(" vs").next().unwrap_or_default();
    let unit: String = unit.chars().filter(|c| !c.is_whitespace()).collect();
    if quantity.is_empty() || unit.is_empty() {
        return plain;
    }
    format!("{quantity}_{unit}")
}

/// A delimiter in words, for an error.
fn delimiter_name(delimiter: char) -> &'static str {
    match delimiter {
        '\t' => "tabs, as the header has one",
        ';' => "`;`, as the header has one",
        _ => "`,`, as the header has no tab nor `;`",
    }
}

/// The fields of one CSV line split at `delimiter`, each trimmed and unquoted; `None` when
/// a quote is not closed.
fn fields(line: &str, delimiter: char) -> Option<Vec<String>> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            '"' if quoted => quoted = false,
            '"' if field.trim().is_empty() => {
                field.clear();
                quoted = true;
            }
            c if c == delimiter && !quoted => {
                fields.push(field.trim().to_owned());
                field.clear();
            }
            c => field.push(c),
        }
    }
    (!quoted).then(|| {
        fields.push(field.trim().to_owned());
        fields
    })
}

/// A cell's number, refused when absent or not finite.
fn number(column: &str, row: usize, value: Option<f64>, text: &str) -> Result<f64, TableError> {
    value
        .filter(|v| v.is_finite())
        .ok_or_else(|| TableError::NotANumber {
            column: column.to_owned(),
            row,
            text: crate::text::cut(text, ECHOED_CELL_CHARS),
        })
}

/// Refuses a header of more than [`MAX_COLUMNS`] names or a name past
/// [`COLUMN_NAME_MAX_CHARS`], before any cell is read.
fn check_header<S: AsRef<str>>(names: &[S]) -> Result<(), TableError> {
    if names.len() > MAX_COLUMNS {
        return Err(TableError::TooManyColumns(names.len()));
    }
    for name in names {
        let chars = name.as_ref().chars().count();
        if chars > COLUMN_NAME_MAX_CHARS {
            return Err(TableError::LongName {
                column: crate::text::cut(name.as_ref(), COLUMN_NAME_MAX_CHARS),
                chars,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_and_both_json_shapes_read_the_same_table() {
        let csv = "# Table 3\ncycles, hardness_mpa\n10, 2551\n\n60, 2727\n";
        let rows =
            r#"[{"cycles": 10, "hardness_mpa": 2551}, {"cycles": 60, "hardness_mpa": 2727}]"#;
        let columns = r#"{"cycles": [10, 60], "hardness_mpa": [2551, 2727]}"#;
        for text in [csv, rows, columns] {
            let table = Table::parse(text).expect("a valid table");
            assert_eq!(table.column("cycles").expect("present"), &[10.0, 60.0]);
            assert_eq!(
                table.column("hardness_mpa").expect("present"),
                &[2551.0, 2727.0]
            );
        }
    }

    #[test]
    fn lab_headers_are_read_as_the_documented_names_and_the_mapping_reported() {
        for (header, name) in [
            ("Time (s)", "time_s"),
            ("Time [s]", "time_s"),
            ("time/s", "time_s"),
            ("Volume (mm³)", "volume_mm3"),
            ("Volume [mm3]", "volume_mm3"),
            ("Wear volume (µm³)", "wear_volume_um3"),
            ("Potential (V)", "potential_v"),
            ("E (V vs SCE)", "potential_v"),
            ("Ewe/V", "potential_v"),
            ("Vf (mV vs. Ref.)", "potential_mv"),
            ("time_s", "time_s"),
        ] {
            assert_eq!(column_name(header), name, "{header}");
        }
        // A tribometer's CSV: the headers mapped, the time converted, the mapping kept.
        let table = Table::parse("Time (min),Volume (mm³)\n5,0.00118\n60,0.01172\n").expect("read");
        assert_eq!(table.column("time_s").expect("mapped"), &[300.0, 3600.0]);
        assert_eq!(
            table.renamed(),
            [
                ("Time (min)".to_owned(), "time_s".to_owned()),
                ("Volume (mm³)".to_owned(), "volume_mm3".to_owned())
            ]
        );
        // A potentiostat's tab-separated export, decimal commas included.
        let table = Table::parse("time/s\tEwe/V\n0\t-0,35\n1,5\t-0,41\n").expect("read");
        assert_eq!(table.column("time_s").expect("mapped"), &[0.0, 1.5]);
        assert_eq!(
            table.column("potential_v").expect("mapped"),
            &[-0.35, -0.41]
        );
        // A missing column lists every accepted spelling, each in one pair of backticks.
        let err = table.column("volume_mm3").expect_err("absent").to_string();
        assert!(
            err.starts_with("no column `volume_mm3`; accepted: `volume_mm3`, `volume_um3`"),
            "{err}"
        );
        assert!(!err.contains("``"), "{err}");
    }

    #[test]
    fn bad_cells_and_missing_columns_are_named() {
        let err = Table::parse("cycles,hardness_mpa\n10,abc\n").expect_err("not a number");
        assert!(err.to_string().contains("`hardness_mpa`: row 1"), "{err}");
        let err = Table::parse("cycles,hardness_mpa\n10\n").expect_err("ragged");
        assert!(matches!(err, TableError::Ragged { row: 1, .. }));
        let table = Table::parse("cycles\n10\n").expect("valid");
        let err = table.column("hardness_mpa").expect_err("missing");
        assert!(err.to_string().contains("`hardness_mpa`"), "{err}");
        assert!(matches!(Table::parse("cycles\n"), Err(TableError::Empty)));
        let err = Table::parse("cycles, hardness_mpa,cycles,x,x\n1,2,3,4,5\n").expect_err("twice");
        assert_eq!(
            err.to_string(),
            "the header names `cycles`, `x` more than once; each column needs its own name"
        );
        assert!(Table::parse(r#"{"a": [1, 2], "b": [1]}"#).is_err());
        assert!(Table::parse(r#"[{"a": 1}, {"a": null}]"#).is_err());
        assert!(Table::from_columns(&[("a", &[1.0, 2.0]), ("b", &[1.0])]).is_err());
        assert!(Table::from_columns(&[("a", &[f64::NAN])]).is_err());
        let err = Table::parse("time_s,potential_v\n1,0,5\n").expect_err("ragged");
        assert!(err.to_string().contains("`,`"), "{err}");
        assert!(err.to_string().contains("decimal comma"), "{err}");
        let err = Table::parse("time_s;potential_v\n1;0;5\n").expect_err("ragged");
        assert!(err.to_string().contains("`;`"), "{err}");
        let err = Table::parse("\"time_s,potential_v\n1,2\n").expect_err("unclosed");
        assert!(matches!(err, TableError::Unclosed { row: 0 }), "{err}");
        let err = Table::parse("time_s,time_min\n1,2\n").expect_err("time twice");
        assert!(err.to_string().contains("`time_s`"), "{err}");
    }

    #[test]
    fn european_excel_quoted_headers_and_units_in_the_names_read_the_same_table() {
        let plain = Table::parse("time_s,potential_v,volume_mm3\n60,-0.3,0.002\n120,-0.35,0.004\n")
            .expect("valid");
        let european =
            "\"Time_min\";\"Potential_mV\";\"volume_um3\"\n1;-300;2000000\n2;-350;4000000\n";
        let hours = r#"{"time_h": [0.016666666666666666, 0.03333333333333333],
                        "potential_mv": [-300, -350], "volume_mm3": [0.002, 0.004]}"#;
        for text in [european, hours] {
            let table = Table::parse(text).expect("valid");
            let mut names = table.names().to_vec();
            names.sort();
            assert_eq!(names, ["potential_v", "time_s", "volume_mm3"], "{text}");
            for name in plain.names() {
                let (got, want) = (
                    table.column(name).expect("present"),
                    plain.column(name).expect("present"),
                );
                for (g, w) in got.iter().zip(want) {
                    // One multiplication by the factor: within one rounding of the value.
                    assert!(
                        (g - w).abs() <= f64::EPSILON * w.abs(),
                        "{name}: {g} vs {w}"
                    );
                }
            }
        }
        let decimal = Table::parse("time_s;potential_v\n1,5;-0,25\n").expect("valid");
        assert_eq!(decimal.column("time_s").expect("present"), &[1.5]);
        assert_eq!(decimal.column("potential_v").expect("present"), &[-0.25]);
        let quoted = Table::parse("\"a, b\",c\n1,\"2\"\n").expect("valid");
        assert_eq!(quoted.names(), ["a, b", "c"]);
        assert_eq!(spellings("volume_mm3"), ["volume_mm3", "volume_um3"]);
    }

    /// A header of 100,000 names once reached a check of every pair; it is refused on its
    /// count, and a long name or cell is echoed cut.
    #[test]
    fn a_wide_header_or_a_long_name_is_refused_before_the_cells() {
        let header: Vec<String> = (0..100_000).map(|i| format!("c{i}")).collect();
        let csv = format!("{}\n1\n", header.join(","));
        assert!(matches!(
            Table::from_csv(&csv),
            Err(TableError::TooManyColumns(100_000))
        ));
        let long = "n".repeat(10_000);
        let refused = Table::from_csv(&format!("cycles,{long}\n1,2\n")).expect_err("long");
        assert!(refused.to_string().len() < 200, "{refused}");
        let refused = Table::from_csv(&format!("cycles\n{long}\n")).expect_err("no number");
        assert!(refused.to_string().len() < 200, "{refused}");
    }
}
