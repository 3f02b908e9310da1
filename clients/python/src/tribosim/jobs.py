"""Jobs: one scene run on the server's worker pool."""

from __future__ import annotations

import builtins
import copy
import json
import os
import time
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any, Union

import httpx

from ._http import Http, dumps, list_params
from ._progress import Progress
from ._routes import route
from .errors import RunFailedError, TransportError, WaitTimeoutError
from .events import CycleEvent, Event, StatusEvent, parse
from .measurements import Measurements
from .records import JobInfo
from .result import Result

#: A scene: its JSON as a mapping, or the path of a JSON file.
SceneInput = Union[Mapping[str, Any], str, "os.PathLike[str]"]

_SUBMIT = route("POST", "/api/v1/jobs")
_LIST = route("GET", "/api/v1/jobs")
_GET = route("GET", "/api/v1/jobs/{id}")
_DELETE = route("DELETE", "/api/v1/jobs/{id}")
_PATCH = route("PATCH", "/api/v1/jobs/{id}")
_EVENTS = route("GET", "/api/v1/jobs/{id}/events")
_RESULT = route("GET", "/api/v1/jobs/{id}/result")
_RESULT_CSV = route("GET", "/api/v1/jobs/{id}/result.csv")
_SCENE = route("GET", "/api/v1/jobs/{id}/scene")
_REPORT = route("GET", "/api/v1/jobs/{id}/report")
_COMPARISON = route("GET", "/api/v1/report")
_PROFILES_CSV = route("GET", "/api/v1/jobs/{id}/profiles.csv")
_PRESSURE_CSV = route("GET", "/api/v1/jobs/{id}/pressure.csv")

#: Attempts in a row to follow a job's events again after the stream broke (a dropped
#: connection, a server restarting: it serves its jobs' events again once up), and the
#: seconds between them.
MAX_RECONNECTS = 3
RECONNECT_DELAY_S = 1.0


class _Unset:
    """A label not given to `Job.label` (None clears it)."""


UNSET = _Unset()


class Jobs:
    """``client.jobs``: submit scenes, list and find jobs."""

    def __init__(self, http: Http) -> None:
        self._http = http

    @_SUBMIT.implements
    def submit(
        self,
        scene: SceneInput,
        name: str | None = None,
        *,
        sample: str | None = None,
        note: str | None = None,
        tags: Sequence[str] = (),
    ) -> Job:
        """Queues `scene` (a mapping, or a JSON file's path; ``{}`` is the paper's test,
        ``{"preset": ..., "overrides": {...}}`` starts from a preset) under `name` (the
        scene's own name otherwise), labelled with `sample`, `note` and `tags`. An invalid
        scene (or a label past its bound) raises `ValidationError` naming every bad field; a
        full queue `RateLimitedError`.

        A file is sent as it is when no `name` is given, so the server refuses a key given
        twice in it as it would from curl."""
        body = _scene_body(scene, name)
        labels = {"sample": sample, "note": note, "tags": ",".join(tags) if tags else None}
        params = {key: value for key, value in labels.items() if value is not None}
        answer = self._http.json(
            _SUBMIT, params=params, content=body, content_type="application/json"
        )
        return Job(self._http, JobInfo.from_json(answer))

    @_LIST.implements
    def list(
        self,
        *,
        status: str | None = None,
        name: str | None = None,
        q: str | None = None,
        tag: str | None = None,
        page_size: int = 100,
    ) -> builtins.list[Job]:
        """Every job, newest first, or those with `status` (one, or several
        comma-separated) whose name contains `name`, whose name, sample, note or a tag
        contains `q`, with one of the tags `tag` (comma-separated), each case-insensitively;
        read a page of `page_size` at a time."""
        params = list_params(page_size, status=status, name=name, q=q, tag=tag)
        return [Job(self._http, JobInfo.from_json(raw)) for raw in self._http.pages(_LIST, params)]

    @_GET.implements
    @_COMPARISON.implements
    def report(self, jobs: Iterable[Job | str], path: str | os.PathLike[str] | None = None) -> str:
        """The printable report comparing 2 to 8 ended `jobs` (`Job`s or ids): one
        self-contained HTML file (docs/report.md), written to `path` when given."""
        ids = ",".join(job.id if isinstance(job, Job) else str(job) for job in jobs)
        html = self._http.send(_COMPARISON, params={"jobs": ids}).text
        return _saved(html, path)

    def get(self, job_id: str) -> Job:
        """The job of `job_id` (`NotFoundError` if there is none)."""
        return Job(self._http, _fetch(self._http, job_id))


