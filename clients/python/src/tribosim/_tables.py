"""Tables in and out: pandas and numpy are optional (the ``pandas`` extra), imported when a
DataFrame or an array is asked for, with the install command in the error when missing."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

if TYPE_CHECKING:
    import numpy
    import pandas

#: A table sent to the server: a DataFrame, columns (name -> values), rows (one mapping per
#: row), CSV text, or a CSV file given as a `pathlib.Path` (any `os.PathLike`).
TableInput = Union[
    "pandas.DataFrame",
    Mapping[str, Sequence[Any]],
    Sequence[Mapping[str, Any]],
    str,
    "os.PathLike[str]",
]

_HINT = "pip install 'tribosim[pandas]' (pandas and numpy)"


def require_pandas() -> Any:
    """The pandas module, or an ImportError that says how to install it."""
    try:
        import pandas as pd
    except ImportError as e:
        raise ImportError(f"this needs pandas: {_HINT}") from e
    return pd


def require_numpy() -> Any:
    """The numpy module, or an ImportError that says how to install it."""
    try:
        import numpy as np
    except ImportError as e:
        raise ImportError(f"this needs numpy: {_HINT}") from e
    return np


def frame(data: Any) -> pandas.DataFrame:
    """A DataFrame of rows (a list of mappings) or columns (a mapping of lists)."""
    return require_pandas().DataFrame(data)


def table_body(table: TableInput) -> tuple[bytes, str]:
    """The body and content type that send `table`: a DataFrame (a named index as a column
    too) or columns or rows as JSON (numbers as they are, no formatting on the way), text as
    CSV, a path as its file's CSV.

    A ``str`` is CSV text; a single-line string naming an existing file is refused with a
    hint, since sending a file name as a table would only get "missing column" back."""
    from ._http import dumps

    if isinstance(table, os.PathLike):
        return Path(table).read_bytes(), "text/csv"
    if isinstance(table, str):
        if "\n" not in table and Path(table).is_file():
            raise TypeError(
                f"{table!r} is a file name: pass pathlib.Path({table!r}) to send the file"
            )
        return table.encode(), "text/csv"
    if _is_dataframe(table):
        df: Any = table
        if any(name is not None for name in df.index.names):
            df = df.reset_index()
        columns = {str(name): df[name].tolist() for name in df.columns}
        return dumps(columns), "application/json"
    if isinstance(table, Mapping):
        return dumps({str(k): list(v) for k, v in table.items()}), "application/json"
    return dumps([dict(row) for row in table]), "application/json"


def table_json(table: TableInput) -> Any:
    """`table` as a JSON value (CSV text stays text), for a field of a JSON request."""
    import json

    body, content_type = table_body(table)
    text = body.decode()
    return json.loads(text) if content_type == "application/json" else text


def _is_dataframe(value: Any) -> bool:
    return type(value).__name__ == "DataFrame" and hasattr(value, "columns")


def as_array(values: Any) -> numpy.ndarray:
    """A float array of `values` (nested lists as the JSON has them)."""
    array: numpy.ndarray = require_numpy().asarray(values, dtype=float)
    return array
