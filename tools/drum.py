#!/usr/bin/env python3
"""Rotating drum: dynamic angle of repose and flow regime against the Froude
number and the rolling resistance (docs/VALIDATION.md, "Rotating drum").

    tools/drum.py BINARY [--variant ci|medium|full] [--backends cpu,cuda]
                  [--jobs N] [--keep DIR [--reuse] [--prune]] [--plots DIR]
                  [--budget-s S] [--save FILE.json]
    tools/drum.py --replot FILE.json [--plots DIR]
    tools/drum.py --write-cases

A drum of radius R along y, periodic along its axis (no end caps, so no cap
friction), is filled to 30 % with equal spheres by a random fill,
settles under gravity at rest, then turns at Fr = omega^2 R / g from
`settle` on. The tool writes one scene per (Fr, rolling_friction) case, runs
them, and reads the CSV snapshots of the last part of the run (the drum
turned by at least `transient` radians) to measure, in the drum's
cross-section (x, z):

* the angle of the bed's centroid: for a flat surface the bed is a circular
  segment, symmetric about the line from the axis through its centroid, so
  the surface is at right angles to that line;
* the free surface: in the frame of that first estimate, columns across the
  middle 80 % of the chord, each column's solid fraction profile (sphere
  volumes binned by centre, summed over the snapshots) and the height where it
  falls to half the bulk's; a line fitted to those heights corrects the angle
  (the dynamic angle of repose); the slope of the middle third of the surface
  against the outer thirds' measures its curvature (an S-shaped, cascading
  surface is steeper in the middle than at its ends);
* the airborne fraction: particles centred more than two diameters above the
  fitted surface (free flight: cataracting);
* the fraction above the axis and the particles' mean angular velocity about
  the axis against the drum's (centrifuging: a ring carried round with the
  wall).

The regime follows from those numbers by the thresholds below, which are
ours (docs/VALIDATION.md gives the reference regime map, Mellmann 2001).
--variant ci runs the CTest validation_drum (a few hundred spheres) and
asserts; medium and full print the table (and plots with --plots when
matplotlib is found). Exit status: 0 pass, 1 a check failed, 2 usage or
run error. Standard library only, except the optional plots.
"""
import argparse
import concurrent.futures
import glob
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import budget_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE_DIR = os.path.join(ROOT, "cases", "validation", "drum")
G = 9.81

# Sizes: drum radius R [m], periodic length L [m], sphere radius r [m],
# settle time [s], rotation to discard [rad] and to measure over [rad], the
# snapshots per measured radian, and the cases (Fr, rolling_friction).
VARIANTS = {
    "ci": dict(R=0.02, L=0.012, r=0.001, settle=0.25, transient=1.2, measure=0.8, per_rad=12,
               cases=[(0.01, 0.0), (0.01, 0.3), (3.0, 0.0)]),
    "medium": dict(R=0.03, L=0.012, r=0.001, settle=0.3, transient=1.5, measure=1.5, per_rad=10,
                   cases=[(1e-3, 0.0), (1e-2, 0.0), (3e-2, 0.0), (0.1, 0.0), (0.3, 0.0), (1.0, 0.0), (3.0, 0.0),
                          (1e-2, 0.1), (1e-2, 0.3)]),
    # The GPU run (bench/validation_drum_gpu.sh), sized for its wall budget:
    # 1.5 rad to reach the angle and 1.5 rad measured, a fast bed spun up
    # over 2 revolutions and measured over one, and no Fr = 1e-3 (at 0.44
    # rad/s it alone would take 2.6e5 steps, the budget's longest path).
    "full": dict(R=0.05, L=0.04, r=0.001, settle=0.4, transient=1.5, measure=1.5, per_rad=10, spin_up_turns=2,
                 cases=[(3e-3, 0.0), (1e-2, 0.0), (3e-2, 0.0), (0.1, 0.0), (0.3, 0.0),
                        (0.6, 0.0), (1.0, 0.0), (1.5, 0.0), (3.0, 0.0),
                        (1e-2, 0.1), (1e-2, 0.2), (1e-2, 0.4), (0.1, 0.3)]),
}
FILL = 0.30            # bed cross-section / drum cross-section, at the packing below
PACKING = 0.60         # solid fraction assumed for the settled bed (sets the count)
DENSITY = 2500.0       # glass [kg/m^3]
STIFFNESS = 500.0      # linear normal stiffness [N/m]: overlap under the bed's weight < 0.5 % of d
RESTITUTION = 0.5
FRICTION = 0.5         # sphere-sphere
WALL_FRICTION = 0.8    # sphere-drum: high, so that the bed does not slip on the smooth wall ...
WALL_ROLLING = 0.5     # ... nor roll on it like ball bearings (a rough drum's wall; docs/VALIDATION.md)
STEP_FRACTION = 0.1    # of the contact time
SPIN_UP_FROUDE = 0.3   # from here on the drum turns SPIN_UP_TURNS revolutions before measuring
SPIN_UP_TURNS = 3

