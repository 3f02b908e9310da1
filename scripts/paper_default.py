#!/usr/bin/env python3
"""The default scene `{}` against the paper, and its corrosion numbers against grid.

Prints the two markdown tables of docs/accuracy.md's section "The default scene against
Table 3": the wear volume at Table 3's five times (the scene records those cycles exactly),
and the final potential and WAC volume at several grids against the finest.

    python3 scripts/paper_default.py [path/to/tribosim]   (default target/release/tribosim)
"""

import json
import subprocess
import sys

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/tribosim"
# Table 3: rubbing time (s, = cycles at 60 rpm) -> measured volume and spread, 1e-3 mm^3.
TABLE3 = {10: (0.97, 2.0), 60: (1.09, 0.1), 300: (1.18, 0.0), 1800: (5.33, 0.7), 3600: (11.72, 0.2)}
GRIDS = [48, 64, 96, 144, 192]


def run(scene):
    out = subprocess.run(
        [BIN, "run", "-"], input=json.dumps(scene), capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout)


def table3():
    result = run({})
    at = {r["cycle"]: r for r in result["cycles"]}
    print(
        f"`{{}}` with k = {result['summary']['archard_k']:.4e} "
        f"({result['summary']['solves']} solves, {result['summary']['wall_s']:.1f} s):\n"
    )
    print("| time (s) | Table 3 volume (1e-3 mm^3) | model (1e-3 mm^3) | model - measured |")
    print("|---|---|---|---|")
    for cycle, (measured, spread) in TABLE3.items():
        model = at[cycle]["wear_volume_mm3"] * 1e3
        print(
            f"| {cycle} | {measured} ± {spread} | {model:.3f} | {model - measured:+.3f} "
            f"({(model - measured) / measured:+.1%}) |"
        )


def grid_study():
    rows = []
    for cells in GRIDS:
        s = run({"numerics": {"grid": cells}})["summary"]
        rows.append(
            (cells, s["potential_v"], s["wac_volume_mm3"], s["wear_volume_mm3"], s["wall_s"])
        )
    ref = rows[-1]
    print(f"\nAgainst the finest grid ({ref[0]} cells per side):\n")
    print(
        "| grid | final potential (V vs Ag/AgCl) | error (mV) | WAC (mm^3) | relative error "
        "| wear volume error | wall (s) |"
    )
    print("|---|---|---|---|---|---|---|")
    for cells, pot, wac, vol, wall in rows:
        print(
            f"| {cells} | {pot:.4f} | {1e3 * (pot - ref[1]):+.2f} | {wac:.4e} | "
            f"{(wac - ref[2]) / ref[2]:+.2e} | {(vol - ref[3]) / ref[3]:+.2e} | {wall:.1f} |"
        )


if __name__ == "__main__":
    table3()
    grid_study()
