#!/usr/bin/env python3
"""Silo discharge against the Beverloo law: write the scenes, run them, fit C and k.

    tools/silo_beverloo.py BINARY [--variant ci|medium|full] [--backend cpu|cuda]
                           [--mpiexec "mpiexec -n 2"] [--keep DIR] [--plot FILE]
    tools/silo_beverloo.py --write-cases

A flat-bottomed cylindrical silo is filled by an inlet near its top, which
keeps feeding during the discharge and so keeps the fill level; a gate
(a plate with an `active` window) under an orifice plate opens at t_open; a
half-space outlet below removes what has fallen through. The mass flow is
counted by a `measurements` flow disk in the orifice plane; the bulk density
rho_b = phi rho_p by a `measurements` average of the solid fraction phi in the
bulk of the silo just before the gate opens. Beverloo et al. (1961):

    W = C rho_b sqrt(g) (D0 - k d)^(5/2)

so W^(2/5) = (C rho_b sqrt(g))^(2/5) (D0 - k d) is linear in D0: a least
squares line gives k (its zero crossing over d) and C (from its slope).

The published ranges are C = 0.55-0.65 and k = 1.3-1.6 for spheres (Beverloo
et al. 1961; Nedderman 1992, ch. 10; Mankoc et al. 2007 for the validity:
D0 > ~5 d, silo diameter > 2.5 D0 and > D0 + 30 d, fill height > 1.2 silo
diameters; below ~5 d the flow intermits and Beverloo over-predicts). Each run's rate must
lie in the band those ranges give, widened by TOL_BAND; its rates over the
two halves of the measuring window must agree within TOL_STEADY. Exit status
0 when every check passes, 1 when one fails, 2 on a usage or run error.

Variants: `ci` (orifices 6 and 7 d, ~4.7k particles, the CTest validation_silo),
`medium` (three orifices, ~4.5k particles, a CPU run for the docs), `full` (five
orifices D0 = 6-15 d in a silo of 46 d filled 58 d high, ~105k particles, the
GPU run of bench/validation_silo_gpu.sh; its scenes are
cases/validation/silo/*.yaml), `smoke` (the full variant's set-up in
miniature, to check the GPU script on a CPU). --budget-s stops the runs
still going after that many seconds and analyses each over the window it
reached (at least MIN_WINDOW).
Standard library only (matplotlib for --plot, when present).
"""
import argparse
import concurrent.futures
import csv
import math
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

import budget_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE_DIR = os.path.join(ROOT, "cases", "validation", "silo")

# Published ranges for spheres (Beverloo et al. 1961; Nedderman 1992).
C_RANGE = (0.55, 0.65)
K_RANGE = (1.3, 1.6)
# A run's rate may lie this far (relative) outside the band of the published
# ranges: the noise of a rate over a few hundred particles (a few percent)
# and the small CI silo's walls (D/D0 = 2.8) with margin (docs/VALIDATION.md).
TOL_BAND = 0.10
# The rates over the two halves of the measuring window must agree within this
# (relative to their mean): a steady flow's halves differ by its noise alone.
TOL_STEADY = 0.10

G = 9.81              # m/s^2
RHO_P = 2500.0        # particle density [kg/m^3] (glass)
D = 0.002             # mean particle diameter [m]; radii uniform in D/2 (1 +- SPREAD)
SPREAD = 0.1

