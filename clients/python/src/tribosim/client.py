"""The client: one connection to a tribosim server, with its resources."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ._http import Http
from ._routes import route
from .calibrations import Calibrations
from .jobs import Jobs
from .records import Preset
from .studies import Studies
from .surfaces import Surfaces

#: Where the client connects when neither `base_url` nor ``TRIBOSIM_URL`` says.
DEFAULT_URL = "http://127.0.0.1:8080"
#: Seconds any one request may take to connect, send or answer (an event stream waits
#: longer between events: `_http.STREAM_READ_TIMEOUT_S`).
DEFAULT_TIMEOUT_S = 30.0

_PAGE = route("GET", "/")
_PAGE_FILE = route("GET", "/static/{path}")
_GUIDE = route("GET", "/docs/{name}")
_HEALTH = route("GET", "/healthz")
_OPENAPI = route("GET", "/api/v1/openapi.yaml")
_PRESETS = route("GET", "/api/v1/presets")
_MATERIALS = route("GET", "/api/v1/materials")


class Client:
    """A tribosim server.

    - `base_url`: the server's address; default ``TRIBOSIM_URL``, else
      ``http://127.0.0.1:8080``.
    - The token (a server bound beyond loopback requires one): `token`, else the first
      line of `token_file`, else ``TRIBOSIM_TOKEN``, else ``TRIBOSIM_TOKEN_FILE``'s first
      line, else none. The server's own ``--token-file`` takes the same file.
    - `timeout`: seconds any one request may take.

    Use it in a ``with`` block, or `close()` it, to close its connections."""

    def __init__(
        self,
        base_url: str | None = None,
        token: str | None = None,
        token_file: str | os.PathLike[str] | None = None,
        timeout: float = DEFAULT_TIMEOUT_S,
    ) -> None:
        url = base_url or os.environ.get("TRIBOSIM_URL") or DEFAULT_URL
        self._http = Http(url, _token(token, token_file), timeout)
        self.base_url = self._http.base_url
        self.jobs = Jobs(self._http)
        self.studies = Studies(self._http)
        self.calibrations = Calibrations(self._http)
        self.surfaces = Surfaces(self._http)

    def __repr__(self) -> str:
        return f"<tribosim.Client {self.base_url}>"

    def __enter__(self) -> Client:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def close(self) -> None:
        self._http.close()

    @_HEALTH.implements
    def health(self) -> str:
        """``"ok"`` when the server is up (no token needed)."""
        status: str = self._http.json(_HEALTH)["status"]
        return status

    @_PRESETS.implements
    def presets(self) -> list[Preset]:
        """The built-in scenes."""
        return [Preset.from_json(raw) for raw in self._http.json(_PRESETS)]

    @_MATERIALS.implements
    def materials(self) -> dict[str, Any]:
        """The materials library a scene names in ``disc.material`` and ``ball.material``:
        ``discs``, ``balls`` (each value with its source key, or ``None`` and why) and the
        ``references`` they cite (docs/materials.md)."""
        library: dict[str, Any] = self._http.json(_MATERIALS)
        return library

    @_OPENAPI.implements
    def openapi(self) -> str:
        """The server's OpenAPI description, YAML text (no token needed)."""
        return self._http.send(_OPENAPI).text

    @_PAGE.implements
    def page(self) -> str:
        """The results page's HTML (open `base_url` in a browser to use it)."""
        return self._http.send(_PAGE).text

    @_PAGE_FILE.implements
    def page_file(self, path: str) -> bytes:
        """One of the page's files by its path under the page's folder (``js/main.js``):
        its styles, modules and the vendored uPlot."""
        return self._http.send(_PAGE_FILE, path=path).content

    @_GUIDE.implements
    def guide(self, name: str) -> str:
        """One of the guides, as the server's binary holds them (``scene.md``, ``result.md``,
        ...): Markdown text."""
        return self._http.send(_GUIDE, name=name).text


def _token(token: str | None, token_file: str | os.PathLike[str] | None) -> str | None:
    if token:
        return token
    if token_file is not None:
        return _first_line(token_file)
    if os.environ.get("TRIBOSIM_TOKEN"):
        return os.environ["TRIBOSIM_TOKEN"]
    if os.environ.get("TRIBOSIM_TOKEN_FILE"):
        return _first_line(os.environ["TRIBOSIM_TOKEN_FILE"])
    return None


def _first_line(path: str | os.PathLike[str]) -> str | None:
    """The token in a file as the server reads its ``--token-file``: the first line, trimmed."""
    lines = Path(path).read_text().splitlines()
    return lines[0].strip() if lines and lines[0].strip() else None
