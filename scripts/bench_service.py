#!/usr/bin/env python3
"""Service benchmark (its latency and throughput targets), against a running `tribosim serve`.

    cargo build --release && ./target/release/tribosim serve --data-dir "$(mktemp -d)" &
    python3 scripts/bench_service.py [--base http://127.0.0.1:8080]

Prints: submit-to-first-event latency with an idle worker (median and max of 20 jobs),
whether 50 concurrent event-stream clients on one job each received every cycle and the
final status, and the round trip of GET /api/v1/jobs/{id} (median of 200, one kept-alive
connection). Standard library only.
"""

import argparse
import http.client
import json
import statistics
import threading
import time
import urllib.parse

SMALL = {
    "preset": "dalmau2018-316l",
    "overrides": {"numerics": {"grid": 32}, "test": {"cycles": 20}},
}
LONGER = {
    "preset": "dalmau2018-316l",
    "overrides": {"numerics": {"grid": 64, "cycle_step": 1}, "test": {"cycles": 100}},
}


def connect(base):
    url = urllib.parse.urlparse(base)
    return http.client.HTTPConnection(url.hostname, url.port or 80, timeout=600)


def submit(base, scene):
    conn = connect(base)
    conn.request("POST", "/api/v1/jobs", json.dumps(scene), {"content-type": "application/json"})
    response = conn.getresponse()
    body = json.loads(response.read())
    conn.close()
    if response.status != 202:
        raise SystemExit(f"submit: {response.status} {body}")
    return body["id"]


def events(base, job_id, first_only=False):
    """Reads the event stream; returns (cycle ids seen, final status, time of first event)."""
    conn = connect(base)
    conn.request("GET", f"/api/v1/jobs/{job_id}/events", headers={"accept": "text/event-stream"})
    response = conn.getresponse()
    cycles, status, first_at, kind = [], None, None, None
    while True:
        line = response.readline()
        if not line:
            break
        line = line.decode().rstrip("\n")
        if line.startswith("event:"):
            kind = line.split(":", 1)[1].strip()
        elif line.startswith("data:") and kind == "cycle":
            first_at = first_at or time.perf_counter()
            cycles.append(json.loads(line[5:])["cycle"])
            if first_only:
                break
        elif line.startswith("data:") and kind == "status":
            status = json.loads(line[5:])["status"]
            break
    conn.close()
    return cycles, status, first_at


def wait_final(base, job_id):
    conn = connect(base)
    while True:
        conn.request("GET", f"/api/v1/jobs/{job_id}")
        job = json.loads(conn.getresponse().read())
        if job["status"] in ("succeeded", "failed", "cancelled"):
            conn.close()
            return job
        time.sleep(0.05)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--base", default="http://127.0.0.1:8080")
    base = parser.parse_args().base

    latencies = []
    for _ in range(20):
        start = time.perf_counter()
        job_id = submit(base, SMALL)
        _, _, first_at = events(base, job_id, first_only=True)
        latencies.append(first_at - start)
        wait_final(base, job_id)
    print(
        f"submit to first event (idle worker, 20 jobs): median "
        f"{statistics.median(latencies) * 1e3:.1f} ms, max {max(latencies) * 1e3:.1f} ms"
    )

    job_id = submit(base, LONGER)
    results = [None] * 50

    def follow(k):
        results[k] = events(base, job_id)

    threads = [threading.Thread(target=follow, args=(k,)) for k in range(50)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    final = wait_final(base, job_id)
    complete = sum(
        1
        for cycles, status, _ in results
        if status == final["status"]
        and cycles == sorted(set(cycles))
        and len(cycles) == len(results[0][0])
    )
    print(
        f"50 event-stream clients on one job: {complete} of 50 got all "
        f"{len(results[0][0])} cycle events and the final status ({final['status']})"
    )

    conn = connect(base)
    times = []
    for _ in range(200):
        start = time.perf_counter()
        conn.request("GET", f"/api/v1/jobs/{job_id}")
        conn.getresponse().read()
        times.append(time.perf_counter() - start)
    conn.close()
    print(
        f"GET /api/v1/jobs/{{id}} round trip (200, keep-alive): median "
        f"{statistics.median(times) * 1e6:.0f} us"
    )


if __name__ == "__main__":
    main()
