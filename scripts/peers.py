#!/usr/bin/env python3
"""Our contact solver beside two public peers, Tamaas and ContactMechanics, in one run.

Both peers solve the cases of `tribosim bench contact` (src/bench/contact/mod.rs) on the same
grids: the paper's Hertz contact (R 3 mm, F 5 N, E* from alumina on 316L, square domain
0.256 mm, sphere apex on a cell corner, free (non-periodic) boundary, tolerance 1e-8) and
the same contact with the pressure cap Y = 2551 MPa / 2.8. Errors are against the
references our own benchmark reports (Hertz's analytic solution; our fine-grid solution of
the capped case), read from `tribosim bench contact --json` run in the same process tree.

The rough cases (scripts/peers_rough.py) follow: a rough flat on the periodic half-space,
the very same height arrays that `tribosim bench rough --surfaces` writes given to all three.

Run through scripts/peers.sh, which prepares the venv and the release build. Writes the
tables to stdout and a markdown fragment (default docs/peers.md); `--only rough` rewrites
only its rough section, `--only smooth` keeps the rough section there.
"""

import argparse
import contextlib
import datetime
import importlib.metadata
import json
import os
import platform
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import peers_rough

# The paper's case, as in src/bench/contact/mod.rs.
RADIUS_M = 3e-3
LOAD_N = 5.0
BALL = (300e9, 0.21)  # alumina: E, nu
DISC = (205e9, 0.28)  # AISI 316L
DOMAIN_M = 0.256e-3
YIELD_PA = 2551e6 / 2.8
TOLERANCE = 1e-8
CASES = ("hertz", "capped")

# Relative margin for "at the cap": peers scale pressures by a cell area or a modulus, so a
# capped cell can sit one rounding step below Y.
AT_CAP = 1e-12


def reduced_modulus():
    """E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2."""
    return 1.0 / sum((1.0 - nu * nu) / e for e, nu in (BALL, DISC))


def hertz_scales():
    """Hertz's peak pressure and approach: the scales of the peers' absolute tolerances."""
    a = (3.0 * LOAD_N * RADIUS_M / (4.0 * reduced_modulus())) ** (1.0 / 3.0)
    return 3.0 * LOAD_N / (2.0 * np.pi * a * a), a * a / RADIUS_M


def cap_pa(case):
    return YIELD_PA if case == "capped" else np.inf


def grid(n):
    """Cell size and the separation h = r^2 / (2R) at the cell centres of an n x n grid
    centred on the apex, so the apex lies on a cell corner (our Grid's convention)."""
    dx = DOMAIN_M / n
    x = (np.arange(n) + 0.5 - n / 2) * dx
    xx, yy = np.meshgrid(x, x, indexing="ij")
    return dx, (xx * xx + yy * yy) / (2.0 * RADIUS_M)


@dataclass
class Outcome:
    """A solved contact: pressure (Pa) and elastic displacement K p (m) per cell."""

    pressure: np.ndarray
    displacement: np.ndarray
    iterations: int | None


def approach(outcome, h, cap):
    """Mean of K p + h over the free cells (0 < p < Y), as our solver defines it."""
    p = outcome.pressure
    free = (p > 0) & (p < cap * (1 - AT_CAP))
    return float(np.mean((outcome.displacement + h)[free]))


def residual(outcome, h, cap):
    """Our solver's stopping measure on any answer: the worst complementarity violation
    (|g| on free cells, penetration on zero cells, opening on capped cells) over max |K p|."""
    p, u = outcome.pressure, outcome.displacement
    g = u + h - approach(outcome, h, cap)
    capped = p >= cap * (1 - AT_CAP)
    free = (p > 0) & ~capped
    violation = np.where(free, np.abs(g), 0.0)
    violation = np.maximum(violation, np.where(p <= 0, -g, 0.0))
    violation = np.maximum(violation, np.where(capped, g, 0.0))
    return float(violation.max() / np.abs(u).max())


def measures(outcome, h, dx, cap):
    p = outcome.pressure
    return {
        "pmax_pa": float(p.max()),
        "area_m2": float(np.count_nonzero(p > 0) * dx * dx),
        "approach_m": approach(outcome, h, cap),
        "plastic_area_m2": float(np.count_nonzero(p >= cap * (1 - AT_CAP)) * dx * dx),
    }


