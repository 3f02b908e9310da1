"""Jobs: submit, follow, wait, results as DataFrames, cancel and delete, refusals."""

from __future__ import annotations

import csv
import io
import json
import re
import socket
import sys
from datetime import datetime, timezone
from pathlib import Path

import pytest

import tribosim

from conftest import ENDLESS, REPO, SMALL, Server

#: The cycle record's columns that are counts, not quantities with a unit.
COUNTS = {"cycle", "iterations", "contact_islands"}
UNIT = re.compile(r"_(s|mm3|mm2|um|mpa|v|ma|c)$")
#: A job that sends an event for every cycle.
EVERY_CYCLE = {
    "preset": "dalmau2018-316l",
    "overrides": {"test": {"cycles": 1000}, "numerics": {"grid": 32, "cycle_step": 1}},
}


def test_submit_wait_and_result(small_job: tribosim.Job) -> None:
    assert small_job.info.status == "succeeded"
    assert small_job.info.name == "pytest small"
    result = small_job.result()
    assert result.complete
    assert result.summary["cycles"] == 20
    assert result.warnings == []
    assert "plasticity" in {model.name for model in result.models}

    cycles = result.cycles
    assert len(cycles) == len(result.raw["cycles"])
    assert cycles["cycle"].iloc[-1] == 20
    assert cycles["wear_volume_mm3"].iloc[-1] == result.summary["wear_volume_mm3"]
    # One meaning in every run: the wear volume is the total, mechanical part plus WAC.
    assert (cycles["wear_volume_mm3"] == cycles["total_volume_mm3"]).all()
    assert "mechanical_volume_mm3" in cycles.columns
    assert cycles["cycle"].is_monotonic_increasing
    for column in set(cycles.columns) - COUNTS:
        assert UNIT.search(column), f"{column} has no unit in its name"


def test_profiles_in_long_form(small_job: tribosim.Job) -> None:
    result = small_job.result()
    profiles = result.profiles
    assert list(profiles.columns) == ["cycle", "y_um", "depth_um"]
    raw = result.raw["profiles"]
    assert len(profiles) == sum(len(p["y_um"]) for p in raw)
    assert sorted(profiles["cycle"].unique()) == [p["cycle"] for p in raw]
    last = profiles[profiles["cycle"] == 20]
    assert last["depth_um"].max() == pytest.approx(result.summary["max_depth_um"], rel=1e-12)
    wide = profiles.pivot(index="y_um", columns="cycle", values="depth_um")
    assert wide.shape == (len(raw[0]["y_um"]), len(raw))


def test_pressure_maps_as_arrays(small_job: tribosim.Job) -> None:
    maps = small_job.result().pressure_maps
    assert [m.cycle for m in maps] == [1, 20]
    for m in maps:
        assert m.pressure_mpa.shape == (len(m.y_um), len(m.x_um))
        assert m.pressure_mpa.max() > 0


def test_result_csv_is_the_cycles_table(small_job: tribosim.Job) -> None:
    rows = list(csv.DictReader(io.StringIO(small_job.result_csv())))
    cycles = small_job.result().cycles
    assert [int(row["cycle"]) for row in rows] == cycles["cycle"].tolist()
    # The server writes each number as its shortest exact decimal, so it reads back equal
    # with a correctly rounding parser (Python's float; pandas before 3 is not one).
    assert [float(row["wear_volume_mm3"]) for row in rows] == cycles["wear_volume_mm3"].tolist()
    assert "cycles_stepped_over" in rows[0]


def test_profiles_and_pressure_as_csv_and_a_compact_result(small_job: tribosim.Job) -> None:
    result = small_job.result()
    profiles = list(csv.DictReader(io.StringIO(small_job.profiles_csv())))
    assert len(profiles) == len(result.profiles)
    pressure = list(csv.DictReader(io.StringIO(small_job.pressure_csv())))
    assert len(pressure) == sum(m.pressure_mpa.size for m in result.pressure_maps)
    assert float(pressure[0]["pressure_mpa"]) == result.pressure_maps[0].pressure_mpa[0][0]
    compact = small_job.result(compact=True)
    assert compact.pressure_maps == [] and len(compact.profiles) == len(profiles)


def test_scene_as_run(small_job: tribosim.Job) -> None:
    scene = small_job.scene()
    assert scene["name"] == "pytest small"
    assert scene["test"]["cycles"] == 20
    assert scene["numerics"]["grid"] == 64
    assert "preset" not in scene


