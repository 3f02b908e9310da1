#!/usr/bin/env python3
"""The rough disc's default numerics, chosen by speed against error: each candidate's cost
and its errors, written into docs/accuracy.md ("## Rough wear: the default by speed
against error").

The disc is the 4 um cut-off rough disc of `scripts/rough_levers.py` (rms 0.1 um, Hurst
0.8, cut-offs 4 and 50 um, seed 1) over 600 cycles. Each candidate's errors are against
the same disc solved every cycle at tolerance 1e-8 (the reference, computed once and kept
in `--reference`, since it is the slowest run); its cost is the CPU time of `tribosim run`
(user plus system, of the child process) over the smooth disc's with the default numerics,
as the median of three pairs run alternately (smooth, rough, smooth, rough, ...), so the
machine's speed, which moves by tens of percent, cancels within each pair.

The targets (the issue that asked for this study): at most 20 times the smooth disc, with
errors within 1e-3 in volume and deepest point, 5e-3 in the WAC and 2 mV in E. A load
change of 2e-5 relative moves E by up to 1 mV and the WAC by up to 1e-3 (the floor of
`scripts/rough_seeds.py`; the issue's review measured 2 mV), so those two cannot be asked
closer than that of any candidate.

Usage: scripts/rough_default.py [--bin target/release/tribosim] [--reference FILE]
[--markdown docs/accuracy.md] [--only LABEL ...] (about 5 minutes on 2 cores with the
build of 2026-12-01, 3 more the first time, for the reference). Standard library only.
"""

import argparse
import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rough_levers import CYCLES, SURFACE, write_section  # noqa: E402  (the same disc, one definition)

HEADING = "## Rough wear: the default by speed against error"
PAIRS = 3
REFERENCE = {"cycle_step": 1, "tolerance": 1e-8}
# (label, numerics of the rough run), spelled out, since `auto` on a rough disc is itself
# the choice this study makes. `cycle_step: auto` solves every cycle of a rough disc, so
# every candidate does; automatic steps were measured before that (`choice`).
CANDIDATES = [
    ("every cycle, 1e-6 (the smooth disc's tolerance)", {"cycle_step": 1, "tolerance": 1e-6}),
    ("every cycle, 1e-5", {"cycle_step": 1, "tolerance": 1e-5}),
    ("every cycle, 1e-4 (the rough disc's default)", {"cycle_step": 1, "tolerance": 1e-4}),
    ("every cycle, 1e-3", {"cycle_step": 1, "tolerance": 1e-3}),
]
# (summary key, name, how its error is written): relative for the volumes and the depth,
# in mV for the potential.
OUTPUTS = [
    ("wear_volume_mm3", "volume", "relative"),
    ("max_depth_um", "deepest point", "relative"),
    ("wac_volume_mm3", "WAC", "relative"),
    ("potential_v", "E", "mV"),
]
TARGETS = {"volume": 1e-3, "deepest point": 1e-3, "WAC": 5e-3, "E": 2.0}
MOST_TIMES_SMOOTH = 20.0


def scene(rough, numerics):
    out = {"test": {"cycles": CYCLES}}
    if rough:
        out["disc"] = {"surface": SURFACE}
    if numerics:
        out["numerics"] = numerics
    return out


def timed_run(binary, the_scene, workdir):
    """Runs the scene; its result and the child's CPU time, s."""
    path = os.path.join(workdir, f"{len(os.listdir(workdir))}.json")
    with open(path, "w") as f:
        json.dump(the_scene, f)
    out = path + ".out"
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        [binary, "run", path, "-o", out],
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(out) as f:
        result = json.load(f)
    os.remove(out)
    return result, cpu


def errors(summary, reference):
    row = {}
    for key, name, kind in OUTPUTS:
        value, ref = summary[key], reference[key]
        row[name] = (value - ref) * 1e3 if kind == "mV" else (value - ref) / abs(ref)
    return row


