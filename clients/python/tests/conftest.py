"""The tests run against the real binary: `TRIBOSIM_BIN`, by default the repository's
``target/release/tribosim`` (nothing is built here; ``cargo build --release`` first). Each
server listens on a port the kernel picks (``--addr 127.0.0.1:0``; the server logs the
address it got) with a temporary data directory."""

from __future__ import annotations

import os
import re
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

import tribosim

REPO = Path(__file__).resolve().parents[3]
BIN = Path(os.environ.get("TRIBOSIM_BIN") or REPO / "target" / "release" / "tribosim")

#: The paper's preset, small: a run takes tens of milliseconds.
SMALL = {
    "preset": "dalmau2018-316l",
    "overrides": {"test": {"cycles": 20}, "numerics": {"grid": 64}},
}
#: A run that goes on until it is cancelled (a million cycles, the scene's limit).
ENDLESS = {
    "preset": "dalmau2018-316l",
    "overrides": {"test": {"cycles": 1000000}, "numerics": {"grid": 32}},
}

#: Seconds a server may take to log its address: it first checks every stored job.
START_TIMEOUT_S = 60.0


class Server:
    """A ``tribosim serve`` process with its data in `directory` (its log there too, named
    after `addr`'s port); `url` once it answers ``/healthz``."""

    def __init__(self, directory: Path, args: list[str], addr: str = "127.0.0.1:0") -> None:
        if not BIN.is_file():
            raise RuntimeError(
                f"no tribosim binary at {BIN}: cargo build --release, or set TRIBOSIM_BIN"
            )
        self.log = directory / f"server-{addr.rsplit(':', 1)[1]}-{time.monotonic_ns()}.log"
        # The server reads TRIBOSIM_TOKEN itself: each test server gets only the token its
        # arguments give.
        env = {k: v for k, v in os.environ.items() if not k.startswith("TRIBOSIM_")}
        with open(self.log, "wb") as log:
            self.process = subprocess.Popen(
                [
                    str(BIN),
                    "serve",
                    "--addr",
                    addr,
                    "--data-dir",
                    str(directory / "data"),
                    *args,
                ],
                stdout=log,
                stderr=log,
                env=env,
            )
        self.url = self._address()

    def _address(self) -> str:
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline:
            found = re.search(r"serving on (http://[0-9.:]+)", self.log.read_text())
            if found:
                assert httpx.get(found.group(1) + "/healthz").json() == {"status": "ok"}
                return found.group(1)
            if self.process.poll() is not None:
                break
            time.sleep(0.05)
        self.stop()
        raise RuntimeError(f"the server did not start:\n{self.log.read_text()}")

    def stop(self) -> None:
        self.process.terminate()
        try:
            self.process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()

    def panics(self) -> list[str]:
        return [line for line in self.log.read_text().splitlines() if "panicked" in line]


def serve(tmp: Path, args: list[str]) -> Iterator[Server]:
    server = Server(tmp, args)
    try:
        yield server
    finally:
        server.stop()
    assert server.panics() == [], server.log.read_text()


@pytest.fixture(scope="session")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Server]:
    """A server without a token, two workers."""
    yield from serve(tmp_path_factory.mktemp("server"), ["--workers", "2"])


@pytest.fixture(scope="session")
def client(server: Server) -> Iterator[tribosim.Client]:
    with tribosim.Client(server.url) as client:
        yield client


@pytest.fixture()
def small_job(client: tribosim.Client) -> tribosim.Job:
    """A small job, ended."""
    job = client.jobs.submit(SMALL, name="pytest small")
    job.wait(progress=False)
    return job
