//! A result's tables as CSV, for spreadsheet users: the cycles, the profiles, the pressure
//! maps; and the result without its pressure maps, for big grids.

use serde::Deserialize;
use serde_json::Value;

use time::format_description::well_known::Rfc3339;

use crate::simulation::{CycleRecord, PressureMap, Profile, Provenance};

/// The CSV columns: the cycle record's with its names (units in the names), the later
/// corrosion fields and the loaded depth after the first three so that earlier columns keep
/// their places, the cycles stepped over since the previous row, then the result's provenance, the same on
/// every row, so that the file stays one table any CSV reader takes and a row copied
/// elsewhere still says where it comes from.
const HEADER: &str = "cycle,time_s,wear_volume_mm3,max_depth_um,max_pressure_mpa,\
                      contact_area_mm2,plastic_area_mm2,contact_islands,hardness_mpa,approach_um,iterations,\
                      potential_v,anodic_area_mm2,wac_volume_mm3,contact_chord_um,anodic_current_ma,\
                      charge_c,total_volume_mm3,mechanical_volume_mm3,loaded_max_depth_um,cycles_stepped_over,\
                      tribosim_version,git_commit,scene_sha256,computed_at,cores";

/// Only the cycles and the provenance of a result; the rest of the document is skipped
/// unparsed.
#[derive(Deserialize)]
struct Cycles {
    cycles: Vec<CycleRecord>,
    #[serde(default)]
    provenance: Option<Provenance>,
}

/// The provenance columns' cells: empty for a result written before it was recorded.
fn provenance_cells(provenance: Option<&Provenance>) -> [String; 5] {
    let Some(p) = provenance else {
        return Default::default();
    };
    [
        p.build.tribosim_version.clone(),
        p.build.git_commit.clone(),
        p.scene_sha256.clone(),
        p.build.computed_at.format(&Rfc3339).unwrap_or_default(),
        p.build.cores.to_string(),
    ]
}

/// The `cycles` of a result JSON as CSV: one row per solved cycle. The corrosion columns are
/// always present and empty for a scene without corrosion, so every file has one shape.
/// `cycles_stepped_over` counts the cycles between the previous row and this one that were
/// not solved: with `numerics.cycle_step` "auto" the previous solve stood for them (the
/// cycle loop's step, Fig. 4), wearing the groove at its pressure.
pub fn cycles_csv(result_json: &[u8]) -> Result<String, serde_json::Error> {
    let Cycles { cycles, provenance } = serde_json::from_slice(result_json)?;
    let provenance = provenance_cells(provenance.as_ref());
    let mut csv = String::with_capacity(64 + cycles.len() * 160);
    csv.push_str(&crate::csv::line(
        &HEADER.split(',').collect::<Vec<_>>(),
        "\r\n",
    ));
    let mut previous = 0;
    for c in &cycles {
        let stepped_over = c.cycle.saturating_sub(previous + 1);
        previous = c.cycle;
        let optional = |value: Option<f64>| value.map(|v| v.to_string()).unwrap_or_default();
        let cells = [
            c.cycle.to_string(),
            c.time_s.to_string(),
            c.wear_volume_mm3.to_string(),
            c.max_depth_um.to_string(),
            c.max_pressure_mpa.to_string(),
            c.contact_area_mm2.to_string(),
            c.plastic_area_mm2.to_string(),
            c.contact_islands.to_string(),
            c.hardness_mpa.to_string(),
            c.approach_um.to_string(),
            c.iterations.to_string(),
            optional(c.potential_v),
            optional(c.anodic_area_mm2),
            optional(c.wac_volume_mm3),
            optional(c.contact_chord_um),
            optional(c.anodic_current_ma),
            optional(c.charge_c),
            optional(c.total_volume_mm3),
            optional(c.mechanical_volume_mm3),
            c.loaded_max_depth_um.to_string(),
            stepped_over.to_string(),
        ];
        let row: Vec<&str> = cells
            .iter()
            .chain(&provenance)
            .map(String::as_str)
            .collect();
        csv.push_str(&crate::csv::line(&row, "\r\n"));
    }
    Ok(csv)
}

/// Only the profiles of a result.
#[derive(Deserialize)]
struct Profiles {
    profiles: Vec<Profile>,
}

/// Only the pressure maps of a result.
#[derive(Deserialize)]
struct PressureMaps {
    pressure_maps: Vec<PressureMap>,
}

/// The `profiles` of a result JSON as CSV in long form, one row per point:
/// `cycle,y_um,depth_um`.
pub fn profiles_csv(result_json: &[u8]) -> Result<String, serde_json::Error> {
    let Profiles { profiles } = serde_json::from_slice(result_json)?;
    let mut csv = crate::csv::line(&["cycle", "y_um", "depth_um"], "\r\n");
    for p in &profiles {
        for (y, depth) in p.y_um.iter().zip(&p.depth_um) {
            let cells = [p.cycle.to_string(), y.to_string(), depth.to_string()];
            csv.push_str(&crate::csv::line(&cells, "\r\n"));
        }
    }
    Ok(csv)
}

