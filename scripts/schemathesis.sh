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

source scripts/lib/server.sh
# One worker and a small queue: generated scenes can be valid and long, and must not
# starve the machine.
start_server --workers 1 --queue-capacity 4
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

status="$(server_status "$status")"
echo "== server: $(grep -c "finished processing request" "$work/server.log") requests; statuses: $(grep -o "status=[0-9][0-9]*" "$work/server.log" | sort | uniq -c | tr -s " \n" " ")"
exit "$status"
