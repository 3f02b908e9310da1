//! Measured points a lab attaches to a job, to draw beside the model: a wear volume against
//! time or cycles, a groove profile across the track, an open-circuit potential against time. Each is a
//! small table (CSV or JSON, units in the column names) read by the calibration's table
//! parser and checked as the calibration checks its own tables: every cell a finite number,
//! times and positions strictly increasing, volumes not negative.

use std::collections::BTreeMap;

use serde::Serialize;
use thiserror::Error;

use crate::calibration::{
    CalibrationError, Table, TableError, quoted, require_at_least, require_increasing, spellings,
};
use crate::json::{self, JsonError};

/// A checked table: column name to values, every column of one length.
pub type Columns = BTreeMap<String, Vec<f64>>;

/// What was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MeasurementKind {
    /// The wear track volume against time or cycles (Table 3's quantity).
    WearVolume,
    /// The groove's depth across the track (Fig. 12's quantity).
    Profile,
    /// The open-circuit potential (OCP) against time (Fig. 6's quantity), as the calibration
    /// names it; `potential` is accepted for it.
    Ocp,
}

/// Whether a column must be present.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Presence {
    /// Always.
    Required,
    /// When given, checked like the others.
    Optional,
    /// One of the kind's abscissas (`time_s` or `cycles`) must be present.
    Abscissa,
}

/// One column a kind accepts and what its values must satisfy.
struct Column {
    name: &'static str,
    presence: Presence,
    /// Strictly increasing row by row (a time, a cycle count, a position along a scan).
    increasing: bool,
    /// The smallest allowed value.
    minimum: Option<f64>,
}

const fn column(
    name: &'static str,
    presence: Presence,
    increasing: bool,
    minimum: Option<f64>,
) -> Column {
    Column {
        name,
        presence,
        increasing,
        minimum,
    }
}

const WEAR_VOLUME: &[Column] = &[
    column("time_s", Presence::Abscissa, true, Some(0.0)),
    column("cycles", Presence::Abscissa, true, Some(0.0)),
    column("volume_mm3", Presence::Required, false, Some(0.0)),
    column("spread_mm3", Presence::Optional, false, Some(0.0)),
];

const PROFILE: &[Column] = &[
    column("y_mm", Presence::Required, true, None),
    // Negative depths are material piled up beside the groove.
    column("depth_um", Presence::Required, false, None),
];

const POTENTIAL: &[Column] = &[
    column("time_s", Presence::Required, true, Some(0.0)),
    column("potential_v", Presence::Required, false, None),
];

impl MeasurementKind {
    /// Every kind, in the order of the API's answer.
    pub const ALL: [Self; 3] = [Self::WearVolume, Self::Profile, Self::Ocp];

    /// The kind as the API spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::WearVolume => "wear_volume",
            Self::Profile => "profile",
            Self::Ocp => "ocp",
        }
    }

    /// The kind called `name`, or `potential`: the OCP's other name.
    pub fn from_name(name: &str) -> Option<Self> {
        if name == "potential" {
            return Some(Self::Ocp);
        }
        Self::ALL.into_iter().find(|kind| kind.name() == name)
    }

    /// The file that holds it in the job's directory (the OCP's under its other name, so
    /// that tables stored under it stay readable).
    pub fn file(self) -> &'static str {
        match self {
            Self::WearVolume => "measured_wear_volume.json",
            Self::Profile => "measured_profile.json",
            Self::Ocp => "measured_potential.json",
        }
    }

    fn columns(self) -> &'static [Column] {
        match self {
            Self::WearVolume => WEAR_VOLUME,
            Self::Profile => PROFILE,
            Self::Ocp => POTENTIAL,
        }
    }
}

/// A job's measurements, as `GET /api/v1/jobs/{id}/measurements` answers: each kind's
/// table, or null.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Measurements {
    /// The wear volume table.
    pub wear_volume: Option<Columns>,
    /// The profile table.
    pub profile: Option<Columns>,
    /// The open-circuit potential table.
    pub ocp: Option<Columns>,
}

impl Measurements {
    /// The table of `kind`.
    pub fn slot(&mut self, kind: MeasurementKind) -> &mut Option<Columns> {
        match kind {
            MeasurementKind::WearVolume => &mut self.wear_volume,
            MeasurementKind::Profile => &mut self.profile,
            MeasurementKind::Ocp => &mut self.ocp,
        }
    }
}

/// How the body of a PUT is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `text/csv`: a header row, then one row per point.
    Csv,
    /// `application/json`: an array of row objects, or an object of column arrays.
    Json,
}

