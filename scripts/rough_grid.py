#!/usr/bin/env python3
"""The grid and short cut-off study of a rough-disc wear run, written into
docs/accuracy.md ("## Rough wear: grid and cut-off").

One seeded self-affine surface (Hurst 0.8, long cut-off 50 um, random phases of seed 1) is
made once on a 192 um periodic square of 0.125 um pixels and given to `tribosim run` as a
measured map, so every grid samples the very same heights (a synthetic surface's phases
depend on its grid). The grid study runs the map band-limited at a 4 um short cut-off
(rms 0.1 um, the disc of "Rough wear: speed levers") on grids of 4 to 16 cells across that
cut-off; the cut-off study runs the same spectrum cut at 8, 4 and 2 um, each on 8 cells
across its cut-off (the simulation's rule). Each run is the paper's scene over 150 cycles,
every cycle solved, with `bem_contact`, on a fixed 192 um square. Times are ratios to the
8-cell grid's run of the same invocation.

Usage: scripts/rough_grid.py [--bin target/release/tribosim] [--markdown docs/accuracy.md]
(about 10 minutes on 2 cores). Needs numpy.
"""

import datetime
import os
import subprocess
import sys
import tempfile

import numpy as np
from rough_levers import arguments, profile_error, run_scene, write_section, yield_cut_mm3

HEADING = "## Rough wear: grid and cut-off"
SIDE_UM = 192.0
PIXEL_UM = 0.125
CYCLES = 150
HURST = 0.8
LONG_CUTOFF_UM = 50.0
SEED = 1
# The cut-off whose band has the rms height below; the others keep its amplitudes.
REFERENCE_CUTOFF_UM = 4.0
RMS_HEIGHT_UM = 0.1
GRID_CELLS_PER_CUTOFF = [4, 6, 8, 12, 16]
CUTOFFS_UM = [8.0, 4.0, 2.0]
# The share of the first cycle's plastic area below which the run-in has ended.
RUN_IN_SHARE = 0.05
# The cut after this cycle is the one the groove makes past its first yield groove.
LATE_CUT_FROM = 10
OUTPUTS = [
    ("wear_volume_mm3", "volume", "mm^3"),
    ("max_depth_um", "depth", "um"),
    ("wac_volume_mm3", "WAC", "mm^3"),
]


def spectrum(short_um):
    """The seeded Fourier amplitudes between the cut-offs, C(q) ~ q^-2(1+H), on the pixels
    of the square (the same phases for every cut-off)."""
    n = round(SIDE_UM / PIXEL_UM)
    q = 2 * np.pi * np.fft.fftfreq(n, d=PIXEL_UM)
    qn = np.hypot(*np.meshgrid(q, q))
    phase = np.random.default_rng(SEED).uniform(0, 2 * np.pi, (n, n))
    band = (qn >= 2 * np.pi / LONG_CUTOFF_UM) & (qn <= 2 * np.pi / short_um) & (qn > 0)
    amplitude = np.where(band, np.where(qn > 0, qn, 1.0) ** -(1 + HURST), 0.0)
    return np.fft.ifft2(amplitude * np.exp(1j * phase)).real


def write_map(short_um, workdir):
    """The map cut at `short_um`, in m, scaled as the reference band; its path, rms height
    and rms slope (um, -)."""
    scale = RMS_HEIGHT_UM / spectrum(REFERENCE_CUTOFF_UM).std()
    heights = spectrum(short_um) * scale
    gy, gx = np.gradient(heights, PIXEL_UM)
    path = os.path.join(workdir, f"map-{short_um:g}um.txt")
    np.savetxt(path, heights * 1e-6, fmt="%.6e")
    return path, heights.std(), float(np.sqrt(np.mean(gx**2 + gy**2)))


def run(binary, surface, cells_per_cutoff, short_um, workdir):
    cells = round(SIDE_UM / short_um * cells_per_cutoff)
    scene = {
        "test": {"cycles": CYCLES},
        "corrosion": {"anodic_area": "bem_contact"},
        "numerics": {"grid": cells, "domain_um": SIDE_UM, "cycle_step": 1},
    }
    extra = ["--surface", surface, "--pixel-um", str(PIXEL_UM)]
    return run_scene(binary, scene, workdir, extra)


def yielding_ends(result):
    """The first cycle whose plastic area is under RUN_IN_SHARE of the first cycle's: the end
    of the run-in (fresh asperities at the widening track's edges keep a few cells capped)."""
    first = result["cycles"][0]["plastic_area_mm2"]
    ends = (c["cycle"] for c in result["cycles"] if c["plastic_area_mm2"] < RUN_IN_SHARE * first)
    return next(ends, "none")


