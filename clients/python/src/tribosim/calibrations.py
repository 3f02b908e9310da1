"""Calibrations: the model's parameters fitted to a lab's table (docs/calibration.md)."""

from __future__ import annotations

import builtins
import json
import os
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ._http import Http, list_params
from ._routes import route
from ._tables import TableInput, frame, table_json
from .errors import RunFailedError, WaitTimeoutError
from .records import CalibrationInfo

if TYPE_CHECKING:
    import pandas

_SUBMIT = route("POST", "/api/v1/calibrations")
_LIST = route("GET", "/api/v1/calibrations")
_GET = route("GET", "/api/v1/calibrations/{id}")
_DELETE = route("DELETE", "/api/v1/calibrations/{id}")


@dataclass(frozen=True)
class Estimate:
    """A fitted value with its standard error (from the table's own scatter)."""

    value: float
    standard_error: float


class Calibrations:
    """``client.calibrations``: fits of ``hardness`` (``cycles`` or ``time_s``,
    ``hardness_mpa``), ``tafel`` (``potential_v``, ``current_density_a_cm2``), ``ocp``
    (``time_s``, ``potential_v``) and ``archard`` (``time_s`` or ``cycles``,
    ``volume_mm3``, optionally ``spread_mm3``)."""

    def __init__(self, http: Http) -> None:
        self._http = http

    @_SUBMIT.implements
    def submit(
        self,
        kind: str,
        table: TableInput,
        scene: Mapping[str, Any] | str | os.PathLike[str] | None = None,
        *,
        include_bulk: bool | None = None,
        e_corr_v: float | None = None,
        tafel_overpotential_max_v: float | None = None,
        tafel_overpotential_min_v: float | None = None,
        regime_change: int | str | None = None,
    ) -> Calibration:
        """Starts a fit of `table` (a DataFrame, columns, rows, CSV text or a CSV file's
        `pathlib.Path`) with `scene` (a mapping or a JSON file's path; the paper's preset
        by default). The options are the command's: `include_bulk` (hardness), `e_corr_v`
        and the Tafel domain's ends as E - E_corr in V, `tafel_overpotential_max_v` and
        `tafel_overpotential_min_v` (tafel; chosen from the data when absent),
        `regime_change` (archard: a cycle or ``"auto"``). A table the fit cannot
        use raises `ValidationError` naming ``table`` (its message the column and row);
        two fits running already `RateLimitedError`."""
        body: dict[str, Any] = {"kind": kind, "table": table_json(table)}
        if scene is not None:
            body["scene"] = (
                json.loads(Path(scene).read_text())
                if isinstance(scene, (str, os.PathLike))
                else scene
            )
        options = {
            name: value
            for name, value in [
                ("include_bulk", include_bulk),
                ("e_corr_v", e_corr_v),
                ("tafel_overpotential_max_v", tafel_overpotential_max_v),
                ("tafel_overpotential_min_v", tafel_overpotential_min_v),
                ("regime_change", regime_change),
            ]
            if value is not None
        }
        if options:
            body["options"] = options
        return Calibration(
            self._http, CalibrationInfo.from_json(self._http.json(_SUBMIT, json=body))
        )

    @_SUBMIT.implements
    def fit(
        self,
        kind: str,
        table: TableInput,
        scene: Mapping[str, Any] | str | os.PathLike[str] | None = None,
        *,
        include_bulk: bool | None = None,
        e_corr_v: float | None = None,
        tafel_overpotential_max_v: float | None = None,
        tafel_overpotential_min_v: float | None = None,
        regime_change: int | str | None = None,
        timeout: float | None = None,
    ) -> Fit:
        """`submit`, then `Calibration.wait`: the fit, once done."""
        calibration = self.submit(
            kind,
            table,
            scene,
            include_bulk=include_bulk,
            e_corr_v=e_corr_v,
            tafel_overpotential_max_v=tafel_overpotential_max_v,
            tafel_overpotential_min_v=tafel_overpotential_min_v,
            regime_change=regime_change,
        )
        return calibration.wait(timeout=timeout)

    @_LIST.implements
    def list(
        self, *, status: str | None = None, kind: str | None = None, page_size: int = 100
    ) -> builtins.list[Calibration]:
        """The calibrations the server keeps, newest first, or those with `status` or of
        `kind` (one, or several comma-separated); their `info` lacks the result until
        `refresh()`."""
        params = list_params(page_size, status=status, kind=kind)
        return [
            Calibration(self._http, CalibrationInfo.from_json(raw))
            for raw in self._http.pages(_LIST, params)
        ]

    @_GET.implements
    def get(self, calibration_id: str) -> Calibration:
        """The calibration of `calibration_id` (`NotFoundError` if the server has none:
        it keeps the last 100 in memory, and forgets them when it restarts)."""
        return Calibration(self._http, _fetch(self._http, calibration_id))


