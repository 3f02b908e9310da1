"""The rough cases of scripts/peers.py: a rough flat pressed by a rigid flat on the periodic
elastic half-space, the very same height arrays given to tribosim, Tamaas and
ContactMechanics.

`tribosim bench rough --json --surfaces DIR` generates one seeded self-affine surface at
N = 2048, samples it on each grid of its study, solves each grid, writes each height array
to DIR as a text matrix in m (every height in the shortest form that reads back to the same
float) and prints its rows (`study` `rough_grid`). The peers read those files, so all
three solve the same discrete problem: the same heights, grid, E* and mean pressure.
Measures are computed the same way for all three from each answer's pressure and its own
operator's displacement: real contact area is the fraction of cells with p > 0, the
approach delta the mean of u + h over those cells (h the separation from the highest
point), the mean gap the mean of u + h - delta over all cells.
"""

import json
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

# The tolerance all three are given (ours is the contact study's, in every row).
TOLERANCE = 1e-8


def separation(heights):
    """The gap at zero approach: from the highest point down."""
    return heights.max() - heights


def rough_measures(pressure, displacement, heights):
    """Real area fraction, mean gap (m) and our stopping measure on any answer: the worst
    complementarity violation (|g| in contact, penetration outside) over max |u|."""
    h = separation(heights)
    contact = pressure > 0
    delta = float(np.mean((displacement + h)[contact]))
    gap = displacement + h - delta
    violation = np.where(contact, np.abs(gap), np.maximum(-gap, 0.0))
    return {
        "area_fraction": float(np.mean(contact)),
        "mean_gap_m": float(np.mean(gap)),
        "residual": float(violation.max() / np.abs(displacement).max()),
    }


class TamaasRough:
    """Tamaas: the periodic Westergaard operator (its default for a `basic_2d` model) with
    PolonskyKeerRey."""

    name = "Tamaas"
    criterion = (
        "its own error reaching 1e-8: |sum p g| / (sum p * std(h)), the complementarity of "
        "pressure and gap relative to the load times the surface's rms height. Solved in "
        "units of the square's side and E*; iterations from its log."
    )

    def __init__(self, captured_stderr, log_line):
        import tamaas

        self.tm = tamaas
        self.captured_stderr, self.log_line = captured_stderr, log_line
        tamaas.set_log_level(tamaas.LogLevel.info)

    def build(self, case):
        tm, n, side = self.tm, case["n"], case["side_m"]
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
        model.E, model.nu = 1.0, 0.0  # with nu = 0, E is the E* of the contact
        solver = tm.PolonskyKeerRey(model, case["heights"] / side, TOLERANCE)
        solver.max_iter = 100_000
        solver.dump_freq = solver.max_iter  # log the first and last iterations only
        return {"model": model, "solver": solver, "log": []}

    def solve(self, case, state):
        with self.captured_stderr() as log:
            state["solver"].solve(case["mean_pressure_pa"] / case["modulus_pa"])
        state["log"] = log

    def outcome(self, case, state):
        model = state["model"]
        p = np.array(model.traction)
        # The periodic operator takes fields with a component axis.
        u = np.zeros(p.shape + (1,))
        model.operators["Westergaard::neumann"](p[..., None].copy(), u)
        u = u[..., 0]
        steps = [int(m.group(1)) for m in map(self.log_line.match, state["log"]) if m]
        return p * case["modulus_pa"], u * case["side_m"], max(steps) if steps else None


class ContactMechanicsRough:
    """ContactMechanics: PeriodicFFTElasticHalfSpace with its Polonsky-Keer constrained
    conjugate gradients."""

    name = "ContactMechanics"
    criterion = (
        "all of: rms and max penetration < pentol = 1e-8 x the surface's rms height, largest "
        "change of u in the step < pentol, tensile force < forcetol = 1e-8 x mean pressure x "
        "cell area, relative change of the load and of the offset < thermotol = 1e-8. Forces "
        "are per cell; the load is the mean pressure times the square's area."
    )

    def __init__(self):
        from ContactMechanics import PeriodicFFTElasticHalfSpace
        from ContactMechanics.Optimization import constrained_conjugate_gradients

        self.half_space = PeriodicFFTElasticHalfSpace
        self.ccg = constrained_conjugate_gradients

    def build(self, case):
        n, side = case["n"], case["side_m"]
        return {"substrate": self.half_space((n, n), case["modulus_pa"], (side, side))}

    def solve(self, case, state):
        cell = case["pixel_m"] ** 2
        result = self.ccg(
            state["substrate"],
            case["heights"],
            external_force=case["mean_pressure_pa"] * case["side_m"] ** 2,
            pentol=TOLERANCE * float(np.std(case["heights"])),
            forcetol=TOLERANCE * case["mean_pressure_pa"] * cell,
            thermotol=TOLERANCE,
        )
        if not result.success:
            raise RuntimeError(f"ContactMechanics: {result.message}")
        state["result"] = result

    def outcome(self, case, state):
        result = state["result"]
        return result.jac / case["pixel_m"] ** 2, result.x, int(result.nit)


