#!/usr/bin/env bash
# The Python client (clients/python): installs it with its extras into a virtualenv (PyPI),
# checks its style (ruff) and types (mypy --strict), runs its tests against the release
# binary (each test server on a free loopback port with a temporary data directory), then
# executes the example notebook against a server started here. The executed notebook is
# kept in $CARGO_TARGET_DIR/python-client/ to look at.
#
# Environment: TRIBOSIM_BIN (a built binary; default: cargo build --release),
# CARGO_TARGET_DIR (where the virtualenv is kept).
set -euo pipefail
cd "$(dirname "$0")/.."

repo="$(pwd)"
target_dir="$(realpath -m "${CARGO_TARGET_DIR:-target}")"
venv="$target_dir/python-client-venv"
out="$target_dir/python-client"

if [ -z "${TRIBOSIM_BIN:-}" ]; then
    cargo build --release --quiet --bin tribosim
    TRIBOSIM_BIN="$target_dir/release/tribosim"
fi
export TRIBOSIM_BIN

[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
echo "== installing clients/python[pandas,progress,plot,test] into $venv"
"$venv/bin/pip" install --quiet --disable-pip-version-check \
    --constraint clients/python/ci-constraints.txt "./clients/python[pandas,progress,plot,test]"

echo "== ruff and mypy --strict"
(cd clients/python && "$venv/bin/ruff" format --check --quiet src tests \
    && "$venv/bin/ruff" check --quiet src tests && "$venv/bin/mypy" src)
echo "== ruff on scripts/, in the client's style"
"$venv/bin/ruff" format --config clients/python/pyproject.toml --check --quiet scripts
"$venv/bin/ruff" check --config clients/python/pyproject.toml --quiet scripts

echo "== pytest clients/python/tests against $TRIBOSIM_BIN"
"$venv/bin/python" -m pytest -q -p no:cacheprovider clients/python/tests

source scripts/lib/server.sh
start_server --workers 2
echo "== executing clients/python/examples/paper_and_study.ipynb against $base"
mkdir -p "$out"
started="$(date +%s)"
TRIBOSIM_URL="$base" "$venv/bin/python" - "$repo/clients/python/examples/paper_and_study.ipynb" \
    "$out/paper_and_study.ipynb" <<'EOF'
import sys
from pathlib import Path

import nbclient
import nbformat

source, executed = Path(sys.argv[1]), Path(sys.argv[2])
notebook = nbformat.read(source, as_version=4)
# Run in the notebook's folder, as for a person opening it there; a failing cell raises.
# (The kernel's warning about unencrypted TCP concerns its loopback sockets.)
nbclient.NotebookClient(
    notebook, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(source.parent)}}
).execute()
nbformat.write(notebook, executed)
EOF
echo "== notebook executed in $(( $(date +%s) - started )) s; written to $out/paper_and_study.ipynb"
exit "$(server_status 0)"
