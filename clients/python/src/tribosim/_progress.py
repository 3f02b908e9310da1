"""A progress bar while waiting: tqdm's with the ``progress`` extra (a widget in a notebook
that has ipywidgets), else a line on standard error rewritten in place."""

from __future__ import annotations

import importlib.util
import sys
from typing import Any


class Progress:
    """Progress towards `total` `unit`s (cycles, members); `to(n)` moves it to `n`."""

    def __init__(self, total: int, description: str, unit: str, enabled: bool) -> None:
        self._total = total
        self._description = description
        self._done = 0
        self._bar: Any | None = None
        self._plain = False
        if not enabled:
            return
        try:
            tqdm = _tqdm()
        except ImportError:
            self._plain = True
            return
        self._bar = tqdm(total=total, desc=description, unit=" " + unit)

    def to(self, done: int, note: str = "") -> None:
        """Shows `done` of the total, and `note` (a status) beside it."""
        step, self._done = done - self._done, done
        if self._bar is not None:
            if note:
                self._bar.set_postfix_str(note, refresh=False)
            self._bar.update(step)
        elif self._plain:
            sys.stderr.write(f"\r{self._description}: {done}/{self._total} {note}".rstrip())
            sys.stderr.flush()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
        elif self._plain:
            sys.stderr.write("\n")


def _tqdm() -> Any:
    """tqdm.auto's bar where ipywidgets is there to draw it; tqdm's text bar otherwise, which
    a notebook shows too (tqdm.auto would fall back to it with a warning in every notebook
    without ipywidgets)."""
    from tqdm import tqdm

    if importlib.util.find_spec("ipywidgets") is None:
        return tqdm
    from tqdm.auto import tqdm as auto

    return auto
