"""The routes of the service that the client calls, each with the methods that call it.

Every method that sends a request is declared with the route it uses::

    _GET = route("GET", "/api/v1/jobs/{id}")

    class Job:
        @_GET.implements
        def refresh(self) -> JobInfo:
            return JobInfo.from_json(self._http.json(_GET, id=self.id))

and sends it through that same `Route`, so the path a method declares is the path it
calls. `REGISTRY` is the one table of them all; ``tests/test_routes.py`` checks it against
``openapi.yaml`` both ways: a route of the API without a method here fails, and so does a
route here that the API does not have.
"""

from __future__ import annotations

from typing import Callable, NamedTuple, TypeVar

F = TypeVar("F", bound=Callable[..., object])

#: (method, path) -> the qualified names of the client's methods that call it.
REGISTRY: dict[tuple[str, str], list[str]] = {}


class Route(NamedTuple):
    """One route of the API: an HTTP method and a path with ``{name}`` parameters."""

    method: str
    path: str

    def implements(self, function: F) -> F:
        """Records `function` as a client method that calls this route."""
        REGISTRY.setdefault((self.method, self.path), []).append(function.__qualname__)
        return function


def route(method: str, path: str) -> Route:
    """A route, entered in `REGISTRY` (with no method yet) as soon as it is declared."""
    declared = Route(method.upper(), path)
    REGISTRY.setdefault((declared.method, declared.path), [])
    return declared