def table(rows, reference, base):
    head = (
        "| run | cells | cell um | iterations a solve | time / 8 cells | run-in ends | "
        + " | ".join(f"{name} {unit}" for _, name, unit in OUTPUTS)
        + " | "
        + " | ".join(f"{name} error" for _, name, _ in OUTPUTS)
        + " | profile L1 error |"
    )
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for label, r in rows:
        s, ref = r["summary"], reference["summary"]
        grid = next(m["reason"] for m in r["models"] if m["name"] == "grid").split(" cells")[0]
        cell = SIDE_UM / int(grid.split(" x ")[0])
        values = [f"{s[k]:.4g}" for k, _, _ in OUTPUTS]
        errors = [f"{(s[k] - ref[k]) / abs(ref[k]):+.1e}" for k, _, _ in OUTPUTS]
        if r is reference:
            errors = ["reference"] * len(OUTPUTS)
        lines.append(
            f"| {label} | {grid} | {cell:.3f} | {s['iterations'] / s['solves']:.1f} | "
            f"{s['wall_s'] / base:.2f} | {yielding_ends(r)} | "
            + " | ".join(values)
            + " | "
            + " | ".join(errors)
            + f" | {profile_error(r, reference):.1e} |"
        )
    return "\n".join(lines)


def extrapolation(grid_rows):
    """Richardson's extrapolation of the volume to zero cells from the two finest grids, at
    first order (the errors of the table fall about linearly with the cell), as words."""
    by = dict(grid_rows)
    fine, finer = by["12 cells per cut-off"]["summary"], by["16 cells per cut-off"]["summary"]
    rule = by["8 cells per cut-off"]["summary"]
    v12, v16, v8 = (s["wear_volume_mm3"] for s in (fine, finer, rule))
    # Every run solves every cycle, so each is its own reference for the cut.
    runs = [by[f"{cells} cells per cut-off"] for cells in (8, 16)]
    cut8, cut16 = (yield_cut_mm3(r, r) for r in runs)
    first8, first16 = (yield_cut_mm3(r, r) - yield_cut_mm3(r, r, 1) for r in runs)
    late8, late16 = (yield_cut_mm3(r, r, LATE_CUT_FROM) for r in runs)
    # Cells of 1/12 and 1/16 of the cut-off: V(0) = V16 + (V16 - V12) h16 / (h12 - h16).
    limit = v16 + (v16 - v12) * (1 / 16) / (1 / 12 - 1 / 16)
    return (
        f"The volume rises with the cells at about first order in the cell size; extrapolated "
        f"so from 12 and 16 cells, its limit lies {limit / v16 - 1:.1%} above 16 cells and "
        f"{limit / v8 - 1:.1%} above the rule's 8. The difference is all the yield cut's "
        f"(eq. 13; the groove less Archard's passes, `yield_cut_mm3` in "
        f"`scripts/rough_levers.py`): Archard's part, {v16 - cut16:.4e} mm^3 on 16 cells and "
        f"{v8 - cut8:.4e} mm^3 on 8, does not depend on the grid, and the cut on 8 cells, "
        f"{cut8:.4e} mm^3, is {cut8 / cut16 - 1:+.1%} against 16 cells'. It is not the "
        f"first contact's: the cut of cycle 1 differs by {first8 / first16 - 1:+.1%}, and the "
        f"cut after cycle {LATE_CUT_FROM} by {late8 / late16 - 1:+.1%}. The grid decides how much "
        f"the groove yields cycle after cycle, past the first cycles' yield groove."
    )


