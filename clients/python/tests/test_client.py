"""The client's own calls: health, presets, materials, the page; and errors that no route
has."""

from __future__ import annotations

import math
import uuid

import pytest

import tribosim


def test_health(client: tribosim.Client) -> None:
    assert client.health() == "ok"


def test_presets(client: tribosim.Client) -> None:
    presets = client.presets()
    paper = next(p for p in presets if p.name == "dalmau2018-316l")
    assert paper.scene["test"]["load_n"] == 5.0
    assert "Dalmau" in paper.description
    # Table 3 (Dalmau et al. 2018): the wear volume at 3600 s, 11.72e-3 mm^3.
    assert [row["time_s"] for row in paper.measured] == [10, 60, 300, 1800, 3600]
    assert paper.measured[-1]["wear_volume_mm3"] == 11.72e-3


def test_materials(client: tribosim.Client) -> None:
    library = client.materials()
    titanium = next(d for d in library["discs"] if d["name"] == "ti6al4v")
    # MatWeb MTP644's modulus, as docs/materials.md lists it.
    assert titanium["youngs_modulus_gpa"]["value"] == 114.0
    assert titanium["electrochemistry"] is None
    keys = {r["key"] for r in library["references"]}
    assert titanium["youngs_modulus_gpa"]["source"] in keys
    silicon_nitride = next(b for b in library["balls"] if b["name"] == "si3n4")
    assert silicon_nitride["poisson_ratio"]["value"] is None


def test_page(client: tribosim.Client) -> None:
    assert "<html" in client.page().lower()
    assert b"import" in client.page_file("js/main.js")
    assert b"body" in client.page_file("page.css")
    assert client.guide("scene.md").startswith("# ")


def test_an_id_that_is_not_a_uuid_is_refused_as_a_request(client: tribosim.Client) -> None:
    with pytest.raises(tribosim.RefusedError) as refused:
        client.jobs.get("not-a-uuid")
    assert refused.value.status == 400
    assert not isinstance(refused.value, tribosim.NotFoundError)


def test_unknown_ids_are_not_found(client: tribosim.Client) -> None:
    unknown = str(uuid.uuid4())
    for get in (client.jobs.get, client.studies.get, client.calibrations.get, client.surfaces.get):
        with pytest.raises(tribosim.NotFoundError) as missing:
            get(unknown)
        assert missing.value.status == 404
        assert unknown in missing.value.message


def test_nan_is_refused_before_sending(client: tribosim.Client) -> None:
    with pytest.raises(ValueError):
        client.jobs.submit({"test": {"load_n": math.nan}})


def test_numpy_values_are_sent_as_numbers(client: tribosim.Client) -> None:
    np = pytest.importorskip("numpy")
    with pytest.raises(tribosim.ValidationError) as refused:
        client.jobs.submit({"test": {"load_n": np.float64(-1.0), "cycles": np.int64(0)}})
    assert [f.path for f in refused.value.fields] == ["test.load_n", "test.cycles"]


def test_no_server_is_a_transport_error() -> None:
    # Port 1 (tcpmux) has no listener on a test machine: the connection is refused.
    with (
        tribosim.Client("http://127.0.0.1:1", timeout=5) as client,
        pytest.raises(tribosim.TransportError),
    ):
        client.health()