@dataclass
class Timing:
    """A solver's cold runs on one grid: the fields the smooth and rough tables share."""

    solver: str
    n: int
    wall_s: float | None = None
    solve_s: float | None = None
    runs: int | None = None
    cpu_per_wall: float | None = None
    iterations: int | None = None
    residual: float | None = None
    failure: str | None = None


@dataclass
class RoughMeasurement(Timing):
    area_fraction: float | None = None
    mean_gap_m: float | None = None


def timed_runs(out, build, solve, reps, budget_s):
    """Up to `reps` cold runs of `build()` then `solve(state)` (fewer once `budget_s` is
    spent): their median wall, solve and CPU share into `out`. The last state, or None with
    `out.failure` set when the peer raised (a peer's failure is a result to report)."""
    walls, solves, cpus, state = [], [], [], None
    try:
        while len(walls) < reps and sum(walls) < budget_s:
            cpu, start = time.process_time(), time.perf_counter()
            state = build()
            built = time.perf_counter()
            solve(state)
            end = time.perf_counter()
            walls.append(end - start)
            solves.append(end - built)
            cpus.append(time.process_time() - cpu)
    except Exception as error:  # a peer's failure is a result to report, not a crash
        out.failure = f"{type(error).__name__}: {error}"
        return None
    out.wall_s = statistics.median(walls)
    out.solve_s = statistics.median(solves)
    out.runs = len(walls)
    out.cpu_per_wall = sum(cpus) / sum(walls)
    return state


def ours_rough(binary, surfaces):
    """Our rows of `bench rough`, which also writes the height arrays to `surfaces`."""
    run = subprocess.run(
        [binary, "bench", "rough", "--json", "--surfaces", str(surfaces)],
        check=True,
        capture_output=True,
        text=True,
    )
    rows = [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]
    return {r["n"]: r for r in rows if r.get("study") == "rough_grid"}


def case_of(row):
    heights = np.loadtxt(row["surface_file"], comments="#")
    n = row["n"]
    if heights.shape != (n, n):
        raise ValueError(f"{row['surface_file']}: {heights.shape}, expected {n} x {n}")
    return {
        "n": n,
        "heights": heights,
        "pixel_m": row["pixel_m"],
        "side_m": n * row["pixel_m"],
        "modulus_pa": row["reduced_modulus_pa"],
        "mean_pressure_pa": row["mean_pressure_pa"],
    }


def our_rough(row):
    return RoughMeasurement(
        solver="tribosim",
        n=row["n"],
        wall_s=row["wall_s"],
        solve_s=row["solve_s"],
        runs=row["runs"],
        iterations=row["iterations"],
        area_fraction=row["area_fraction"],
        mean_gap_m=row["mean_gap_m"],
        residual=row["residual"],
    )


def beyond_cap(previous_s, cap_s):
    """Why a peer is not run on a grid, or None: four times its time on the grid below (an
    FFT solve's cost grows a little faster than the cell count) beyond `cap_s`."""
    if previous_s is None:
        return None
    expected_s = 4 * previous_s
    if expected_s <= cap_s:
        return None
    return f"not run: expected about {expected_s:.0f} s, beyond the {cap_s:g} s cap"


def measure_rough(peer, case, reps, budget_s, cap_s, previous_s):
    """Median over up to `reps` cold runs (fewer once `budget_s` is spent); not run at all
    when its time on the grid below, `previous_s`, says it would take beyond `cap_s`."""
    out = RoughMeasurement(peer.name, case["n"])
    out.failure = beyond_cap(previous_s, cap_s)
    if out.failure:
        return out
    state = timed_runs(
        out, lambda: peer.build(case), lambda st: peer.solve(case, st), reps, budget_s
    )
    if out.failure:
        return out
    p, u, iterations = peer.outcome(case, state)
    found = rough_measures(p, u, case["heights"])
    out.iterations = iterations
    out.area_fraction = found["area_fraction"]
    out.mean_gap_m = found["mean_gap_m"]
    out.residual = found["residual"]
    return out


def run_rough(args, peers):
    """Our rows, then each peer on each grid's array: {n: (ours, [peers])} and the rows."""
    print("running tribosim bench rough --json ...", file=sys.stderr)
    rows = ours_rough(args.binary, Path(args.surfaces))
    groups, last = {}, {p.name: None for p in peers}
    for n in args.rough_sizes:
        case = case_of(rows[n])
        found = []
        for peer in peers:
            print(f"rough N = {n}: {peer.name} ...", file=sys.stderr)
            m = measure_rough(peer, case, args.reps, args.budget, args.cap, last[peer.name])
            last[peer.name] = m.wall_s if m.wall_s is not None else float("inf")
            found.append(m)
        groups[n] = (our_rough(rows[n]), found)
    return groups, rows