# The surface is read over this fraction of the chord about its middle (the
# rest meets the wall, where the columns are too short for a bulk).
SURFACE_SPAN = 0.8
# Regime thresholds (ours; docs/VALIDATION.md).
CENTRIFUGE_ABOVE = 0.3      # fraction of particles above the axis ...
CENTRIFUGE_CORROTATE = 0.9  # ... turning with the drum at this fraction of its rate
CATARACT_AIRBORNE = 0.03    # fraction in free flight (> 2 d above the surface)
CASCADE_CURVATURE = 6.0     # middle slope minus the ends' slopes [deg]

# CI assertions (docs/VALIDATION.md says where the bounds come from).
CI_ANGLE_BOUNDS = (20.9, 36.0)   # mu = 0.5, no rolling resistance, rolling regime (Jop et al. 2005, widened above)
CI_WALL_LAYER = 0.9              # the layer on the wall turns with the drum (no slip)
CI_ROLLING_GAIN = 4.0            # degrees gained with rolling_friction 0.3


def omega(fr, R):
    return math.sqrt(fr * G / R)


def rotation_plan(v, fr):
    """Radians the drum turns before measuring and while measuring. A bed
    carried round the wall (Fr near or above 1) spins up over revolutions,
    not over the fraction of one that lifts a rolling bed to its angle."""
    if fr >= SPIN_UP_FROUDE:
        turns = v.get("spin_up_turns", SPIN_UP_TURNS)
        return max(v["transient"], turns * 2 * math.pi), max(v["measure"], 2 * math.pi)
    return v["transient"], v["measure"]


def case_name(fr, mu_r):
    return "fr%g_mur%g" % (fr, mu_r)