def _fetch(http: Http, calibration_id: str) -> CalibrationInfo:
    return CalibrationInfo.from_json(http.json(_GET, id=calibration_id))


class Calibration:
    """One calibration. `info` is its record as last seen; `refresh()` asks again."""

    def __init__(self, http: Http, info: CalibrationInfo) -> None:
        self._http = http
        self.id = info.id
        self.info = info

    def __repr__(self) -> str:
        return f"<Calibration {self.id} {self.info.kind} {self.info.status}>"

    @_GET.implements
    def refresh(self) -> CalibrationInfo:
        self.info = _fetch(self._http, self.id)
        return self.info

    @_DELETE.implements
    def cancel(self) -> CalibrationInfo:
        """Stops a running fit (its run under way ends within a cycle); an ended fit is
        left as it is."""
        if self.refresh().status != "running":
            return self.info
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self.info = CalibrationInfo.from_json({**answer.json(), "result": None})
        return self.info

    @_DELETE.implements
    def delete(self) -> None:
        """Forgets the fit on the server, cancelling it first if it runs."""
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self._http.send(_DELETE, id=self.id)

    @_GET.implements
    def wait(self, timeout: float | None = None, poll_s: float = 0.2) -> Fit:
        """Polls every `poll_s` seconds until the fit has ended; its `Fit`, or
        `RunFailedError` with the server's reason (it did not converge, a run failed)."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while self.refresh().status == "running":
            if deadline is not None and time.monotonic() > deadline:
                raise WaitTimeoutError(f"calibration {self.id} is still running")
            time.sleep(poll_s)
        if self.info.status != "succeeded" or self.info.result is None:
            raise RunFailedError(f"calibration {self.id} failed: {self.info.error}", self.info)
        return Fit(self.info.kind, self.info.result)


class Fit:
    """A succeeded fit: the JSON ``tribosim calibrate -o`` writes, in `raw`."""

    def __init__(self, kind: str, raw: dict[str, Any]) -> None:
        self.kind = kind
        self.raw = raw

    def __repr__(self) -> str:
        values = ", ".join(
            f"{name}={e.value:.4g}+-{e.standard_error:.2g}" for name, e in self.values.items()
        )
        return f"<Fit {self.kind}: {values}>"

    @property
    def values(self) -> dict[str, Estimate]:
        """Every fitted value with its standard error, by name (``a_mpa``, ``archard_k``,
        ...; a two-regime Archard fit's as ``one_regime.archard_k``,
        ``two_regimes.archard_k_before``, ...)."""
        return dict(_estimates(self.raw, ""))

    @property
    def estimates(self) -> pandas.DataFrame:
        """`values` as a table: one row per parameter, ``value`` and ``standard_error``."""
        rows = [
            {"parameter": name, "value": e.value, "standard_error": e.standard_error}
            for name, e in self.values.items()
        ]
        return frame(rows).set_index("parameter")

    @property
    def residuals(self) -> pandas.DataFrame:
        """Each point of the table against the fit (measured, fitted and their residual,
        units in the column names)."""
        points = self.raw.get("residuals", self.raw.get("points", []))
        return frame(points)

    @property
    def scene(self) -> dict[str, Any]:
        """The scene with the fitted values filled in, ready to submit."""
        scene: dict[str, Any] = self.raw["scene"]
        return scene


def _estimates(value: Any, prefix: str) -> Iterator[tuple[str, Estimate]]:
    """The ``{"value", "standard_error"}`` objects anywhere in a fit, but its scene."""
    if not isinstance(value, dict):
        return
    if set(value) == {"value", "standard_error"}:
        yield prefix, Estimate(float(value["value"]), float(value["standard_error"]))
        return
    for name, inner in value.items():
        if name != "scene":
            yield from _estimates(inner, f"{prefix}.{name}" if prefix else name)
