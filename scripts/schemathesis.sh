#!/usr/bin/env bash
# Fuzzes the live server from openapi.yaml with schemathesis (PyPI): every operation gets
# generated requests, and the run fails on any 5xx, any status code, content type, header
# or body that openapi.yaml does not describe. Starts the release binary on a free loopback
# port with a temporary data directory and stops it afterwards; a crashed or panicking
# server fails the run too.
#
# Environment: TRIBOSIM_BIN (a built binary; default: cargo build --release),
# SCHEMATHESIS_MAX_EXAMPLES (default 100 per operation), CARGO_TARGET_DIR (where the
# virtualenv is kept).
set -euo pipefail
cd "$(dirname "$0")/.."

repo="$(pwd)"
target_dir="$(realpath -m "${CARGO_TARGET_DIR:-target}")"
venv="$target_dir/schemathesis-venv"
version="4.32.5"
if [ "$("$venv/bin/schemathesis" --version 2>/dev/null)" != "schemathesis, version $version" ]; then
    echo "== installing schemathesis $version into $venv"
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check "schemathesis==$version"
fi

if [ -z "${TRIBOSIM_BIN:-}" ]; then
    cargo build --release --quiet --bin tribosim
    TRIBOSIM_BIN="$target_dir/release/tribosim"
fi

work="$(mktemp -d)"
server_pid=""
cleanup() {
    if [ -n "$server_pid" ]; then
        kill -TERM "$server_pid" 2>/dev/null || true
        wait "$server_pid" 2>/dev/null || true
    fi
    rm -rf "$work"
}
trap cleanup EXIT

# Port 0: the kernel picks a free port, and the server logs the one it got. One worker and
# a small queue: generated scenes can be valid and long, and must not starve the machine.
"$TRIBOSIM_BIN" serve --addr 127.0.0.1:0 --data-dir "$work/data" --workers 1 \
    --queue-capacity 4 2>"$work/server.log" &
server_pid=$!
base=""
for _ in $(seq 600); do
    base="$(grep -o 'serving on http://[0-9.:]*' "$work/server.log" | head -n1 | cut -d' ' -f3 || true)"
    [ -n "$base" ] && break
    kill -0 "$server_pid" 2>/dev/null || { cat "$work/server.log"; echo "server exited" >&2; exit 1; }
    sleep 0.1
done
[ -n "$base" ] || { cat "$work/server.log"; echo "server did not start" >&2; exit 1; }
echo "== schemathesis against $base"

# The event stream is left out: on a generated job it stays open until the job ends, which
# schemathesis reports as a timeout. tests/service.rs covers it.
# Run from the temporary directory, where schemathesis leaves its cache.
status=0
(cd "$work" && "$venv/bin/schemathesis" run "$repo/openapi.yaml" \
    --url "$base" \
    --checks not_a_server_error,status_code_conformance,content_type_conformance,response_headers_conformance,response_schema_conformance \
    --exclude-path '/api/v1/jobs/{id}/events' \
    --max-examples "${SCHEMATHESIS_MAX_EXAMPLES:-100}" \
    --workers 1 \
    --request-timeout 30 \
    --suppress-health-check too_slow \
    --seed 1) \
    || status=$?

if ! kill -0 "$server_pid" 2>/dev/null; then
    echo "the server died during the run" >&2
    status=1
fi
if grep -q "panicked" "$work/server.log"; then
    grep -B2 -A5 "panicked" "$work/server.log" >&2
    status=1
fi
echo "== server: $(grep -c "finished processing request" "$work/server.log") requests; statuses: $(grep -o "status=[0-9][0-9]*" "$work/server.log" | sort | uniq -c | tr -s " \n" " ")"
exit "$status"
