#!/usr/bin/env bash
# Our contact solver beside Tamaas and ContactMechanics: makes a venv with the
# public PyPI packages under target/peers-venv if missing, builds the release binary, then
# runs scripts/peers.py, which prints the tables and rewrites docs/peers.md: the smooth
# Hertz and capped cases, then the rough cases on the very same height arrays
# (scripts/peers_rough.py; the peers at N = 2048 take minutes each).
# Usage: scripts/peers.sh [peers.py options, e.g. --sizes 64 128 --reps 5, --only rough]
# Run it on an otherwise idle machine: the times are the point. The smooth cases take about
# half an hour, most of it Tamaas's KatoSaturated on the capped case (thousands of
# iterations) and both peers on Hertz at N = 2048; the rough ones about 25 minutes, most of
# it the peers at N = 2048.
set -euo pipefail
cd "$(dirname "$0")/.."

venv=target/peers-venv
# The versions whose conventions scripts/peers.py documents.
packages=(tamaas==2.9.0 contactmechanics==1.8.3 numpy)
if ! "$venv/bin/python" -c 'import tamaas, ContactMechanics, numpy' 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --upgrade pip
    "$venv/bin/pip" install --quiet "${packages[@]}"
fi

cargo build --release --quiet
exec "$venv/bin/python" scripts/peers.py --binary "${CARGO_TARGET_DIR:-target}/release/tribosim" "$@"
