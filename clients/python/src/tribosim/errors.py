"""The client's exceptions: one hierarchy under `TribosimError`.

Every error answer of the service is JSON ``{"error": "...", "fields": [{"path",
"message"}]}`` (openapi.yaml, ``Error``); `ApiError` carries it parsed, and its subclass
says which kind of answer it was:

- `RefusedError`: a 4xx, the request's fault;
  - `ValidationError` (422): invalid content, every bad field in `fields`;
  - `AuthError` (401), `NotFoundError` (404), `ConflictError` (409);
  - `RateLimitedError` (429): the queue or the calibrations are full, `retry_after_s`;
- `ServerError`: a 5xx (507 when its disk is full).

`TransportError` is a request that got no answer (the server is down or unreachable), and
`RunFailedError` a job, study or calibration that ended without what was waited for.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any


class TribosimError(Exception):
    """Base of every error the client raises."""


@dataclass(frozen=True)
class FieldError:
    """One field the server refused: its dotted path (``test.load_n``; empty for the
    whole document) and what is wrong, with the allowed range."""

    path: str
    message: str

    def __str__(self) -> str:
        return f"{self.path or '(document)'}: {self.message}"


class ApiError(TribosimError):
    """An error answer of the service."""

    def __init__(
        self,
        status: int,
        message: str,
        fields: list[FieldError],
        method: str,
        url: str,
        headers: Mapping[str, str] | None = None,
    ) -> None:
        self.status = status
        self.message = message
        self.fields = fields
        self.method = method
        self.url = url
        self.headers: dict[str, str] = dict(headers or {})
        super().__init__(str(self))

    def __str__(self) -> str:
        lines = [f"{self.status} {self.message} ({self.method} {self.url})"]
        lines.extend(f"  {field}" for field in self.fields)
        return "\n".join(lines)

    def field(self, path: str) -> FieldError | None:
        """The refused field at `path`, if the answer names it."""
        return next((field for field in self.fields if field.path == path), None)


class RefusedError(ApiError):
    """A 4xx: the server refused the request."""


class ValidationError(RefusedError):
    """422: the content is invalid; `fields` names every bad field."""


class AuthError(RefusedError):
    """401: the bearer token is missing or wrong."""


class NotFoundError(RefusedError):
    """404: no job, study, calibration or surface has this id."""


class ConflictError(RefusedError):
    """409: the thing exists but is not in a state that has what was asked for (a result
    of a job still running, a surface a queued job uses, a damaged job)."""


class RateLimitedError(RefusedError):
    """429: the queue (or the calibrations' places) are full; retry after `retry_after_s`
    seconds when the server says."""

    @property
    def retry_after_s(self) -> float | None:
        value = self.headers.get("retry-after")
        try:
            return float(value) if value is not None else None
        except ValueError:
            return None


class ServerError(ApiError):
    """A 5xx: the server failed (or its disk is full, 507)."""


class TransportError(TribosimError):
    """No answer: the connection failed or timed out (the cause is chained)."""


class RunFailedError(TribosimError):
    """A job, study or calibration ended without what was waited for; `record` is its
    last state as the server gave it."""

    def __init__(self, message: str, record: Any) -> None:
        self.record = record
        super().__init__(message)


class WaitTimeoutError(TribosimError, TimeoutError):
    """A wait ran past its `timeout`; the job, study or calibration goes on."""


_BY_STATUS = {
    401: AuthError,
    404: NotFoundError,
    409: ConflictError,
    422: ValidationError,
    429: RateLimitedError,
}


def error_for(
    status: int, body: Any, method: str, url: str, headers: Mapping[str, str]
) -> ApiError:
    """The exception for an error answer; a body not of the documented shape (a proxy's
    page, say) keeps its text as the message."""
    if isinstance(body, dict) and isinstance(body.get("error"), str):
        message = body["error"]
        fields = [
            FieldError(str(f.get("path", "")), str(f.get("message", "")))
            for f in body.get("fields") or []
            if isinstance(f, dict)
        ]
    else:
        message, fields = (str(body) if body else "(no body)"), []
    kind = _BY_STATUS.get(status) or (ServerError if status >= 500 else RefusedError)
    return kind(status, message, fields, method, url, headers)
