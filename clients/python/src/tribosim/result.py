"""A job's result (docs/result.md) with its tables as DataFrames and its maps as arrays."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ._tables import as_array, frame

if TYPE_CHECKING:
    import numpy
    import pandas


@dataclass(frozen=True)
class Model:
    """What the run modelled or chose (``plasticity``, ``grid``, ...), and why."""

    name: str
    active: bool
    reason: str


@dataclass(frozen=True)
class PressureMap:
    """The contact pressure at one cycle: `pressure_mpa[iy, ix]` over `y_um` and `x_um`."""

    cycle: int
    x_um: numpy.ndarray
    y_um: numpy.ndarray
    pressure_mpa: numpy.ndarray


@dataclass(frozen=True)
class WearMap:
    """The reciprocating rig's wear at the end of the run: `depth_um[iy, ix]` over `y_um`
    (across the track) and `x_um` (along the stroke, from its middle)."""

    x_um: numpy.ndarray
    y_um: numpy.ndarray
    depth_um: numpy.ndarray


class Result:
    """The result JSON of a job. Columns keep the server's names, units in the names
    (``total_volume_mm3``, ``time_s``); `raw` is the whole document as it came. The volume a
    profilometer measures, Table 3's, is ``total_volume_mm3`` in every run;
    ``mechanical_volume_mm3`` and ``wac_volume_mm3`` are its parts."""

    def __init__(self, raw: dict[str, Any]) -> None:
        self.raw = raw

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"<Result complete={self.complete} cycles={s.get('cycles')} "
            f"total_volume_mm3={s.get('total_volume_mm3')}>"
        )

    @property
    def complete(self) -> bool:
        """False for a failed or cancelled job's result: the cycles solved before it stopped."""
        return bool(self.raw["complete"])

    @property
    def scene(self) -> dict[str, Any]:
        """The scene as run, every default filled in."""
        scene: dict[str, Any] = self.raw["scene"]
        return scene

    @property
    def summary(self) -> dict[str, Any]:
        """The totals: ``cycles``, ``total_volume_mm3``, ``max_depth_um``, ``archard_k``, ..."""
        summary: dict[str, Any] = self.raw["summary"]
        return summary

    @property
    def models(self) -> list[Model]:
        return [Model(m["name"], bool(m["active"]), m["reason"]) for m in self.raw["models"]]

    @property
    def warnings(self) -> list[str]:
        """What in the scene looks wrong without being invalid (empty when nothing does)."""
        return list(self.raw.get("warnings", []))

    @property
    def surface(self) -> dict[str, Any] | None:
        """The statistics of a rough disc's initial surface; None for a smooth disc."""
        return self.raw.get("surface")

    @property
    def cycles(self) -> pandas.DataFrame:
        """One row per solved cycle (``cycle``, ``time_s``, ``total_volume_mm3``,
        ``mechanical_volume_mm3``, ``max_depth_um``, ...; the corrosion columns only with
        corrosion)."""
        return frame(self.raw["cycles"])

    @property
    def profiles(self) -> pandas.DataFrame:
        """The groove across the track, long form: one row per (``cycle``, ``y_um``) with its
        ``depth_um`` (positive into the disc). ``profiles.pivot(index="y_um",
        columns="cycle", values="depth_um")`` gives a column per cycle."""
        rows = [
            {"cycle": p["cycle"], "y_um": y, "depth_um": d}
            for p in self.raw["profiles"]
            for y, d in zip(p["y_um"], p["depth_um"])
        ]
        return frame(rows) if rows else frame({"cycle": [], "y_um": [], "depth_um": []})

    @property
    def pressure_maps(self) -> list[PressureMap]:
        """The contact pressure at the first and the last solved cycle."""
        return [
            PressureMap(
                int(m["cycle"]),
                as_array(m["x_um"]),
                as_array(m["y_um"]),
                as_array(m["pressure_mpa"]),
            )
            for m in self.raw["pressure_maps"]
        ]

    @property
    def stroke_map(self) -> WearMap | None:
        """The reciprocating rig's wear map (block-averaged to at most 400 columns along the
        stroke); None for a ball on a rotating disc."""
        stroke = self.raw.get("stroke")
        if stroke is None:
            return None
        m = stroke["map"]
        return WearMap(as_array(m["x_um"]), as_array(m["y_um"]), as_array(m["depth_um"]))

    @property
    def axial_profile(self) -> pandas.DataFrame:
        """The depth along the reciprocating track's centre line, ``x_um`` and ``depth_um``;
        empty for a ball on a rotating disc."""
        stroke = self.raw.get("stroke")
        if stroke is None:
            return frame({"x_um": [], "depth_um": []})
        return frame(stroke["axial_profile"])

    @property
    def stroke_traces(self) -> pandas.DataFrame:
        """The reciprocating rig's potential and current over a cycle, long form: one row per
        (``cycle``, ``time_s``) with ``position_um``, ``anodic_area_mm2``, ``potential_v`` and
        ``anodic_current_ma``; empty without corrosion or on a rotating disc."""
        columns = ["time_s", "position_um", "anodic_area_mm2", "potential_v", "anodic_current_ma"]
        traces = (self.raw.get("stroke") or {}).get("traces", [])
        rows = [
            {"cycle": t["cycle"], **{c: t[c][i] for c in columns}}
            for t in traces
            for i in range(len(t["time_s"]))
        ]
        return frame(rows) if rows else frame({c: [] for c in ["cycle", *columns]})
