#!/usr/bin/env python3
"""Speed against error of the reciprocating rig's numerics (docs/rig-accuracy.md, "The
reciprocating rig").

Runs one reciprocating scene at several grids and cycle-step settings with the release
binary, and compares each run's wear volume, deepest point, the depth across the track's
middle and along its axis, and the mean potential with the finest run (the reference:
every cycle solved, at the densest grid listed). Times are the runs' own `summary.wall_s`
and their ratio to the reference's, measured in this one script.

    python3 scripts/stroke_accuracy.py --bin target/release/tribosim --cycles 20 \
        --grids 24 32 48 64 96 144
"""

import argparse
import json
import subprocess
import sys
import tempfile


def run(binary: str, scene: dict) -> dict:
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(scene, f)
        path = f.name
    out = path + ".out.json"
    done = subprocess.run([binary, "run", path, "-o", out], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{binary} run failed on {json.dumps(scene)}:\n{done.stderr}")
    with open(out) as f:
        return json.load(f)


def relative(got: float, want: float) -> float:
    return (got - want) / want if want else float("nan")


def profile_error(got_x, got_d, want_x, want_d) -> float:
    """The largest difference of two depth profiles on their own abscissae, linearly
    interpolated onto the reference's, relative to the reference's deepest point."""

    def at(x):
        if x <= got_x[0] or x >= got_x[-1]:
            return 0.0
        lo, hi = 0, len(got_x) - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if got_x[mid] <= x:
                lo = mid
            else:
                hi = mid
        w = (x - got_x[lo]) / (got_x[hi] - got_x[lo])
        return (1 - w) * got_d[lo] + w * got_d[hi]

    deepest = max(want_d)
    return max(abs(at(x) - d) for x, d in zip(want_x, want_d)) / deepest


def scene(cycles: int, stroke_mm: float, grid, step: str) -> dict:
    return {
        "name": f"stroke-{grid}-{step}",
        "test": {"cycles": cycles, "reciprocating": {"stroke_mm": stroke_mm}},
        "numerics": {"grid": grid, "cycle_step": 1 if step == "every_cycle" else step},
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", default="target/release/tribosim")
    parser.add_argument("--cycles", type=int, default=20)
    parser.add_argument("--stroke-mm", type=float, default=2.0)
    parser.add_argument("--grids", nargs="+", default=["32", "48", "64", "96"])
    parser.add_argument("--steps", nargs="+", default=["auto"])
    args = parser.parse_args()
    grids = [g if g == "auto" else int(g) for g in args.grids]
    reference = run(args.bin, scene(args.cycles, args.stroke_mm, grids[-1], "every_cycle"))
    ref_s = reference["summary"]
    ref_mid = reference["profiles"][-1]
    ref_axis = reference["stroke"]["axial_profile"]
    print(
        f"reference: grid {grids[-1]}, every cycle, {ref_s['wall_s']:.1f} s, "
        f"{ref_s['solves']} solves, volume {ref_s['wear_volume_mm3']:.4e} mm^3"
    )
    print(
        "| grid | step | wall s | x reference | solves | volume | deepest | middle "
        "profile | axial profile | E mean |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for grid in grids:
        for step in args.steps:
            r = run(args.bin, scene(args.cycles, args.stroke_mm, grid, step))
            s = r["summary"]
            mid = r["profiles"][-1]
            axis = r["stroke"]["axial_profile"]
            e = s.get("potential_v")
            e_err = (e - ref_s["potential_v"]) * 1e3 if e is not None else float("nan")
            across = profile_error(
                mid["y_um"], mid["depth_um"], ref_mid["y_um"], ref_mid["depth_um"]
            )
            along = profile_error(
                axis["x_um"], axis["depth_um"], ref_axis["x_um"], ref_axis["depth_um"]
            )
            print(
                f"| {grid} | {step} | {s['wall_s']:.1f} | {s['wall_s'] / ref_s['wall_s']:.3f} "
                f"| {s['solves']} "
                f"| {relative(s['wear_volume_mm3'], ref_s['wear_volume_mm3']):+.1e} "
                f"| {relative(s['max_depth_um'], ref_s['max_depth_um']):+.1e} "
                f"| {across:.1e} | {along:.1e} "
                f"| {e_err:+.2f} mV |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
