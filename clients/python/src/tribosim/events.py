"""A job's server-sent events: ``event: cycle`` (``id:`` the cycle number, data the cycle
record) per solved cycle, then one ``event: status`` with the final job record."""

from __future__ import annotations

import json
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any, Union

from .records import JobInfo


@dataclass(frozen=True)
class CycleEvent:
    """One solved cycle: its number and its record (``wear_volume_mm3``, ``time_s``, ...)."""

    cycle: int
    record: dict[str, Any]


@dataclass(frozen=True)
class StatusEvent:
    """The job's final record; the stream ends after it."""

    job: JobInfo


Event = Union[CycleEvent, StatusEvent]


def parse(lines: Iterable[str]) -> Iterator[Event]:
    """The events of an event stream's lines (the text/event-stream format: ``field:
    value`` lines, a blank line ending each event, ``:`` lines comments, which the server's
    keep-alives are). Events of other types are skipped."""
    kind = "message"
    data: list[str] = []
    event_id: str | None = None
    for line in lines:
        if not line:
            if data:
                event = _event(kind, event_id, "\n".join(data))
                if event is not None:
                    yield event
            kind, data, event_id = "message", [], None
            continue
        if line.startswith(":"):
            continue
        name, _, value = line.partition(":")
        value = value[1:] if value.startswith(" ") else value
        if name == "event":
            kind = value
        elif name == "data":
            data.append(value)
        elif name == "id":
            event_id = value


def _event(kind: str, event_id: str | None, data: str) -> Event | None:
    if kind == "cycle":
        record = json.loads(data)
        return CycleEvent(int(event_id) if event_id else int(record["cycle"]), record)
    if kind == "status":
        return StatusEvent(JobInfo.from_json(json.loads(data)))
    return None
