#!/usr/bin/env bash
# Checks the `rust-version` of Cargo.toml against what the code and its dependency tree
# really need:
#  1. no dependency resolved for this platform declares a higher `rust-version`
#     (cargo metadata), so the declared minimum is not below the tree's;
#  2. the crate, its tests and benches build with exactly that toolchain (installed by
#     rustup, minimal profile, about 10 s and 60 MB), which also catches language features
#     newer than the declared version (clippy's `incompatible_msrv` catches only library
#     items).
# Environment: CARGO_TARGET_DIR (the MSRV build goes to its `msrv/` subfolder).
set -euo pipefail
cd "$(dirname "$0")/.."

declared="$(sed -n 's/^rust-version = "\(.*\)"$/\1/p' Cargo.toml)"
[ -n "$declared" ] || { echo "Cargo.toml has no rust-version" >&2; exit 1; }
host="$(rustc -vV | sed -n 's/^host: //p')"

cargo metadata --format-version 1 --locked --filter-platform "$host" |
    python3 -c '
import json, sys
declared = sys.argv[1]
def version(v):
    return tuple(int(x) for x in v.split("."))[:3] + (0,) * (3 - len(v.split(".")))
meta = json.load(sys.stdin)
ours = set(meta["workspace_members"])
resolved = {node["id"] for node in meta["resolve"]["nodes"]} - ours
needs = sorted(
    ((version(p["rust_version"]), p["name"], p["version"]) for p in meta["packages"]
     if p["id"] in resolved and p.get("rust_version")),
    reverse=True)
top = needs[0]
print("== the dependency tree needs Rust %s (%s %s); Cargo.toml declares %s"
      % (".".join(map(str, top[0])), top[1], top[2], declared))
if version(declared) < top[0]:
    sys.exit("rust-version %s is below what %s %s declares" % (declared, top[1], top[2]))
' "$declared"

toolchain="$declared"
[[ "$toolchain" =~ ^[0-9]+\.[0-9]+$ ]] && toolchain="$toolchain.0"
echo "== building with Rust $toolchain"
rustup toolchain install "$toolchain" --profile minimal --no-self-update >/dev/null
CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target}/msrv" cargo "+$toolchain" check --all-targets --locked --quiet
echo "== Rust $toolchain builds the crate, its tests and benches"
