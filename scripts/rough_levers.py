#!/usr/bin/env python3
"""The speed levers of a rough-disc wear run, as speed against error, written into
docs/accuracy.md ("## Rough wear: speed levers").

Runs the 4 um cut-off rough disc of issue 29 (rms 0.1 um, Hurst 0.8, cut-offs 4 and 50 um,
seed 1) over 600 cycles with each lever, the smooth disc of the same scene as the time
baseline, and both with every cycle solved as the references of the errors. Then the rough
example of docs/scene.md (2 um short cut-off) over its first 40 cycles, with the defaults,
and the rough disc solved every cycle over 150 cycles at its Archard k and at four times it
(how stiff the wear update is at the scale of the cells, and that the implicit update holds).
Each time is a ratio to the smooth auto run of the same invocation, so the machine's speed
cancels.

Usage: scripts/rough_levers.py [--bin target/release/tribosim] [--markdown docs/accuracy.md]
(about 6 minutes on 2 cores). Standard library only.
"""

import argparse
import datetime
import json
import math
import os
import subprocess
import sys
import tempfile

HEADING = "## Rough wear: speed levers"
CYCLES = 600
SURFACE = {
    "kind": "synthetic",
    "rms_height_um": 0.1,
    "hurst": 0.8,
    "short_cutoff_um": 4,
    "long_cutoff_um": 50,
    "seed": 1,
}
# The smooth disc's default numerics, spelled out: on a rough disc `auto` solves every
# cycle at 1e-4 (`scripts/rough_default.py`), and these runs measure the steps at the
# smooth disc's bound and tolerance.
AUTO = {"cycle_step": "auto", "cycle_step_bound": 0.01, "tolerance": 1e-6}
# (label, rough, numerics); the first rough and smooth entries with cycle_step 1 are the
# references, the smooth auto run the time baseline.
RUNS = [
    ("smooth, auto (baseline)", False, {}),
    ("smooth, every cycle (reference)", False, {"cycle_step": 1}),
    ("rough, every cycle (reference)", True, {"cycle_step": 1, "tolerance": 1e-6}),
    ("rough, auto, bound 0.01 (the smooth disc's default)", True, AUTO),
    ("rough, auto, bound 0.02", True, dict(AUTO, cycle_step_bound=0.02)),
    ("rough, auto, bound 0.05", True, dict(AUTO, cycle_step_bound=0.05)),
    ("rough, auto, bound 0.1", True, dict(AUTO, cycle_step_bound=0.1)),
    ("rough, auto, 2 threads", True, dict(AUTO, threads=2)),
    ("rough, auto, tolerance 1e-5", True, dict(AUTO, tolerance=1e-5)),
]
# The rough example of docs/scene.md, over the cycles its solves are hardest.
DOCS_EXAMPLE = {
    "disc": {"surface": dict(SURFACE, short_cutoff_um=2)},
    "corrosion": {"anodic_area": "bem_contact"},
    "test": {"cycles": 40},
}
# The wear update's stiffness: the rough disc solved every cycle at the run's Archard k and
# at STIFF_K_FACTOR times it, measured from the cycle after the run-in to the last.
STIFFNESS_CYCLES = (51, 150)
STIFF_K_FACTOR = 4
# The yield cut's share of the growth is measured from this cycle on: past the first
# cycles' yield groove.
YIELD_CUT_FROM = 100
OUTPUTS = [
    ("wear_volume_mm3", "volume"),
    ("max_depth_um", "depth"),
    ("wac_volume_mm3", "WAC"),
    ("potential_v", "E"),
]


def run(binary, label, rough, numerics, workdir):
    scene = {"test": {"cycles": CYCLES}}
    if rough:
        scene["disc"] = {"surface": SURFACE}
    if numerics:
        scene["numerics"] = numerics
    return label, rough, numerics, run_scene(binary, scene, workdir)


