//! A study's summary: one row per member with its varied values and its run's summary or
//! its error, as JSON and as a markdown or CSV table.

use std::fmt::Display;

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

use crate::simulation::{Build, Summary};

use super::{Member, MemberOutcome};

/// The summary of a study that ran.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudySummary {
    /// The axes' paths, in the order given.
    pub axes: Vec<String>,
    /// Worker threads used.
    pub workers: usize,
    /// Wall-clock time of the whole study, s.
    pub wall_s: f64,
    /// One row per member, in the expansion order.
    pub members: Vec<MemberRow>,
    /// The build and the machine that wrote the summary, and when (each member's own run
    /// has its scene's SHA-256 in its result's provenance); absent from summaries written
    /// before it was recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub provenance: Option<Build>,
}

/// One member of a study that ran.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MemberRow {
    /// The member's position in the expansion order, from 0.
    pub index: usize,
    /// Each axis's path and the value it took.
    pub values: Map<String, Value>,
    /// The run's summary, when it finished.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub summary: Option<Summary>,
    /// Why the run stopped, when it did not finish.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Where a member that has not ended is, in a summary taken while the study runs (the
    /// service's); absent once it has ended, so always absent from `tribosim study`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pending: Option<Pending>,
}

/// Where a member that has not ended is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Pending {
    /// Waiting for a worker.
    Queued,
    /// Running.
    Running,
}

impl Pending {
    /// The state as the JSON spells it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Queued => "queued",
            Self::Running => "running",
        }
    }
}

/// The table's columns after the member number and the axes: `wear_volume_mm3` is the
/// total a profilometer measures, and `mechanical_volume_mm3` its mechanical part;
/// `warnings` flags a member whose numbers come with a caveat (after the older columns,
/// which keep their places).
const COLUMNS: [&str; 11] = [
    "cycles",
    "wear_volume_mm3",
    "max_depth_um",
    "wac_volume_mm3",
    "potential_v",
    "archard_k",
    "wall_s",
    "solves",
    "mechanical_volume_mm3",
    "error",
    "warnings",
];

impl StudySummary {
    /// Gathers the outcomes of `members` (as [`super::run_members`] returns them).
    pub fn new(
        members: &[Member],
        outcomes: &[MemberOutcome],
        workers: usize,
        wall_s: f64,
    ) -> Self {
        let results = outcomes
            .iter()
            .map(|outcome| match &outcome.result {
                Ok(result) => Ok(result.summary.clone()),
                Err(error) => Err(error),
            })
            .collect();
        Self::from_results(members, results, workers, wall_s)
    }

    /// Gathers each member's run summary, or why it has none, in the members' order: a
    /// study whose members ran elsewhere (a cluster's job array) is summarised by this same
    /// path. A member's `error` is the text of why it has none.
    pub fn from_results<E: Display>(
        members: &[Member],
        results: Vec<Result<Summary, E>>,
        workers: usize,
        wall_s: f64,
    ) -> Self {
        let axes = members
            .first()
            .map(|m| m.values.iter().map(|(path, _)| path.clone()).collect())
            .unwrap_or_default();
        let members = members
            .iter()
            .zip(results)
            .map(|(member, result)| {
                let (summary, error) = match result {
                    Ok(summary) => (Some(summary), None),
                    Err(error) => (None, Some(error.to_string())),
                };
                MemberRow {
                    index: member.index,
                    values: member.values.iter().cloned().collect(),
                    summary,
                    error,
                    pending: None,
                }
            })
            .collect();
        Self {
            axes,
            workers,
            wall_s,
            members,
            provenance: Some(Build::now()),
        }
    }

    /// How many members ended without a result.
    pub fn failed(&self) -> usize {
        self.members
            .iter()
            .filter(|m| m.summary.is_none() && m.pending.is_none())
            .count()
    }

    /// The header and the cells of each row, as text.
    fn cells(&self) -> (Vec<String>, Vec<Vec<String>>) {
        let header = std::iter::once("member".to_owned())
            .chain(self.axes.iter().cloned())
            .chain(COLUMNS.iter().map(|c| (*c).to_owned()))
            .collect();
        let rows = self.members.iter().map(|row| self.row_cells(row)).collect();
        (header, rows)
    }

