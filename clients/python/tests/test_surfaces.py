"""Height maps: a numpy array or a file uploaded, listed, read, deleted."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import tribosim

from conftest import ENDLESS

#: The heights go as text with 9 significant digits (tribosim.surfaces.HEIGHT_DIGITS): each
#: within 5e-9 of itself relatively, so their rms too.
SENT_RELATIVE = 5e-9


def heights(ny: int = 48, nx: int = 64) -> np.ndarray:
    return np.random.default_rng(7).normal(0.0, 1e-7, (ny, nx))


def test_upload_an_array(client: tribosim.Client) -> None:
    h = heights()
    surface = client.surfaces.upload(h, pixel_um=0.5, name="pytest array")
    assert (surface.ny, surface.nx) == h.shape
    assert (surface.pixel_x_um, surface.pixel_y_um) == (0.5, 0.5)
    assert surface.format == "matrix" and surface.name == "pytest array"
    rms_um = np.sqrt(np.mean((h - h.mean()) ** 2)) * 1e6
    assert surface.statistics["rms_height_um"] == pytest.approx(rms_um, rel=2 * SENT_RELATIVE)
    assert client.surfaces.get(surface.id) == surface
    assert surface.id in [s.id for s in client.surfaces.list()]
    client.surfaces.delete(surface.id)
    with pytest.raises(tribosim.NotFoundError):
        client.surfaces.get(surface.id)


def test_upload_a_file(client: tribosim.Client, tmp_path: Path) -> None:
    path = tmp_path / "disc.txt"
    np.savetxt(path, heights(32, 40))
    surface = client.surfaces.upload_file(path, pixel_um=1.0)
    assert (surface.nx, surface.ny, surface.name) == (40, 32, "disc.txt")
    client.surfaces.delete(surface.id)


def test_a_file_in_nm(client: tribosim.Client, tmp_path: Path) -> None:
    h = heights(32, 40)
    in_m, in_nm = tmp_path / "m.txt", tmp_path / "nm.txt"
    np.savetxt(in_m, h)
    np.savetxt(in_nm, h * 1e9)
    from_m = client.surfaces.upload_file(in_m, pixel_um=1.0)
    from_nm = client.surfaces.upload_file(in_nm, pixel_um=1.0, height_unit="nm")
    # savetxt's 18 digits, then one multiplication each way: the same rms to 1e-12.
    assert from_nm.statistics["rms_height_um"] == pytest.approx(
        from_m.statistics["rms_height_um"], rel=1e-12
    )


def test_an_array_in_um_is_named_at_upload(client: tribosim.Client) -> None:
    # The test's heights scaled to 0.2 um rms, then passed as m: 0.2 m rms, refused at the
    # upload with the unit named; with height_unit="um" the same array is stored.
    h = heights(32, 40)
    in_um = h * (0.2 / np.sqrt(np.mean((h - h.mean()) ** 2)))
    with pytest.raises(tribosim.ValidationError) as refused:
        client.surfaces.upload(in_um, pixel_um=2)
    assert [f.path for f in refused.value.fields] == ["height_unit"]
    assert "height_unit=um" in str(refused.value)
    surface = client.surfaces.upload(in_um, pixel_um=2, height_unit="um")
    # The client sends 9 significant digits, each height rounded by at most 5e-9 of itself.
    assert surface.statistics["rms_height_um"] == pytest.approx(0.2, rel=1e-8)
    client.surfaces.delete(surface.id)


def test_a_map_that_cannot_be_read(client: tribosim.Client, tmp_path: Path) -> None:
    path = tmp_path / "disc.txt"
    np.savetxt(path, heights(32, 40))
    with pytest.raises(tribosim.ValidationError) as refused:
        client.surfaces.upload_file(path)
    assert [f.path for f in refused.value.fields] == ["body"]
    with pytest.raises(tribosim.ValidationError) as refused:
        client.surfaces.upload(heights(), pixel_um=-1)
    assert [f.path for f in refused.value.fields] == ["pixel_um"]
    with pytest.raises(ValueError):
        client.surfaces.upload(np.zeros(10), pixel_um=1)


def test_a_surface_in_use_is_kept(client: tribosim.Client) -> None:
    surface = client.surfaces.upload(heights(), pixel_um=0.5)
    scene = {
        **ENDLESS,
        "overrides": {**ENDLESS["overrides"], "disc": {"surface": surface.disc_surface()}},
    }
    job = client.jobs.submit(scene)
    with pytest.raises(tribosim.ConflictError) as refused:
        client.surfaces.delete(surface.id)
    assert job.id in refused.value.message
    job.delete()
    client.surfaces.delete(surface.id)
