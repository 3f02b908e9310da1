#!/usr/bin/env bash
# The paper's 3600-cycle scene timed against an earlier commit in one run: builds the
# commit in a worktree under target/ (its own target directory, so the current build is
# untouched), then runs the two binaries alternately and prints each one's CPU seconds
# (minimum and median; the run is single-threaded, and CPU time moves less than wall time
# under other work on the machine) and the ratio of the medians. This machine's speed
# varies by tens of percent from day to day: a ratio measured in one run is what compares.
# Usage: scripts/speedup.sh [COMMIT (default 954fd23, main when the speed targets were
# set)] [RUNS (default 5)] [SCENE (default scenes/dalmau2018.json)]
set -euo pipefail
cd "$(dirname "$0")/.."

base=${1:-954fd23}
runs=${2:-5}
scene=${3:-scenes/dalmau2018.json}
tree=target/speedup-worktree
target=${CARGO_TARGET_DIR:-target}

cargo build --release --quiet
if [ ! -d "$tree" ]; then
    git worktree add --detach "$tree" "$base" > /dev/null
fi
git -C "$tree" checkout --quiet --detach "$base"
(cd "$tree" && CARGO_TARGET_DIR=../speedup-target cargo build --release --quiet --bin tribosim)

current=$target/release/tribosim
earlier=target/speedup-target/release/tribosim
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for _ in $(seq "$runs"); do
    for label in earlier current; do
        binary=$earlier
        [ "$label" = current ] && binary=$current
        /usr/bin/time -f "$label %U %e" "$binary" run "$scene" -o "$out/result.json" \
            2>&1 > /dev/null | tail -n 1
        python3 -c 'import json, sys; s = json.load(open(sys.argv[1]))["summary"]; print("volume", sys.argv[2], s["wear_volume_mm3"], s["max_depth_um"])' \
            "$out/result.json" "$label"
    done
done | python3 -c '
import statistics, sys
cpu, result = {}, {}
for line in sys.stdin:
    words = line.split()
    if words[0] == "volume":
        result[words[1]] = (float(words[2]), float(words[3]))
    else:
        cpu.setdefault(words[0], []).append(float(words[1]))
for label in ("earlier", "current"):
    v = cpu[label]
    print(f"{label}: CPU min {min(v):.2f} s, median {statistics.median(v):.2f} s over {len(v)} runs; "
          f"volume {result[label][0]:.10g} mm3, depth {result[label][1]:.6g} um")
ratio = statistics.median(cpu["earlier"]) / statistics.median(cpu["current"])
minima = min(cpu["earlier"]) / min(cpu["current"])
print(f"speedup (ratio of the medians): {ratio:.2f}; of the minima: {minima:.2f}")
'