/// Why a measurement table was refused; [`MeasurementError::column`] names the column.
#[derive(Debug, Error)]
pub enum MeasurementError {
    /// The CSV is not UTF-8 text.
    #[error("the table is not UTF-8 text")]
    NotText,
    /// The JSON is malformed (a key given twice included).
    #[error("malformed JSON: {0}")]
    Json(#[from] JsonError),
    /// The table cannot be read, or a cell is not a finite number.
    #[error(transparent)]
    Table(#[from] TableError),
    /// A column this kind does not know (a misspelt unit, say).
    #[error(
        "unknown column `{column}`{}; a {kind} table takes {} (units in the name, or in \
         brackets, parentheses or after `/`: `Time (s)`, `Volume [mm3]`, `time/s`)",
        header.as_ref().map(|h| format!(" (read from the header `{h}`)")).unwrap_or_default(),
        quoted(allowed, ", ")
    )]
    UnknownColumn {
        /// The column.
        column: String,
        /// The header it was read from, when that was written otherwise (`Wear (µm³)`).
        header: Option<String>,
        /// The kind.
        kind: &'static str,
        /// The columns it may have, in every unit accepted.
        allowed: Vec<String>,
    },
    /// A value the calibration would refuse too: a time not increasing, a negative volume.
    #[error(transparent)]
    Value(CalibrationError),
}

impl MeasurementError {
    /// The column at fault (alternatives joined by " or "); empty for the whole table.
    pub fn column(&self) -> String {
        match self {
            Self::Table(TableError::NotANumber { column, .. }) => column.clone(),
            Self::Table(TableError::DuplicateColumns(names)) => names.join(", "),
            Self::Table(TableError::MissingColumn { wanted, .. }) => wanted.join(" or "),
            Self::UnknownColumn { column, .. } => column.clone(),
            Self::Value(
                CalibrationError::NotIncreasing { column, .. }
                | CalibrationError::BelowMinimum { column, .. },
            ) => (*column).to_owned(),
            _ => String::new(),
        }
    }
}

/// A table refused, with the kind it was sent as.
#[derive(Debug)]
pub struct InvalidTable {
    /// The kind the table was sent as.
    pub kind: MeasurementKind,
    /// Why it was refused.
    pub error: MeasurementError,
}

/// A header read under another name: `Time (s)` as `time_s`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Renamed {
    /// The header as the table wrote it.
    pub header: String,
    /// The column it was read as.
    pub column: String,
}

/// A table read and checked: its columns, and the headers read under another name.
#[derive(Debug, Clone, PartialEq)]
pub struct Read {
    /// The columns, under the names the fits use.
    pub columns: Columns,
    /// The headers written otherwise (`Time (s)`), with the column each was read as.
    pub renamed: Vec<Renamed>,
}

/// Reads and checks a table of `kind` from a request body.
pub fn parse(kind: MeasurementKind, format: Format, body: &[u8]) -> Result<Read, InvalidTable> {
    read(kind, format, body).map_err(|error| InvalidTable { kind, error })
}

fn read(kind: MeasurementKind, format: Format, body: &[u8]) -> Result<Read, MeasurementError> {
    let table = match format {
        Format::Csv => {
            Table::from_csv(std::str::from_utf8(body).map_err(|_| MeasurementError::NotText)?)?
        }
        Format::Json => Table::from_json(&json::from_slice(body)?)?,
    };
    let columns = check(kind, &table)?;
    let renamed = table
        .renamed()
        .iter()
        .map(|(header, column)| Renamed {
            header: header.clone(),
            column: column.clone(),
        })
        .collect();
    Ok(Read { columns, renamed })
}

