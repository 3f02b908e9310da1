"""Measured height maps, stored on the server and named by id from a scene's
``disc.surface``: ``{"kind": "measured", "id": surface.id, "remove_tilt": False}``."""

from __future__ import annotations

import builtins
import io
import os
from pathlib import Path
from typing import TYPE_CHECKING

from ._http import Http
from ._routes import route
from ._tables import require_numpy
from .records import Surface

if TYPE_CHECKING:
    import numpy as np

_UPLOAD = route("POST", "/api/v1/surfaces")
_LIST = route("GET", "/api/v1/surfaces")
_GET = route("GET", "/api/v1/surfaces/{id}")
_DELETE = route("DELETE", "/api/v1/surfaces/{id}")

#: Significant digits of each height in the text matrix sent: 9 write any float32 map
#: exactly, beyond any profilometer's resolution, and keep a 2048 x 2048 map (the contact
#: grid's largest side) under the server's 64 MiB body limit: 61.6 MiB, 15.4 bytes a height,
#: for normally distributed heights of rms 0.1 um (half of them negative, one byte longer).
HEIGHT_DIGITS = 9


class Surfaces:
    """``client.surfaces``: upload, list, read and delete height maps."""

    def __init__(self, http: Http) -> None:
        self._http = http

    @_UPLOAD.implements
    def upload(
        self,
        heights_m: np.ndarray,
        pixel_um: float,
        name: str | None = None,
        height_unit: str | None = None,
    ) -> Surface:
        """Stores `heights_m` (a 2-D array of heights indexed ``[iy, ix]``: one row per line
        across the track; in m, or in `height_unit`, ``m``, ``um`` or ``nm``, for an array
        as a profiler exports it) with its square `pixel_um`; the answer has its id, size
        and statistics. A map the server cannot use raises `ValidationError` naming
        ``body``, ``pixel_um`` or ``height_unit``: heights in um passed as m give an rms
        height no ball-on-disc surface has, refused here and not at the run."""
        heights = require_numpy().asarray(heights_m, dtype=float)
        if heights.ndim != 2:
            raise ValueError(f"a height map is a 2-D array, not {heights.ndim}-D")
        text = io.StringIO()
        require_numpy().savetxt(text, heights, fmt=f"%.{HEIGHT_DIGITS}g")
        return self._upload(text.getvalue().encode(), pixel_um, name, "matrix", height_unit)

    @_UPLOAD.implements
    def upload_file(
        self,
        path: str | os.PathLike[str],
        pixel_um: float | None = None,
        name: str | None = None,
        format: str | None = None,
        height_unit: str | None = None,
    ) -> Surface:
        """Stores the map file at `path` as ``tribosim run --surface`` reads it: Gwyddion's
        ``.gsf``, three columns ``x y z`` in m, or a text matrix of heights in m (with its
        `pixel_um`); `format` (``gsf``, ``matrix``, ``xyz``) when the content should not
        decide; `height_unit` (``m``, ``um``, ``nm``) for a text map whose heights are not
        in m. `name` defaults to the file's name."""
        body = Path(path).read_bytes()
        name = Path(path).name if name is None else name
        return self._upload(body, pixel_um, name, format, height_unit)

    def _upload(
        self,
        body: bytes,
        pixel_um: float | None,
        name: str | None,
        format: str | None,
        height_unit: str | None = None,
    ) -> Surface:
        given = [
            ("pixel_um", pixel_um),
            ("name", name),
            ("format", format),
            ("height_unit", height_unit),
        ]
        query = {key: value for key, value in given if value is not None}
        # Bytes whatever the format: the server refuses `text/plain`, which a web page of
        # another site could send to it without asking.
        raw = self._http.json(
            _UPLOAD, params=query, content=body, content_type="application/octet-stream"
        )
        return Surface.from_json(raw)

    @_LIST.implements
    def list(self) -> builtins.list[Surface]:
        """Every stored map, oldest first."""
        return [Surface.from_json(raw) for raw in self._http.json(_LIST)]

    @_GET.implements
    def get(self, surface_id: str) -> Surface:
        """One map's size and statistics (`NotFoundError` if there is none)."""
        return Surface.from_json(self._http.json(_GET, id=surface_id))

    @_DELETE.implements
    def delete(self, surface_id: str) -> None:
        """Deletes the map; `ConflictError` while a queued or running job's scene names it."""
        self._http.send(_DELETE, id=surface_id)
