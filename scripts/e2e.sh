#!/usr/bin/env bash
# End-to-end test of the results page (static/: index.html, its ES modules and the vendored
# uPlot) in headless Chromium: Debian's chromium (installed with apt-get when
# /usr/bin/chromium is missing; needs root), driven by playwright-core from tests/e2e (npm
# ci). Starts the release binary on a free loopback port with a temporary data directory,
# serving static/ from disk (--static-dir), runs tests/e2e/page.test.mjs against it (which
# also writes docs/screenshots/*.png), and stops the server. Exits non-zero on failure.
# That the binary's built-in copies are these files, byte for byte and with their content
# types, is tests/http.rs's to check.
#
# Environment: TRIBOSIM_BIN (a built binary; default: cargo build --release),
# E2E_GRID and E2E_CYCLES (the test run's grid and cycles, default 128 and 3600, tests/e2e/lib.mjs),
# SCREENSHOT_DIR (default docs/screenshots).
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$(pwd)"

if [ ! -x /usr/bin/chromium ]; then
    echo "== installing Debian's chromium"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi

echo "== npm ci in tests/e2e"
(cd tests/e2e && npm ci --no-audit --no-fund --loglevel=error)

if [ -z "${TRIBOSIM_BIN:-}" ]; then
    cargo build --release --quiet --bin tribosim
    TRIBOSIM_BIN="$(realpath -m "${CARGO_TARGET_DIR:-target}")/release/tribosim"
fi

source scripts/lib/server.sh
start_server --static-dir "$repo/static" --workers 1
echo "== the page test against $base"

status=0
(cd tests/e2e && TRIBOSIM_URL="$base" SCREENSHOT_DIR="${SCREENSHOT_DIR:-$repo/docs/screenshots}" node page.test.mjs) || status=$?

status="$(server_status "$status")"
[ "$status" = 0 ] || tail -n 30 "$work/server.log" >&2
exit "$status"
