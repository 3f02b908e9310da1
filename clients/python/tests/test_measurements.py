"""Measured points attached to a job, from a DataFrame, CSV text or a file."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

import tribosim

from conftest import REPO

TABLE3_WEAR = REPO / "docs" / "calibration" / "table3_wear.csv"


def test_put_get_delete(small_job: tribosim.Job, tmp_path: Path) -> None:
    wear = pd.read_csv(TABLE3_WEAR, comment="#")
    tables = small_job.measurements.put("wear_volume", wear)
    pd.testing.assert_frame_equal(
        tables["wear_volume"][list(wear.columns)], wear, check_dtype=False
    )
    assert tables["profile"] is None and tables["ocp"] is None

    small_job.measurements.put("profile", "y_mm,depth_um\n-0.1,0\n0,0.2\n0.1,0\n")
    potential = tmp_path / "potential.csv"
    potential.write_text("# during rubbing\ntime_s,potential_v\n1,-0.30\n2,-0.35\n")
    small_job.measurements.put("potential", potential)

    tables = small_job.measurements.get()
    assert tables["profile"] is not None and tables["profile"]["depth_um"].tolist() == [0, 0.2, 0]
    assert tables["ocp"] is not None and tables["ocp"]["potential_v"].tolist() == [
        -0.30,
        -0.35,
    ]

    left = small_job.measurements.delete("profile")
    assert left["profile"] is None and left["wear_volume"] is not None
    assert small_job.measurements.get()["profile"] is None


def test_a_named_index_is_sent_as_a_column(small_job: tribosim.Job) -> None:
    wear = pd.read_csv(TABLE3_WEAR, comment="#").set_index("time_s")
    tables = small_job.measurements.put("wear_volume", wear)
    assert tables["wear_volume"] is not None
    assert tables["wear_volume"]["time_s"].tolist() == wear.index.tolist()


def test_columns_and_rows(small_job: tribosim.Job) -> None:
    columns = {"cycles": [10, 20], "volume_mm3": [1e-4, 2e-4]}
    rows = [{"cycles": 10, "volume_mm3": 1e-4}, {"cycles": 20, "volume_mm3": 2e-4}]
    first = small_job.measurements.put("wear_volume", columns)["wear_volume"]
    second = small_job.measurements.put("wear_volume", rows)["wear_volume"]
    assert first is not None and second is not None
    pd.testing.assert_frame_equal(first, second)


def test_a_bad_table_names_its_column(small_job: tribosim.Job) -> None:
    with pytest.raises(tribosim.ValidationError) as refused:
        small_job.measurements.put("ocp", "time_s,potential_v\n1,-0.3\n0,-0.2\n")
    assert refused.value.fields[0].path == "time_s"
    assert "row 2" in refused.value.fields[0].message


def test_an_unknown_kind_is_refused(small_job: tribosim.Job) -> None:
    with pytest.raises(tribosim.RefusedError) as refused:
        small_job.measurements.put("hardness", "cycles,hardness_mpa\n10,2551\n")
    assert refused.value.status == 400


def test_a_file_name_is_not_a_table(small_job: tribosim.Job) -> None:
    with pytest.raises(TypeError, match="pathlib.Path"):
        small_job.measurements.put("wear_volume", str(TABLE3_WEAR))


def test_scores_against_the_finished_run(small_job: tribosim.Job) -> None:
    small_job.measurements.put("wear_volume", "cycles;volume_um3;spread_um3\n1;1000;500\n")
    scores = small_job.measurements.scores()
    wear = scores["wear_volume"]
    assert wear["x_column"] == "cycles" and wear["column"] == "volume_mm3"
    point = wear["points"][0]
    assert point["measured"] == pytest.approx(1e-6)
    assert point["residual"] == pytest.approx(point["measured"] - point["model"])
    assert point["z_score"] == pytest.approx(point["residual"] / 5e-7)
    assert scores["profile"] is None
    csv = small_job.measurements.scores_csv().splitlines()
    assert csv[0].startswith("kind,x_column,x,column,measured,model,residual,z_score")
    assert csv[1].startswith("wear_volume,cycles,1,volume_mm3,")


def test_a_lab_export_is_read_and_its_headers_reported(small_job: tribosim.Job) -> None:
    # Shaped like a tribometer's CSV export: units in parentheses, a superscript three.
    csv = "Time (s),Volume (mm³)\n1,0.0001\n2,0.0002\n"
    tables = small_job.measurements.put("wear_volume", csv)
    assert tables["wear_volume"]["volume_mm3"].tolist() == [0.0001, 0.0002]
    assert small_job.measurements.renamed == {"Time (s)": "time_s", "Volume (mm³)": "volume_mm3"}
