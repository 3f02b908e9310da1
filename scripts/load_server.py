"""The tribosim server the load test drives, and its tally of checks.

Standard library only; Linux only (/proc): imported by scripts/load_test.py.
"""

from __future__ import annotations

import http.client
import json
import re
import signal
import subprocess
import threading
from pathlib import Path


class Server:
    """A tribosim server on a free loopback port."""

    def __init__(self, binary: str, data: Path, *extra: str) -> None:
        # Held for the server's life, and closed by stop().
        self.log = open(data.parent / "server.log", "ab")  # noqa: SIM115
        self.proc = subprocess.Popen(
            [binary, "serve", "--addr", "127.0.0.1:0", "--data-dir", str(data), *extra],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        self.port = 0
        assert self.proc.stderr is not None
        for raw in self.proc.stderr:
            self.log.write(raw)
            found = re.search(rb"serving on http://127\.0\.0\.1:(\d+)", raw)
            if found:
                self.port = int(found.group(1))
                break
        if not self.port:
            raise SystemExit("the server did not start")
        threading.Thread(target=self._drain, daemon=True).start()

    def _drain(self) -> None:
        assert self.proc.stderr is not None
        for raw in self.proc.stderr:
            self.log.write(raw)

    def status(self) -> dict[str, int]:
        """VmRSS and VmHWM, MiB."""
        text = Path(f"/proc/{self.proc.pid}/status").read_text()
        return {
            key: int(re.search(rf"{key}:\s+(\d+) kB", text).group(1)) // 1024
            for key in ("VmRSS", "VmHWM")
        }

    def reset_peak(self) -> None:
        """Resets VmHWM to the current RSS (Linux >= 4.0, writing 5 to clear_refs)."""
        Path(f"/proc/{self.proc.pid}/clear_refs").write_text("5")

    def alive(self) -> bool:
        return self.proc.poll() is None

    def stop(self, kill: bool = False) -> None:
        if self.alive():
            self.proc.send_signal(signal.SIGKILL if kill else signal.SIGTERM)
        self.proc.wait(timeout=30)
        self.log.close()

    def request(
        self,
        method: str,
        path: str,
        body: bytes | None = None,
        content_type: str = "application/json",
        timeout: float = 600,
    ) -> tuple[int, dict[str, str], bytes]:
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        headers = {"content-type": content_type} if body is not None else {}
        conn.request(method, path, body, headers)
        response = conn.getresponse()
        data = response.read()
        conn.close()
        return response.status, {k.lower(): v for k, v in response.getheaders()}, data

    def json(self, method: str, path: str, document=None):
        body = None if document is None else json.dumps(document).encode()
        status, headers, data = self.request(method, path, body)
        return status, headers, (json.loads(data) if data else None)


class Checks:
    def __init__(self, report_only: bool) -> None:
        self.report_only = report_only
        self.failed: list[str] = []
        self.passed = 0

    def check(self, what: str, ok: bool, figure: str) -> None:
        print(f"  {'ok  ' if ok else 'FAIL'} {what}: {figure}", flush=True)
        if ok:
            self.passed += 1
        else:
            self.failed.append(what)
