//! `numerics.record_cycles`: the cycles at which the state is recorded exactly (solved there,
//! its profile kept), `"auto"` for the paper's Table 3 times within the run or a list.

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Table 3's rubbing times, s: where the paper measured wear volume and hardness.
pub const TABLE3_TIMES_S: [f64; 5] = [10.0, 60.0, 300.0, 1800.0, 3600.0];

/// The most cycles a scene may name: each is a solved cycle and a kept profile.
pub const MAX_RECORD_CYCLES: usize = 1000;

/// Which cycles are recorded exactly.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum RecordCycles {
    /// Table 3's times, as cycles at the scene's speed, within the run.
    #[default]
    Auto,
    /// These cycles.
    Cycles(Vec<u64>),
}

impl RecordCycles {
    /// The cycles to record for a run of `total` cycles at `speed_rpm`, ascending, each once.
    /// Named cycles beyond the run are the validator's to refuse; here they are left out.
    pub fn resolve(&self, total: u64, speed_rpm: f64) -> Vec<u64> {
        let mut cycles: Vec<u64> = match self {
            Self::Auto => TABLE3_TIMES_S
                .iter()
                .map(|time_s| (time_s * speed_rpm / 60.0).round().max(1.0) as u64)
                .collect(),
            Self::Cycles(cycles) => cycles.clone(),
        };
        cycles.retain(|&c| (1..=total).contains(&c));
        cycles.sort_unstable();
        cycles.dedup();
        cycles
    }
}

impl Serialize for RecordCycles {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::Auto => serializer.serialize_str("auto"),
            Self::Cycles(cycles) => cycles.serialize(serializer),
        }
    }
}

impl<'de> Deserialize<'de> for RecordCycles {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(deserializer)?;
        if value.as_str() == Some("auto") {
            return Ok(Self::Auto);
        }
        Vec::<u64>::deserialize(&value)
            .map(Self::Cycles)
            .map_err(|e| {
                D::Error::custom(format!(
                    "expected \"auto\" (Table 3's times) or a list of whole cycle numbers ({e})"
                ))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_is_table_3_within_the_run_at_the_scenes_speed() {
        assert_eq!(
            RecordCycles::Auto.resolve(3600, 60.0),
            [10, 60, 300, 1800, 3600]
        );
        assert_eq!(RecordCycles::Auto.resolve(300, 60.0), [10, 60, 300]);
        // 30 rpm: half a cycle per second.
        assert_eq!(
            RecordCycles::Auto.resolve(3600, 30.0),
            [5, 30, 150, 900, 1800]
        );
    }

    #[test]
    fn a_list_is_sorted_and_deduplicated_and_round_trips() {
        let named = RecordCycles::Cycles(vec![50, 7, 50]);
        assert_eq!(named.resolve(100, 60.0), [7, 50]);
        let json = serde_json::to_value(&named).expect("serialises");
        assert_eq!(json, serde_json::json!([50, 7, 50]));
        let back: RecordCycles = serde_json::from_value(json).expect("parses");
        assert_eq!(back, named);
        let auto: RecordCycles = serde_json::from_str("\"auto\"").expect("parses");
        assert_eq!(auto, RecordCycles::Auto);
        let bad = serde_json::from_str::<RecordCycles>("[1.5]").expect_err("not whole");
        assert!(
            bad.to_string().contains("list of whole cycle numbers"),
            "{bad}"
        );
    }
}