def errors(values, reference):
    """Relative errors as in src/bench/contact/mod.rs (plastic area only where the reference
    has one)."""
    out = {
        "err_pmax": values["pmax_pa"] / reference["pmax_pa"] - 1,
        "err_area": values["area_m2"] / reference["area_m2"] - 1,
        "err_delta": values["approach_m"] / reference["approach_m"] - 1,
        "err_plastic_area": None,
    }
    if reference["plastic_area_m2"] > 0:
        out["err_plastic_area"] = values["plastic_area_m2"] / reference["plastic_area_m2"] - 1
    return out


@contextlib.contextmanager
def captured_stderr():
    """Collects what C++ code writes to file descriptor 2 (Tamaas's log) into a list."""
    lines = []
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+") as tmp:
        os.dup2(tmp.fileno(), 2)
        try:
            yield lines
        finally:
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            lines.extend(tmp.read().splitlines())


# An iteration line of Tamaas's log: iteration, cost, error.
LOG_LINE = re.compile(r"^\s*(\d+)\s+\S+\s+\S+\s*$")


class TamaasPeer:
    """Tamaas: the DC-FFT Boussinesq operator (`registerNonPeriodic`) with Polonsky-Keer-Rey
    for `hertz` and KatoSaturated, its solver for pressures bounded by a saturation
    pressure, for `capped`."""

    name = "Tamaas"
    package = "tamaas"
    criterion = (
        "its own error reaching 1e-8: for PolonskyKeerRey |sum p g| / (sum p * std(h)), "
        "the complementarity of pressure and gap relative to the load times the surface's "
        "standard deviation (checked against computeError()); KatoSaturated reports its own "
        "error through the same interface and is given the same 1e-8."
    )
    notes = (
        "Solved in units of the domain side and E* (KatoSaturated stalls at its first "
        "iterate in SI units; PolonskyKeerRey gives the same answer in either). Iterations "
        "are read from Tamaas's log."
    )

    def __init__(self):
        import tamaas

        self.tm = tamaas
        tamaas.set_log_level(tamaas.LogLevel.info)
        self.modulus = reduced_modulus()

    def build(self, case, n):
        tm = self.tm
        dx, h = grid(n)
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
        model.E, model.nu = 1.0, 0.0  # with nu = 0, E is the E* of the contact
        tm.ModelFactory.registerNonPeriodic(model, "dcfft")
        # Tamaas's surface is a height: the sphere is -h.
        if case == "capped":
            solver = tm.KatoSaturated(model, -h / DOMAIN_M, TOLERANCE, YIELD_PA / self.modulus)
        else:
            solver = tm.PolonskyKeerRey(model, -h / DOMAIN_M, TOLERANCE)
        solver.setIntegralOperator("dcfft")
        solver.max_iter = 200_000
        solver.dump_freq = solver.max_iter  # log the first and last iterations only
        return {"model": model, "solver": solver, "log": []}

    def solve(self, state):
        mean_pressure = LOAD_N / (self.modulus * DOMAIN_M * DOMAIN_M)
        with captured_stderr() as log:
            state["solver"].solve(mean_pressure)
        state["log"] = log

    def outcome(self, state):
        model = state["model"]
        p = np.array(model.traction)
        # The model's displacement is shifted by the approach: apply the operator instead.
        u = np.zeros_like(p)
        model.operators["dcfft"](p, u)
        steps = [int(m.group(1)) for m in map(LOG_LINE.match, state["log"]) if m]
        return Outcome(p * self.modulus, u * DOMAIN_M, max(steps) if steps else None)