def _fetch(http: Http, job_id: str) -> JobInfo:
    return JobInfo.from_json(http.json(_GET, id=job_id))


class Job:
    """One job. `info` is its record as last seen; `refresh()` asks again."""

    def __init__(self, http: Http, info: JobInfo) -> None:
        self._http = http
        self.id = info.id
        self.info = info
        self.measurements = Measurements(http, info.id)

    def __repr__(self) -> str:
        return f"<Job {self.id} {self.info.status} {self.info.name!r}>"

    @_GET.implements
    def refresh(self) -> JobInfo:
        """The job's status and progress now."""
        self.info = _fetch(self._http, self.id)
        return self.info

    @_EVENTS.implements
    def events(self, after: int = 0) -> Iterator[Event]:
        """The job's events as they come: a `CycleEvent` per solved cycle after cycle
        `after`, then its `StatusEvent`, then the end. If the stream breaks, it is followed
        again from the last cycle received (``Last-Event-ID``), up to `MAX_RECONNECTS` times
        in a row."""
        return self._events(after, None)

    @_EVENTS.implements
    def wait(
        self, progress: bool = True, timeout: float | None = None, check: bool = True
    ) -> JobInfo:
        """Follows the job's events until it ends, with a progress bar over its cycles, and
        returns its final record. `check` raises `RunFailedError` for a job that did not
        succeed; `timeout` (s) raises `WaitTimeoutError`, checked whenever the server sends
        anything (at least every 15 s), and leaves the job running."""
        deadline = None if timeout is None else time.monotonic() + timeout
        bar = Progress(self.info.cycles_total, self.info.name, "cycles", progress)
        try:
            bar.to(self.info.cycles_done, self.info.status)
            for event in self._events(self.info.cycles_done, deadline):
                if isinstance(event, CycleEvent):
                    bar.to(event.cycle, "running")
                else:
                    self.info = event.job
                    bar.to(event.job.cycles_done, event.job.status)
        finally:
            bar.close()
        if check and self.info.status != "succeeded":
            raise RunFailedError(
                f"job {self.id} {self.info.status}: {self.info.error or 'no result'}", self.info
            )
        return self.info

    @_DELETE.implements
    def cancel(self) -> JobInfo:
        """Stops the job if it has not ended: a queued one is cancelled at once, a running
        one within a cycle (`wait()` to see it end). An ended job is left as it is. (The
        API's DELETE also deletes an ended job: one that ends in the instant between this
        method's check and its DELETE is deleted.)"""
        if self.refresh().ended:
            return self.info
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self.info = JobInfo.from_json(answer.json())
        return self.info

    @_PATCH.implements
    def label(
        self,
        *,
        sample: str | None | _Unset = UNSET,
        note: str | None | _Unset = UNSET,
        tags: Sequence[str] | None | _Unset = UNSET,
    ) -> JobInfo:
        """Changes the labels given (None clears one; one not given stays as it is) and
        returns the record; a label past its bound raises `ValidationError` naming it."""
        given = {"sample": sample, "note": note, "tags": tags}
        body = {
            key: (list(value) if key == "tags" and value is not None else value)
            for key, value in given.items()
            if not isinstance(value, _Unset)
        }
        self.info = JobInfo.from_json(self._http.json(_PATCH, json=body, id=self.id))
        return self.info

    @_DELETE.implements
    def delete(self) -> None:
        """Deletes the job and its files; one that has not ended is cancelled first and
        deleted once it has stopped."""
        answer = self._http.send(_DELETE, id=self.id)
        if answer.status_code != 204:
            self.info = JobInfo.from_json(answer.json())
            self.wait(progress=False, check=False)
            self._http.send(_DELETE, id=self.id)

    @_RESULT.implements
    def result(self, compact: bool = False) -> Result:
        """The result of an ended job (`ConflictError` before it ends). A failed or cancelled
        job's result has ``complete`` False and the cycles solved before the stop.
        `compact` leaves the pressure maps out (a big grid's are most of the result)."""
        params = {"compact": "true"} if compact else None
        return Result(self._http.json(_RESULT, params=params, id=self.id))

    @_RESULT_CSV.implements
    def result_csv(self) -> str:
        """The per-cycle table as CSV text, as the page downloads it."""
        return self._http.send(_RESULT_CSV, id=self.id).text

    @_PROFILES_CSV.implements
    def profiles_csv(self) -> str:
        """The depth profiles as CSV text, a row per point: ``cycle,y_um,depth_um``."""
        return self._http.send(_PROFILES_CSV, id=self.id).text

    @_PRESSURE_CSV.implements
    def pressure_csv(self) -> str:
        """The pressure maps as CSV text, a row per cell: ``cycle,x_um,y_um,pressure_mpa``."""
        return self._http.send(_PRESSURE_CSV, id=self.id).text

    @_SCENE.implements
    def scene(self) -> dict[str, Any]:
        """The scene as run, every default filled in; submitting it again runs the same test."""
        scene: dict[str, Any] = self._http.json(_SCENE, id=self.id)
        return scene

    @_REPORT.implements
    def report(self, path: str | os.PathLike[str] | None = None) -> str:
        """The run's printable report with its measurements against the model: one
        self-contained HTML file that prints to A4 and Letter (docs/report.md), written to
        `path` when given."""
        return _saved(self._http.send(_REPORT, id=self.id).text, path)

    def _events(self, after: int, deadline: float | None) -> Iterator[Event]:
        failures = 0
        while True:
            headers = {"last-event-id": str(after)} if after else {}
            cause: Exception | None = None
            try:
                with self._http.stream(_EVENTS, headers, id=self.id) as answer:
                    for event in parse(_until(answer.iter_lines(), deadline)):
                        failures = 0
                        yield event
                        if isinstance(event, StatusEvent):
                            return
                        after = event.cycle
            except (TransportError, httpx.TransportError) as e:
                cause = e
            failures += 1
            if failures > MAX_RECONNECTS:
                problem = cause or "the stream ended before the job's status"
                raise TransportError(f"the events of job {self.id}: {problem}") from cause
            time.sleep(RECONNECT_DELAY_S)


def _until(lines: Iterable[str], deadline: float | None) -> Iterator[str]:
    for line in lines:
        if deadline is not None and time.monotonic() > deadline:
            raise WaitTimeoutError("the wait's timeout passed")
        yield line


def _saved(html: str, path: str | os.PathLike[str] | None) -> str:
    """`html`, written to `path` first when there is one."""
    if path is not None:
        Path(path).write_text(html, encoding="utf-8")
    return html


def _scene_body(scene: SceneInput, name: str | None) -> bytes:
    if isinstance(scene, (str, os.PathLike)):
        text = Path(scene).read_bytes()
        return text if name is None else dumps(named(json.loads(text), name))
    return dumps(scene) if name is None else dumps(named(scene, name))


def named(scene: Mapping[str, Any], name: str) -> dict[str, Any]:
    """A copy of `scene` called `name` (in its overrides when it starts from a preset): how
    `jobs.submit` and `studies.submit` both name what they send."""
    copied: dict[str, Any] = copy.deepcopy(dict(scene))
    target = copied.setdefault("overrides", {}) if "preset" in copied else copied
    target["name"] = name
    return copied
