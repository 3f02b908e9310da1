#!/usr/bin/env python3
"""Two builds of tribosim on the rough disc of `scripts/rough_default.py`, or on a scene
file: the CPU and wall times of build B over build A's, as the medians of alternating pairs
(A, B, A, B, ...), with the iterations and the results' differences, to measure one change
to the solver.

Usage: scripts/rough_ab.py A_BIN B_BIN [--pairs 3] [--numerics JSON] [--cycles N]
[--scene FILE] (a pair takes about 25 s at the defaults). Standard library only.
"""

import argparse
import json
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rough_default import OUTPUTS, scene, timed_run  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--pairs", type=int, default=3)
    parser.add_argument("--numerics", default="{}", help="the rough run's numerics, JSON")
    parser.add_argument("--cycles", type=int)
    parser.add_argument("--scene", help="a scene file to run instead of the rough disc")
    args = parser.parse_args()
    if args.scene:
        with open(args.scene, encoding="utf-8") as file:
            the_scene = json.load(file)
        the_scene.setdefault("test", {})
        the_scene.setdefault("numerics", {}).update(json.loads(args.numerics))
    else:
        the_scene = scene(True, json.loads(args.numerics))
    if args.cycles:
        the_scene["test"]["cycles"] = args.cycles
    ratios, walls, runs = [], [], {}
    with tempfile.TemporaryDirectory() as workdir:
        for _ in range(args.pairs):
            pair, wall = {}, {}
            for name, binary in (("a", args.a), ("b", args.b)):
                result, cpu = timed_run(binary, the_scene, workdir)
                pair[name] = cpu
                wall[name] = result["summary"]["wall_s"]
                runs[name] = result["summary"]
            ratios.append(pair["b"] / pair["a"])
            walls.append(wall["b"] / wall["a"])
            line = {"cpu_s": pair, "b/a": ratios[-1], "wall_s": wall, "wall b/a": walls[-1]}
            print(json.dumps(line), flush=True)
    a, b = runs["a"], runs["b"]
    print(f"B / A CPU: median {statistics.median(ratios):.3f} of {[round(r, 3) for r in ratios]}")
    print(f"B / A wall: median {statistics.median(walls):.3f} of {[round(r, 3) for r in walls]}")
    print(
        f"iterations: A {a['iterations']} in {a['solves']} solves, "
        f"B {b['iterations']} in {b['solves']} solves"
    )
    for key, name, _ in OUTPUTS:
        change = (b[key] - a[key]) / abs(a[key])
        print(f"{name}: A {a[key]:.6e}, B {b[key]:.6e}, relative {change:+.1e}")


if __name__ == "__main__":
    main()