def rough_table(groups):
    header = [
        "N",
        "solver",
        "iterations",
        "time s",
        "solve s",
        "peer / ours",
        "runs",
        "cpu / wall",
        "real area %",
        "mean gap um",
        "area vs ours",
        "gap vs ours",
        "residual (ours)",
    ]
    lines = []
    for n, (mine, peers) in groups.items():
        for m in [mine, *peers]:
            if m.failure:
                lines.append([str(n), m.solver, m.failure, *[""] * (len(header) - 3)])
                continue
            mark = m is mine
            lines.append(
                [
                    str(n),
                    m.solver,
                    "" if m.iterations is None else str(m.iterations),
                    f"{m.wall_s:.4g}",
                    f"{m.solve_s:.4g}",
                    "" if mark else f"{m.wall_s / mine.wall_s:.1f}",
                    "" if m.runs is None else str(m.runs),
                    "" if m.cpu_per_wall is None else f"{m.cpu_per_wall:.2f}",
                    f"{100 * m.area_fraction:.4f}",
                    f"{m.mean_gap_m * 1e6:.6f}",
                    "" if mark else f"{m.area_fraction / mine.area_fraction - 1:+.1e}",
                    "" if mark else f"{m.mean_gap_m / mine.mean_gap_m - 1:+.1e}",
                    f"{m.residual:.1e}",
                ]
            )
    return header, lines


# The heading of the rough section: the last of docs/peers.md, rewritten alone by
# `--only rough`.
HEADING = "## Peers: a rough contact on the very same surface array"


def with_section(existing, section):
    """`existing` with its rough section (from HEADING to the end) replaced by `section`."""
    start = existing.find(HEADING)
    before = (existing if start < 0 else existing[:start]).rstrip()
    if not section.strip():
        return before + "\n"
    return (before + "\n\n" if before else "") + section.strip() + "\n"


def rough_markdown(groups, rows, peers, args, run, markdown_table):
    """The section; `run` names when, where and with which versions it was measured."""
    header, lines = rough_table(groups)
    first = next(iter(rows.values()))
    finest = max(rows)
    criteria = "\n".join(f"- **{p.name}**: {p.criterion}" for p in peers)
    sizes = ", ".join(str(n) for n in groups)
    split = [n for n in groups if rows[n].get("threads", 1) > 1]
    threads_note = (
        f"{rows[split[0]]['threads']} threads from N = {split[0]} on"
        if split
        else "one thread on every grid here"
    )
    return f"""{HEADING}

Measured {run} by `scripts/peers.sh --only rough` (the rough cases of `scripts/peers.sh`,
which runs them after the smooth ones; this section alone is rewritten when run with
`--only rough`).

Case: the rough-surface study of `tribosim bench rough` (docs/accuracy.md): one seeded
self-affine surface generated at N = {finest} and sampled on each grid, pressed by a rigid
flat on the periodic elastic half-space at a mean pressure of
{first["mean_pressure_pa"] / 1e6:.2f} MPa, E* {first["reduced_modulus_pa"] / 1e9:.3f} GPa,
no pressure cap, N = {sizes}. tribosim writes each grid's height array as a text matrix
(`--surfaces`, every height in the shortest form that reads back to the same float) and
Tamaas and ContactMechanics read the very same array. Real area counts the cells with p > 0;
the mean gap is the mean over all cells of u + h - delta (delta the mean of u + h over the
contact), computed the same way for all three from each answer's pressure and its own
operator's displacement. "area vs ours" and "gap vs ours" are a peer's value over ours minus
1: near zero when the three solved the same discrete problem to comparable accuracy.
"residual (ours)" is our stopping measure (worst complementarity violation over max |u|) on
each answer. Ours splits its FFT passes over {threads_note} (`numerics.threads` auto, the
`threads` of `bench rough`'s rows); a peer's "cpu / wall" near 1 on a quiet machine says it
ran on one core. Times as for the smooth cases: construction plus solve, median over up to
{args.reps} cold runs (fewer once {args.budget:g} s are spent; ours those of `bench rough`:
one at N >= 1024); a peer is not run on a grid when four times its time on the grid below
exceeds {args.cap:g} s.

{markdown_table(header, lines)}

Stopping criteria:
- **tribosim**: the worst complementarity violation over max |u| below 1e-8 on a freshly
  computed u, the load carried to 1e-11.
{criteria}
"""
