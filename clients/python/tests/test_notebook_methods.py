"""docs/notebook.md names every public method and property of the client's resources, as
test_routes.py checks that every route has a method: a method added without a word on the
page fails the first test."""

from __future__ import annotations

import inspect
import re

import tribosim

from conftest import REPO

NOTEBOOK_MD = REPO / "docs" / "notebook.md"
#: The classes a notebook's user calls: the client, its resources and what they return.
RESOURCES = [
    tribosim.Client,
    tribosim.Jobs,
    tribosim.Job,
    tribosim.Measurements,
    tribosim.Result,
    tribosim.Studies,
    tribosim.Study,
    tribosim.Calibrations,
    tribosim.Calibration,
    tribosim.Surfaces,
    tribosim.Surface,
]


def public_members(cls: type) -> list[str]:
    """The methods and properties `cls` itself defines, without a leading underscore."""
    return [
        name
        for name, member in vars(cls).items()
        if not name.startswith("_") and (inspect.isfunction(member) or isinstance(member, property))
    ]


def undocumented(page: str, classes: list[type]) -> list[str]:
    """`Class.member` for each member `page` never mentions as ``.member``."""
    return sorted(
        f"{cls.__name__}.{name}"
        for cls in classes
        for name in public_members(cls)
        if not re.search(rf"\.{name}\b", page)
    )


def test_the_notebook_page_names_every_client_method() -> None:
    assert undocumented(NOTEBOOK_MD.read_text(), RESOURCES) == []


def test_a_method_missing_from_the_page_is_reported() -> None:
    page = NOTEBOOK_MD.read_text().replace(".label(", ".relabel(")
    assert undocumented(page, RESOURCES) == ["Job.label"]
    assert "summary_json" in public_members(tribosim.Study)
