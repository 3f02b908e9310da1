"""The example notebook is committed without outputs: scripts/python-client.sh executes it
against a live server, and stored outputs would be one machine's numbers and images."""

from __future__ import annotations

import json

from conftest import REPO

NOTEBOOK = REPO / "clients" / "python" / "examples" / "paper_and_study.ipynb"


def test_the_notebook_has_no_outputs() -> None:
    cells = json.loads(NOTEBOOK.read_text())["cells"]
    code = [cell for cell in cells if cell["cell_type"] == "code"]
    assert code
    assert all(cell["outputs"] == [] and cell["execution_count"] is None for cell in code)