    fn row_cells(&self, row: &MemberRow) -> Vec<String> {
        let mut cells = vec![row.index.to_string()];
        for axis in &self.axes {
            cells.push(row.values.get(axis).map(plain).unwrap_or_default());
        }
        let optional = |x: Option<f64>| x.map(|x| format!("{x:.6e}")).unwrap_or_default();
        match &row.summary {
            Some(s) => cells.extend([
                s.cycles.to_string(),
                format!("{:.6e}", s.wear_volume_mm3),
                format!("{:.4}", s.max_depth_um),
                optional(s.wac_volume_mm3),
                s.potential_v.map(|v| format!("{v:.5}")).unwrap_or_default(),
                format!("{:.6e}", s.wear.archard_k),
                format!("{:.2}", s.wall_s),
                s.solves.to_string(),
                optional(s.mechanical_volume_mm3),
                String::new(),
                s.warnings.join("; "),
            ]),
            None => {
                cells.extend(std::iter::repeat_n(String::new(), COLUMNS.len() - 2));
                let not_done = row.pending.map(|p| format!("not finished ({})", p.name()));
                cells.push(row.error.clone().or(not_done).unwrap_or_default());
                cells.push(String::new());
            }
        }
        cells
    }

    /// The rows as a markdown table.
    pub fn to_markdown(&self) -> String {
        let (header, rows) = self.cells();
        let line = |cells: &[String]| {
            let escaped: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
            format!("| {} |\n", escaped.join(" | "))
        };
        let mut text = line(&header);
        text += &format!("|{}\n", "---|".repeat(header.len()));
        for row in &rows {
            text += &line(row);
        }
        text
    }

    /// The rows as CSV ([`crate::csv::line`]: RFC 4180 quoting, formulas neutralised).
    pub fn to_csv(&self) -> String {
        let (header, rows) = self.cells();
        std::iter::once(header)
            .chain(rows)
            .map(|cells| crate::csv::line(&cells, "\n"))
            .collect()
    }
}

/// A value as a cell: strings without their JSON quotes.
fn plain(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failed_row(error: &str) -> StudySummary {
        StudySummary {
            axes: vec!["corrosion.model".into()],
            workers: 1,
            wall_s: 0.0,
            members: vec![MemberRow {
                index: 0,
                values: [("corrosion.model".to_owned(), Value::from("a|b"))]
                    .into_iter()
                    .collect(),
                summary: None,
                error: Some(error.into()),
                pending: None,
            }],
            provenance: None,
        }
    }

    #[test]
    fn an_error_with_commas_and_quotes_stays_one_csv_cell() {
        let csv = failed_row(r#"cycle 3: "x", then y"#).to_csv();
        let header = csv.lines().next().expect("a header");
        assert!(
            header.ends_with(",solves,mechanical_volume_mm3,error,warnings"),
            "{header}"
        );
        let row = csv.lines().nth(1).expect("a data row");
        // member, the axis, nine empty summary cells, the quoted error, no warnings.
        assert_eq!(row, r#"0,a|b,,,,,,,,,,"cycle 3: ""x"", then y","#);
    }

    #[test]
    fn a_value_a_spreadsheet_would_run_is_text_in_the_csv() {
        let mut summary = failed_row("=1+1");
        summary.members[0].values.insert(
            "corrosion.model".to_owned(),
            Value::from("=HYPERLINK(\"http://example.com\")"),
        );
        let csv = summary.to_csv();
        let row = csv.lines().nth(1).expect("a data row");
        assert_eq!(
            row,
            r#"0,"'=HYPERLINK(""http://example.com"")",,,,,,,,,,'=1+1,"#
        );
    }

    #[test]
    fn a_pipe_in_a_value_does_not_split_a_markdown_cell() {
        let markdown = failed_row("stopped").to_markdown();
        let row = markdown.lines().nth(2).expect("a data row");
        assert!(row.starts_with(r"| 0 | a\|b |"), "{row}");
        assert!(row.ends_with("| stopped |  |"), "{row}");
    }

    #[test]
    fn a_member_whose_run_warned_says_so_in_its_last_column() {
        // A real run whose potential eq. 18 capped at E_corr: the real contact F / H alone.
        let plan = crate::simulation::parse_scene_str(
            r#"{"test": {"cycles": 3}, "numerics": {"grid": 32},
                "corrosion": {"anodic_area": "real_contact"}}"#,
        )
        .expect("a valid scene");
        let setup = crate::simulation::Setup::new(&plan, &crate::simulation::RunOptions::default())
            .expect("a setup");
        let stop = std::sync::atomic::AtomicBool::new(false);
        let result = crate::simulation::run_setup(&setup, &mut |_| {}, &stop).expect("runs");
        let mut study = failed_row("");
        study.members[0].error = None;
        study.members[0].summary = Some(result.summary);
        let csv = study.to_csv();
        let row = csv.lines().nth(1).expect("a data row");
        // The last cell, quoted for its commas: the path and the first clause only, the
        // explanation after it staying in the result's field warnings.
        let cell = r#","corrosion.anodic_area: eq. 18 put the potential above E_corr at 3 solved cycle(s), the first at cycle 1""#;
        assert!(row.ends_with(cell), "{csv}");
    }
}