def scene_text(v, fr, mu_r, out_dir):
    R, L, r = v["R"], v["L"], v["r"]
    w = omega(fr, R)
    rotate = sum(rotation_plan(v, fr))
    duration = v["settle"] + rotate / w
    interval = rotation_plan(v, fr)[1] / (v["per_rad"] * v["measure"] * w)
    count = int(round(FILL * math.pi * R * R * L * PACKING / (4.0 / 3.0 * math.pi * r ** 3)))
    m = 1.2 * r  # domain margin beyond the drum
    return f"""# Rotating drum, Fr = {fr:g}, rolling_friction = {mu_r:g} (tools/drum.py, docs/VALIDATION.md).
# A drum of radius {R:g} m along y, periodic along its axis (no end caps), {100 * FILL:g} % full of
# {r * 2e3:g} mm glass spheres; it settles at rest, then turns from t = {v['settle']:g} s at
# omega = sqrt(Fr g / R) = {w:.6g} rad/s about +y (the bed is dragged towards -x and rises there).
domain: {{min: [{-R - m:.6g}, 0, {-R - m:.6g}], max: [{R + m:.6g}, {L:.6g}, {R + m:.6g}], periodic: [y]}}
gravity: [0, 0, -9.81]
contact_model: linear
effects: {{friction: true, rolling_resistance: true}}
materials:
  - {{name: glass, density: {DENSITY:g}}}
  - {{name: steel, density: 7800}}
pairs:
  - {{materials: [glass, glass], stiffness_normal: {STIFFNESS:g}, restitution: {RESTITUTION:g}, friction: {FRICTION:g}, rolling_friction: {mu_r:g}}}
  - {{materials: [glass, steel], stiffness_normal: {STIFFNESS:g}, restitution: {RESTITUTION:g}, friction: {WALL_FRICTION:g}, rolling_friction: {WALL_ROLLING:g}}}
walls:
  - name: drum
    material: steel
    cylinder: {{base: [0, 0, 0], axis: [0, 1, 0], radius: {R:g}, length: {L:g}, caps: none}}
    motion: {{rotation: {{axis_point: [0, 0, 0], axis: [0, 1, 0], angular_speed: {w:.9g}}}, start: {v['settle']:g}}}
particles:
  - random_fill:
      material: glass
      region: {{cylinder: {{base: [0, {r:g}, 0], axis: [0, 1, 0], radius: {R - r:.6g}, length: {L - 2 * r:.6g}}}}}
      count: {count}
      radius: {r:g}
      seed: 1
time_step: {{fraction_of_contact_time: {STEP_FRACTION:g}}}
duration: {duration:.6g}
output: {{interval: {interval:.6g}, format: csv, directory: {out_dir}}}
"""


def read_csv(path):
    """(time, [(radius, x, z, vx, vz)]) of a CSV snapshot; its first line is
    '# grainstorm particles, time <t> s, step <n>'."""
    with open(path) as f:
        time = float(f.readline().split("time")[1].split()[0])
        cols = f.readline().strip().split(",")
        ix = [cols.index(c) for c in ("radius", "x", "z", "vx", "vz")]
        rows = [line.split(",") for line in f if line.strip()]
    return time, [tuple(float(p[i]) for i in ix) for p in rows]