# Per variant: silo diameter and fill height in d, orifice diameters in d,
# normal stiffness [N/m], and the times [s]: gate opening, start of the
# measuring window, end of the run.
VARIANTS = {
    "ci": dict(silo=16, fill=20, orifices=[6.0, 7.0], stiffness=400.0,
               t_open=0.5, t_measure=0.6, t_end=0.9),
    "medium": dict(silo=16, fill=20, orifices=[4.0, 5.0, 6.0], stiffness=400.0,
                   t_open=0.5, t_measure=0.6, t_end=1.1),
    # The GPU run (bench/validation_silo_gpu.sh): the silo starts from a random
    # fill of the count that fills it (it falls and settles by t_open) instead
    # of being filled by the inlet, which would take 1.4 s of the budget; the
    # inlet starts at t_feed and keeps the level during the discharge.
    # Mankoc et al.'s conditions for every orifice: silo diameter above 2.5 D0
    # and above D0 + 30 d (46 d against 45 d for D0 = 15 d), fill above 1.2 of it.
    "full": dict(silo=46, fill=58, orifices=[6.0, 8.0, 10.0, 12.5, 15.0], stiffness=1000.0,
                 t_open=0.45, t_measure=0.6, t_end=1.2, start="fill", t_feed=0.3),
    # The full variant's set-up in miniature (~1.8k particles, seconds of CPU
    # a run): checks the GPU script's logic on a CPU, not the physics.
    "smoke": dict(silo=12, fill=15, orifices=[5.0, 6.0], stiffness=200.0,
                  t_open=0.25, t_measure=0.3, t_end=0.5, start="fill", t_feed=0.15),
}
# A run stopped early (by the GPU script's wall budget) is analysed over the
# window it reached when that is at least this long [s]; shorter: no rate.
MIN_WINDOW = 0.15
FILL_TOP = 2.2        # a random fill start: the loose fill's region reaches this many fill heights
FILL_PACKING = 0.58   # ... and holds the count of a bed of this solid fraction, fill height high
FLOW_EVERY = 0.005    # s between flow evaluations: a centre falls ~1.5 mm in it at the orifice


def fmt(x):
    return repr(round(x, 9))


def geometry(variant, d0_over_d):
    """The sizes of one orifice of a variant [m], and its times."""
    v = VARIANTS[variant]
    g = dict(v, variant=variant, d0_over_d=d0_over_d, r_silo=v["silo"] * D / 2, d0=d0_over_d * D,
             h_fill=v["fill"] * D, inlet_len=4 * D)
    g["inlet_top"] = g["h_fill"] + g["inlet_len"]
    # The silo's wall reaches the inlet's top, or the top of the loose random
    # fill (fill_particles) for a variant that starts from one.
    g["top"] = max(g["inlet_top"], FILL_TOP * g["h_fill"]) if v.get("start") == "fill" else g["inlet_top"]
    g["below"] = -max(8 * D, g["r_silo"])          # the outlet plane
    g["lo"] = [-g["r_silo"] - D, -g["r_silo"] - D, g["below"] - 2 * D]
    g["hi"] = [g["r_silo"] + D, g["r_silo"] + D, g["top"] + D]
    return g


def vec(x):
    return "[%s]" % ", ".join(fmt(c) for c in x)


def scene_head(g):
    """Domain, materials and walls; the gate opens at t_open (never with t_open None)."""
    gate_window = "" if g["t_open"] is None else ", active: {until: %s}" % g["t_open"]
    return f"""domain: {{min: {vec(g['lo'])}, max: {vec(g['hi'])}}}
gravity: [0, 0, -{G}]
contact_model: linear
precision: fp32
effects: {{friction: true}}
materials:
  - {{name: glass, density: {RHO_P:g}}}
  - {{name: steel, density: 7800}}
pairs:
  - {{materials: [glass, glass], stiffness_normal: {g['stiffness']:g}, restitution: 0.5, friction: 0.5}}
  - {{materials: [glass, steel], stiffness_normal: {g['stiffness']:g}, restitution: 0.5, friction: 0.5}}
walls:
  - {{name: silo, material: steel, cylinder: {{base: [0, 0, 0], axis: [0, 0, 1], radius: {fmt(g['r_silo'])}, length: {fmt(g['top'])}}}}}
  - {{name: bottom, material: steel, plate: {{point: [0, 0, 0], normal: [0, 0, 1], radius: {fmt(g['r_silo'])}, hole: {{radius: {fmt(g['d0'] / 2)}}}}}}}
  - {{name: gate, material: steel, plate: {{point: [0, 0, {fmt(-0.5 * D)}], normal: [0, 0, 1], radius: {fmt(g['d0'])}}}{gate_window}}}
"""


def radii():
    return "{min: %s, max: %s}" % (fmt(D / 2 * (1 - SPREAD)), fmt(D / 2 * (1 + SPREAD)))


def mean_volume():
    """The mean particle volume, radii uniform in r (1 +- SPREAD)."""
    return math.pi / 6 * D ** 3 * (1 + SPREAD ** 2)


