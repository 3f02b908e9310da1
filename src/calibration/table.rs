//! A measurement table: named numeric columns, read from CSV (a header row, then one row
//! per point; blank lines and lines starting with `#` skipped) or JSON (an array of row
//! objects, or an object of equal-length column arrays). Units live in the column names.

use serde_json::Value;
use thiserror::Error;

/// Why a table could not be read, or lacks what a fit needs.
#[derive(Debug, Error)]
pub enum TableError {
    /// No header or no rows.
    #[error("the table is empty: it needs a header row and at least one data row")]
    Empty,
    /// A CSV row with a different number of fields than the header.
    #[error("row {row} has {got} fields, the header has {expected}")]
    Ragged {
        /// The data row, from 1.
        row: usize,
        /// Fields in the header.
        expected: usize,
        /// Fields in the row.
        got: usize,
    },
    /// A cell that is not a finite number.
    #[error("column `{column}`: row {row} is `{text}`, not a finite number")]
    NotANumber {
        /// The column.
        column: String,
        /// The data row, from 1.
        row: usize,
        /// What the cell holds.
        text: String,
    },
    /// A column named twice or more in the header (after trimming): which one a fit would
    /// read is not the table's to leave open.
    #[error("the header names {} more than once; each column needs its own name", .0.iter().map(|c| format!("`{c}`")).collect::<Vec<_>>().join(", "))]
    DuplicateColumns(Vec<String>),
    /// A column the fit needs is absent.
    #[error("no column `{wanted}`; the table has {}", found.iter().map(|c| format!("`{c}`")).collect::<Vec<_>>().join(", "))]
    MissingColumn {
        /// The column (or alternatives) wanted.
        wanted: String,
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
        Self::checked(
            columns.iter().map(|(n, _)| (*n).to_owned()).collect(),
            columns.iter().map(|(_, v)| v.to_vec()).collect(),
        )
    }

    /// Reads CSV text: a header row, then one row per point.
    pub fn from_csv(text: &str) -> Result<Self, TableError> {
        let mut lines = text
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with('#'));
        let names: Vec<String> = lines
            .next()
            .ok_or(TableError::Empty)?
            .split(',')
            .map(|n| n.trim().to_owned())
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
        let mut columns = vec![Vec::new(); names.len()];
        for (index, line) in lines.enumerate() {
            let row = index + 1;
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() != names.len() {
                return Err(TableError::Ragged {
                    row,
                    expected: names.len(),
                    got: fields.len(),
                });
            }
            for ((column, name), text) in columns.iter_mut().zip(&names).zip(fields) {
                column.push(number(name, row, text.parse().ok(), text)?);
            }
        }
        Self::checked(names, columns)
    }

    /// Reads a JSON table: an array of row objects, or an object of column arrays.
    pub fn from_json(value: &Value) -> Result<Self, TableError> {
        match value {
            Value::Array(rows) => {
                let first = rows.first().and_then(Value::as_object);
                let names: Vec<String> = first.ok_or(TableError::Empty)?.keys().cloned().collect();
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
                Self::checked(names, columns)
            }
            Value::Object(map) => {
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
                Self::checked(names, columns)
            }
            other => Err(TableError::JsonShape(format!("got {other}"))),
        }
    }

    /// Refuses a table without rows or with columns of different lengths.
    fn checked(names: Vec<String>, columns: Vec<Vec<f64>>) -> Result<Self, TableError> {
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
        Ok(Self { names, columns })
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
        self.optional(name)
            .ok_or_else(|| self.missing(format!("`{name}`")))
    }

    /// The error for a missing column, `wanted` describing what was looked for.
    pub fn missing(&self, wanted: String) -> TableError {
        TableError::MissingColumn {
            wanted,
            found: self.names.clone(),
        }
    }
}

/// A cell's number, refused when absent or not finite.
fn number(column: &str, row: usize, value: Option<f64>, text: &str) -> Result<f64, TableError> {
    value
        .filter(|v| v.is_finite())
        .ok_or_else(|| TableError::NotANumber {
            column: column.to_owned(),
            row,
            text: text.to_owned(),
        })
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
    }
}
