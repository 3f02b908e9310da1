"""Measured points attached to a job (``wear_volume``, ``profile``, ``potential``), drawn
by the page beside the run's own curves."""

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

#: Each kind's table (or None), as DataFrames.
Tables = dict[str, Optional["pandas.DataFrame"]]


class Measurements:
    """``job.measurements``. The columns, units in the names:

    - ``wear_volume``: ``time_s`` or ``cycles`` (or both), ``volume_mm3``, optionally
      ``spread_mm3``;
    - ``profile``: ``y_mm`` (across the track), ``depth_um`` (positive into the disc);
    - ``potential``: ``time_s``, ``potential_v``.

    A table the server cannot use raises `ValidationError` naming the column (and the row
    in its message)."""

    def __init__(self, http: Http, job_id: str) -> None:
        self._http = http
        self._job_id = job_id

    @_PUT.implements
    def put(self, kind: str, table: TableInput) -> Tables:
        """Attaches `table` (a DataFrame, columns, rows, CSV text or a CSV file's
        `pathlib.Path`) as the job's `kind`, replacing any; returns every table of the job."""
        body, content_type = table_body(table)
        answer = self._http.json(
            _PUT, content=body, content_type=content_type, id=self._job_id, kind=kind
        )
        return _tables(answer)

    @_GET.implements
    def get(self) -> Tables:
        """Every kind's table, None where none is attached."""
        return _tables(self._http.json(_GET, id=self._job_id))

    @_DELETE.implements
    def delete(self, kind: str) -> Tables:
        """Removes the job's `kind` table (none there is no error); returns the tables left."""
        return _tables(self._http.json(_DELETE, id=self._job_id, kind=kind))


def _tables(answer: dict[str, Any]) -> Tables:
    return {kind: None if columns is None else frame(columns) for kind, columns in answer.items()}
