"""The Python examples of docs/notebook.md and the README run, in order, from the
repository's root against a live server, as the pages say they do."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import REPO, Server


def run_examples(page: Path) -> int:
    blocks = re.findall(r"```python\n(.*?)```", page.read_text(), re.DOTALL)
    namespace: dict[str, object] = {}
    for number, block in enumerate(blocks, 1):
        exec(compile(block, f"{page.name}, example {number}", "exec"), namespace)
    return len(blocks)


@pytest.fixture()
def at_the_root(server: Server, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(REPO)
    monkeypatch.setenv("TRIBOSIM_URL", server.url)
    for name in ("TRIBOSIM_TOKEN", "TRIBOSIM_TOKEN_FILE"):
        monkeypatch.delenv(name, raising=False)


def test_the_examples_of_docs_notebook_md_run(at_the_root: None) -> None:
    assert run_examples(REPO / "docs" / "notebook.md") >= 8


def test_the_readme_example_runs(at_the_root: None) -> None:
    assert run_examples(REPO / "README.md") == 1