/// The `pressure_maps` of a result JSON as CSV in long form, one row per cell:
/// `cycle,x_um,y_um,pressure_mpa`.
pub fn pressure_csv(result_json: &[u8]) -> Result<String, serde_json::Error> {
    let PressureMaps { pressure_maps } = serde_json::from_slice(result_json)?;
    let mut csv = crate::csv::line(&["cycle", "x_um", "y_um", "pressure_mpa"], "\r\n");
    for map in &pressure_maps {
        for (y, row) in map.y_um.iter().zip(&map.pressure_mpa) {
            for (x, p) in map.x_um.iter().zip(row) {
                let cells = [
                    map.cycle.to_string(),
                    x.to_string(),
                    y.to_string(),
                    p.to_string(),
                ];
                csv.push_str(&crate::csv::line(&cells, "\r\n"));
            }
        }
    }
    Ok(csv)
}

/// A result JSON with `pressure_maps` empty: the one part of a result that grows with the
/// square of the grid (`pressure.csv` gives them apart).
pub fn compact(result_json: &[u8]) -> Result<Vec<u8>, serde_json::Error> {
    let mut result: Value = serde_json::from_slice(result_json)?;
    if let Some(maps) = result.get_mut("pressure_maps") {
        *maps = Value::Array(Vec::new());
    }
    serde_json::to_vec(&result)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_row_per_cycle_with_empty_corrosion_cells_and_the_cycles_stepped_over() {
        let json = br#"{"scene": {}, "cycles": [
            {"cycle": 1, "time_s": 1.0, "wear_volume_mm3": 0.5, "max_depth_um": 0.25,
             "max_pressure_mpa": 1200.0, "contact_area_mm2": 0.01, "plastic_area_mm2": 0.0,
             "hardness_mpa": 2473.0, "approach_um": 1.5, "iterations": 12},
            {"cycle": 3, "time_s": 3.0, "wear_volume_mm3": 1.5, "max_depth_um": 0.5,
             "max_pressure_mpa": 1100.0, "contact_area_mm2": 0.02, "plastic_area_mm2": 0.001,
             "hardness_mpa": 2500.0, "approach_um": 1.6, "iterations": 9, "contact_islands": 4,
             "potential_v": -0.2, "anodic_area_mm2": 0.3, "wac_volume_mm3": 1e-6,
             "contact_chord_um": 70.0, "anodic_current_ma": 0.03, "charge_c": 0.5,
             "total_volume_mm3": 1.500001, "mechanical_volume_mm3": 1.5,
             "loaded_max_depth_um": 0.75}
        ]}"#;
        let csv = cycles_csv(json).expect("valid result");
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0].split(',').count(), 26);
        assert_eq!(
            lines[1],
            "1,1,0.5,0.25,1200,0.01,0,0,2473,1.5,12,,,,,,,,,0,0,,,,,"
        );
        // Cycle 2 was stepped over: cycle 1's solve stood for it.
        assert_eq!(
            lines[2],
            "3,3,1.5,0.5,1100,0.02,0.001,4,2500,1.6,9,-0.2,0.3,0.000001,70,0.03,0.5,1.500001,1.5,0.75,1,,,,,"
        );
    }

    #[test]
    fn every_row_carries_the_provenance() {
        let json = br#"{"cycles": [
            {"cycle": 1, "time_s": 1.0, "wear_volume_mm3": 0.5, "max_depth_um": 0.25,
             "max_pressure_mpa": 1200.0, "contact_area_mm2": 0.01, "plastic_area_mm2": 0.0,
             "hardness_mpa": 2473.0, "approach_um": 1.5, "iterations": 12}],
            "provenance": {"tribosim_version": "0.1.0", "git_commit": "unknown",
             "computed_at": "2026-11-26T18:00:00Z", "cores": 2, "scene_sha256": "ab12"}}"#;
        let csv = cycles_csv(json).expect("valid result");
        let lines: Vec<&str> = csv.lines().collect();
        assert!(lines[0].ends_with(",tribosim_version,git_commit,scene_sha256,computed_at,cores"));
        assert!(
            lines[1].ends_with(",0,0.1.0,unknown,ab12,2026-11-26T18:00:00Z,2"),
            "{}",
            lines[1]
        );
    }

    #[test]
    fn profiles_and_maps_are_one_row_per_point_and_compact_drops_the_maps() {
        let json = br#"{"complete": true, "cycles": [],
            "profiles": [{"cycle": 1, "y_um": [-1.5, 0.0], "depth_um": [0.0, 0.25]},
                         {"cycle": 3, "y_um": [0.0], "depth_um": [0.5]}],
            "pressure_maps": [{"cycle": 3, "x_um": [-1.0, 1.0], "y_um": [0.0],
                               "pressure_mpa": [[900.0, -0.0]]}]}"#;
        let profiles = profiles_csv(json).expect("valid");
        assert_eq!(
            profiles,
            "cycle,y_um,depth_um\r\n1,-1.5,0\r\n1,0,0.25\r\n3,0,0.5\r\n"
        );
        let pressure = pressure_csv(json).expect("valid");
        assert_eq!(
            pressure,
            "cycle,x_um,y_um,pressure_mpa\r\n3,-1,0,900\r\n3,1,0,-0\r\n"
        );
        let compact: Value = serde_json::from_slice(&compact(json).expect("valid")).expect("JSON");
        assert_eq!(compact["pressure_maps"], serde_json::json!([]));
        assert_eq!(compact["profiles"][1]["cycle"], 3);
        assert_eq!(compact["complete"], true);
    }
}
