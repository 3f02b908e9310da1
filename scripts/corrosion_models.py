#!/usr/bin/env python3
"""The depassivated-area models against the paper's Fig. 14 reading, A_a = 50 F / H.

Prints the markdown tables of docs/corrosion.md: the default run `{}` at Table 3's five times;
each model's fitted parameter, potential and A_a / (F / H) at those times; and each model's
potential at 30, 60, 120 rpm and 2, 5, 10 N after 10 s and 3600 s of rubbing.

The models the scene offers (`depassivated_wake`, `hertz_band`, `wear_track`, `real_contact`,
`bem_contact`) are run by the binary, their parameters fitted by `tribosim calibrate ocp`
on docs/calibration/paper_ocp.csv. Two models the scene does not offer are computed here
from the default run's records: the band as wide as the solved contact, A_a = F / H +
W v tau with W = contact_area / contact_chord, and Mischler's law A_a = K v sqrt(F / H).

    python3 scripts/corrosion_models.py [path/to/tribosim]   (default target/release/tribosim)
"""

import json
import math
import subprocess
import sys

BIN = sys.argv[1] if len(sys.argv) > 1 else "target/release/tribosim"
TABLE = "docs/calibration/paper_ocp.csv"
# Table 3: rubbing time (s) -> hardness measured in the track (MPa), total volume (mm^3).
TABLE3 = {
    10: (2551, 0.97e-3),
    60: (2727, 1.09e-3),
    300: (2854, 1.18e-3),
    1800: (2933, 5.33e-3),
    3600: (2953, 11.72e-3),
}
# Table 2's cell, the paper's i_a and electrode.
E_CORR, A_C, B_C, I_A, A_EXP_CM2 = -0.10, -3.31, 0.56, 0.01, 2.56
LOAD_N = 5.0


def eq18(area_mm2):
    """Eq. 18 capped at E_corr, V vs Ag/AgCl (3 M KCl)."""
    area_cm2 = area_mm2 * 1e-2
    return min(E_CORR, E_CORR + A_C - B_C * math.log10(I_A * area_cm2 / (A_EXP_CM2 - area_cm2)))


def paper_potential(time_s):
    return eq18(50 * LOAD_N / TABLE3[time_s][0])


def run(scene):
    out = subprocess.run(
        [BIN, "run", "-"], input=json.dumps(scene), capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout)


def calibrate(scene):
    with open("/tmp/corrosion_models_scene.json", "w") as f:
        json.dump(scene, f)
    out = subprocess.run(
        [BIN, "calibrate", "ocp", TABLE, "--scene", "/tmp/corrosion_models_scene.json"],
        capture_output=True,
        text=True,
        check=True,
    )
    return json.loads(out.stdout)


def by_time(result, rpm=60):
    return {round(r["time_s"]): r for r in result["cycles"]}


def golden(f, lo, hi):
    """Minimum of f over [lo, hi] by golden section on ln x."""
    a, b = math.log(lo), math.log(hi)
    g = (math.sqrt(5) - 1) / 2
    for _ in range(200):
        c, d = b - g * (b - a), a + g * (b - a)
        if f(math.exp(c)) < f(math.exp(d)):
            b = d
        else:
            a = c
    return math.exp((a + b) / 2)


def fit_on_records(area_of, lo, hi):
    """A parameter fitted by least squares on the potentials of A_a = area_of(record, p)."""
    records = by_time(run({}))

    def rss(p):
        return sum((paper_potential(t) - eq18(area_of(records[t], p))) ** 2 for t in TABLE3)

    return golden(rss, lo, hi)


def real_mm2(record, load=LOAD_N):
    return load / record["hardness_mpa"]


def speed_mm_s(rpm):
    return 2 * math.pi * 2.992 * rpm / 60


def solved_band(record, tau, rpm=60, load=LOAD_N):
    width_mm = record["contact_area_mm2"] / (record["contact_chord_um"] * 1e-3)
    return real_mm2(record, load) + width_mm * speed_mm_s(rpm) * tau


def mischler(record, k, rpm=60, load=LOAD_N):
    return k * speed_mm_s(rpm) * math.sqrt(real_mm2(record, load))


def default_table():
    result = run({})
    at = by_time(result)
    print(f"`{{}}` ({result['summary']['solves']} solves, {result['summary']['wall_s']:.1f} s):\n")
    print(
        "| time (s) | paper's E (V) | model E (V) | A_a (mm^2) | F / H (mm^2) | A_a / (F/H) "
        "| L (um) | I (uA) | charge (C) | WAC (1e-3 mm^3) | track = total (1e-3 mm^3) "
        "| mechanical (1e-3 mm^3) "
        "| Table 3 total | WAC / Table 3 | WAC / model total |"
    )
    print("|" + "---|" * 15)
    for t, (_, measured) in TABLE3.items():
        r = at[t]
        wac = r["wac_volume_mm3"]
        print(
            f"| {t} | {paper_potential(t):.4f} | {r['potential_v']:.4f} "
            f"| {r['anodic_area_mm2']:.4f} | {real_mm2(r):.5f} "
            f"| {r['anodic_area_mm2'] / real_mm2(r):.1f} | {r['contact_chord_um']:.1f} "
            f"| {r['anodic_current_ma'] * 1e3:.2f} | {r['charge_c']:.4f} | {wac * 1e3:.3f} "
            f"| {r['total_volume_mm3'] * 1e3:.3f} "
            f"| {r['mechanical_volume_mm3'] * 1e3:.3f} "
            f"| {measured * 1e3:.2f} | {wac / measured:.1%} | {wac / r['total_volume_mm3']:.1%} |"
        )
    print()


