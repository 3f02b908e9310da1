#!/usr/bin/env python3
"""Two builds of tribosim on the rough disc of `scripts/rough_default.py`: the CPU time of
build B over build A's, as the median of alternating pairs (A, B, A, B, ...), with the
iterations and the results' differences, to measure one change to the solver.

Usage: scripts/rough_ab.py A_BIN B_BIN [--pairs 3] [--numerics JSON] [--cycles N]
(a pair takes about 80 s at the defaults). Standard library only.
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
    args = parser.parse_args()
    the_scene = scene(True, json.loads(args.numerics))
    if args.cycles:
        the_scene["test"]["cycles"] = args.cycles
    ratios, runs = [], {}
    with tempfile.TemporaryDirectory() as workdir:
        for _ in range(args.pairs):
            pair = {}
            for name, binary in (("a", args.a), ("b", args.b)):
                result, cpu = timed_run(binary, the_scene, workdir)
                pair[name] = cpu
                runs[name] = result["summary"]
            ratios.append(pair["b"] / pair["a"])
            print(json.dumps({"cpu_s": pair, "b/a": pair["b"] / pair["a"]}), flush=True)
    a, b = runs["a"], runs["b"]
    print(f"B / A CPU: median {statistics.median(ratios):.3f} of {[round(r, 3) for r in ratios]}")
    print(
        f"iterations: A {a['iterations']} in {a['solves']} solves, "
        f"B {b['iterations']} in {b['solves']} solves"
    )
    for key, name, _ in OUTPUTS:
        change = (b[key] - a[key]) / abs(a[key])
        print(f"{name}: A {a[key]:.6e}, B {b[key]:.6e}, relative {change:+.1e}")


if __name__ == "__main__":
    main()