def test_events(small_job: tribosim.Job) -> None:
    events = list(small_job.events())
    *cycles, status = events
    assert all(isinstance(e, tribosim.CycleEvent) for e in cycles)
    assert isinstance(status, tribosim.StatusEvent)
    assert status.job.status == "succeeded"
    numbers = [e.cycle for e in cycles if isinstance(e, tribosim.CycleEvent)]
    assert numbers == small_job.result().cycles["cycle"].tolist()
    assert cycles[0].record["cycle"] == numbers[0]  # type: ignore[union-attr]


def test_events_after_a_cycle(small_job: tribosim.Job) -> None:
    after = list(small_job.events(after=10))
    numbers = [e.cycle for e in after if isinstance(e, tribosim.CycleEvent)]
    assert numbers and min(numbers) > 10
    assert isinstance(after[-1], tribosim.StatusEvent)


def test_submit_a_file(client: tribosim.Client) -> None:
    path = REPO / "scenes" / "quick.json"
    job = client.jobs.submit(path)
    assert job.info.name == json.loads(path.read_text())["overrides"]["name"]
    renamed = client.jobs.submit(str(path), name="quick, renamed")
    assert renamed.info.name == "quick, renamed"
    for j in (job, renamed):
        assert j.wait(progress=False).status == "succeeded"


def test_a_key_given_twice_in_a_file_is_refused(client: tribosim.Client, tmp_path: Path) -> None:
    path = tmp_path / "twice.json"
    path.write_text('{"test": {"cycles": 5, "cycles": 6}}')
    with pytest.raises(tribosim.ValidationError) as refused:
        client.jobs.submit(path)
    assert refused.value.fields[0].path == "test.cycles"


def test_a_bad_scene_names_its_fields(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.ValidationError) as refused:
        client.jobs.submit({"test": {"load_n": -1, "cycles": 0}})
    error = refused.value
    assert error.status == 422
    assert [f.path for f in error.fields] == ["test.load_n", "test.cycles"]
    load = error.field("test.load_n")
    assert load is not None and "> 0 N" in load.message
    text = str(error)
    assert text.splitlines()[0].startswith("422 invalid scene: 2 problems")
    assert "  test.load_n: must be > 0 N" in text
    assert "  test.cycles: " in text


def test_list(client: tribosim.Client, small_job: tribosim.Job) -> None:
    assert small_job.id in [job.id for job in client.jobs.list()]
    again = client.jobs.get(small_job.id)
    assert again.info == small_job.refresh()


def test_progress_bar(small_job: tribosim.Job, capsys: pytest.CaptureFixture[str]) -> None:
    small_job.wait(progress=True)
    err = capsys.readouterr().err
    assert "pytest small" in err and "20/20" in err


def test_progress_without_tqdm(
    small_job: tribosim.Job, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "tqdm", None)
    small_job.wait(progress=True)
    assert capsys.readouterr().err.endswith("pytest small: 20/20 succeeded\n")


def test_cancel_a_running_job(client: tribosim.Client) -> None:
    job = client.jobs.submit(ENDLESS)
    with pytest.raises(tribosim.ConflictError):
        job.result()
    with pytest.raises(tribosim.WaitTimeoutError):
        job.wait(progress=False, timeout=0.2)
    job.cancel()
    with pytest.raises(tribosim.RunFailedError) as failed:
        job.wait(progress=False)
    assert isinstance(failed.value.record, tribosim.JobInfo)
    assert failed.value.record.status == "cancelled"
    partial = job.result()
    assert not partial.complete
    assert len(partial.cycles) == len(partial.raw["cycles"])
    job.delete()
    with pytest.raises(tribosim.NotFoundError):
        job.refresh()


def test_cancel_leaves_an_ended_job(small_job: tribosim.Job) -> None:
    assert small_job.cancel().status == "succeeded"
    assert small_job.refresh().status == "succeeded"


def test_delete_stops_a_running_job_first(client: tribosim.Client) -> None:
    job = client.jobs.submit(ENDLESS)
    job.delete()
    with pytest.raises(tribosim.NotFoundError):
        client.jobs.get(job.id)


def test_a_deleted_job_is_not_found(client: tribosim.Client) -> None:
    job = client.jobs.submit(SMALL)
    job.wait(progress=False)
    job.delete()
    for call in (job.refresh, job.result, job.result_csv, job.scene, lambda: list(job.events())):
        with pytest.raises(tribosim.NotFoundError):
            call()