class ContactMechanicsPeer:
    """ContactMechanics: FreeFFTElasticHalfSpace (Love's rectangle kernel, zero padding)
    with its Polonsky-Keer constrained conjugate gradients; the cap through `hardness`."""

    name = "ContactMechanics"
    package = "contactmechanics"
    criterion = (
        "all of: rms and max penetration < pentol = 1e-8 x Hertz's approach (our residual's "
        "denominator, max |u|, is the approach at the apex), largest change of u in the step "
        "< pentol, tensile force (and force beyond the hardness) < forcetol = 1e-8 x p0 x cell "
        "area, relative change of the load and of the offset < thermotol = 1e-8."
    )
    notes = (
        "Forces are per cell (pressure x cell area), so the cap is passed as hardness = Y x "
        "cell area. Its Polonsky-Keer may switch to over-relaxation when almost no cell is "
        "free (not the case here)."
    )

    def __init__(self):
        from ContactMechanics import FreeFFTElasticHalfSpace
        from ContactMechanics.Optimization import constrained_conjugate_gradients

        self.half_space = FreeFFTElasticHalfSpace
        self.ccg = constrained_conjugate_gradients
        self.p0, self.delta0 = hertz_scales()

    def build(self, case, n):
        dx, h = grid(n)
        substrate = self.half_space((n, n), reduced_modulus(), (DOMAIN_M, DOMAIN_M))
        return {"case": case, "dx": dx, "h": h, "substrate": substrate}

    def solve(self, state):
        dx = state["dx"]
        hardness = {"hardness": YIELD_PA * dx * dx} if state["case"] == "capped" else {}
        result = self.ccg(
            state["substrate"],
            -state["h"],  # the rigid body's heights: the sphere is -h
            external_force=LOAD_N,
            pentol=TOLERANCE * self.delta0,
            forcetol=TOLERANCE * self.p0 * dx * dx,
            thermotol=TOLERANCE,
            **hardness,
        )
        if not result.success:
            raise RuntimeError(f"ContactMechanics: {result.message}")
        state["result"] = result

    def outcome(self, state):
        dx, result = state["dx"], state["result"]
        n = state["h"].shape[0]
        # `jac` is the compressive force per cell; `x` the displacement on the padded grid,
        # equal to K p in the grid (u = offset - h in contact).
        return Outcome(result.jac / (dx * dx), result.x[:n, :n], int(result.nit))


@dataclass
class Measurement(peers_rough.Timing):
    case: str = ""
    errors: dict = field(default_factory=dict)
    uniform_wall_s: float | None = None


def measure(peer, case, n, reference, reps, budget_s):
    """Median over up to `reps` cold runs (fewer once `budget_s` is spent) of construction
    (model, kernel, operator) plus solve; errors from the last run."""
    out = Measurement(solver=peer.name, n=n, case=case)
    state = peers_rough.timed_runs(out, lambda: peer.build(case, n), peer.solve, reps, budget_s)
    if out.failure:
        return out
    outcome = peer.outcome(state)
    dx, h = grid(n)
    out.iterations = outcome.iterations
    out.residual = residual(outcome, h, cap_pa(case))
    out.errors = errors(measures(outcome, h, dx, cap_pa(case)), reference)
    return out


def ours(binary):
    """Our grid rows, keyed by (case, n), from one `bench contact --json` run."""
    run = subprocess.run(
        [binary, "bench", "contact", "--json"], check=True, capture_output=True, text=True
    )
    rows = [json.loads(line) for line in run.stdout.splitlines() if line.startswith("{")]
    return {(r["case"], r["n"]): r for r in rows if r.get("study") == "contact_grid"}


def our_measurement(row):
    return Measurement(
        solver="tribosim",
        case=row["case"],
        n=row["n"],
        wall_s=row["wall_s"],
        solve_s=row["solve_s"],
        runs=row["runs"],
        iterations=row["iterations"],
        residual=row["residual"],
        errors={k: row[k] for k in ("err_pmax", "err_area", "err_delta", "err_plastic_area")},
        uniform_wall_s=row["build_s"] + row["uniform_solve_s"],
    )


def fmt_err(value):
    return "-" if value is None else f"{value:+.2e}"


