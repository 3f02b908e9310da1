//! What a field descriptor is: a scene field's path, unit and allowed values, from which the
//! range checks word their messages and `docs/scene.md` its table, so the two cannot differ.

use super::format::num;

/// The values a scene field accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    /// One line of text of at most this many characters, with no character the text rule
    /// refuses ([`crate::text`]).
    Text(usize),
    /// An object of the fields listed under its path.
    Object,
    /// An object of fields, or `null` (or absent) to leave the section out.
    OptionalObject,
    /// A finite number.
    Finite,
    /// A finite number > 0.
    Positive,
    /// A number in `[lo, hi]`.
    Closed(f64, f64),
    /// A finite number `>= lo`.
    AtLeast(f64),
    /// A number in the open interval `(lo, hi)`.
    Open(f64, f64),
    /// A whole number in `lo..=hi`.
    Whole(u64, u64),
    /// `"auto"` or a whole number in `lo..=hi`.
    AutoOrWhole(u64, u64),
    /// `"auto"` or a number > 0 and <= the bound.
    AutoOrUpTo(f64),
    /// `"auto"` or a number in `[lo, hi]`.
    AutoOrClosed(f64, f64),
    /// `"auto"` or 1.
    AutoOrOne,
    /// One of these names.
    OneOf(&'static [&'static str]),
    /// `[[cycles, MPa], ...]` pairs for the hardness fit, or `null`.
    HardnessTable,
    /// `true` or `false`.
    Bool,
    /// `"auto"` or a list of at most this many cycles of the run.
    AutoOrCycles(u64),
}

impl Range {
    /// Whether the number `value` is allowed (for the ranges of numbers; the number part of
    /// `"auto"`-or-number ranges).
    pub fn admits(self, value: f64) -> bool {
        match self {
            Self::Finite => value.is_finite(),
            Self::Positive => value > 0.0 && value.is_finite(),
            Self::Closed(lo, hi) | Self::AutoOrClosed(lo, hi) => {
                (lo..=hi).contains(&value) && value.is_finite()
            }
            Self::AtLeast(lo) => value >= lo && value.is_finite(),
            Self::Open(lo, hi) => value > lo && value < hi,
            Self::AutoOrUpTo(hi) => value > 0.0 && value <= hi,
            Self::Whole(lo, hi) | Self::AutoOrWhole(lo, hi) => {
                value.fract() == 0.0 && value >= lo as f64 && value <= hi as f64
            }
            Self::AutoOrOne => value.to_bits() == 1f64.to_bits(),
            Self::Text(_) | Self::Object | Self::OptionalObject | Self::OneOf(_) => false,
            Self::HardnessTable | Self::Bool | Self::AutoOrCycles(_) => false,
        }
    }

    /// Whether the field is a plain number (so an empty unit means dimensionless).
    pub fn is_number(self) -> bool {
        matches!(
            self,
            Self::Finite | Self::Positive | Self::Closed(..) | Self::AtLeast(_) | Self::Open(..)
        )
    }

    /// Whether the whole number `value` is allowed.
    pub fn admits_whole(self, value: u64) -> bool {
        match self {
            Self::Whole(lo, hi) | Self::AutoOrWhole(lo, hi) => (lo..=hi).contains(&value),
            other => other.admits(value as f64),
        }
    }

