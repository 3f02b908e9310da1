//! Studies: one base scene run across the combinations of some of its values ("what if the
//! load were 2, 5 or 10 N at 30 or 60 rpm"). A study expands to one ordinary scene per
//! combination ([`Study::members`]), runs them on worker threads ([`run_members`]) and
//! gathers one row per member ([`StudySummary`]). Plain synchronous code over
//! [`crate::simulation`]; the command line drives it through [`command`], and through
//! [`slurm`] writes it as a Slurm job array and collects the results.

mod axes;
pub mod command;

mod expand;
mod run;
pub mod slurm;
mod summary;

use serde_json::Value;
use thiserror::Error;

use crate::json::JsonError;
use crate::scene::{Scene, SceneErrors};
use crate::text::{Lines, NAME_MAX_CHARS, TextError, check};

pub use axes::{AXIS_PATH_MAX_CHARS, AXIS_VALUE_MAX_CHARS, Axis, AxisValues, MAX_RANGE_STEPS};
pub use run::{MemberOutcome, run_members};
pub use summary::{MemberRow, Pending, StudySummary};

/// The most members a study may have unless the caller raises it: at the paper's full test
/// (about 6 s a run on one core) 1000 members are hours of a workstation's time, which a
/// user should ask for knowingly.
pub const MAX_MEMBERS: usize = 1000;

/// The most axes a study may have: at two values each, 16 axes are 65,536 members, far past
/// any member limit; an axis of one value is an override, which belongs in the base. Counted
/// before any axis is read, and it bounds a member's name, which lists every axis's value.
pub const MAX_AXES: usize = 16;

/// A base scene and the axes along which it varies.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The study's own name, if the file gives one (else [`Study::name`] makes one).
    pub name: Option<String>,
    /// Any scene document, including the `{"preset": ..., "overrides": ...}` form.
    pub base: Value,
    /// The axes, in the order given: the first varies slowest across the members.
    pub axes: Vec<Axis>,
}

/// One combination of the axes' values and the scene it gives.
#[derive(Debug, Clone, PartialEq)]
pub struct Member {
    /// Position in the expansion order, from 0.
    pub index: usize,
    /// Each axis's path and the value it takes here, in the axes' order.
    pub values: Vec<(String, Value)>,
    /// The base scene with these values set.
    pub scene: Scene,
}

/// Why a study was refused before any member ran.
#[derive(Debug, Error)]
pub enum StudyError {
    /// The study file is not JSON, or gives a key twice.
    #[error("{0}")]
    Json(#[from] JsonError),
    /// The study document does not have the study's shape (`base` and `axes`, an optional
    /// `name`, nothing else).
    #[error("invalid study: {0}")]
    Shape(#[source] serde_json::Error),
    /// `base` is not a JSON object, so no scene.
    #[error("`base` must be a scene (a JSON object)")]
    BaseNotObject,
    /// The study's `name` is too long or holds a character the text rule refuses.
    #[error("`name`: {0}")]
    Name(#[source] TextError),
    /// More axes than [`MAX_AXES`].
    #[error("the study has {axes} axes; at most {MAX_AXES}")]
    TooManyAxes {
        /// How many axes it has.
        axes: usize,
    },
    /// A study with no axes is a single run.
    #[error("the study has no axes; give at least one under `axes` (or use `tribosim run`)")]
    NoAxes,
    /// An axis's values are malformed or empty.
    #[error("axis `{axis}`: {message}")]
    Axis {
        /// The axis's dotted path.
        axis: String,
        /// What is wrong with its values.
        message: String,
    },
    /// The combinations exceed the member limit.
    #[error("the axes give {members} members ({sizes}), over the limit of {limit}")]
    TooManyMembers {
        /// How many members the axes give (saturated at `usize::MAX`).
        members: usize,
        /// Each axis with its count of values, as `test.load_n: 3 x test.speed_rpm: 2`.
        sizes: String,
        /// The limit in force.
        limit: usize,
    },
    /// A member's scene is refused by the scene parser, which names the field (an unknown
    /// path is an unknown field there).
    #[error("member {index} ({values}): {source}")]
    Member {
        /// The member's position in the expansion order.
        index: usize,
        /// Its values, as `test.load_n = 2, test.speed_rpm = 30`.
        values: String,
        /// What the scene parser reported.
        #[source]
        source: SceneErrors,
    },
}

/// The values of a member as a person reads them: `test.load_n = 2, test.speed_rpm = 30`.
pub fn describe_values(values: &[(String, Value)]) -> String {
    values
        .iter()
        .map(|(path, value)| format!("{path} = {value}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The study document as written: the base and the axes in the file's order (a JSON object
/// read into a map would sort them).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyFile {
    #[serde(default)]
    name: Option<String>,
    base: Value,
    axes: axes::OrderedAxes,
}

impl Study {
    /// Parses a study: `{"name": ..., "base": SCENE, "axes": {"test.load_n": [2, 5, 10],
    /// ...}}` (`name` optional), each axis a list of values or `{"from": A, "to": B,
    /// "steps": N}`. Refuses a key given twice anywhere, as a scene does; a name as a
    /// scene's name is refused ([`NAME_MAX_CHARS`], [`crate::text`]); more than
    /// [`MAX_AXES`] axes, counted before any is read.
    pub fn parse(text: &str) -> Result<Self, StudyError> {
        crate::json::from_str(text)?;
        let file: StudyFile = serde_json::from_str(text).map_err(StudyError::Shape)?;
        if let Some(name) = &file.name {
            check(name, NAME_MAX_CHARS, Lines::One).map_err(StudyError::Name)?;
        }
        if file.axes.0.len() > MAX_AXES {
            return Err(StudyError::TooManyAxes {
                axes: file.axes.0.len(),
            });
        }
        let axes = file
            .axes
            .0
            .into_iter()
            .map(|(path, values)| Axis::from_json(path, &values))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            name: file.name,
            base: file.base,
            axes,
        })
    }

    /// What the study is called: the file's `name`, or else the name its base scene writes
    /// (`name`, or `overrides.name` under a preset). A preset's own name describes that
    /// one test ("316L vs alumina, 5 N, 60 rpm"), which the axes contradict, so a study
    /// that writes neither is called after the preset and its axes (`dalmau2018-316l varied
    /// in test.load_n, test.speed_rpm`); a base of neither a preset nor a name is the
    /// default scene's `untitled`.
    pub fn name(&self) -> String {
        if let Some(name) = &self.name {
            return name.clone();
        }
        let written = ["/name", "/overrides/name"]
            .iter()
            .find_map(|at| self.base.pointer(at).and_then(Value::as_str));
        let name = match written {
            Some(written) => written.to_owned(),
            None => match self.base.get("preset").and_then(Value::as_str) {
                Some(preset) => {
                    let paths: Vec<&str> = self.axes.iter().map(|a| a.path.as_str()).collect();
                    format!("{preset} varied in {}", paths.join(", "))
                }
                None => Scene::default().name,
            },
        };
        // A name the scene's check would refuse stops its members at parsing, which says
        // why; here it only has to be a name a member can carry.
        crate::text::tidy(&name, NAME_MAX_CHARS)
    }

    /// How many members the axes give, from their counts alone (no value is built),
    /// saturating rather than overflowing.
    pub fn member_count(&self) -> usize {
        self.axes
            .iter()
            .fold(1usize, |n, axis| n.saturating_mul(axis.values.len()))
    }
}