def table_rows(groups):
    """One line per solver: cells of the markdown table."""
    header = [
        "case",
        "N",
        "solver",
        "iterations",
        "time s",
        "solve s",
        "peer / ours",
        "peer / ours uniform",
        "runs",
        "cpu / wall",
        "err p_max",
        "err area",
        "err approach",
        "err plastic area",
        "residual (ours)",
        "err diff vs ours",
    ]
    lines = []
    for (case, n), (mine, peers) in groups.items():
        for m in [mine, *peers]:
            if m.failure:
                lines.append([case, str(n), m.solver, m.failure, *[""] * (len(header) - 4)])
                continue
            ratio = "" if m is mine else f"{m.wall_s / mine.wall_s:.1f}"
            uniform = "" if m is mine else f"{m.wall_s / mine.uniform_wall_s:.1f}"
            diff = ""
            if m is not mine:
                pairs = [(m.errors[k], mine.errors[k]) for k in m.errors]
                diff = f"{max(abs(a - b) for a, b in pairs if a is not None):.1e}"
            lines.append(
                [
                    case,
                    str(n),
                    m.solver,
                    "" if m.iterations is None else str(m.iterations),
                    f"{m.wall_s:.4g}",
                    f"{m.solve_s:.4g}",
                    ratio,
                    uniform,
                    "" if m.runs is None else str(m.runs),
                    "" if m.cpu_per_wall is None else f"{m.cpu_per_wall:.2f}",
                    fmt_err(m.errors["err_pmax"]),
                    fmt_err(m.errors["err_area"]),
                    fmt_err(m.errors["err_delta"]),
                    fmt_err(m.errors["err_plastic_area"]),
                    f"{m.residual:.1e}",
                    diff,
                ]
            )
    return header, lines


def plain_table(header, lines):
    widths = [max(len(row[i]) for row in [header, *lines]) for i in range(len(header))]
    return "\n".join(
        "  ".join(cell.rjust(w) for cell, w in zip(row, widths)) for row in [header, *lines]
    )


def markdown_table(header, lines):
    rows = [header, ["---"] * len(header), *lines]
    return "\n".join("| " + " | ".join(row) + " |" for row in rows)


def machine(load):
    info = dict(
        line.split(":", 1)
        for line in subprocess.run(
            ["lscpu"], capture_output=True, text=True, check=True
        ).stdout.splitlines()
        if ":" in line
    )
    return (
        f"{info['Model name'].strip()}, {info['CPU(s)'].strip()} logical CPUs "
        f"(load average {load:.1f} before the run: other work skews the times)"
    )


def versions(binary):
    packages = ["numpy", "tamaas", "ContactMechanics", "SurfaceTopography", "muGrid"]
    found = [f"{p} {importlib.metadata.version(p)}" for p in packages]
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True
    ).stdout.strip()
    ours_version = subprocess.run(
        [binary, "--version"], capture_output=True, text=True
    ).stdout.strip()
    python = platform.python_version()
    return f"{ours_version} (commit {commit or 'unknown'}), Python {python}, " + ", ".join(found)


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