def measure(binary, label, numerics, reference, workdir):
    ratios, cpus, result = [], [], None
    for _ in range(PAIRS):
        _, smooth_cpu = timed_run(binary, scene(False, {}), workdir)
        result, rough_cpu = timed_run(binary, scene(True, numerics), workdir)
        ratios.append(rough_cpu / smooth_cpu)
        cpus.append((smooth_cpu, rough_cpu))
    s = result["summary"]
    window = next(m["reason"] for m in result["models"] if m["name"] == "solve_window")
    fallbacks = (
        int(re.search(r"fell back to the whole grid in (\d+) of", window).group(1))
        if "fell back" in window
        else 0
    )
    restarts = (
        int(re.search(r"uniform pressure in (\d+) of", window).group(1))
        if "uniform pressure in" in window
        else 0
    )
    row = {
        "label": label,
        "numerics": numerics,
        "ratio": statistics.median(ratios),
        "ratios": ratios,
        "cpu_s": cpus,
        "solves": s["solves"],
        "iterations": s["iterations"],
        "fallbacks": fallbacks,
        "restarts": restarts,
        "errors": errors(s, reference["summary"]),
    }
    print(json.dumps(row), flush=True)
    return row


def verdict(row):
    misses = [name for name, limit in TARGETS.items() if abs(row["errors"][name]) > limit]
    if row["ratio"] > MOST_TIMES_SMOOTH:
        misses.append("time")
    return "meets both" if not misses else "misses " + ", ".join(misses)


def table(rows):
    head = (
        "| candidate | solves | iterations a solve | fallbacks / restarts | "
        "CPU / smooth (median of 3 pairs) | CPU s, rough (smooth) | "
        + " | ".join(f"{name} error" for _, name, _ in OUTPUTS)
        + " | against the targets |"
    )
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for row in rows:
        e = row["errors"]
        cells = [
            f"{e[name]:+.1e}" if kind == "relative" else f"{e[name]:+.2f} mV"
            for _, name, kind in OUTPUTS
        ]
        lines.append(
            f"| {row['label']} | {row['solves']} | {row['iterations'] / row['solves']:.2f} | "
            f"{row['fallbacks']} / {row['restarts']} | "
            f"{row['ratio']:.1f} ({', '.join(f'{r:.1f}' for r in row['ratios'])}) | "
            f"{', '.join(f'{r:.1f} ({m:.2f})' for m, r in row.get('cpu_s') or [])} | "
            + " | ".join(cells)
            + f" | {verdict(row)} |"
        )
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bin", default="target/release/tribosim")
    parser.add_argument(
        "--reference",
        default="docs/accuracy/rough-4um-600-reference.json",
        help="the every-cycle 1e-8 run's summary, written the first time",
    )
    parser.add_argument("--markdown")
    parser.add_argument("--only", nargs="*", help="candidates' labels to run (all if absent)")
    parser.add_argument(
        "--rows",
        help="write the table from these rows (the JSON lines a run printed) instead of running",
    )
    args = parser.parse_args()
    if args.rows:
        with open(args.rows) as f:
            rows = [json.loads(line) for line in f if line.startswith("{")]
        finish(args, rows)
        return
    with tempfile.TemporaryDirectory() as workdir:
        if os.path.exists(args.reference):
            with open(args.reference) as f:
                reference = json.load(f)
        else:
            result, cpu = timed_run(args.bin, scene(True, REFERENCE), workdir)
            reference = {"scene": result["scene"], "summary": result["summary"], "cpu_s": cpu}
            with open(args.reference, "w") as f:
                json.dump(reference, f, indent=1)
        rows = [
            measure(args.bin, label, numerics, reference, workdir)
            for label, numerics in CANDIDATES
            if not args.only or label in args.only
        ]
    finish(args, rows)