def conditions():
    """(label, test overrides) of the speed and load series."""
    return [
        ("30 rpm", {"speed_rpm": 30}),
        ("60 rpm, 5 N", {}),
        ("120 rpm", {"speed_rpm": 120}),
        ("2 N", {"load_n": 2}),
        ("10 N", {"load_n": 10}),
    ]


def with_test(test, corrosion):
    rpm = test.get("speed_rpm", 60)
    scene = {"test": dict(test, cycles=int(3600 * rpm / 60))}
    if corrosion is not None:
        scene["corrosion"] = corrosion
    return scene


def potentials(result, rpm):
    at = {r["cycle"]: r["potential_v"] for r in result["cycles"]}
    return at[int(10 * rpm / 60)], at[int(3600 * rpm / 60)]


def models_table():
    fitted = {}
    rows = []
    for name, corrosion, key in [
        ("depassivated_wake (default)", {}, "repassivation_time_s"),
        ("hertz_band", {"anodic_area": "hertz_band"}, "repassivation_time_s"),
        ("wear_track (Fig. 13)", {"anodic_area": "wear_track"}, None),
        ("real_contact x factor", {"anodic_area": "real_contact"}, "anodic_area_factor"),
        ("bem_contact x factor", {"anodic_area": "bem_contact"}, "anodic_area_factor"),
    ]:
        if key is None:
            value, se, parameter = 1.0, 0.0, "factor 1 (not fitted)"
            scene_corrosion = dict(corrosion)
        else:
            fit = calibrate({"corrosion": corrosion})
            value, se = fit[key]["value"], fit[key]["standard_error"]
            parameter = f"{key} = {value:.4g} +- {se:.2g}"
            scene_corrosion = dict(corrosion, **{key: value})
        fitted[name] = scene_corrosion
        at = by_time(run({"corrosion": scene_corrosion}))
        cells = [(at[t]["potential_v"], at[t]["anodic_area_mm2"] / real_mm2(at[t])) for t in TABLE3]
        rows.append((name, parameter, cells))
    tau_band = fit_on_records(solved_band, 1e-4, 0.99)
    k_sqrt = fit_on_records(mischler, 1e-4, 10.0)
    records = by_time(run({}))
    for name, parameter, area in [
        (
            "band of the solved contact's width (not offered)",
            f"tau = {tau_band:.4g} s",
            lambda r: solved_band(r, tau_band),
        ),
        (
            "Mischler, K v sqrt(F / H) (not offered)",
            f"K = {k_sqrt:.4g} s",
            lambda r: mischler(r, k_sqrt),
        ),
    ]:
        cells = [(eq18(area(records[t])), area(records[t]) / real_mm2(records[t])) for t in TABLE3]
        rows.append((name, parameter, cells))
    print(
        "| model | fitted | "
        + " | ".join(f"{t} s: E (V), A_a / (F/H)" for t in TABLE3)
        + " | rms vs paper (mV) |"
    )
    print("|" + "---|" * (len(TABLE3) + 3))
    print(
        "| the paper, A_a = 50 F / H | | "
        + " | ".join(f"{paper_potential(t):.3f}, 50" for t in TABLE3)
        + " | |"
    )
    for name, parameter, cells in rows:
        rms = math.sqrt(
            sum((c[0] - paper_potential(t)) ** 2 for c, t in zip(cells, TABLE3)) / len(TABLE3)
        )
        print(
            f"| {name} | {parameter} | "
            + " | ".join(f"{e:.3f}, {r:.1f}" for e, r in cells)
            + f" | {rms * 1e3:.0f} |"
        )
    print()
    return fitted, tau_band, k_sqrt


def predictions(fitted, tau_band, k_sqrt):
    print("| model | " + " | ".join(label for label, _ in conditions()) + " |")
    print("|" + "---|" * (len(conditions()) + 1))
    lines = {name: [] for name in fitted}
    lines["band of the solved contact's width"] = []
    lines["Mischler"] = []
    lines["the paper's constant ratio, 50 F / H"] = []
    for _label, test in conditions():
        rpm = test.get("speed_rpm", 60)
        for name, corrosion in fitted.items():
            result = run(with_test(test, corrosion))
            lines[name].append(potentials(result, rpm))
        result = run(with_test(test, {}))
        at = {r["cycle"]: r for r in result["cycles"]}
        ends = [at[int(10 * rpm / 60)], at[int(3600 * rpm / 60)]]
        load = test.get("load_n", LOAD_N)
        lines["band of the solved contact's width"].append(
            tuple(eq18(solved_band(r, tau_band, rpm, load)) for r in ends)
        )
        lines["Mischler"].append(tuple(eq18(mischler(r, k_sqrt, rpm, load)) for r in ends))
        lines["the paper's constant ratio, 50 F / H"].append(
            tuple(eq18(50 * load / r["hardness_mpa"]) for r in ends)
        )
    for name, cells in lines.items():
        print(f"| {name} | " + " | ".join(f"{a:.3f} ({b:.3f})" for a, b in cells) + " |")
    print()


if __name__ == "__main__":
    default_table()
    predictions(*models_table())