def measure(v, fr, files):
    """Angle [deg], curvature [deg], airborne, above-axis and co-rotation
    fractions, and the angle's spread over the snapshots."""
    R, r = v["R"], v["r"]
    w = omega(fr, R)
    t_from = v["settle"] + rotation_plan(v, fr)[0] / w
    snaps = [s for t, s in map(read_csv, files) if t >= t_from - 1e-9]
    if len(snaps) < 3:
        raise RuntimeError("only %d snapshots in the measuring window" % len(snaps))
    # Centroid angle per snapshot: positive when the bed is dragged the way
    # the drum turns (towards -x for a turn about +y).
    per_snap = []
    above, corot, wall, n_wall = 0.0, 0.0, 0.0, 0
    n_all = 0
    for s in snaps:
        xc = sum(p[1] for p in s) / len(s)
        zc = sum(p[2] for p in s) / len(s)
        per_snap.append(math.degrees(math.atan2(-xc, -zc)))
        above += sum(1 for p in s if p[2] > 0)
        # angular velocity about +y of each particle: (z vx - x vz) / rho^2
        corot += sum((p[2] * p[3] - p[1] * p[4]) / max(p[1] ** 2 + p[2] ** 2, 1e-30) for p in s) / w
        n_all += len(s)
        # the layer touching the drum: its centres turn at about (R - r) / R omega without slip
        for rad, x, z, vx, vz in s:
            rho2 = x * x + z * z
            if rho2 > (R - 1.5 * rad) ** 2:
                wall += (z * vx - x * vz) / rho2 / w
                n_wall += 1
    above /= n_all
    corot /= n_all
    theta0 = sum(per_snap) / len(per_snap)
    spread = (sum((a - theta0) ** 2 for a in per_snap) / len(per_snap)) ** 0.5
    res = dict(centroid_angle=theta0, angle_spread=spread, above=above, corotation=corot,
               wall_layer=wall / max(n_wall, 1), snapshots=len(snaps),
               angle=float("nan"), curvature=float("nan"), airborne=float("nan"))
    if above > CENTRIFUGE_ABOVE:
        return res
    # Frame of the first estimate: n points from the bed's centroid side to
    # the free surface (away from the centroid), u along the surface.
    t = math.radians(theta0)
    nx, nz = math.sin(t), math.cos(t)        # unit normal to the surface, upwards
    ux, uz = nz, -nx                         # along the surface
    # The chord's distance from the axis for a flat segment of this fill.
    h0 = chord_distance(FILL)
    half_chord = R * math.sqrt(1 - h0 * h0)
    col = 2.0 * (2 * r)
    ncol = max(3, int(2 * SURFACE_SPAN * half_chord / col))
    u0 = -ncol * col / 2
    dn = r / 2
    nbin = int(2.2 * R / dn)
    vol = [[0.0] * nbin for _ in range(ncol)]
    for s in snaps:
        for rad, x, z, _, _ in s:
            u, n = x * ux + z * uz, x * nx + z * nz
            i, k = int(math.floor((u - u0) / col)), int(math.floor((n + 1.1 * R) / dn))
            if 0 <= i < ncol and 0 <= k < nbin:
                vol[i][k] += 4.0 / 3.0 * math.pi * rad ** 3
    bulk_cell = col * dn * v["L"] * len(snaps)
    us, ns = [], []
    for i in range(ncol):
        phi = [c / bulk_cell for c in vol[i]]
        n_s = surface_height(phi, dn, -1.1 * R, -h0 * R, r)
        if n_s is not None:
            us.append(u0 + (i + 0.5) * col)
            ns.append(n_s)
    if len(us) < 3:
        return res
    slope = fit_slope(us, ns)
    # The surface rises towards -u (the side the bed is dragged to) when the
    # first estimate is too small: add the residual slope.
    res["angle"] = theta0 - math.degrees(math.atan(slope))
    third = max(2, len(us) // 3)
    mid = slice((len(us) - third) // 2, (len(us) - third) // 2 + third)
    s_mid = fit_slope(us[mid], ns[mid])
    s_lo = fit_slope(us[:third], ns[:third])
    s_hi = fit_slope(us[-third:], ns[-third:])
    res["curvature"] = math.degrees(math.atan(-s_mid)) - 0.5 * (
        math.degrees(math.atan(-s_lo)) + math.degrees(math.atan(-s_hi)))
    # Airborne: centred more than two diameters above the fitted surface line.
    a = sum(ns) / len(ns) - slope * sum(us) / len(us)
    air = 0
    for s in snaps:
        for rad, x, z, _, _ in s:
            u, n = x * ux + z * uz, x * nx + z * nz
            if n > a + slope * u + 4 * r:
                air += 1
    res["airborne"] = air / n_all
    return res


def chord_distance(fill):
    """h (in R) of the chord that cuts a circular segment of area fill * pi R^2
    below it: (acos(h) - h sqrt(1 - h^2)) / pi = fill, by bisection."""
    lo, hi = -1.0, 1.0
    for _ in range(60):
        h = 0.5 * (lo + hi)
        if (math.acos(h) - h * math.sqrt(1 - h * h)) / math.pi > fill:
            lo = h
        else:
            hi = h
    return 0.5 * (lo + hi)


def surface_height(phi, dn, n_min, n_guess, r):
    """Where the column's solid fraction falls to half the bulk's, searching
    down from the top; the bulk is the mean over the 4 r below the first
    estimate's surface less 3 r."""
    k_guess = int((n_guess - n_min) / dn)
    lo = max(0, k_guess - int(7 * r / dn))
    hi = max(lo + 1, k_guess - int(3 * r / dn))
    bulk = sum(phi[lo:hi]) / (hi - lo)
    if bulk < 0.2:
        return None
    half = 0.5 * bulk
    # smooth over one diameter (centre binning leaves a layering)
    w = max(1, int(2 * r / dn))
    sm = [sum(phi[max(0, k - w // 2):k + w // 2 + 1]) / len(phi[max(0, k - w // 2):k + w // 2 + 1])
          for k in range(len(phi))]
    for k in range(len(sm) - 1, lo, -1):
        if sm[k - 1] >= half > sm[k]:
            f = (sm[k - 1] - half) / (sm[k - 1] - sm[k])
            return n_min + (k - 0.5 + f) * dn
    return None


def fit_slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0


def regime(m):
    if m["above"] > CENTRIFUGE_ABOVE and m["corotation"] > CENTRIFUGE_CORROTATE:
        return "centrifuging"
    if m["above"] > CENTRIFUGE_ABOVE:
        return "cataracting"
    if m["airborne"] > CATARACT_AIRBORNE:
        return "cataracting"
    if m["curvature"] > CASCADE_CURVATURE:
        return "cascading"
    return "rolling"


def prepare_case(binary, backend, v, fr, mu_r, work, reuse):
    """Writes one case's scene; returns its run (budget_runs.Run), or None
    where --reuse finds a finished run of the very same scene."""
    name = case_name(fr, mu_r)
    out = os.path.join(work, backend, name)
    scene = os.path.join(work, backend, name + ".yaml")
    os.makedirs(os.path.dirname(scene), exist_ok=True)
    text = scene_text(v, fr, mu_r, out)
    if reuse and same_run(scene, text, os.path.join(out, "run.log")):
        return None
    if os.path.isdir(out):
        shutil.rmtree(out)
    with open(scene, "w") as f:
        f.write(text)
    return budget_runs.Run("%s/%s" % (backend, name), [binary, "run", scene, "--backend", backend, "--out", out],
                           os.path.join(work, backend, name + ".log"))


def measure_case(backend, v, fr, mu_r, work, prune):
    """The measured numbers of one case's run directory (a run stopped by the
    budget: over the snapshots of the window it reached)."""
    out = os.path.join(work, backend, case_name(fr, mu_r))
    files = sorted(glob.glob(os.path.join(out, "particles_*.csv")))
    m = measure(v, fr, files)
    m["last"] = [(round(x, 7), round(z, 7)) for _, x, z, _, _ in read_csv(files[-1])[1]]  # to 0.1 um, enough for a plot
    with open(os.path.join(out, "run.log")) as f:
        lines = f.readlines()
    done = [line.strip() for line in lines if line.startswith("done:")]
    stopped = [line.strip() for line in lines if line.startswith("stopped by a signal")]
    m["run"] = done[-1] if done else (stopped[-1] if stopped else "")
    m["complete"] = bool(done)
    if prune:  # the snapshots of a full run take gigabytes; keep the logs
        for f in files:
            os.remove(f)
    return m


def planned_snapshots(v, fr):
    """Snapshots the measuring window holds when the run completes: those at
    multiples of the output interval from the window's start to the end (and
    the last, which the run writes at its end)."""
    w = omega(fr, v["R"])
    t_from = v["settle"] + rotation_plan(v, fr)[0] / w
    interval = rotation_plan(v, fr)[1] / (v["per_rad"] * v["measure"] * w)
    end = run_seconds(v, fr)
    times = [k * interval for k in range(int(end / interval) + 1)]
    if end - times[-1] > 1e-9:
        times.append(end)
    return sum(1 for t in times if t >= t_from - 1e-9)


def run_seconds(v, fr):
    """Simulated seconds of a case."""
    return v["settle"] + sum(rotation_plan(v, fr)) / omega(fr, v["R"])


def same_run(scene, text, log):
    """A finished earlier run of this very scene, its snapshots kept."""
    try:
        with open(scene) as f, open(log) as g:
            return f.read() == text and any(line.startswith("done:") for line in g)
    except OSError:
        return False


def fmt(x, f="%.1f"):
    return "-" if x != x else f % x


def print_table(results, v):
    print("drum R = %g m (D/d = %g), periodic length %g m, fill %.0f %%, mu = %g, wall mu = %g, e = %g"
          % (v["R"], v["R"] / v["r"], v["L"], 100 * FILL, FRICTION, WALL_FRICTION, RESTITUTION))
    head = "| backend | Fr | rolling_friction | omega [rad/s] | angle [deg] | centroid angle [deg] | spread [deg] | curvature [deg] | airborne | above axis | co-rotation | wall layer | regime | snapshots measured |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for (backend, fr, mu_r), m in results:
        print("| %s | %g | %g | %.4g | %s | %s | %s | %s | %s | %.3f | %.3f | %.2f | %s | %d of %d%s |" % (
            backend, fr, mu_r, omega(fr, v["R"]), fmt(m["angle"]), fmt(m["centroid_angle"]),
            fmt(m["angle_spread"]), fmt(m["curvature"]), fmt(m["airborne"], "%.3f"),
            m["above"], m["corotation"], m["wall_layer"], regime(m), m["snapshots"], planned_snapshots(v, fr),
            "" if m.get("complete", True) else " (stopped by the budget)"))


def check_ci(results):
    failed = 0

    def check(ok, what):
        nonlocal failed
        print("%s: %s" % ("ok" if ok else "FAIL", what))
        failed += not ok

    by = {}
    for (backend, fr, mu_r), m in results:
        by.setdefault(backend, {})[(fr, mu_r)] = m
    for backend, ms in by.items():
        missing = [k for k in ((0.01, 0.0), (0.01, 0.3), (3.0, 0.0)) if k not in ms]
        if missing:   # a run a budget stopped before its measuring window
            check(False, "%s: no measurement of the case(s) Fr, rolling_friction = %s" % (backend, missing))
            continue
        plain, rolling, fast = ms[(0.01, 0.0)], ms[(0.01, 0.3)], ms[(3.0, 0.0)]
        lo, hi = CI_ANGLE_BOUNDS
        check(lo <= plain["angle"] <= hi,
              "%s: Fr 0.01, mu 0.5: dynamic angle %.1f deg within [%g, %g]" % (backend, plain["angle"], lo, hi))
        check(regime(plain) == "rolling", "%s: Fr 0.01 rolls (regime %s)" % (backend, regime(plain)))
        check(plain["wall_layer"] >= CI_WALL_LAYER, "%s: Fr 0.01: the layer on the wall turns at %.2f of the drum's rate (at least %g)"
              % (backend, plain["wall_layer"], CI_WALL_LAYER))
        check(rolling["angle"] >= plain["angle"] + CI_ROLLING_GAIN,
              "%s: rolling_friction 0.3 raises the angle by %.1f deg (at least %g)"
              % (backend, rolling["angle"] - plain["angle"], CI_ROLLING_GAIN))
        check(regime(fast) == "centrifuging",
              "%s: Fr 3 centrifuges (above axis %.2f, co-rotation %.2f)" % (backend, fast["above"], fast["corotation"]))
    return failed


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary", nargs="?")
    ap.add_argument("--variant", choices=sorted(VARIANTS), default="ci")
    ap.add_argument("--backends", default=os.environ.get("GS_TEST_BACKENDS", "cpu"))
    ap.add_argument("--jobs", type=int, default=1, help="cases run at once")
    ap.add_argument("--keep", help="run in this directory and keep it")
    ap.add_argument("--reuse", action="store_true",
                    help="with --keep: measure a finished earlier run of the same scene instead of running it again")
    ap.add_argument("--prune", action="store_true", help="with --keep: delete the snapshots once measured")
    ap.add_argument("--plots", help="write matplotlib plots here")
    ap.add_argument("--save", help="write the results (and each case's last cross-section) to this JSON file")
    ap.add_argument("--replot", help="the table and the plots (into --plots) of a --save file; no runs")
    ap.add_argument("--budget-s", type=float, help="wall seconds for the runs: then what still runs is stopped "
                    "(SIGTERM) and measured over the snapshots it wrote")
    ap.add_argument("--write-cases", action="store_true", help="(re)write cases/validation/drum/")
    a = ap.parse_args()
    if a.write_cases:
        write_cases()
        return 0
    if a.replot:
        with open(a.replot) as f:
            saved = json.load(f)
        v = VARIANTS[saved["variant"]]
        results = [(tuple(k), m) for k, m in saved["results"]]
        print_table(results, v)
        from drum_plots import plot  # matplotlib only when asked for
        plot(results, v, a.plots or ".", regime)
        return 0
    if not a.binary:
        ap.error("BINARY is required")
    v = VARIANTS[a.variant]
    deadline = budget_runs.deadline_from(a.budget_s)   # the plan's checks count too
    work = a.keep or tempfile.mkdtemp(prefix="drum_")
    jobs = [(b, fr, mu_r) for b in a.backends.split(",") for fr, mu_r in v["cases"]]
    # Longest first: with a budget, the long runs set the wall time.
    jobs.sort(key=lambda j: -run_seconds(v, j[1]))
    results = []
    try:
        runs = [prepare_case(a.binary, b, v, fr, mu_r, work, a.reuse) for b, fr, mu_r in jobs]
        if a.budget_s:
            budget_runs.print_plan("drum", a.binary, [(r.name, r.cmd[2]) for r in runs if r])
        budget_runs.run_all([r for r in runs if r], deadline, jobs=max(1, a.jobs),
                            label="drum")
        failed = [r for r in runs if r and r.status == "failed"]
        if failed:
            raise RuntimeError("%s failed with exit code %d:\n%s" % (failed[0].name, failed[0].returncode,
                                                                      failed[0].output()))
        with concurrent.futures.ProcessPoolExecutor(max_workers=max(1, min(len(jobs), os.cpu_count() or 1))) as ex:
            futs = [ex.submit(measure_case, b, v, fr, mu_r, work, a.prune) for b, fr, mu_r in jobs]
            for j, r, f in zip(jobs, runs, futs):
                try:
                    results.append((j, f.result()))
                except (RuntimeError, IndexError, OSError) as e:
                    if r is None or r.status not in ("stopped", "not started"):
                        raise
                    print("%s %s: %s by the budget before its measuring window (%s)" % (
                        j[0], case_name(*j[1:]), r.status, e))
    except (RuntimeError, OSError) as e:
        sys.stderr.write("drum: %s\n" % e)
        return 2
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    results.sort(key=lambda jm: (jm[0][0], jm[0][2], jm[0][1]))
    if a.save:   # the measured numbers and each case's last cross-section: --replot makes the plots elsewhere
        with open(a.save, "w") as f:
            json.dump(dict(variant=a.variant, results=[[list(k), m] for k, m in results]), f)
    print_table(results, v)
    for (backend, fr, mu_r), m in results:
        print("%s %s: %s" % (backend, case_name(fr, mu_r), m["run"]))
    if a.plots:
        from drum_plots import plot  # matplotlib only when asked for
        plot(results, v, a.plots, regime)
    if a.variant == "ci":
        failed = check_ci(results)
        print("%d check(s) failed" % failed if failed else "all checks passed")
        return 1 if failed else 0
    return 0


def write_cases():
    """The medium variant's scenes, to run by hand (outputs under out/drum/)."""
    v = VARIANTS["medium"]
    os.makedirs(CASE_DIR, exist_ok=True)
    for fr, mu_r in v["cases"]:
        name = case_name(fr, mu_r)
        with open(os.path.join(CASE_DIR, name + ".yaml"), "w") as f:
            f.write(scene_text(v, fr, mu_r, "out/drum/" + name))


if __name__ == "__main__":
    sys.exit(main())