    /// What the field must be, in words that follow "must be", with `unit` ("" for none)
    /// after each bound.
    pub fn describe(self, unit: &str) -> String {
        let u = if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        };
        let of = if unit.is_empty() {
            String::new()
        } else {
            format!(" of {unit}")
        };
        match self {
            Self::Text(most) => crate::text::describe(most, crate::text::Lines::One),
            Self::Object => "an object of the fields below".to_owned(),
            Self::OptionalObject => {
                "an object of the fields below, or null or absent for none".to_owned()
            }
            Self::Finite => "a finite number".to_owned(),
            Self::Positive => format!("> 0{u} and finite"),
            Self::Closed(lo, hi) => format!("in [{}, {}]{u}", num(lo), num(hi)),
            Self::AtLeast(lo) => format!(">= {}{u} and finite", num(lo)),
            Self::Open(lo, hi) => {
                format!("in the open interval ({}, {}){u}", num(lo), num(hi))
            }
            Self::Whole(lo, hi) => format!("a whole number{of} in {lo}..={hi}"),
            Self::AutoOrWhole(lo, hi) => format!("\"auto\" or a whole number{of} in {lo}..={hi}"),
            Self::AutoOrUpTo(hi) => format!("\"auto\" or > 0{u} and <= {}{u}", num(hi)),
            Self::AutoOrClosed(lo, hi) => format!("\"auto\" or in [{}, {}]{u}", num(lo), num(hi)),
            Self::AutoOrOne => {
                "1 (every cycle solved) or \"auto\" (steps chosen under an error bound)".to_owned()
            }
            Self::OneOf(names) => {
                let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
                format!("one of {}", quoted.join(", "))
            }
            Self::HardnessTable => "null, or a list of [cycles, MPa] pairs, cycles >= 1 and \
                                    strictly increasing, MPa > 0; the fitted law must stay \
                                    > 0 MPa over the run"
                .to_owned(),
            Self::Bool => "true or false".to_owned(),
            Self::AutoOrCycles(most) => {
                format!("\"auto\" or a list of at most {most} cycles, each in 1..=`test.cycles`")
            }
        }
    }
}

/// One field a scene accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    /// Dotted path, e.g. `test.load_n`.
    pub path: &'static str,
    /// Unit of the value as written ("" for dimensionless numbers and non-numbers).
    pub unit: &'static str,
    /// The values accepted.
    pub range: Range,
    /// Why the bounds are where they are, appended to the range check's message ("" when
    /// the range needs no reason).
    pub why: &'static str,
    /// What the field means.
    pub meaning: &'static str,
    /// Where the paper's model uses it (equation, table or figure).
    pub feeds: &'static str,
}

impl Field {
    /// The allowed values in words, with the reason for the bounds.
    pub fn allowed(&self) -> String {
        let range = self.range.describe(self.unit);
        if self.why.is_empty() {
            range
        } else {
            format!("{range} ({})", self.why)
        }
    }

    /// The message of a range check that the value `got` failed.
    pub fn message(&self, got: &str) -> String {
        format!("must be {}, got {got}", self.allowed())
    }

    /// [`Self::message`] for a number.
    pub fn number_message(&self, value: f64) -> String {
        self.message(&num(value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_inclusive_or_exclusive_as_described() {
        assert!(Range::Closed(0.0, 2.0).admits(2.0));
        assert!(!Range::Closed(0.0, 2.0).admits(f64::NAN));
        assert!(!Range::Open(-1.0, 0.5).admits(-1.0));
        assert!(!Range::Positive.admits(0.0));
        assert!(!Range::Positive.admits(f64::INFINITY));
        assert!(Range::AtLeast(0.0).admits(0.0));
        assert!(Range::AutoOrUpTo(10.0).admits(10.0));
        assert!(!Range::AutoOrUpTo(10.0).admits(0.0));
        assert!(Range::Whole(1, 5).admits_whole(5));
        assert!(!Range::Whole(1, 5).admits_whole(0));
        assert!(!Range::Whole(1, 5).admits(2.5));
    }

    #[test]
    fn messages_name_the_range_its_reason_and_the_value() {
        let field = Field {
            path: "test.load_n",
            unit: "N",
            range: Range::Positive,
            why: "",
            meaning: "",
            feeds: "",
        };
        assert_eq!(
            field.number_message(-5.0),
            "must be > 0 N and finite, got -5"
        );
        let grid = Field {
            unit: "cells",
            range: Range::AutoOrWhole(8, 2048),
            why: "a reason",
            ..field
        };
        assert_eq!(
            grid.message("4096"),
            "must be \"auto\" or a whole number of cells in 8..=2048 (a reason), got 4096"
        );
    }
}
