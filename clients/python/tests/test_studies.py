"""Studies: submit, wait, the summary as a DataFrame and CSV, the members' jobs."""

from __future__ import annotations

import io
import json
from pathlib import Path

import pandas as pd
import pytest

import tribosim

from conftest import ENDLESS, SMALL

STUDY = {
    "base": SMALL,
    "axes": {"test.load_n": [2, 5], "test.speed_rpm": {"from": 30, "to": 60, "steps": 1}},
}
#: What the summary's CSV writes: 7 significant digits (``2.998530e-5``), so it reads back
#: within half a unit of the 7th digit.
CSV_RELATIVE = 5e-7


@pytest.fixture(scope="module")
def study(client: tribosim.Client) -> tribosim.Study:
    study = client.studies.submit(STUDY)
    study.wait(progress=False)
    return study


def test_summary(study: tribosim.Study) -> None:
    assert study.info.status == "succeeded"
    summary = study.summary()
    assert summary["member"].tolist() == [0, 1, 2, 3]
    # The first axis varies slowest.
    assert summary["test.load_n"].tolist() == [2, 2, 5, 5]
    assert summary["test.speed_rpm"].tolist() == [30, 60, 30, 60]
    for column in [
        "cycles",
        "wear_volume_mm3",
        "max_depth_um",
        "wac_volume_mm3",
        "potential_v",
        "archard_k",
    ]:
        assert summary[column].notna().all()
    assert summary["error"].isna().all() and summary["pending"].isna().all()
    # Archard wear grows with the load; per cycle it does not depend on the speed.
    by_load = summary.groupby("test.load_n")["wear_volume_mm3"]
    assert by_load.min()[5] > by_load.max()[2]
    assert by_load.nunique().tolist() == [1, 1]


def test_summary_csv(study: tribosim.Study) -> None:
    table = pd.read_csv(io.StringIO(study.summary_csv()))
    summary = study.summary()
    assert table["member"].tolist() == summary["member"].tolist()
    assert table["wear_volume_mm3"].tolist() == pytest.approx(
        summary["wear_volume_mm3"].tolist(), rel=CSV_RELATIVE
    )


def test_members_are_jobs(study: tribosim.Study) -> None:
    summary = study.summary()
    jobs = study.jobs()
    assert len(jobs) == 4
    for job, volume in zip(jobs, summary["wear_volume_mm3"]):
        assert job.result().summary["wear_volume_mm3"] == volume


def test_list_and_get(client: tribosim.Client, study: tribosim.Study) -> None:
    assert study.id in [s.id for s in client.studies.list()]
    assert client.studies.get(study.id).info == study.info
    assert study.summary_json()["axes"] == ["test.load_n", "test.speed_rpm"]


def test_a_bad_study_names_the_field(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.ValidationError) as refused:
        client.studies.submit({"base": SMALL, "axes": {"test.lod_n": [1, 2]}})
    assert [f.path for f in refused.value.fields] == ["base.overrides.test.lod_n"]


def test_submit_a_file(client: tribosim.Client, tmp_path: Path) -> None:
    path = tmp_path / "study.json"
    path.write_text(json.dumps({"base": SMALL, "axes": {"test.load_n": [3]}}))
    study = client.studies.submit(path)
    assert study.wait(progress=False).counts["succeeded"] == 1
    study.delete()


def test_submit_takes_a_name_as_jobs_submit_does(client: tribosim.Client, tmp_path: Path) -> None:
    path = tmp_path / "study.json"
    path.write_text(json.dumps({"base": SMALL, "axes": {"test.load_n": [3]}}))
    submitted = {
        "from a file": client.studies.submit(path, name="from a file"),
        "from a mapping": client.studies.submit(
            {"base": SMALL, "axes": {"test.load_n": [3]}}, name="from a mapping"
        ),
    }
    for name, study in submitted.items():
        assert study.info.name == name
        study.wait(progress=False)
        # A member is named after the base's name and its values.
        assert all(job.info.name.startswith(name) for job in study.jobs())
        study.delete()
    # The name goes into a copy: the mapping given is left as it was.
    assert "name" not in SMALL["overrides"]


def test_cancel_and_delete(client: tribosim.Client) -> None:
    study = client.studies.submit({"base": ENDLESS, "axes": {"test.load_n": [2, 5, 10]}})
    study.cancel()
    with pytest.raises(tribosim.RunFailedError):
        study.wait(progress=False)
    assert study.info.status == "cancelled"
    summary = study.summary()
    assert summary["error"].notna().all()
    job_ids = [m["job_id"] for m in study.info.members]
    study.delete()
    with pytest.raises(tribosim.NotFoundError):
        study.refresh()
    with pytest.raises(tribosim.NotFoundError):
        client.jobs.get(job_ids[0])


def test_report(study: tribosim.Study, tmp_path: Path) -> None:
    html = study.report(tmp_path / "study.html")
    assert html.startswith("<!DOCTYPE html>")
    assert "<table>" in html and "<svg" in html
    assert (tmp_path / "study.html").read_text(encoding="utf-8") == html