def markdown(header, lines, peers, args, reference_n, load):
    date = now()
    criteria = "\n".join(f"- **{p.name}**: {p.criterion} {p.notes}" for p in peers)
    return f"""## Peers: the same contacts in Tamaas and ContactMechanics

Measured {date} on {machine(load)} by `scripts/peers.sh` (regenerate with that one command; it
makes a venv under `target/peers-venv`, builds the release binary, runs `scripts/peers.py`
and rewrites this file). Versions: {versions(args.binary)}.

Cases: the paper's Hertz contact (R 3 mm, F 5 N, E* {reduced_modulus() / 1e9:.3f} GPa, square
domain 0.256 mm, apex on a cell corner, free boundary, tolerance 1e-8) and the same contact
capped at Y = 2551 MPa / 2.8 = {YIELD_PA / 1e6:.2f} MPa. Every solver gets the same grid and
separation. Errors are `value / reference - 1` against Hertz's analytic solution (`hertz`)
and against our own N = {reference_n} solution of the same case (`capped`, which has no
analytic answer; its p_max error is p_max / Y - 1). Contact area counts cells with p > 0,
plastic area cells at the cap, approach is the mean of K p + h over the free cells.

"time s" is the median over cold runs of construction (model, kernel and operator) plus
solve, the same for every solver, and "solve s" the solve alone; "peer / ours" is the ratio
of the times. Our cold solve is the one `tribosim contact` and a run's first cycle make:
from the coarse-to-fine start (the same contact solved on grids of half the cells per side
down to 32, to 1e-4, interpolated; their operators and solves are in our time, their
iterations not in our count, which is the fine grid's); "peer / ours uniform" is the ratio
to our solve from the uniform pressure, as the peers start (timed alternately with the cold
one by `tribosim bench contact`). "runs" counts the runs behind each median (ours those of
`tribosim bench contact`; a peer's up to {args.reps}, fewer once {args.budget:g} s are
spent; a peer is not run on a grid when four times its time on the grid below exceeds
{args.cap:g} s). All three are single-threaded; "cpu / wall", the process CPU time over wall
time of a peer's runs, shows it (near 1 on a quiet machine, lower when other work shares the
cores). "residual (ours)" is our stopping measure (worst complementarity violation over max
|K p|) evaluated on each answer with that solver's own operator; "err diff vs ours" is the
largest absolute difference between a peer's errors and ours: near zero when both solved the
same discrete problem.

{markdown_table(header, lines)}

Stopping criteria:
- **tribosim**: the worst complementarity violation over max |K p| below 1e-8, on a freshly
  computed K p, with the load carried to 1e-11.
{criteria}
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--binary", default="target/release/tribosim")
    parser.add_argument(
        "--sizes",
        type=int,
        nargs="+",
        default=[64, 128, 256, 512, 1024, 2048],
        help="grids of the smooth cases; a case runs on those of them that `bench contact` "
        "solves (the capped case stops at 1024, half its reference)",
    )
    parser.add_argument("--reps", type=int, default=3, help="runs per median")
    parser.add_argument(
        "--budget",
        type=float,
        default=60.0,
        help="seconds after which a peer's measurement stops repeating",
    )
    parser.add_argument("--out", default="docs/peers.md")
    parser.add_argument(
        "--only", choices=["smooth", "rough"], help="run one set of cases; the default runs both"
    )
    parser.add_argument("--rough-sizes", type=int, nargs="+", default=[256, 512, 1024, 2048])
    parser.add_argument(
        "--cap",
        type=float,
        default=900.0,
        help="seconds beyond which a peer's run on a grid is not started (four times its "
        "time on the grid below)",
    )
    parser.add_argument(
        "--surfaces",
        default="target/rough-surfaces",
        help="where `tribosim bench rough` writes the height arrays the peers read",
    )
    args = parser.parse_args()

    load = os.getloadavg()[0]
    out = Path(args.out)
    text = out.read_text() if out.exists() else ""
    if args.only != "rough":
        text = peers_rough.with_section(smooth(args, load), rough_part(text))
    if args.only != "smooth":
        peers = [
            peers_rough.TamaasRough(captured_stderr, LOG_LINE),
            peers_rough.ContactMechanicsRough(),
        ]
        groups, rows = peers_rough.run_rough(args, peers)
        header, lines = peers_rough.rough_table(groups)
        print(plain_table(header, lines))
        run = f"{now()} on {machine(load)}; versions: {versions(args.binary)}"
        section = peers_rough.rough_markdown(groups, rows, peers, args, run, markdown_table)
        text = peers_rough.with_section(text, section)
    out.write_text(text)
    print(f"wrote {args.out}", file=sys.stderr)


def rough_part(text):
    """The rough section of an existing fragment, or nothing."""
    start = text.find(peers_rough.HEADING)
    return "" if start < 0 else text[start:]


def smooth(args, load):
    """The smooth cases: run, printed, and their markdown."""
    print("running tribosim bench contact --json ...", file=sys.stderr)
    mine = ours(args.binary)
    peers = [TamaasPeer(), ContactMechanicsPeer()]
    groups = {}
    for case in CASES:
        last = {p.name: None for p in peers}
        for n in (n for n in args.sizes if (case, n) in mine):
            row = mine[(case, n)]
            reference = row["reference"]
            found = []
            for peer in peers:
                print(f"{case} N = {n}: {peer.name} ...", file=sys.stderr)
                skipped = peers_rough.beyond_cap(last[peer.name], args.cap)
                m = (
                    Measurement(solver=peer.name, n=n, case=case, failure=skipped)
                    if skipped
                    else measure(peer, case, n, reference, args.reps, args.budget)
                )
                last[peer.name] = m.wall_s if m.wall_s is not None else float("inf")
                found.append(m)
            groups[(case, n)] = (our_measurement(row), found)

    header, lines = table_rows(groups)
    print(plain_table(header, lines))
    reference_n = next(r["reference"]["n"] for r in mine.values() if r["case"] == "capped")
    return markdown(header, lines, peers, args, reference_n, load)


if __name__ == "__main__":
    main()