def fill_particles(g):
    """A random fill, loose over FILL_TOP fill heights, of the count of a bed
    FILL_PACKING dense up to the fill height: it falls and settles before the
    gate opens."""
    r_max = D / 2 * (1 + SPREAD)
    count = int(FILL_PACKING * math.pi * g["r_silo"] ** 2 * g["h_fill"] / mean_volume())
    return f"""particles:
  - random_fill:
      material: glass
      region: {{cylinder: {{base: [0, 0, {fmt(r_max)}], axis: [0, 0, 1], radius: {fmt(g['r_silo'] - r_max)}, length: {fmt(g['top'] - 2 * r_max)}}}}}
      count: {count}
      radius: {radii()}
      seed: 11
"""


def inlet_section(g):
    """The inlet rains particles (at 0.5 m/s down) over the top: each batch
    places up to 15 % of its region's volume; where the bed reaches the
    region, places are refused and the level stays there (shortfalls)."""
    r_in = g["r_silo"] - 0.6 * D
    interval = 0.015
    rate = 0.15 * math.pi * r_in ** 2 * g["inlet_len"] / mean_volume() / interval
    start = "    start: %s\n" % g["t_feed"] if g.get("t_feed") else ""
    return f"""inlets:
  - name: feed
    material: glass
    region: {{cylinder: {{base: [0, 0, {fmt(g['h_fill'])}], axis: [0, 0, 1], radius: {fmt(r_in)}, length: {fmt(g['inlet_len'])}}}}}
    radius: {radii()}
    rate: {{count: {rate:.0f}}}
    interval: {interval}
    velocity: [0, 0, -0.5]
    seed: 7
{start}"""


def outlet_section(g):
    return "outlets:\n  - {name: below, half_space: {point: [0, 0, %s], normal: [0, 0, -1]}}\n" % fmt(g["below"])


def flow_item(g, start):
    return ("    - {name: orifice, plane: {point: [0, 0, 0], normal: [0, 0, -1]}, radius: %s, every: %s, start: %s}\n"
            % (fmt(g["d0"] / 2), FLOW_EVERY, start))


def average_items(g):
    """The bulk (well inside the walls, above the floor, below the surface)
    and the whole silo (its mass shows whether the inlet keeps the level)."""
    half, r = 0.5 * g["r_silo"], g["r_silo"]
    return ("    - {name: bulk, box: {min: %s, max: %s}, quantities: [solid_fraction], every: 0.05}\n"
            "    - {name: silo, box: {min: %s, max: %s}, quantities: [solid_fraction], every: 0.05}\n" %
            (vec([-half, -half, 0.35 * g["h_fill"]]), vec([half, half, 0.75 * g["h_fill"]]),
             vec([-r, -r, 0]), vec([r, r, g["top"]])))


def scene(variant, d0_over_d, out_dir):
    """The scene text of one orifice of a variant."""
    g = geometry(variant, d0_over_d)
    return (f"""# Silo discharge against the Beverloo law (docs/VALIDATION.md), variant {variant}:
# written by tools/silo_beverloo.py; D0 = {d0_over_d:g} d, d = {D * 1e3:g} mm, silo diameter {g['silo']} d,
# fill height {g['fill']} d kept by the inlet, gate opens at t = {g['t_open']} s.
""" + scene_head(g) + (fill_particles(g) if g.get("start") == "fill" else "") + inlet_section(g) + outlet_section(g) +
            "measurements:\n  flows:\n" + flow_item(g, g["t_open"]) + "  averages:\n" + average_items(g) +
            f"""time_step: {{fraction_of_contact_time: 0.1}}
duration: {g['t_end']}
output: {{interval: {g['t_open']}, directory: {out_dir}, format: csv}}
""")


def case_name(d0_over_d):
    return "silo_D0_%s" % ("%g" % d0_over_d).replace(".", "p")


