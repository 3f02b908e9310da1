"""Measured points attached to a job (``wear_volume``, ``profile``, ``ocp``), drawn by the
page beside the run's own curves and scored against them."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Optional

from ._http import Http
from ._routes import route
from ._tables import TableInput, frame, table_body

if TYPE_CHECKING:
    import pandas

_GET = route("GET", "/api/v1/jobs/{id}/measurements")
_PUT = route("PUT", "/api/v1/jobs/{id}/measurements/{kind}")
_DELETE = route("DELETE", "/api/v1/jobs/{id}/measurements/{kind}")
_SCORES = route("GET", "/api/v1/jobs/{id}/scores")
_SCORES_CSV = route("GET", "/api/v1/jobs/{id}/scores.csv")

#: Each kind's table (or None), as DataFrames.
Tables = dict[str, Optional["pandas.DataFrame"]]


class Measurements:
    """``job.measurements``. The columns, units in the names:

    - ``wear_volume``: ``time_s`` or ``cycles`` (or both), ``volume_mm3``, optionally
      ``spread_mm3``;
    - ``profile``: ``y_mm`` (across the track), ``depth_um`` (positive into the disc);
    - ``ocp`` (the open-circuit potential; ``potential`` is accepted for it): ``time_s``,
      ``potential_v``.

    Other units in a column's name are converted (``time_min``, ``potential_mv``,
    ``volume_um3``, ``depth_nm``, ``y_um``, ...). A table the server cannot use raises
    `ValidationError` naming the column (and the row in its message)."""

    def __init__(self, http: Http, job_id: str) -> None:
        self._http = http
        self._job_id = job_id
        #: The headers the last `put` read under another name, each with its column.
        self.renamed: dict[str, str] = {}

    @_PUT.implements
    def put(self, kind: str, table: TableInput) -> Tables:
        """Attaches `table` (a DataFrame, columns, rows, CSV text or a CSV file's
        `pathlib.Path`) as the job's `kind`, replacing any; returns every table of the job.
        Headers as lab software writes them (``Time (s)``, ``Volume [mm3]``) are read as the
        documented names; `renamed` then holds how (``{"Time (s)": "time_s"}``)."""
        body, content_type = table_body(table)
        answer = self._http.json(
            _PUT, content=body, content_type=content_type, id=self._job_id, kind=kind
        )
        self.renamed = {r["header"]: r["column"] for r in answer.pop("renamed", [])}
        return _tables(answer)

    @_GET.implements
    def get(self) -> Tables:
        """Every kind's table, None where none is attached."""
        return _tables(self._http.json(_GET, id=self._job_id))

    @_DELETE.implements
    def delete(self, kind: str) -> Tables:
        """Removes the job's `kind` table (none there is no error); returns the tables left."""
        return _tables(self._http.json(_DELETE, id=self._job_id, kind=kind))

    @_SCORES.implements
    def scores(self) -> dict[str, Any]:
        """Each attached table against the finished job's result: per kind (None without a
        table) the columns compared, ``rms_residual`` and ``points``, each with ``x``,
        ``measured``, ``model``, ``residual`` and ``z_score`` (None where there is none)."""
        scores: dict[str, Any] = self._http.json(_SCORES, id=self._job_id)
        return scores

    @_SCORES_CSV.implements
    def scores_csv(self) -> str:
        """The scores as CSV text, one row per measured point, as the page downloads it."""
        return self._http.send(_SCORES_CSV, id=self._job_id).text


def _tables(answer: dict[str, Any]) -> Tables:
    return {kind: None if columns is None else frame(columns) for kind, columns in answer.items()}
