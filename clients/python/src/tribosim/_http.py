"""Sending one request of a `Route` and turning an error answer into its exception."""

from __future__ import annotations

import json as jsonlib
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any, Union
from urllib.parse import quote

import httpx

from ._routes import Route
from .errors import TransportError, error_for

#: Seconds an event stream may stay silent before the client gives up on it: the server
#: sends a keep-alive comment at least every 15 s, so four missed in a row mean the
#: connection is gone.
STREAM_READ_TIMEOUT_S = 60.0

Params = Mapping[str, Union[str, int, float]]


def dumps(value: Any) -> bytes:
    """JSON of `value`, refusing NaN and infinities (not JSON; the server would answer 400)
    and writing numpy scalars and arrays as plain numbers and lists."""
    return jsonlib.dumps(value, allow_nan=False, default=_plain).encode()


def _plain(value: Any) -> Any:
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


class Http:
    """The connection to one server, with its token."""

    def __init__(self, base_url: str, token: str | None, timeout: float) -> None:
        headers = {"authorization": f"Bearer {token}"} if token else {}
        self.base_url = base_url.rstrip("/")
        self._client = httpx.Client(base_url=self.base_url, headers=headers, timeout=timeout)

    def close(self) -> None:
        self._client.close()

    def send(
        self,
        route: Route,
        *,
        params: Params | None = None,
        json: Any = None,
        content: bytes | None = None,
        content_type: str | None = None,
        **path: str,
    ) -> httpx.Response:
        """Sends `route` with the `path` parameters filled in; raises the `ApiError` of an
        error answer and `TransportError` when there is none."""
        request = self._request(route, params, json, content, content_type, path)
        try:
            response = self._client.send(request)
        except httpx.TransportError as e:
            raise TransportError(f"{route.method} {request.url}: {e}") from e
        _check(response)
        return response

    def json(self, route: Route, **kwargs: Any) -> Any:
        """The JSON answer of `send`."""
        return self.send(route, **kwargs).json()

    @contextmanager
    def stream(
        self, route: Route, headers: dict[str, str], **path: str
    ) -> Iterator[httpx.Response]:
        """The answer of `route`, read as it arrives (an event stream)."""
        request = self._request(route, None, None, None, None, path)
        request.headers.update(headers)
        request.extensions["timeout"] = httpx.Timeout(
            self._client.timeout.connect, read=STREAM_READ_TIMEOUT_S
        ).as_dict()
        try:
            response = self._client.send(request, stream=True)
        except httpx.TransportError as e:
            raise TransportError(f"{route.method} {request.url}: {e}") from e
        try:
            if response.status_code >= 400:
                response.read()
                _check(response)
            yield response
        finally:
            response.close()

    def _request(
        self,
        route: Route,
        params: Params | None,
        json: Any,
        content: bytes | None,
        content_type: str | None,
        path: Mapping[str, str],
    ) -> httpx.Request:
        url = route.path.format(**{k: quote(str(v), safe="") for k, v in path.items()})
        headers = {}
        if json is not None:
            content, content_type = dumps(json), "application/json"
        if content_type is not None:
            headers["content-type"] = content_type
        return self._client.build_request(
            route.method, url, params=params, content=content, headers=headers
        )


def _check(response: httpx.Response) -> None:
    if response.status_code < 400:
        return
    try:
        body: Any = response.json()
    except ValueError:
        body = response.text
    raise error_for(
        response.status_code,
        body,
        response.request.method,
        str(response.request.url),
        response.headers,
    )