def read_rows(path):
    """The rows of a CSV file by its header, '#' comment lines (a snapshot's first) skipped."""
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def flow_rates(run_dir, t_measure, t_end):
    """Mass rates [kg/s] over [t_measure, t_end] and its two halves, from the
    cumulative net mass through the orifice disk, and the removed.csv rate."""
    rows = [r for r in read_rows(os.path.join(run_dir, "flow_orifice.csv")) if r["material"] == "all"]
    series = [(float(r["time"]), float(r["cumulative_net_mass"]), int(r["cumulative_net_count"])) for r in rows]

    def at(t):  # the evaluation nearest t
        return min(series, key=lambda s: abs(s[0] - t))

    t_end = min(t_end, series[-1][0])   # a run stopped by the budget: the window it reached
    if t_end - t_measure < MIN_WINDOW:
        raise ValueError("the run reached t = %.3f s only: no window of %.2f s from %.3f s" % (t_end, MIN_WINDOW, t_measure))
    a, m, b = at(t_measure), at(0.5 * (t_measure + t_end)), at(t_end)
    rate = (b[1] - a[1]) / (b[0] - a[0])
    first = (m[1] - a[1]) / (m[0] - a[0])
    second = (b[1] - m[1]) / (b[0] - m[0])
    # The same window from the outlet's removal log: each particle is removed
    # a fixed fall time after it crossed, so a steady rate is the same.
    removed = [(float(r["time"]), float(r["outlet_mass"])) for r in read_rows(os.path.join(run_dir, "removed.csv"))
               if r["outlet"] == "below"]
    def removed_at(t):
        before = [x for x in removed if x[0] <= t]
        return before[-1][1] if before else 0.0
    removed_rate = (removed_at(t_end) - removed_at(t_measure)) / (t_end - t_measure)
    return dict(rate=rate, first=first, second=second, count=b[2] - a[2], removed_rate=removed_rate,
                series=series, window=(a[0], b[0]))


def solid_fraction_before(run_dir, name, t):
    """The box's solid fraction at the last evaluation before time t."""
    rows = [r for r in read_rows(os.path.join(run_dir, "average_%s.csv" % name)) if float(r["time"]) < t]
    return float(rows[-1]["solid_fraction"]), float(rows[-1]["mass"])


def overlaps(run_dir, t, r_silo, d0):
    """Mean and largest overlap over d of the contacts (particle-particle, the
    bottom plate, the gate, the silo's wall; not the orifice's rim) in the
    snapshot at time t (the bed at rest before the gate opens), from a cell
    list over the centres."""
    # The snapshot nearest t (its time may lie a rounding above t: the step
    # count of t_open is rounded to whole steps).
    snapshots = [r for r in read_rows(os.path.join(run_dir, "timeseries.csv"))
                 if os.path.exists(os.path.join(run_dir, "particles_%010d.csv" % int(r["step"])))]
    step = int(min(snapshots, key=lambda r: abs(float(r["time"]) - t))["step"])
    rows = read_rows(os.path.join(run_dir, "particles_%010d.csv" % step))
    p = [(float(r["x"]), float(r["y"]), float(r["z"]), float(r["radius"])) for r in rows]
    cells = {}
    for i, (x, y, z, _) in enumerate(p):
        cells.setdefault((int(math.floor(x / D)), int(math.floor(y / D)), int(math.floor(z / D))), []).append(i)
    found = []
    for i, (x, y, z, r) in enumerate(p):
        c = (int(math.floor(x / D)), int(math.floor(y / D)), int(math.floor(z / D)))
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in cells.get((c[0] + dx, c[1] + dy, c[2] + dz), ()):
                        if j <= i:
                            continue
                        q = p[j]
                        o = r + q[3] - math.sqrt((x - q[0]) ** 2 + (y - q[1]) ** 2 + (z - q[2]) ** 2)
                        if o > 0:
                            found.append(o)
        rho = math.hypot(x, y)
        if rho >= d0 / 2 and abs(z) < r:          # the bottom plate, beside the orifice
            found.append(r - abs(z))
        if rho <= d0 and 0 <= z + 0.5 * D < r:     # the gate under the orifice
            found.append(r - (z + 0.5 * D))
        if rho + r > r_silo:
            found.append(rho + r - r_silo)
    if not found:
        return 0.0, 0.0, 0
    return sum(found) / len(found) / D, max(found) / D, len(found)