def test_events_follow_a_job_across_a_restart(tmp_path: Path) -> None:
    # A fixed port, so that the client finds the restarted server where the first one was.
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        addr = f"127.0.0.1:{probe.getsockname()[1]}"
    first = Server(tmp_path, ["--workers", "1"], addr)
    try:
        with tribosim.Client(first.url) as client:
            job = client.jobs.submit(EVERY_CYCLE)
            events = job.events()
            seen = [next(events) for _ in range(3)]
            # Stopped with the job running, the server runs it again from its first cycle
            # once restarted on the same data; the same iterator goes on after the last
            # cycle it received.
            first.stop()
            restarted = datetime.now(timezone.utc)
            second = Server(tmp_path, ["--workers", "1"], addr)
            try:
                rest = list(events)
            finally:
                second.stop()
    finally:
        first.stop()
    numbers = [e.cycle for e in seen + rest if isinstance(e, tribosim.CycleEvent)]
    assert numbers == list(range(1, EVERY_CYCLE["overrides"]["test"]["cycles"] + 1))
    assert first.panics() == [] and second.panics() == []
    status = rest[-1]
    assert isinstance(status, tribosim.StatusEvent) and status.job.status == "succeeded"
    # The run that ended is the second server's.
    assert status.job.started_at is not None
    assert datetime.fromisoformat(status.job.started_at[:26] + "+00:00") > restarted


def test_the_list_pages_and_filters(client: tribosim.Client, small_job: tribosim.Job) -> None:
    other = client.jobs.submit(SMALL, name="pytest list Other")
    other.wait(progress=False)
    every = client.jobs.list()
    # Pages of one job at a time, followed to the end, give the same list, newest first.
    assert [job.id for job in client.jobs.list(page_size=1)] == [job.id for job in every]
    assert every.index(next(j for j in every if j.id == other.id)) < every.index(
        next(j for j in every if j.id == small_job.id)
    )
    named = client.jobs.list(name="LIST other", status="succeeded,failed")
    assert [job.id for job in named] == [other.id]
    assert client.jobs.list(status="queued", name="pytest list other") == []


def test_report_of_a_run_and_of_two(
    client: tribosim.Client, small_job: tribosim.Job, tmp_path: Path
) -> None:
    path = tmp_path / "report.html"
    html = small_job.report(path)
    assert html.startswith("<!DOCTYPE html>")
    assert path.read_text(encoding="utf-8") == html
    assert html.count("<svg") == 6
    assert small_job.result().raw["provenance"]["scene_sha256"] in html
    other = client.jobs.submit(SMALL, name="pytest other")
    other.wait(progress=False)
    compared = client.jobs.report([small_job, other.id])
    assert "pytest small" in compared and "pytest other" in compared
    with pytest.raises(tribosim.ApiError):
        client.jobs.report([small_job])


def test_labels_at_submit_changed_after_and_searched(client: tribosim.Client) -> None:
    job = client.jobs.submit(SMALL, name="pytest labels", sample="S-7", tags=["paper", "5N"])
    assert (job.info.sample, job.info.note, job.info.tags) == ("S-7", None, ["paper", "5N"])
    info = job.label(note="re-polished", tags=["wet"])
    assert (info.sample, info.note, info.tags) == ("S-7", "re-polished", ["wet"])
    assert job.label(sample=None).sample is None
    assert [j.id for j in client.jobs.list(q="RE-POLISHED")] == [job.id]
    assert [j.id for j in client.jobs.list(tag="wet")] == [job.id]
    with pytest.raises(tribosim.ValidationError) as refused:
        job.label(note="x" * 2001)
    assert refused.value.fields[0].path == "note"
    job.wait(progress=False)
    job.delete()


def test_a_reciprocating_result_has_its_map_profile_and_traces(
    client: tribosim.Client, small_job: tribosim.Job
) -> None:
    rig = client.jobs.submit(
        {
            "test": {"cycles": 6, "reciprocating": {"stroke_mm": 0.6, "frequency_hz": 1.0}},
            "numerics": {"grid": 32, "record_cycles": [3]},
        },
        name="pytest stroke",
    )
    rig.wait(progress=False)
    result = rig.result()
    wear_map = result.stroke_map
    assert wear_map is not None
    assert wear_map.depth_um.shape == (len(wear_map.y_um), len(wear_map.x_um))
    axial = result.axial_profile
    assert list(axial.columns) == ["x_um", "depth_um"]
    assert float(axial["depth_um"].max()) == pytest.approx(result.summary["max_depth_um"])
    traces = result.stroke_traces
    # 200 samples a cycle at the first, the recorded and the last cycle (docs/result.md).
    assert sorted(set(traces["cycle"])) == [1, 3, 6]
    assert len(traces) == 3 * 200
    disc = small_job.result()
    assert disc.stroke_map is None and disc.axial_profile.empty and disc.stroke_traces.empty
