"""Every route of openapi.yaml has a client method, and the client calls no other route.
The client declares each method's route in `tribosim._routes.REGISTRY` (see its module
doc); a route added to openapi.yaml without a method fails the first test."""

from __future__ import annotations

import yaml

import tribosim
from tribosim._routes import REGISTRY

from conftest import REPO

OPENAPI = REPO / "openapi.yaml"
METHODS = {"get", "put", "post", "delete", "patch", "head", "options"}


def api_routes() -> set[tuple[str, str]]:
    paths = yaml.safe_load(OPENAPI.read_text())["paths"]
    return {
        (method.upper(), path)
        for path, item in paths.items()
        for method in item
        if method in METHODS
    }


def without_method(
    api: set[tuple[str, str]], registry: dict[tuple[str, str], list[str]]
) -> list[tuple[str, str]]:
    return sorted(route for route in api if not registry.get(route))


def test_every_route_of_the_api_has_a_client_method() -> None:
    api = api_routes()
    assert ("GET", "/healthz") in api and ("PUT", "/api/v1/jobs/{id}/measurements/{kind}") in api
    assert without_method(api, REGISTRY) == []


def test_a_route_without_a_method_is_reported() -> None:
    unknown = ("GET", "/api/v1/jobs/{id}/not-a-route")
    assert without_method(api_routes() | {unknown}, REGISTRY) == [unknown]


def test_the_client_calls_only_routes_of_the_api() -> None:
    assert sorted(set(REGISTRY) - api_routes()) == []


def test_the_methods_are_named() -> None:
    assert REGISTRY[("GET", "/api/v1/jobs/{id}/result")] == ["Job.result"]
    assert sorted(REGISTRY[("DELETE", "/api/v1/jobs/{id}")]) == ["Job.cancel", "Job.delete"]


def test_the_server_serves_the_description_read_here(client: tribosim.Client) -> None:
    assert client.openapi() == OPENAPI.read_text()