def run_status(run_dir):
    """done, or stopped (by a signal: the budget), from a kept run's log."""
    try:
        with open(os.path.join(run_dir, "run.log")) as f:
            return "stopped" if any(line.startswith("stopped by a signal") for line in f) else "done"
    except OSError:
        return "done"


def steps_per_second(run_dir):
    """The run's particle-steps per second (its run.log's `done:` line), or nan."""
    try:
        with open(os.path.join(run_dir, "run.log")) as f:
            done = [line for line in f if line.startswith("done:")]
        return float(done[-1].split(",")[-1].split()[0]) if done else float("nan")
    except (OSError, ValueError, IndexError):
        return float("nan")


def beverloo(c, k, rho_b, d0):
    return c * rho_b * math.sqrt(G) * max(d0 - k * D, 0.0) ** 2.5


def band(rho_b, d0):
    """The Beverloo rate range of the published C and k ranges."""
    return beverloo(C_RANGE[0], K_RANGE[1], rho_b, d0), beverloo(C_RANGE[1], K_RANGE[0], rho_b, d0)


def fit(points, rho_b):
    """Least squares of W^(2/5) = a (D0 - k d) over (D0, W): returns C, k."""
    xs = [p[0] for p in points]
    ys = [p[1] ** 0.4 for p in points]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    intercept = my - slope * mx
    return slope ** 2.5 / (rho_b * math.sqrt(G)), -intercept / slope / D


def make_run(args, variant, d0_over_d, work):
    """Writes one orifice's scene; returns its run (budget_runs.Run)."""
    name = case_name(d0_over_d)
    out = os.path.join(work, name)
    path = os.path.join(work, name + ".yaml")
    with open(path, "w") as f:
        f.write(scene(variant, d0_over_d, out))
    cmd = shlex.split(args.mpiexec) if args.mpiexec else []
    cmd += [args.binary, "run", path, "--backend", args.backend, "--out", out, "--overwrite"]
    return budget_runs.Run(name, cmd, os.path.join(work, name + ".log"))


def write_cases():
    os.makedirs(CASE_DIR, exist_ok=True)
    for d0 in VARIANTS["full"]["orifices"]:
        with open(os.path.join(CASE_DIR, case_name(d0) + ".yaml"), "w") as f:
            f.write(scene("full", d0, "out/" + case_name(d0)))
    print("wrote %d scenes to %s" % (len(VARIANTS["full"]["orifices"]), CASE_DIR))


def plot(path, results, rho_b, c_fit, k_fit):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: no plot")
        return
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for r in results:
        ts = [s[0] for s in r["series"]]
        ax1.plot(ts, [s[1] * 1e3 for s in r["series"]], label="D0 = %g d" % r["d0"])
    ax1.set_xlabel("t [s]")
    ax1.set_ylabel("mass through the orifice [g]")
    ax1.legend()
    xs = [r["d0"] for r in results]
    ax2.plot(xs, [r["rate"] * 1e3 for r in results], "o", label="grainstorm")
    grid = [min(xs) * 0.9 + i * (max(xs) * 1.05 - min(xs) * 0.9) / 50 for i in range(51)]
    lo = [band(rho_b, x * D)[0] * 1e3 for x in grid]
    hi = [band(rho_b, x * D)[1] * 1e3 for x in grid]
    ax2.fill_between(grid, lo, hi, alpha=0.3, label="Beverloo, C 0.55-0.65, k 1.3-1.6")
    ax2.plot(grid, [beverloo(c_fit, k_fit, rho_b, x * D) * 1e3 for x in grid], "k--",
             label="fit C = %.3f, k = %.2f" % (c_fit, k_fit))
    ax2.set_xlabel("D0 / d")
    ax2.set_ylabel("W [g/s]")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print("plot:", path)


