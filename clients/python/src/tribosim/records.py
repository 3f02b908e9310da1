"""The records the service answers with, as typed values. Each keeps the whole JSON in
`raw`, so a field the server adds later is there before the client names it."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, TypeVar

R = TypeVar("R", bound="Record")

#: The job statuses after which nothing changes.
JOB_ENDED = frozenset({"succeeded", "failed", "cancelled", "damaged"})
#: The study statuses once every member has ended.
STUDY_ENDED = frozenset({"succeeded", "partial", "failed", "cancelled"})


@dataclass(frozen=True)
class Record:
    raw: dict[str, Any] = field(repr=False, compare=False)

    @classmethod
    def from_json(cls: type[R], raw: dict[str, Any]) -> R:
        """The record of `raw`; a field `raw` lacks is None."""
        names = [f.name for f in fields(cls) if f.name != "raw"]
        return cls(raw=raw, **{name: raw.get(name) for name in names})


@dataclass(frozen=True)
class JobInfo(Record):
    """A job's status and progress (openapi.yaml, ``Job``)."""

    id: str
    name: str
    sample: str | None
    note: str | None
    tags: list[str] | None
    status: str
    cycles_done: int
    cycles_total: int
    eta_s: float | None
    error: str | None
    rerun_reason: str | None
    queue_position: int | None
    created_at: str
    started_at: str | None
    finished_at: str | None

    @property
    def ended(self) -> bool:
        return self.status in JOB_ENDED


@dataclass(frozen=True)
class StudyInfo(Record):
    """A study with its members' statuses (openapi.yaml, ``Study``)."""

    id: str
    name: str
    status: str
    created_at: str
    axes: list[dict[str, Any]]  # {"path", "values"}
    members: list[dict[str, Any]]  # {"index", "job_id", "values", "status"}
    counts: dict[str, int]

    @property
    def ended(self) -> bool:
        return self.status in STUDY_ENDED


@dataclass(frozen=True)
class CalibrationInfo(Record):
    """A calibration: ``running``, then ``succeeded`` with its `result`, ``failed`` with
    its `error`, or ``cancelled`` (openapi.yaml, ``Calibration``; in a list,
    ``CalibrationInfo``, without the result)."""

    id: str
    kind: str
    status: str
    created_at: str
    finished_at: str | None
    result: dict[str, Any] | None
    error: str | None


@dataclass(frozen=True)
class Surface(Record):
    """A stored height map: its size, pixel and statistics (openapi.yaml, ``Surface``)."""

    id: str
    name: str
    format: str
    nx: int
    ny: int
    pixel_x_um: float
    pixel_y_um: float
    statistics: dict[str, Any]
    #: What to check before trusting the map, e.g. a Hurst exponent outside 0 to 1.
    warnings: list[str]
    created_at: str

    def disc_surface(self, remove_tilt: bool = False) -> dict[str, Any]:
        """The scene's ``disc.surface`` that runs on this map."""
        return {"kind": "measured", "id": self.id, "remove_tilt": remove_tilt}


@dataclass(frozen=True)
class Preset(Record):
    """A built-in scene, usable as ``{"preset": name, "overrides": {...}}``."""

    name: str
    description: str
    scene: dict[str, Any]
    #: What was measured on the preset's test, a row per time (``time_s``,
    #: ``hardness_mpa``, ``hardness_spread_mpa``, ``wear_volume_mm3``, ``spread_mm3``):
    #: the paper's Table 3 for ``dalmau2018-316l``.
    measured: list[dict[str, Any]]