def centre_line(grid_rows):
    """Where the grid's late cut is made: the contact's centre line, measured once with a
    build that wrote each solve's capped cells (a result does not carry them); and the
    volumes' difference at the end of the run-in and at the end of the run, from this
    invocation's runs."""
    by = dict(grid_rows)
    coarse, fine = by["8 cells per cut-off"], by["16 cells per cut-off"]
    end = yielding_ends(fine)

    def difference(cycle):
        volumes = [
            next(c["wear_volume_mm3"] for c in r["cycles"] if c["cycle"] == cycle)
            for r in (coarse, fine)
        ]
        return volumes[0] - volumes[1], volumes[0] / volumes[1] - 1

    if not isinstance(end, int):
        sys.exit(f"the 16-cell run's run-in did not end within its {CYCLES} cycles")
    at_end, at_last = difference(end), difference(CYCLES)
    return (
        f"Where the cut after cycle {LATE_CUT_FROM} differs, measured once on this map over "
        f"30 cycles with a build that wrote each solve's capped cells (a result does not carry "
        f"them): in the track's middle 50 um, every row is cut to the level of its cell on "
        f"the contact's centre line (|x| under 0.5 um, on a plateau of the earlier cuts), the "
        f"most pressed of the row. That cell's interpenetration, averaged over the rows, falls "
        f"by 17 to 19% a cycle: from 3.9 nm at cycle 10 to 0.49 nm at cycle 20 on 8 cells, "
        f"from 4.3 to 0.70 nm on 16, and below 0.12 nm from cycle 25 on both. Summed over "
        f"cycles 11 to 30 it is 17.4% smaller on 8 cells and 6.6% smaller on 12 than on 16, "
        f"as the cut of those cycles is (about 15% on 8 cells). The finer cells press that "
        f"line harder by resolving the contact, not by sampling finer heights: on the 8-cell "
        f"grid's own heights, interpolated bilinearly onto 16 cells, the volume at cycle 30 "
        f"came 92% of the way from 8 cells' to 16 cells' on the map (5.525e-4 mm^3 against "
        f"5.350e-4 and 5.541e-4), and the centre line's interpenetration over cycles 11 to 30 "
        f"16.3% above 8 cells'. Nor is it where the cells sit on the centre line: 8 cells "
        f"with one on it (385 across) gave 5.352e-4 mm^3 at cycle 30. What the grid moves is "
        f"the band of each row that sits at the cap: at cycle 20 it spans 13.0 um along the "
        f"sliding direction on 8 cells and 14.7 um on 16. The pressure along that direction "
        f"is nearly flat at the cap there, so a small difference in the solved pressure moves "
        f"the band's ends by microns, and the interpenetration grows about as the band's "
        f"width squared (16 cells against 8: widths squared 1.29 times, interpenetrations "
        f"1.43 times). Most of the grid's error is made by the end of the run-in: the volume "
        f"on 8 cells differs from 16 cells' by {at_end[0]:.2e} mm^3 "
        f"({at_end[1]:+.1%}) at cycle {end}, the end of the run-in on 16 cells, and by "
        f"{at_last[0]:.2e} mm^3 ({at_last[1]:+.1%}) at cycle {CYCLES}. Past the run-in the "
        f"difference grows more slowly than Archard's part, which does not depend on the grid, "
        f"so the relative error shrinks: run once over 300 cycles, -3.45% at cycle 30, -2.34% "
        f"at 150 and -1.92% at 300."
    )


def section(grid_rows, cutoff_rows, maps, binary):
    version = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    base = dict(grid_rows)["8 cells per cut-off"]["summary"]["wall_s"]
    surfaces = "; ".join(
        f"cut at {cut:g} um: rms height {h:.4f} um, rms slope {s:.4f}" for cut, (h, s) in maps
    )
    return f"""{HEADING}

One seeded self-affine surface (Hurst {HURST}, long cut-off {LONG_CUTOFF_UM:g} um, seed {SEED}),
made once on a {SIDE_UM:g} um periodic square of {PIXEL_UM} um pixels and run as a measured
map, so that every grid samples the same heights: the paper's scene over {CYCLES} cycles,
every cycle solved, `bem_contact`, on a fixed {SIDE_UM:g} um square. "run-in ends" is the
first cycle whose plastic area is under {RUN_IN_SHARE:.0%} of the first cycle's. Measured by
`scripts/rough_grid.py --markdown docs/accuracy.md` on {when} ({os.cpu_count()} cores,
{version.strip()}).
Surfaces: {surfaces}.

The grid: the map cut at {REFERENCE_CUTOFF_UM:g} um on grids of 4 to 16 cells across the
cut-off (8 is the simulation's rule, `CELLS_PER_SHORT_WAVELENGTH`); errors against 16 cells.

{table(grid_rows, dict(grid_rows)["16 cells per cut-off"], base)}

{extrapolation(grid_rows)}

{centre_line(grid_rows)}

The short cut-off: the same spectrum cut at {", ".join(f"{c:g}" for c in CUTOFFS_UM)} um, each
on 8 cells across its cut-off; differences against the finest cut-off. These are different
surfaces, not a convergence: how much of the wear the finer roughness decides.

{table(cutoff_rows, cutoff_rows[-1][1], base)}
"""


def main():
    args = arguments(__doc__)
    with tempfile.TemporaryDirectory() as workdir:
        maps, paths = [], {}
        for cut in CUTOFFS_UM:
            path, rms, slope = write_map(cut, workdir)
            maps.append((cut, (rms, slope)))
            paths[cut] = path
        grid_rows = []
        for cells in GRID_CELLS_PER_CUTOFF:
            r = run(args.bin, paths[REFERENCE_CUTOFF_UM], cells, REFERENCE_CUTOFF_UM, workdir)
            grid_rows.append((f"{cells} cells per cut-off", r))
            print(f"{cells} cells: {r['summary']['wall_s']:.1f} s", file=sys.stderr)
        cutoff_rows = []
        for cut in CUTOFFS_UM:
            if cut == REFERENCE_CUTOFF_UM:
                r = dict(grid_rows)["8 cells per cut-off"]
            else:
                r = run(args.bin, paths[cut], 8, cut, workdir)
            cutoff_rows.append((f"cut-off {cut:g} um", r))
            print(f"cut-off {cut:g} um: {r['summary']['wall_s']:.1f} s", file=sys.stderr)
    body = section(grid_rows, cutoff_rows, maps, args.bin)
    write_section(body, args.markdown, HEADING)


if __name__ == "__main__":
    main()