def measure(out, v, d0, seconds, status="done"):
    """Everything the table shows of one run directory (a run stopped early:
    over the window it reached)."""
    r = flow_rates(out, v["t_measure"], v["t_end"])
    phi, _ = solid_fraction_before(out, "bulk", v["t_open"])
    _, mass_open = solid_fraction_before(out, "silo", v["t_open"])
    _, mass_end = solid_fraction_before(out, "silo", v["t_end"] + 1)
    # The overlaps need the particle snapshots; a copy of the logs alone
    # (bench/validation_silo_gpu.sh's OUT/runs) has none.
    have_snapshots = os.path.exists(os.path.join(out, "particles_%010d.csv" % 0))
    mean_overlap, max_overlap, contacts = (overlaps(out, v["t_open"], v["silo"] * D / 2, d0 * D) if have_snapshots
                                           else (float("nan"), float("nan"), 0))
    r.update(d0=d0, phi=phi, seconds=seconds, mass_open=mass_open, mass_end=mass_end,
             mean_overlap=mean_overlap, max_overlap=max_overlap, contacts=contacts, status=status,
             steps_per_s=steps_per_second(out))
    return r


def report(results, v, args, backend, g):
    """Prints the table and the fit; returns the failed checks."""
    phi = sum(r["phi"] for r in results) / len(results)
    rho_b = phi * RHO_P
    print("variant %s, d = %g mm, silo %d d, fill %d d, rho_p = %g kg/m^3, backend %s%s" %
          (args.variant, D * 1e3, v["silo"], v["fill"], RHO_P, backend, ", " + args.mpiexec if args.mpiexec else ""))
    print("measuring window %.3f-%.3f s (gate opens at %.3f s)" % (v["t_measure"], v["t_end"], v["t_open"]))
    if g != 9.81:
        print("analysed with g = %g m/s^2 (the runs used 9.81)" % g)
    print("| D0/d | phi (bulk, at rest) | W [g/s] | W 1st half | W 2nd half | removed.csv W | particles | "
          "Beverloo band [g/s] | W / W(C=0.58, k=1.5) | silo mass open -> end [g] | overlap/d mean, max | window [s] | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    failures = []
    for r in results:
        lo, hi = band(rho_b, r["d0"] * D)
        ref = beverloo(0.58, 1.5, rho_b, r["d0"] * D)
        window = "%.2f-%.2f%s" % (r["window"][0], r["window"][1],
                                  " (stopped by the budget)" if r["status"] == "stopped" else "")
        print("| %g | %.4f | %.3f | %.3f | %.3f | %.3f | %d | %.3f-%.3f | %.3f | %.1f -> %.1f | %.5f, %.4f | %s | %.0f |" %
              (r["d0"], r["phi"], r["rate"] * 1e3, r["first"] * 1e3, r["second"] * 1e3, r["removed_rate"] * 1e3,
               r["count"], lo * 1e3, hi * 1e3, r["rate"] / ref, r["mass_open"] * 1e3, r["mass_end"] * 1e3,
               r["mean_overlap"], r["max_overlap"], window, r["seconds"]))
        r["clogged"] = r["second"] < 0.05 * ref
        if r["clogged"]:
            failures.append("%s, D0 = %g d: the flow stopped (an arch clogged the orifice): W = %.4g g/s, then "
                            "%.4g g/s; below about 5 d an orifice clogs (Zuriguel et al. 2005)" %
                            (backend, r["d0"], r["first"] * 1e3, r["second"] * 1e3))
            continue
        if not (lo * (1 - TOL_BAND) <= r["rate"] <= hi * (1 + TOL_BAND)):
            failures.append("%s, D0 = %g d: W = %.4g g/s outside the Beverloo band %.4g-%.4g g/s (+-%d %%)" %
                            (backend, r["d0"], r["rate"] * 1e3, lo * 1e3, hi * 1e3, TOL_BAND * 100))
        if abs(r["first"] - r["second"]) > TOL_STEADY * r["rate"]:
            failures.append("%s, D0 = %g d: not steady, W = %.4g g/s then %.4g g/s (tolerance %d %%)" %
                            (backend, r["d0"], r["first"] * 1e3, r["second"] * 1e3, TOL_STEADY * 100))
    print("rho_b = phi rho_p = %.4f x %g = %.1f kg/m^3" % (phi, RHO_P, rho_b))
    flowing = [r for r in results if not r["clogged"]]
    if len(flowing) >= 2:
        c_fit, k_fit = fit([(r["d0"] * D, r["rate"]) for r in flowing], rho_b)
        print("fit of W^(2/5) against D0 (%d flowing orifices): C = %.3f, k = %.2f (published: C %.2f-%.2f, k %.1f-%.1f)" %
              (len(flowing), c_fit, k_fit, C_RANGE[0], C_RANGE[1], K_RANGE[0], K_RANGE[1]))
        if args.plot:
            plot(args.plot, flowing, rho_b, c_fit, k_fit)
    return failures


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("binary", nargs="?")
    p.add_argument("--variant", choices=sorted(VARIANTS), default="ci")
    p.add_argument("--backend", help="cpu or cuda; default: each of GS_TEST_BACKENDS (default cpu)")
    p.add_argument("--mpiexec", default="", help='launcher prefix, e.g. "mpiexec -n 2"')
    p.add_argument("--keep", help="run in this directory and keep it")
    p.add_argument("--jobs", type=int, default=1, help="runs at once (CPU runs on a machine with cores to spare; "
                   "several on one GPU)")
    p.add_argument("--budget-s", type=float, help="wall seconds for the runs: then what still runs is stopped "
                   "(SIGTERM) and analysed over the window it reached")
    p.add_argument("--analyse", help="analyse the runs kept in this directory (of --keep) without running")
    p.add_argument("--plot", help="write a plot (PNG) here")
    p.add_argument("--g-scale", type=float, default=1.0,
                   help="analyse with g scaled by this (a deliberate break: the check must fail)")
    p.add_argument("--write-cases", action="store_true")
    args = p.parse_args()
    if args.write_cases:
        write_cases()
        return 0
    if not args.binary and not args.analyse:
        p.error("give the grainstorm binary")
    global G
    v = VARIANTS[args.variant]
    deadline = budget_runs.deadline_from(args.budget_s)
    backends = [args.backend] if args.backend else os.environ.get("GS_TEST_BACKENDS", "cpu").split(",")
    failures = []
    for backend in backends:
        args.backend = backend
        work = os.path.abspath(args.analyse or args.keep or tempfile.mkdtemp(prefix="silo_"))
        os.makedirs(work, exist_ok=True)
        results = []
        try:
            if args.analyse:
                runs = [(os.path.join(work, case_name(d0)), float("nan"), run_status(os.path.join(work, case_name(d0))))
                        for d0 in v["orifices"]]
            else:
                batch = [make_run(args, args.variant, d0, work) for d0 in v["orifices"]]
                if args.budget_s:
                    budget_runs.print_plan("silo", args.binary, [(r.name, os.path.join(work, r.name + ".yaml"))
                                                                 for r in batch])
                budget_runs.run_all(batch, deadline, jobs=args.jobs, label="silo")
                failed = [r for r in batch if r.status == "failed"]
                if failed:
                    raise RuntimeError("%s failed with exit status %d" % (failed[0].name, failed[0].returncode))
                runs = [(os.path.join(work, r.name), r.wall(), r.status) for r in batch]
            todo = [(out, d0, seconds, status) for d0, (out, seconds, status) in zip(v["orifices"], runs)
                    if os.path.exists(os.path.join(out, "flow_orifice.csv"))]
            # The analysis (pure Python, seconds per run at full size) of all runs at once.
            with concurrent.futures.ProcessPoolExecutor(max_workers=max(1, min(len(todo), os.cpu_count() or 1))) as pool:
                futures = [pool.submit(measure, out, v, d0, seconds, status) for out, d0, seconds, status in todo]
                for (out, d0, _, status), f in zip(todo, futures):
                    try:
                        results.append(f.result())
                    except ValueError as e:
                        if status != "stopped":
                            raise
                        print("D0 = %g d: %s (stopped by the budget)" % (d0, e))
        except (RuntimeError, OSError, KeyError, ValueError, IndexError) as e:
            print("error:", e)
            return 2
        finally:
            if not args.keep and not args.analyse:
                shutil.rmtree(work, ignore_errors=True)
        if not results:
            print("error: no run in %s reached its measuring window (at least %.2f s of it)" % (work, MIN_WINDOW))
            return 2
        g_run, G = G, G * args.g_scale  # the analysis's g (the runs use 9.81)
        failures += report(results, v, args, backend, G)
        G = g_run
    for f in failures:
        print("FAIL:", f)
    print("silo: %s" % ("FAILED" if failures else "all checks passed"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
