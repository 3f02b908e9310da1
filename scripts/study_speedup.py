#!/usr/bin/env python3
"""Wall time of a study on the service with 1 and with 2 workers, in one sitting.

For each worker count: starts `tribosim serve` on a free loopback port with a fresh data
directory, POSTs the study, polls it until every member has ended, and prints the wall
time from the POST to the last member's end (the summary's `wall_s`), the CPU time the
server used, and the load average. The runs alternate (1, 2, 1, 2, ...) so that a change
in the machine's load falls on both.

    python3 scripts/study_speedup.py [--bin target/release/tribosim]
        [--study scenes/study-12.json] [--repeat 2]
"""

import argparse
import json
import os
import re
import subprocess
import tempfile
import threading
import time
import urllib.request


def request(method, url, body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(url, data=data, method=method)
    if data is not None:
        req.add_header("Content-Type", "application/json")
    with urllib.request.urlopen(req, timeout=60) as response:
        return json.load(response)


def run(binary, study, workers):
    with tempfile.TemporaryDirectory() as data:
        server = subprocess.Popen(
            [
                binary,
                "serve",
                "--addr",
                "127.0.0.1:0",
                "--data-dir",
                data,
                "--workers",
                str(workers),
                "--queue-capacity",
                "64",
            ],
            stderr=subprocess.PIPE,
            text=True,
            env={**os.environ, "RUST_LOG": "info"},
        )
        try:
            for line in server.stderr:
                found = re.search(r"serving on (http://\S+)", line)
                if found:
                    base = found.group(1)
                    break
            # The log must be read to its end, or the server blocks once the pipe is full.
            threading.Thread(target=server.stderr.read, daemon=True).start()
            started = time.monotonic()
            record = request("POST", f"{base}/api/v1/studies", study)
            while record["status"] in ("queued", "running"):
                time.sleep(0.05)
                record = request("GET", f"{base}/api/v1/studies/{record['id']}")
            polled = time.monotonic() - started
            summary = request("GET", f"{base}/api/v1/studies/{record['id']}/summary")
            with open(f"/proc/{server.pid}/stat") as stat:
                fields = stat.read().rsplit(")", 1)[1].split()
            cpu_s = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
        finally:
            server.terminate()
            server.wait()
    return record["status"], summary["wall_s"], polled, cpu_s


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bin", default="target/release/tribosim")
    parser.add_argument("--study", default="scenes/study-12.json")
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    with open(args.study) as f:
        study = json.load(f)
    walls = {1: [], 2: []}
    for _ in range(args.repeat):
        for workers in (1, 2):
            load = os.getloadavg()[0]
            status, wall, polled, cpu = run(args.bin, study, workers)
            walls[workers].append(wall)
            print(
                f"workers {workers}: {status}, wall {wall:.2f} s (polled {polled:.2f} s), "
                f"server CPU {cpu:.2f} s, load average {load:.1f}",
                flush=True,
            )
    one, two = min(walls[1]), min(walls[2])
    print(
        f"best of {args.repeat}: 1 worker {one:.2f} s, 2 workers {two:.2f} s, "
        f"speed-up {one / two:.2f}"
    )


if __name__ == "__main__":
    main()
