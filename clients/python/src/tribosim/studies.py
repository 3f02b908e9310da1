"""Studies: a base scene run across the combinations of some of its values (docs/study.md);
each member an ordinary job."""

from __future__ import annotations

import builtins
import json
import os
import time
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Union

from ._http import Http, dumps, list_params
from ._progress import Progress
from ._routes import route
from ._tables import frame
from .errors import RunFailedError, WaitTimeoutError
from .jobs import Job, Jobs, named
from .records import StudyInfo

if TYPE_CHECKING:
    import pandas

#: A study: ``{"base": scene, "axes": {path: values}}`` as a mapping, or a JSON file's path.
StudyInput = Union[Mapping[str, Any], str, "os.PathLike[str]"]

_SUBMIT = route("POST", "/api/v1/studies")
_LIST = route("GET", "/api/v1/studies")
_GET = route("GET", "/api/v1/studies/{id}")
_DELETE = route("DELETE", "/api/v1/studies/{id}")
_SUMMARY = route("GET", "/api/v1/studies/{id}/summary")
_SUMMARY_CSV = route("GET", "/api/v1/studies/{id}/summary.csv")
_REPORT = route("GET", "/api/v1/studies/{id}/report")

_ENDED_MEMBERS = ("succeeded", "failed", "cancelled", "damaged", "deleted")


class Studies:
    """``client.studies``: submit studies, list and find them."""

    def __init__(self, http: Http) -> None:
        self._http = http

    @_SUBMIT.implements
    def submit(self, study: StudyInput, name: str | None = None) -> Study:
        """Queues every member of `study` (a mapping or a JSON file's path), or none, under
        `name` (the base scene's own name otherwise, as `jobs.submit` takes it): a bad
        axis or member scene raises `ValidationError` naming it (``axes.<path>``,
        ``base.<path>``), no room in the queue `RateLimitedError`."""
        body = _study_body(study, name)
        raw = self._http.json(_SUBMIT, content=body, content_type="application/json")
        return Study(self._http, StudyInfo.from_json(raw))

    @_LIST.implements
    def list(
        self, *, status: str | None = None, name: str | None = None, page_size: int = 100
    ) -> builtins.list[Study]:
        """Every study, newest first, or those with `status` (one, or several
        comma-separated) whose name contains `name` (case-insensitively)."""
        params = list_params(page_size, status=status, name=name)
        return [
            Study(self._http, StudyInfo.from_json(raw)) for raw in self._http.pages(_LIST, params)
        ]

    @_GET.implements
    def get(self, study_id: str) -> Study:
        """The study of `study_id` (`NotFoundError` if there is none)."""
        return Study(self._http, _fetch(self._http, study_id))


def _study_body(study: StudyInput, name: str | None) -> bytes:
    """The study as sent: a file as it is without `name`, else its base named `name` (a study
    without a base is sent as it is, for the server to refuse naming ``base``)."""
    if isinstance(study, (str, os.PathLike)):
        text = Path(study).read_bytes()
        if name is None:
            return text
        loaded: Mapping[str, Any] = json.loads(text)
    else:
        loaded = study
    if name is None or "base" not in loaded:
        return dumps(loaded)
    return dumps({**loaded, "base": named(loaded["base"], name)})


def _fetch(http: Http, study_id: str) -> StudyInfo:
    return StudyInfo.from_json(http.json(_GET, id=study_id))


class Study:
    """One study. `info` is its record as last seen; `refresh()` asks again."""

    def __init__(self, http: Http, info: StudyInfo) -> None:
        self._http = http
        self.id = info.id
        self.info = info

    def __repr__(self) -> str:
        return f"<Study {self.id} {self.info.status} {len(self.info.members)} members>"

    @_GET.implements
    def refresh(self) -> StudyInfo:
        """The study and its members' statuses now."""
        self.info = _fetch(self._http, self.id)
        return self.info

    def jobs(self) -> list[Job]:
        """The members' jobs, in member order (each with its own events and result)."""
        jobs = Jobs(self._http)
        return [jobs.get(member["job_id"]) for member in self.info.members]

    @_GET.implements
    def wait(
        self,
        progress: bool = True,
        timeout: float | None = None,
        check: bool = True,
        poll_s: float = 0.5,
    ) -> StudyInfo:
        """Polls the study every `poll_s` seconds until every member has ended, with a
        progress bar over the members, and returns its final record. `check` raises
        `RunFailedError` unless every member succeeded; `timeout` (s) raises
        `WaitTimeoutError` and leaves the study running."""
        deadline = None if timeout is None else time.monotonic() + timeout
        bar = Progress(len(self.info.members), f"study {self.id[:8]}", "members", progress)
        try:
            while True:
                info = self.refresh()
                bar.to(sum(info.counts.get(s, 0) for s in _ENDED_MEMBERS), info.status)
                if info.ended:
                    break
                if deadline is not None and time.monotonic() > deadline:
                    raise WaitTimeoutError(f"study {self.id} is {info.status}")
                time.sleep(poll_s)
        finally:
            bar.close()
        if check and info.status != "succeeded":
            raise RunFailedError(f"study {self.id} {info.status}: {info.counts}", info)
        return info

    @_SUMMARY.implements
    def summary_json(self) -> dict[str, Any]:
        """The summary as the server gives it: ``axes``, ``workers``, ``wall_s``,
        ``members`` (each with ``summary``, ``error`` or ``pending``)."""
        summary: dict[str, Any] = self._http.json(_SUMMARY, id=self.id)
        return summary

    @_SUMMARY.implements
    def summary(self) -> pandas.DataFrame:
        """One row per member: ``member``, a column per axis (its dotted path), the run's
        summary (``total_volume_mm3``, ``max_depth_um``, ``wac_volume_mm3``, ...,
        ``warnings``: the run's warnings as a list, a caveat on that member's numbers such as a
        potential capped at E_corr; NaN when it warned of nothing), and ``error`` and
        ``pending`` (None for a member with a result)."""
        rows = [
            {
                "member": m["index"],
                **m["values"],
                **m.get("summary", {}),
                "error": m.get("error"),
                "pending": m.get("pending"),
            }
            for m in self.summary_json()["members"]
        ]
        return frame(rows)

    @_SUMMARY_CSV.implements
    def summary_csv(self) -> str:
        """The summary as the CSV table ``tribosim study --csv`` writes."""
        return self._http.send(_SUMMARY_CSV, id=self.id).text

    @_REPORT.implements
    def report(self, path: str | os.PathLike[str] | None = None) -> str:
        """The study's printable report, its table and each quantity against each axis:
        one self-contained HTML file (docs/report.md), written to `path` when given."""
        html = self._http.send(_REPORT, id=self.id).text
        if path is not None:
            Path(path).write_text(html, encoding="utf-8")
        return html

    @_DELETE.implements
    def cancel(self) -> StudyInfo:
        """Cancels the members that have not ended (running ones stop within a cycle);
        those that ended keep their results. A study whose members have all ended is left
        as it is (the API's DELETE would delete it)."""
        if self.refresh().ended:
            return self.info
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self.info = StudyInfo.from_json(answer.json())
        return self.info

    @_DELETE.implements
    def delete(self) -> None:
        """Deletes the study, its members' jobs and their files; members still going are
        cancelled first and the study deleted once they have stopped."""
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self.info = StudyInfo.from_json(answer.json())
            self.wait(progress=False, check=False)
            self._http.send(_DELETE, id=self.id)