def choice(rows):
    """The paragraph under the table: what the default is and why, from the rows."""
    chosen = next(r for r in rows if "rough disc's default" in r["label"])
    before = next(r for r in rows if "smooth disc's tolerance" in r["label"])
    within = [r for r in rows if verdict(r) in ("meets both", "misses time")]
    fewest = min(within, key=lambda r: r["iterations"])
    e = chosen["errors"]
    return (
        f'The rough disc\'s default is "{chosen["label"].split(" (")[0]}": '
        f"`numerics.tolerance: auto` is 1e-4 on a rough disc (1e-6 on a smooth one), and "
        f"`cycle_step: auto` solves every cycle of a rough disc. It took "
        f"{chosen['iterations']} iterations against {before['iterations']} at the smooth "
        f"disc's tolerance, and its errors ({e['volume']:+.1e} in volume, {e['WAC']:+.1e} in "
        f"the WAC, {e['E']:+.2f} mV in E) sit at the floor the WAC and E have (a load change "
        f"of 2e-5 moves E by up to 1 mV and the WAC by up to 1e-3, the next section's floor) "
        f'and far below the grid\'s own error, 2 to 5% ("Rough wear: grid and cut-off"). '
        f"Of the candidates within the error targets, "
        f'the one with the fewest iterations is "{fewest["label"]}" '
        f"({fewest['iterations']}). From a tolerance of 1e-4 on, the contact's transforms "
        f"compute in single precision (the `precision` model), whose round-off stays under "
        f"1/100 of it: at 1e-4 that took 0.746 of the CPU time of double precision "
        f'("Rough wear: single precision"); in double precision (commit c54b2e9) this row '
        f"read 32.3 times the smooth disc.\n\n"
        f"Automatic steps, as a smooth disc takes them, were measured by this script before "
        f"`auto` stopped stepping on a rough disc (commit a9546d2, the same reference): at "
        f"1e-5 (the default then) 522 solves, 4230 iterations, 36.6 times the smooth disc "
        f"(36.6, 35.9, 36.9), errors -2.3e-4 in volume, -1.3e-4 in the deepest point, "
        f"-3.2e-3 in the WAC and -1.57 mV in E; every cycle at 1e-4 in the same invocation "
        f"32.3 times (33.0, 31.2, 32.3), 0.88 of it, with the errors its row had then (-7.2e-5 "
        f"in volume, +1.0e-5 in the deepest point, -3.9e-3 in the WAC, -1.06 mV in E, before "
        f"the cap release was damped); and at "
        f"1e-4, 521 solves erred by -1.8e-3 in volume, beyond the target. A step skips the "
        f'yield cuts of its cycles ("Rough wear: speed levers"), which costs more accuracy '
        f"than the 13% fewer solves save time. Iterations are the measure that does not move "
        f"with the machine: the CPU ratios spread by tens of percent between pairs, as each "
        f'pair\'s ratio in brackets shows. {time_target(rows)} ("fallbacks / restarts" '
        f"counts the solves whose free-set preconditioner stalled and whose warm start began "
        f'again from the uniform pressure; "Rough wear: where the time goes" for the shares).\n'
    )


def time_target(rows):
    """The sentence on the time target, from the verdicts of `rows`."""
    meeting = [r["label"] for r in rows if verdict(r) == "meets both"]
    if not meeting:
        return (
            "No candidate within the error targets meets the time target: a rough solve "
            "costs several smooth ones, since its cells are four times smaller and its "
            "contact churns at the cap"
        )
    names = ", ".join(f'"{label}"' for label in meeting)
    return (
        f"Within the error targets, {names} also meets the time target, by the median of "
        f"its pairs; a rough solve still costs several smooth ones, since its cells are four "
        f"times smaller and its contact churns at the cap"
    )


def finish(args, rows):
    """Prints the section of `rows` and writes it into the markdown file, if asked."""
    text = (
        f"{HEADING}\n\n"
        f"Written by `scripts/rough_default.py` on {datetime.date.today()}: the 4 um cut-off "
        f"rough disc over {CYCLES} cycles, errors against the same disc solved every cycle "
        f"at tolerance 1e-8 (`{args.reference}`), costs as CPU time over the smooth disc's "
        f"with the default numerics, the median of {PAIRS} alternating pairs (each pair's "
        f"ratio in brackets). Targets: at most {MOST_TIMES_SMOOTH:g} times the smooth disc; "
        f"errors within {TARGETS['volume']:g} in volume and deepest point, "
        f"{TARGETS['WAC']:g} in the WAC, {TARGETS['E']:g} mV in E.\n\n" + table(rows)
    )
    # The paragraph compares the candidates: only a run of them all writes it and the
    # section (`--only` prints its rows alone).
    if len(rows) < len(CANDIDATES):
        print(text)
        if args.markdown:
            sys.exit("--markdown needs every candidate: leave out --only")
        return
    text += "\n\n" + choice(rows)
    write_section(text, args.markdown, HEADING)


if __name__ == "__main__":
    main()