def run_scene(binary, scene, workdir, extra=()):
    """Runs `scene` (with the further `tribosim run` arguments `extra`) and reads its result."""
    path = os.path.join(workdir, f"{len(os.listdir(workdir))}.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    out = path + ".out"
    command = [binary, "run", path, "-o", out, *extra]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    with open(out) as f:
        return json.load(f)


def profile_error(result, reference):
    """L1 difference of the last profiles, relative to the reference's, on its rows."""
    last = max(p["cycle"] for p in reference["profiles"])
    prof = {p["cycle"]: p for p in result["profiles"]}[last]
    ref = {p["cycle"]: p for p in reference["profiles"]}[last]
    ys, ds = prof["y_um"], prof["depth_um"]

    def at(y):
        if y <= ys[0] or y >= ys[-1]:
            return 0.0
        i = next(k for k in range(1, len(ys)) if ys[k] >= y)
        w = (y - ys[i - 1]) / (ys[i] - ys[i - 1])
        return ds[i - 1] * (1 - w) + ds[i] * w

    diff = sum(abs(at(y) - d) for y, d in zip(ref["y_um"], ref["depth_um"]))
    return diff / sum(abs(d) for d in ref["depth_um"])


def table(rows):
    base = rows[0][3]["summary"]["wall_s"]
    refs = {rough: r for (_, rough, n, r) in rows if n.get("cycle_step") == 1}
    head = (
        "| run | solves | iterations a solve | time / smooth auto | "
        + " | ".join(f"{name} error" for _, name in OUTPUTS)
        + " | profile L1 error | yield cut / every cycle's |"
    )
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for label, rough, _numerics, r in rows:
        s, ref = r["summary"], refs[rough]["summary"]
        errors = [f"{(s[k] - ref[k]) / abs(ref[k]):+.1e}" for k, _ in OUTPUTS]
        cut = yield_cut_mm3(r, refs[rough]) / yield_cut_mm3(refs[rough], refs[rough])
        lines.append(
            f"| {label} | {s['solves']} | {s['iterations'] / s['solves']:.1f} | "
            f"{s['wall_s'] / base:.1f} | "
            + " | ".join(errors)
            + f" | {profile_error(r, refs[rough]):.1e} | {cut:.3f} |"
        )
    return "\n".join(lines)


def yield_cut_mm3(result, reference, first=0):
    """The volume the yield cut (eq. 13) took after cycle `first` of `result`'s run: its
    groove's growth less Archard's passes, k F s / H(n) each at the hardness of every cycle,
    read from `reference` (the same scene solved every cycle). The rest of the groove is
    Archard's whatever the pressure's shape, so the cut is all a cycle step can change of
    the volume. For the scenes here: one k, fitted on the total loss (the groove is then the
    total, `docs/result.md`)."""
    test = reference["scene"]["test"]
    per_pass = (
        reference["summary"]["archard_k"] * test["load_n"] * 2 * math.pi * test["track_radius_mm"]
    )
    archard = sum(per_pass / c["hardness_mpa"] for c in reference["cycles"] if c["cycle"] > first)
    grown = growth_mm3(result, first) if first else result["summary"]["wear_volume_mm3"]
    return grown - archard


def breakdown(rows):
    """Where the rough disc's time goes against the smooth one's, from the rows."""
    by = {label: r["summary"] for label, _, _, r in rows}
    smooth, smooth_every = by[RUNS[0][0]], by[RUNS[1][0]]
    rough_every, rough = by[RUNS[2][0]], by[RUNS[3][0]]

    def per_iteration(s):
        return s["wall_s"] / s["iterations"]

    return (
        f"Every cycle solved, an iteration of the rough disc costs "
        f"{per_iteration(rough_every) / per_iteration(smooth_every):.1f} times the smooth "
        f"disc's (its cells: 8 across the 4 um cut-off against 44 across the contact radius), "
        f"and a solve takes {rough_every['iterations'] / rough_every['solves']:.1f} iterations "
        f"against {smooth_every['iterations'] / smooth_every['solves']:.1f}. Cycle steps save the "
        f"smooth disc {smooth_every['wall_s'] / smooth['wall_s']:.1f} times its time and the "
        f"rough one {rough_every['wall_s'] / rough['wall_s']:.1f} times: on the rough disc the "
        f"per-pass wear moves by 0.4 to 0.9% a cycle at the rim of the track (below), and "
        f"longer steps (the larger bounds) cost the errors the table shows. Not in the table, "
        f"because each is the default: a rough disc's solve starts from the last pressure "
        f"(8% fewer iterations than the extrapolation over 600 cycles, `src/simulation/warm.rs`), "
        f"the load is restored by a shift, which let the 0.05 and 0.1 bounds run at all "
        f"(`src/contact/solver/bounds.rs`), a solve on the whole grid keeps its conjugacy "
        f"through steps that move under 5% of its free cells off the direction "
        f"(`src/contact/solver/progress.rs`), a warm start is judged for a stall from its "
        f"second step on, once the bounds it carried over are rebuilt (the same file), and "
        f"after a stall of the free-set correction the next solves start on the whole grid "
        f"(`src/simulation/run/stalls.rs`). Two more defaults, measured once on this disc with "
        f"a build that switched each off (a scene cannot), in one invocation whose default "
        f"runs took 28.4 and 21.8 s: solving on a window around the last contact (its "
        f"bounding box plus 3%, 45% of the grid's cells on average, checked on the 72% that "
        f"could touch; `src/contact/window.rs`) against the whole grid, 57.2 s for 5111 "
        f"iterations against 5117, with the same results to three digits; and the last "
        f"pressure as the start against a coarse-to-fine start on every solve "
        f"(`src/contact/coarse.rs`, the first solve's), which took 17.1 iterations a solve "
        f"against 9.7, and 66.5 s."
    )


def docs_example(result, rows):
    """The docs' 2 um example: its cost against the smooth baseline, and how it stalled."""
    s, base = result["summary"], rows[0][3]["summary"]
    window = next(m["reason"] for m in result["models"] if m["name"] == "solve_window")
    stalls = window.split("; ", 1)[1] if "; " in window else "no stall"
    return (
        f"The rough example of `docs/scene.md` (2 um short cut-off, `bem_contact`), its first "
        f"{s['cycles']} cycles with the defaults: {s['solves']} solves, "
        f"{s['iterations'] / s['solves']:.1f} iterations a solve, {s['wall_s']:.1f} s, "
        f"{s['wall_s'] / base['wall_s']:.1f} times the smooth disc's 600 cycles. Its contact is "
        f"nearly all at the cap on the plateaus yielding cuts, and its solves stalled: {stalls}."
    )


def effective_modulus_pa(scene):
    """E* of the pair, from the scene's ball and disc."""
    parts = (scene["ball"], scene["disc"])
    inverse = sum((1 - m["poisson_ratio"] ** 2) / (m["youngs_modulus_gpa"] * 1e9) for m in parts)
    return 1 / inverse


def stiffness(binary, workdir, smooth):
    """How the rough disc's contact moves from cycle to cycle, solved every cycle, at the
    run's k and at STIFF_K_FACTOR times it, where the explicit update would alternate."""
    first, last = STIFFNESS_CYCLES
    scene = {
        "test": {"cycles": last},
        "disc": {"surface": SURFACE},
        "numerics": {"cycle_step": 1},
    }
    runs = [run_scene(binary, scene, workdir)]
    k = runs[0]["summary"]["archard_k"]
    stiff = dict(scene, wear={"archard_k": STIFF_K_FACTOR * k})
    runs.append(run_scene(binary, stiff, workdir))
    corr = [
        [change_correlation(r, key, first) for r in runs]
        for key in ("contact_area_mm2", "plastic_area_mm2")
    ]
    # r = pi k l E* / (lambda H) at the grid's shortest wavelength, 2 cells, for l between
    # the rough contact's mean chord and the smooth contact's.
    end = runs[0]["cycles"][-1]
    dy = runs[0]["profiles"][-1]["y_um"][1] - runs[0]["profiles"][-1]["y_um"][0]
    e_star = effective_modulus_pa(runs[0]["scene"])
    chords = (end["contact_chord_um"], smooth["cycles"][-1]["contact_chord_um"])
    r = [math.pi * k * c * e_star / (2 * dy * end["hardness_mpa"] * 1e6) for c in chords]
    return (
        f"Why the rough disc's steps stay short, and why its wear update is implicit: the "
        f"update is stiff at the scale of the cells. A row raised by delta over a wavelength "
        f"lambda across the track carries pi E* delta / lambda more pressure, and one pass "
        f"removes k l / H of depth per unit of pressure over the chord l, so a pass changes "
        f"the row's excess by r = pi k l E* / (lambda H) of itself. With l from the rough "
        f"contact's mean chord ({chords[0]:.0f} um) to the smooth one's ({chords[1]:.0f} um), "
        f"E* {e_star / 1e9:.0f} GPa and H {end['hardness_mpa'] / 1e3:.2f} GPa at cycle "
        f"{last}, r is {r[0]:.1f} to {r[1]:.1f} at the shortest wavelength of the {dy:.2f} um "
        f"cells (2 cells), and about twice that on the 2 um example's cells of half the "
        f"size (the estimate is a row in full contact; a row carried by a few small contact "
        f"spots is stiffer). The paper's update wears the surface with the pressure solved "
        f"before the pass (forward Euler), which alternates and grows beyond r = 2. "
        f"Measured with it (commit 105fc15, before the implicit update): at {STIFF_K_FACTOR} "
        f"times k the consecutive changes of the contact area over cycles 11 to 60 "
        f"correlated at -0.89 and of the plastic area at -0.97; at the run's k, on the fixed "
        f"map of the next section, the run-in (plastic area above 5% of the first cycle's) "
        f"lasted to cycle 26 on 0.5 um cells, 45 on 0.33 um and 120 on 0.25 um, where the "
        f"volume at cycle 150 came out 5.6% above the 0.5 um cells' (the next section has "
        f"the implicit update's). So a rough disc's solve includes the wear of its own "
        f"step's passes (backward Euler, `src/contact/worn_rows.rs`): the excess shrinks "
        f"by 1 / (1 + r), stable at every r while a step is at most twice the last. Solved "
        f"every cycle over cycles {first} to {last}, consecutive changes of the contact "
        f"area now correlate at {corr[0][0]:+.2f} and of the plastic area at {corr[1][0]:+.2f}; at "
        f"{STIFF_K_FACTOR} times k ({STIFF_K_FACTOR * k:.3e}) at {corr[0][1]:+.2f} and "
        f"{corr[1][1]:+.2f}: the jitter of a series of independent changes (-0.5), not "
        f"the alternation (-1). On the 2 um example's finer "
        f"cells, where the explicit update oscillated most, the steps grew: its 3600 cycles "
        f"take 1614 solves and 26,157 iterations (`tribosim run`), against 2650 and 34,461 "
        f"with the explicit update at commit 105fc15."
    )


def short_steps(rows):
    """Why the rough disc's steps stay short past the oscillation: the rim of the track,
    and the yield cut that only a solve makes."""
    by = {label: r for label, _, _, r in rows}
    reference, smooth_reference = by[RUNS[2][0]], by[RUNS[1][0]]
    first = YIELD_CUT_FROM
    share, smooth_share = (
        yield_cut_mm3(r, r, first) / growth_mm3(r, first) for r in (reference, smooth_reference)
    )
    label = RUNS[5][0]
    stepped = by[label]
    solves = stepped["summary"]["solves"]
    cut = yield_cut_mm3(stepped, reference) / yield_cut_mm3(reference, reference)
    chord, wake = (
        mean_at_solves(stepped, reference, key, first)
        for key in ("contact_chord_um", "anodic_area_mm2")
    )
    return (
        f"Why this disc's steps stay short all the same: its per-pass wear profile moves by "
        f"0.4 to 0.9% a cycle, and the moves are the rim's. Measured once on this disc "
        f"solved every cycle, with a build that printed each solve's per-pass profile (a "
        f"result does not carry it): between cycles 300 and 560 the profile moved by 0.42% in "
        f"one cycle, 0.75% in 2, 1.26% in 4, 1.95% in 8 and 2.77% in 16 (about as the 0.6th "
        f"power of the cycles: neither a drift, which would be linear, nor noise, which would "
        f"not grow); consecutive changes were uncorrelated (+0.03); and 53% of a cycle's "
        f"change sat at rows carrying under 30% of the peak, at the edges of the track, where "
        f"it widens onto asperities not yet worn. The widening also yields: after cycle "
        f"{first}, the yield cut (the groove less Archard's passes, `yield_cut_mm3` in this "
        f"script) is {share:.1%} of the rough disc's growth, against {smooth_share:.1%} of the "
        f"smooth disc's. Only a solve cuts, so a step skips the cuts of its cycles, and the "
        f'next solve makes up for them only in part: the run "{label}" ({solves} solves) '
        f"cut {cut:.2f} times the volume cut solving every cycle (the table's last column), "
        f"which is its volume error. The shortfall is the flanks': measured once with a "
        f"build that wrote each row's cut, at cycle 600 two thirds of it lies in the rows "
        f"beyond 60 um from the track's centre, into which the track widened during the run "
        f"(its half-width, where the cut passes 1% of its peak, 65 um at cycle 43 and 96 um "
        f"at 600); there the stepped run's cut is 22 to 47% short, at 30 to 50 um 7 to 16%, "
        f"and within 30 um 0.4%. Its solves meet the uncut asperities: after cycle "
        f"{first}, its contacts' mean chord averaged {chord[0]:.1f} um against {chord[1]:.1f} "
        f"um at the same cycles solving every cycle, and its depassivated wake "
        f"{wake[0]:.3f} mm^2 against {wake[1]:.3f} mm^2, which lowers its potential and raises "
        f"its WAC (the table's errors). A step bound cannot tell this cut from "
        f"the profile's moves, and a cut that follows the skipped cycles does not mend it: "
        f"measured once with a build that lowered each row's truncation level through a step "
        f"at the rate it fell over the last interval (the solve's cut and the cuts predicted "
        f"before it), at bound 0.05: the rate as measured cut 1.55 times what solving every "
        f"cycle cut (+12% in volume, +82% in depth: rows at a flank cut into their valleys, "
        f"the deepest at -68 um 2.16 um deep against 0.49 um; leaving out rows first cut at "
        f"the last solve, +6.3% and +100%), half that rate -1.3% in volume, -3.1% in E and +1.1% "
        f"in WAC, the smaller of the last two intervals' rates +1.6%, +4.4% and -1.1%, and "
        f"the same at bound 0.1 (47 solves) -0.22%, -3.7% and +2.4%. The prediction "
        f"moves the volume's error across zero with its damping, a constant that would have "
        f"to be fitted, and leaves the potential's and the WAC's at 1 to 4%, where those "
        f"of the smooth disc's default are under 0.4%."
    )


def target(rows):
    """What ten times the smooth disc's time leaves the rough disc: how many solves, and the
    table's runs around that count."""
    by = {label: r["summary"] for label, _, _, r in rows}
    smooth, smooth_every, rough_every = (by[RUNS[i][0]] for i in (0, 1, 2))
    rough_solve_s = rough_every["wall_s"] / rough_every["solves"]
    per_solve = rough_solve_s / (smooth["wall_s"] / smooth["solves"])
    allowed = 10 * smooth["wall_s"] / rough_solve_s
    stepped = sorted(
        (s["solves"], label, s) for label, s in by.items() if label.startswith("rough, auto")
    )
    fewer = max(r for r in stepped if r[0] <= allowed)
    more = min(r for r in stepped if r[0] > allowed)

    def error(run):
        return run[2]["wear_volume_mm3"] / rough_every["wear_volume_mm3"] - 1

    smooth_error = smooth["wear_volume_mm3"] / smooth_every["wear_volume_mm3"] - 1
    return (
        f"This is why the target of ten times the smooth disc's time is out of reach of cycle "
        f"steps at the smooth disc's default error: one rough solve, every cycle solved, costs "
        f"{per_solve:.1f} times one of the smooth disc's auto run, so ten times its time "
        f"allows about {allowed:.0f} rough solves in {CYCLES} cycles, steps of "
        f"{CYCLES / allowed:.1f} cycles on average, as many solves as the smooth disc's "
        f'{smooth["solves"]}. The table\'s runs around that count: "{more[1]}" ({more[0]} '
        f'solves) errs by {error(more):+.1e} in volume and "{fewer[1]}" ({fewer[0]} '
        f"solves) by {error(fewer):+.1e}, where the smooth disc's auto run errs by "
        f"{smooth_error:+.1e}."
    )


def mean_at_solves(result, reference, key, first):
    """`key` averaged over `result`'s records after cycle `first`, and `reference`'s at the
    same cycles."""
    at = {c["cycle"]: c[key] for c in reference["cycles"]}
    cycles = [c for c in result["cycles"] if c["cycle"] > first]
    return (
        sum(c[key] for c in cycles) / len(cycles),
        sum(at[c["cycle"]] for c in cycles) / len(cycles),
    )


def growth_mm3(result, first):
    """The groove's growth after cycle `first`, from a run that recorded every cycle."""
    volumes = {c["cycle"]: c["wear_volume_mm3"] for c in result["cycles"]}
    return result["summary"]["wear_volume_mm3"] - volumes[first]


def change_correlation(result, key, first):
    """The mean correlation of consecutive changes of `key` over the cycles from `first`:
    negative when the quantity swings back and forth."""
    x = [c[key] for c in result["cycles"] if c["cycle"] >= first]
    d = [b - a for a, b in zip(x, x[1:])]
    pairs = list(zip(d, d[1:]))
    mean = [sum(p[i] for p in pairs) / len(pairs) for i in (0, 1)]
    cov = sum((a - mean[0]) * (b - mean[1]) for a, b in pairs)
    var = [sum((p[i] - mean[i]) ** 2 for p in pairs) for i in (0, 1)]
    return cov / math.sqrt(var[0] * var[1])


def section(rows, example, stiffness_text, binary):
    version = subprocess.run([binary, "--version"], capture_output=True, text=True).stdout
    when = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    surface = ", ".join(f"{k} {v}" for k, v in SURFACE.items() if k != "kind")
    return f"""{HEADING}

The paper's scene over {CYCLES} cycles on a smooth disc and on a synthetic rough one ({surface}),
each lever alone. Errors are relative to the same disc with every cycle solved; "time / smooth
auto" is the run's wall time over the smooth disc's with the defaults, in the same invocation.
Measured by `scripts/rough_levers.py --markdown docs/accuracy.md` on {when} ({os.cpu_count()}
cores, {version.strip()}); the machine may be shared with other work.

{table(rows)}

{breakdown(rows)}

{stiffness_text}

{short_steps(rows)}

{target(rows)}

{docs_example(example, rows)}
"""


def splice(text, body, heading=HEADING):
    """`text` with the section under `heading` replaced by `body`, or `body` inserted before
    the peers' sections when there is none yet."""
    start = text.find(f"\n{heading}\n")
    if start >= 0:
        end = text.find("\n## ", start + 1 + len(heading))
        end = len(text) if end < 0 else end + 1
        before, after = text[: start + 1], text[end:]
    else:
        peers = text.find("\n## Peers")
        before, after = (text, "") if peers < 0 else (text[: peers + 1], text[peers + 1 :])
    return before.rstrip() + "\n\n" + body.rstrip() + "\n\n" + after.lstrip()


def arguments(doc):
    """The command line both rough-wear scripts take: the binary, and the report to write."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--bin", default="target/release/tribosim")
    parser.add_argument("--markdown")
    return parser.parse_args()


def write_section(body, markdown, heading=HEADING):
    """Prints `body`, and splices it under `heading` into the report `markdown` if given."""
    print(body)
    if markdown:
        with open(markdown) as f:
            text = f.read()
        with open(markdown, "w") as f:
            f.write(splice(text, body, heading).rstrip() + "\n")


def main():
    args = arguments(__doc__)
    with tempfile.TemporaryDirectory() as workdir:
        rows = []
        for label, rough, numerics in RUNS:
            rows.append(run(args.bin, label, rough, numerics, workdir))
            print(f"{label}: {rows[-1][3]['summary']['wall_s']:.1f} s", file=sys.stderr)
        stiffness_text = stiffness(args.bin, workdir, rows[0][3])
        example = run_scene(args.bin, DOCS_EXAMPLE, workdir)
    write_section(section(rows, example, stiffness_text, args.bin), args.markdown)


if __name__ == "__main__":
    main()