/// The table's columns of `kind`, each checked.
fn check(kind: MeasurementKind, table: &Table) -> Result<Columns, MeasurementError> {
    let spec = kind.columns();
    if let Some(unknown) = table
        .names()
        .iter()
        .find(|name| !spec.iter().any(|c| c.name == name.as_str()))
    {
        let header = table
            .renamed()
            .iter()
            .find(|(_, column)| column == unknown)
            .map(|(header, _)| header.clone());
        return Err(MeasurementError::UnknownColumn {
            column: unknown.clone(),
            header,
            kind: kind.name(),
            allowed: spec.iter().flat_map(|c| spellings(c.name)).collect(),
        });
    }
    let abscissas: Vec<&str> = spec
        .iter()
        .filter(|c| c.presence == Presence::Abscissa)
        .map(|c| c.name)
        .collect();
    if !abscissas.is_empty() && abscissas.iter().all(|name| table.optional(name).is_none()) {
        return Err(table.missing(&abscissas).into());
    }
    let mut columns = Columns::new();
    for c in spec {
        let Some(values) = table.optional(c.name) else {
            if c.presence == Presence::Required {
                return Err(table.missing(&[c.name]).into());
            }
            continue;
        };
        if c.increasing {
            require_increasing(c.name, values).map_err(MeasurementError::Value)?;
        }
        if let Some(minimum) = c.minimum {
            require_at_least(c.name, values, minimum).map_err(MeasurementError::Value)?;
        }
        columns.insert(c.name.to_owned(), values.to_vec());
    }
    Ok(columns)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(kind: MeasurementKind, csv: &str) -> MeasurementError {
        let refused = parse(kind, Format::Csv, csv.as_bytes()).expect_err("refused");
        assert_eq!(refused.kind, kind);
        refused.error
    }

    #[test]
    fn csv_and_json_give_the_same_columns() {
        let csv = "time_s,volume_mm3,spread_mm3\n600,0.004,0.001\n3600,0.0118,0.002\n";
        let json = r#"[{"time_s": 600, "volume_mm3": 0.004, "spread_mm3": 0.001},
                       {"time_s": 3600, "volume_mm3": 0.0118, "spread_mm3": 0.002}]"#;
        let kind = MeasurementKind::WearVolume;
        let from_csv = parse(kind, Format::Csv, csv.as_bytes())
            .expect("valid CSV")
            .columns;
        let from_json = parse(kind, Format::Json, json.as_bytes())
            .expect("valid JSON")
            .columns;
        assert_eq!(from_csv, from_json);
        assert_eq!(from_csv["time_s"], [600.0, 3600.0]);
        // The stored shape reads back as a table of its own kind.
        let again = serde_json::to_vec(&from_csv).expect("serialises");
        assert_eq!(
            parse(kind, Format::Json, &again).expect("valid").columns,
            from_csv
        );
    }

    #[test]
    fn a_lab_export_is_read_and_its_headers_reported() {
        // Shaped like a tribometer's export: units in parentheses, a superscript three.
        let csv = include_str!("../../../tests/fixtures/lab/wear_tribometer.csv");
        let read = parse(MeasurementKind::WearVolume, Format::Csv, csv.as_bytes()).expect("read");
        assert_eq!(read.columns["time_s"], [60.0, 300.0, 1800.0, 3600.0]);
        assert_eq!(
            read.columns["volume_mm3"],
            [0.00109, 0.00118, 0.00533, 0.01172]
        );
        let names: Vec<(&str, &str)> = read
            .renamed
            .iter()
            .map(|r| (r.header.as_str(), r.column.as_str()))
            .collect();
        assert_eq!(
            names,
            [
                ("Time (min)", "time_s"),
                ("Volume (mm³)", "volume_mm3"),
                ("Spread (mm³)", "spread_mm3")
            ]
        );
        // Shaped like a potentiostat's tab-separated text export (EC-Lab's column names).
        let tsv = "time/s\tEwe/V\n0\t-0.35\n1.5\t-0.41\n";
        let read = parse(MeasurementKind::Ocp, Format::Csv, tsv.as_bytes()).expect("read");
        assert_eq!(read.columns["potential_v"], [-0.35, -0.41]);
        // A header read as no known column says what it was read from and what is taken.
        let refused = refused(MeasurementKind::WearVolume, "Time (s),Wear (µm³)\n1,2\n");
        let message = refused.to_string();
        assert!(
            message.contains("`wear_um3` (read from the header `Wear (µm³)`)"),
            "{message}"
        );
        assert!(message.contains("`volume_mm3`, `volume_um3`"), "{message}");
    }

    #[test]
    fn each_refusal_names_its_column() {
        use MeasurementKind::{Ocp, Profile, WearVolume};
        let cases = [
            (WearVolume, "volume_mm3\n0.1\n", "time_s or cycles"),
            (
                WearVolume,
                "cycles,volume_mm3\n10,0.1\n20,-0.1\n",
                "volume_mm3",
            ),
            (WearVolume, "cycles,volume_mm3\n10,0.1\n10,0.2\n", "cycles"),
            (
                WearVolume,
                "cycles,volume_mm3,volume_mm^3\n1,0,0\n",
                "volume_mm^3",
            ),
            (Profile, "y_mm,depth_um\n0,1\n0.1,NaN\n", "depth_um"),
            (Profile, "y_mm\n0\n", "depth_um"),
            (Ocp, "time_s,potential_v\n2,-0.2\n1,-0.3\n", "time_s"),
        ];
        for (kind, csv, column) in cases {
            let error = refused(kind, csv);
            assert_eq!(error.column(), column, "{csv}: {error}");
            let first = column.split(' ').next().unwrap_or(column);
            assert!(error.to_string().contains(first), "{error}");
        }
        let error = refused(Ocp, "time_s,potential_v\n2,-0.2\n1,-0.3\n");
        assert!(error.to_string().contains("row 2"), "{error}");
        // A unit not known is named with every spelling the column takes.
        let error = refused(WearVolume, "cycles,volume_cm3\n1,0\n");
        assert_eq!(error.column(), "volume_cm3");
        assert!(
            error.to_string().contains("`volume_mm3`, `volume_um3`"),
            "{error}"
        );
    }

    #[test]
    fn kinds_are_named_as_the_api_spells_them() {
        for kind in MeasurementKind::ALL {
            let json = serde_json::to_value(kind).expect("serialises");
            assert_eq!(json, serde_json::json!(kind.name()));
            assert_eq!(MeasurementKind::from_name(kind.name()), Some(kind));
        }
        assert_eq!(MeasurementKind::from_name("Profile"), None);
        assert_eq!(
            MeasurementKind::from_name("potential"),
            Some(MeasurementKind::Ocp)
        );
    }
}
