#!/usr/bin/env python3
"""Inclined chute flow on a rough base against Silbert et al. (2001).

    tools/chute_flow.py BINARY [--preset ci|medium|full] [--out DIR] [--backend cpu|cuda]
                        [--jobs N] [--write-cases]

L.E. Silbert, D. Ertas, G.S. Grest, T.C. Halsey, D. Levine, S.J. Plimpton,
"Granular flow down an inclined plane: Bagnold scaling and rheology",
Phys. Rev. E 64, 051302 (2001).

A layer of equal spheres (diameter d) on a base of frozen spheres, periodic
in the flow (x) and cross (y) directions, gravity tilted by the inclination
theta. Lengths in d, times in tau = sqrt(d/g), velocities in sqrt(g d). For
each angle the tool writes a scene, runs it, and reads the layer averages
(`measurements: averages`, one slab of height d per layer, docs/MEASUREMENTS.md):

  * the velocity profile u(z), time-averaged over the second half of the run,
    fitted by Bagnold's u(z) = A (h^(3/2) - (h - z)^(3/2)), z above the base
    and h the flowing height (where the solid fraction falls to half its bulk
    value), A by least squares; the rms residual over the layer relative to
    the surface velocity, and those of the best linear (simple shear) and
    plug (constant) profiles for comparison;
  * the bulk solid fraction (mean over the middle half of the layer);
  * whether the layer stops (kinetic energy per mass below STOPPED g d at
    the end) or flows; the flow/no-flow angle between the highest angle that
    stops and the lowest that flows (narrowed by bisection for a preset with
    `bracket` steps).

Each run starts from a pour in simple shear (START_SHEAR_RATE), so that a
Bagnold profile at the end is the flow's own, not the start's.

Presets: `ci` (the CTest validation_chute: one flowing and one stopping run
of 1651 particles, asserting a steady flow with the Bagnold shape at 24 deg
and a stop at 14 deg), `medium` (the same layer at six angles, the CPU
numbers in docs/VALIDATION.md), `full` (the GPU run of
bench/validation_chute_gpu.sh: a 20 d x 10 d box and H = 20, contacts 10x softer
than Silbert's, ten angles side by side, 200 tau). --budget-s stops the runs
still going after that many seconds (SIGTERM) and analyses each over the
time it reached. --reuse re-reads runs kept in
--work (a run of the same preset and angle) instead of running them. Tables (Markdown and CSV) and,
where matplotlib is installed, plots go to --out.

Exit status 0 when every check holds, 1 when one fails, 2 on a usage or run
error. Standard library only (matplotlib optional, for the plots).
"""
import argparse
import concurrent.futures
import csv
import glob
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import budget_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE_DIR = os.path.join(ROOT, "cases", "validation", "chute")

# Units: d = 2 mm glass-like spheres, g = 9.81 m/s^2.
D = 0.002
G = 9.81
DENSITY = 2500.0
TAU = math.sqrt(D / G)
MASS = DENSITY * math.pi / 6 * D**3

# Silbert's contact (their "L3"): k_n = 2e5 m g / d, k_t = 2/7 k_n,
# restitution 0.88, friction 0.5, no rolling resistance.
RESTITUTION = 0.88
FRICTION = 0.5
BASE_AREAL_DENSITY = 1.2   # frozen base spheres per d^2
BASE_THICKNESS = 2.2       # the base's region, in d: centres between 0.5 and 1.7 d
STOPPED = 1e-4             # kinetic energy per mass below this (in g d) at the end: stopped
FILL_FRACTION = 0.25       # solid fraction of the poured layer's random fills
DECAYING = 0.25            # an energy fall over the last quarter that says the flow is dying out
START_SHEAR_RATE = 0.4     # the poured layer's initial shear rate, in 1/tau

# Checks of the ci preset (set from measurement with margin: docs/VALIDATION.md).
CI_BAGNOLD_RESIDUAL = 0.03  # rms residual / surface velocity (measured 0.009)
CI_STEADY = 0.1             # relative change of the kinetic energy between the last two quarters of the run

PRESETS = {
    # stiffness in m g / d; lengths in d; times in tau
    "ci": dict(stiffness=2e3, step_fraction=0.05, lx=12, ly=8, height=16, duration=100, sample_every=1.0,
               flow_angles=[24.0], stop_angles=[14.0], bracket=0, jobs=1),
    "medium": dict(stiffness=2e3, step_fraction=0.05, lx=12, ly=8, height=16, duration=100, sample_every=1.0,
                   flow_angles=[17.0, 20.0, 22.0, 24.0, 26.0], stop_angles=[14.0], bracket=0, jobs=2),
    # The GPU run (bench/validation_chute_gpu.sh), sized for its wall budget:
    # a 20 d x 10 d box (Silbert's, from memory) and H = 20, contacts 10x softer than
    # Silbert's (overlaps still ~1e-3 d at the base), t_c / 10 steps, 200 tau,
    # ten angles side by side (no bisection: its runs would follow each other).
    "full": dict(stiffness=2e4, step_fraction=0.1, lx=20, ly=10, height=20, duration=200, sample_every=1.0,
                 flow_angles=[18.0, 19.0, 20.0, 21.0, 22.0, 23.0, 24.0, 25.0, 26.0], stop_angles=[17.0], bracket=0,
                 jobs=10),
}


def layer_count(p):
    """Slabs of height d from the plane up to well above the free surface."""
    return int(math.ceil(BASE_THICKNESS + 1.6 * p["height"] + 4))


def scene_text(p, theta, out_dir):
    """The scene of one run at inclination theta (degrees)."""
    lx, ly, h = p["lx"] * D, p["ly"] * D, p["height"]
    n_flow = int(round(h * p["lx"] * p["ly"]))     # Silbert's H = N d^2 / (Lx Ly)
    n_base = int(round(BASE_AREAL_DENSITY * p["lx"] * p["ly"]))
    fill_top = BASE_THICKNESS + n_flow * math.pi / 6 / (FILL_FRACTION * p["lx"] * p["ly"])
    layers = layer_count(p)
    top = max(fill_top + 1, layers) * D
    k = p["stiffness"] * MASS * G / D
    t = math.radians(theta)
    duration = p["duration"] * TAU
    every = p["sample_every"] * TAU
    lines = [
        "# Inclined chute flow on a rough base (Silbert et al., Phys. Rev. E 64, 051302, 2001),",
        "# written by tools/chute_flow.py: docs/VALIDATION.md, \"Inclined chute flow\".",
        f"# theta = {theta} deg, H = {h} d (N d^2 / area), k_n = {p['stiffness']:g} m g / d, d = {D} m.",
        f"domain: {{min: [0, 0, 0], max: [{lx:.6g}, {ly:.6g}, {top:.6g}], periodic: [x, y]}}",
        f"gravity: [{G * math.sin(t):.10g}, 0, {-G * math.cos(t):.10g}]",
        "contact_model: linear",
        "effects: {friction: true}",
        "materials:",
        f"  - {{name: glass, density: {DENSITY:g}}}",
        "pairs:",
        f"  - {{materials: [glass, glass], stiffness_normal: {k:.10g}, restitution: {RESTITUTION}, friction: {FRICTION}}}",
        "walls:",
        "  - {name: floor, material: glass, plane: {point: [0, 0, 0], normal: [0, 0, 1]}}",
        f"  - {{name: lid, material: glass, plane: {{point: [0, 0, {top:.6g}], normal: [0, 0, -1]}}}}",
        "particles:",
        "  - random_fill:        # the rough base: frozen spheres in a slab 2.2 d thick",
        "      material: glass",
        f"      region: {{box: {{min: [0, 0, 0], max: [{lx:.6g}, {ly:.6g}, {BASE_THICKNESS * D:.6g}]}}}}",
        f"      count: {n_base}",
        f"      radius: {D / 2:g}",
        "      seed: 1",
        "      frozen: true",
    ]
    # The flowing layer, poured at FILL_FRACTION in slabs that start in simple
    # shear, u = START_SHEAR_RATE z (a fill slab at height s above the base
    # lands near s * FILL_FRACTION / 0.58): the run then relaxes towards its
    # own steady state, or stops, instead of first accelerating from rest,
    # and a Bagnold profile at the end is the flow's, not the start's.
    slabs = max(2, int(round(h / 2)))
    per_slab = [n_flow // slabs + (1 if j < n_flow % slabs else 0) for j in range(slabs)]
    thickness = (fill_top - BASE_THICKNESS) / slabs
    for j in range(slabs):
        lo = BASE_THICKNESS + j * thickness
        landed = (j + 0.5) * thickness * FILL_FRACTION / 0.58
        u0 = START_SHEAR_RATE * landed * math.sqrt(G * D)
        lines += [
            f"  - random_fill:        # flowing layer, slab {j + 1} of {slabs}",
            "      material: glass",
            f"      region: {{box: {{min: [0, 0, {lo * D:.6g}], max: [{lx:.6g}, {ly:.6g}, {(lo + thickness) * D:.6g}]}}}}",
            f"      count: {per_slab[j]}",
            f"      radius: {D / 2:g}",
            f"      velocity: [{u0:.6g}, 0, 0]",
            f"      seed: {j + 2}",
        ]
    lines += [
        f"time_step: {{fraction_of_contact_time: {p['step_fraction']}}}",
        f"duration: {duration:.6g}",
        f"output: {{interval: 0, directory: {out_dir}, format: csv}}",
        "measurements:",
        "  averages:",
        f"    - {{name: all, box: {{min: [0, 0, 0], max: [{lx:.6g}, {ly:.6g}, {top:.6g}]}}, "
        f"quantities: [velocity, granular_temperature], every: {every:.6g}}}",
    ]
    for i in range(layers):
        lines.append(f"    - {{name: z{i:03d}, box: {{min: [0, 0, {i * D:.6g}], max: [{lx:.6g}, {ly:.6g}, {(i + 1) * D:.6g}]}}, "
                     f"quantities: [solid_fraction, velocity], every: {every:.6g}, start: {duration / 2:.6g}}}")
    return "\n".join(lines) + "\n"


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def mean(xs):
    return sum(xs) / len(xs) if xs else float("nan")


def angle_dir(work, theta):
    return os.path.join(work, f"theta_{theta:.3f}".replace(".", "p"))


def prepare_angle(binary, backend, p, theta, work, reuse=False):
    """Writes one angle's scene; returns its run (budget_runs.Run), or None
    where `reuse` finds an earlier run of it in `work`."""
    d = angle_dir(work, theta)
    os.makedirs(d, exist_ok=True)
    scene = os.path.join(d, "scene.yaml")
    out = os.path.join(d, "out")
    if reuse and os.path.exists(os.path.join(out, "average_all.csv")):
        return None
    with open(scene, "w") as f:
        f.write(scene_text(p, theta, "out"))
    return budget_runs.Run(f"theta {theta:g}", [binary, "run", scene, "--backend", backend, "--out", out, "--overwrite"],
                           os.path.join(d, "run.txt"))


def run_angles(binary, backend, p, thetas, work, reuse, jobs, deadline):
    """Runs the angles side by side (at most `jobs` at once) and analyses
    them; a run the deadline stopped is analysed over the time it reached."""
    runs = [prepare_angle(binary, backend, p, t, work, reuse) for t in thetas]
    if deadline:
        budget_runs.print_plan("chute", binary, [(r.name, r.cmd[2]) for r in runs if r])
    budget_runs.run_all([r for r in runs if r], deadline, jobs=jobs, label="chute")
    results = []
    for theta, r in zip(thetas, runs):
        if r and r.status == "failed":
            raise RuntimeError(f"theta {theta}: grainstorm exited {r.returncode}:\n{r.output()}")
        if r and r.status == "not started":
            print(f"theta {theta}: not started (budget)")
            continue
        res = analyse(p, theta, os.path.join(angle_dir(work, theta), "out"), r.wall() if r else float("nan"))
        res["complete"] = r is None or r.status == "done"
        results.append(res)
    return results


def analyse(p, theta, out, wall):
    sgd = math.sqrt(G * D)
    energy = []
    for row in read_csv(os.path.join(out, "average_all.csv")):
        v2 = sum(float(row[f"velocity_{a}"]) ** 2 for a in "xyz")
        energy.append((float(row["time"]) / TAU, (0.5 * v2 + 1.5 * float(row["granular_temperature"])) / (G * D)))
    z, phi, u = [], [], []
    sampled = 0
    for i in range(layer_count(p)):
        rows = read_csv(os.path.join(out, f"average_z{i:03d}.csv"))
        sampled = max(sampled, len(rows))
        z.append(i + 0.5)
        phi.append(mean([float(r["solid_fraction"]) for r in rows]))
        u.append(mean([float(r["velocity_x"]) for r in rows if int(r["particles"]) > 0] or [0.0]) / sgd)
    # Steadiness: the kinetic energy's change between the last two quarters of the run.
    t_end = energy[-1][0]
    third = mean([e for t, e in energy if 0.5 * t_end < t <= 0.75 * t_end])
    fourth = mean([e for t, e in energy if t > 0.75 * t_end])
    res = dict(theta=theta, wall=wall, energy=energy, z=z, phi=phi, u=u, final_energy=energy[-1][1],
               stopped=energy[-1][1] < STOPPED, drift=(fourth - third) / third if third > 0 else float("nan"),
               t_end=t_end, samples=sampled)
    if sampled == 0:   # stopped (by a budget) before the profile's averaging window began
        res.update(h=float("nan"), bulk_phi=float("nan"), amplitude=0.0, surface_u=0.0,
                   residual=dict(bagnold=float("nan"), linear=float("nan"), plug=float("nan")), fit_points=[])
        return res
    res.update(fit_profiles(z, phi, u))
    return res


def least_squares_amplitude(f, ys):
    """A minimising sum (y - A f)^2."""
    ff = sum(a * a for a in f)
    return sum(a * y for a, y in zip(f, ys)) / ff if ff > 0 else 0.0


def fit_profiles(z, phi, u):
    """Bagnold, linear and plug fits of u over the flowing layer (above the base)."""
    base = BASE_THICKNESS
    above = [k for k, zk in enumerate(z) if zk > base]
    bulk_phi = max(phi[k] for k in above) if above else 0.0
    # The free surface: the first layer above the base's top where phi falls below half the bulk.
    surface = next((z[k] for k in above if z[k] > base + 2 and phi[k] < 0.5 * bulk_phi), z[-1])
    h = surface - base
    pts = [k for k in above if z[k] < surface]
    zs = [z[k] - base for k in pts]
    us = [u[k] for k in pts]
    if len(pts) < 3 or max(us) <= 0:
        return dict(h=h, bulk_phi=float("nan"), amplitude=0.0, surface_u=0.0,
                    residual=dict(bagnold=float("nan"), linear=float("nan"), plug=float("nan")), fit_points=pts)
    shapes = {
        "bagnold": [h**1.5 - max(h - s, 0.0) ** 1.5 for s in zs],
        "linear": list(zs),
        "plug": [1.0 for _ in zs],
    }
    scale = max(us)
    residual, amplitude = {}, {}
    for name, f in shapes.items():
        a = least_squares_amplitude(f, us)
        amplitude[name] = a
        residual[name] = math.sqrt(mean([(y - a * fk) ** 2 for y, fk in zip(us, f)])) / scale
    middle = [phi[k] for k in pts if 0.25 * h <= z[k] - base <= 0.75 * h]
    return dict(h=h, bulk_phi=mean(middle), amplitude=amplitude["bagnold"], surface_u=scale,
                residual=residual, fit_points=pts)


def bracket(binary, backend, p, work, low, high, steps, reuse):
    """Bisects the flow/no-flow angle between `low` (stops) and `high` (flows)."""
    runs = []
    for _ in range(steps):
        mid = 0.5 * (low + high)
        r = run_angles(binary, backend, p, [mid], work, reuse, 1, None)[0]
        runs.append(r)
        if r["stopped"]:
            low = mid
        else:
            high = mid
    return low, high, runs


def end_state(r):
    """stops, or flows; flows (decaying) when the energy fell by more than DECAYING in the last quarter."""
    if r["stopped"]:
        return "stops"
    return "flows (decaying)" if r["drift"] < -DECAYING else "flows"


def describe(r):
    res = r["residual"]
    return (f"| {r['theta']:.2f} | {end_state(r)} | {r['final_energy']:.3g} | {r['drift']:+.3f} | "
            f"{r['h']:.1f} | {r['bulk_phi']:.3f} | {r['surface_u']:.2f} | {r['amplitude']:.4f} | "
            f"{res['bagnold']:.3f} | {res['linear']:.3f} | {res['plug']:.3f} | {r['t_end']:.0f}"
            f"{'' if r.get('complete', True) else ' (stopped by the budget)'} | {r['wall']:.0f} |")


def write_tables(out, p, preset, results, bracket_result):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "chute_summary.md"), "w") as f:
        f.write(f"preset {preset}: {p}\n\n")
        f.write("| theta [deg] | end state | E_kin/(m g d) at end | E_kin change, last quarter | h [d] | bulk phi | u_surface [sqrt(gd)] | "
                "Bagnold A | residual Bagnold | residual linear | residual plug | t reached [tau] | wall [s] |\n")
        f.write("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in sorted(results, key=lambda r: r["theta"]):
            f.write(describe(r) + "\n")
        if bracket_result:
            f.write(f"\nflow/no-flow angle between {bracket_result[0]:.3f} and {bracket_result[1]:.3f} deg\n")
    with open(os.path.join(out, "chute_profiles.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["theta_deg", "z_over_d", "solid_fraction", "u_over_sqrt_gd", "bagnold_fit"])
        for r in sorted(results, key=lambda r: r["theta"]):
            for zk, ph, uk in zip(r["z"], r["phi"], r["u"]):
                s = zk - BASE_THICKNESS
                fit = r["amplitude"] * (r["h"] ** 1.5 - max(r["h"] - s, 0.0) ** 1.5) if 0 < s < r["h"] else ""
                w.writerow([r["theta"], zk, ph, uk, fit])
    with open(os.path.join(out, "chute_energy.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["theta_deg", "t_over_tau", "kinetic_energy_over_m_g_d"])
        for r in sorted(results, key=lambda r: r["theta"]):
            for t, e in r["energy"]:
                w.writerow([r["theta"], t, e])


def plot(out, results):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib not found: no plots (the tables are written)")
        return
    flowing = sorted([r for r in results if not r["stopped"] and r["samples"] > 0], key=lambda r: r["theta"])
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    for r in flowing:
        line, = ax[0].plot(r["u"], r["z"], "o", ms=3, label=f"{r['theta']:.1f} deg")
        zs = [BASE_THICKNESS + r["h"] * k / 50 for k in range(51)]
        ax[0].plot([r["amplitude"] * (r["h"] ** 1.5 - (r["h"] - (zk - BASE_THICKNESS)) ** 1.5) for zk in zs], zs,
                   "-", color=line.get_color())
        ax[1].plot(r["phi"], r["z"], "o-", ms=3, color=line.get_color(), label=f"{r['theta']:.1f} deg")
    ax[0].set(xlabel="u / sqrt(g d)", ylabel="z / d", title="velocity (points) and Bagnold fits (lines)")
    ax[1].set(xlabel="solid fraction", ylabel="z / d", title="solid fraction")
    ax[0].legend(fontsize=7)
    thetas = [r["theta"] for r in flowing]
    ax[2].plot(thetas, [r["bulk_phi"] for r in flowing], "o-", label="this code")
    ax[2].set(xlabel="theta [deg]", ylabel="bulk solid fraction", title="bulk solid fraction against theta")
    ax[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "chute_profiles.png"), dpi=120)
    fig, ax = plt.subplots(figsize=(6, 4))
    for r in sorted(results, key=lambda r: r["theta"]):
        ax.semilogy([t for t, _ in r["energy"]], [max(e, 1e-12) for _, e in r["energy"]],
                    label=f"{r['theta']:.2f} deg ({'stops' if r['stopped'] else 'flows'})")
    ax.axhline(STOPPED, color="k", ls=":")
    ax.set(xlabel="t / tau", ylabel="E_kin / (m g d)", title="kinetic energy per mass")
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "chute_energy.png"), dpi=120)


def check_ci(results):
    """The CTest's assertions; returns the failures."""
    failures = []
    for r in results:
        if r["theta"] in PRESETS["ci"]["stop_angles"]:
            if not r["stopped"]:
                failures.append(f"theta {r['theta']}: expected to stop, E_kin = {r['final_energy']:.3g} m g d at the end")
            continue
        res = r["residual"]
        if r["stopped"]:
            failures.append(f"theta {r['theta']}: expected to flow, stopped (E_kin = {r['final_energy']:.3g} m g d)")
        if not abs(r["drift"]) <= CI_STEADY:
            failures.append(f"theta {r['theta']}: not steady: the kinetic energy changed by {r['drift']:+.3f} "
                            f"between the last two quarters (bound {CI_STEADY})")
        if not res["bagnold"] <= CI_BAGNOLD_RESIDUAL:
            failures.append(f"theta {r['theta']}: Bagnold residual {res['bagnold']:.3f} above {CI_BAGNOLD_RESIDUAL}")
        if not (res["bagnold"] < res["linear"] and res["bagnold"] < res["plug"]):
            failures.append(f"theta {r['theta']}: the profile is not closer to Bagnold ({res['bagnold']:.3f}) "
                            f"than to linear ({res['linear']:.3f}) and plug ({res['plug']:.3f})")
    return failures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary", nargs="?", help="grainstorm (not run for the angles --reuse finds in --work)")
    ap.add_argument("--preset", choices=sorted(PRESETS), default="ci")
    ap.add_argument("--out", help="tables and plots here (default: none for ci, chute_<preset> otherwise)")
    ap.add_argument("--work", help="keep the runs here (default: a temporary directory, removed)")
    ap.add_argument("--backend", default="cpu")
    ap.add_argument("--jobs", type=int, help="runs at once (default: the preset's)")
    ap.add_argument("--angles", help="comma-separated angles [deg] instead of the preset's (no bracket)")
    ap.add_argument("--duration", type=float, help="simulated time per run [tau] instead of the preset's")
    ap.add_argument("--height", type=float, help="H [d] instead of the preset's")
    ap.add_argument("--budget-s", type=float, help="wall seconds for the runs: then what still runs is stopped "
                    "(SIGTERM) and analysed over the time it reached (no bisection)")
    ap.add_argument("--reuse", action="store_true", help="read the runs already in --work instead of running them again")
    ap.add_argument("--write-cases", action="store_true", help="(re)write cases/validation/chute/ and exit")
    a = ap.parse_args()
    p = dict(PRESETS[a.preset])
    if a.angles:
        p.update(flow_angles=[float(t) for t in a.angles.split(",")], stop_angles=[], bracket=0)
    if a.duration:
        p["duration"] = a.duration
    if a.height:
        p["height"] = a.height
    if a.write_cases:
        os.makedirs(CASE_DIR, exist_ok=True)
        for preset, theta in (("ci", 24.0), ("ci", 14.0), ("medium", 23.0), ("full", 23.0)):
            path = os.path.join(CASE_DIR, f"chute_{preset}_{theta:.0f}deg.yaml")
            with open(path, "w") as f:
                f.write(scene_text(PRESETS[preset], theta, f"out/chute_{preset}_{theta:.0f}deg"))
            print("wrote", os.path.relpath(path, ROOT))
        return 0
    if not a.binary:
        ap.error("BINARY is required unless --write-cases")
    if not a.reuse and not os.access(a.binary, os.X_OK):
        print(f"not an executable: {a.binary}", file=sys.stderr)
        return 2
    work = a.work or tempfile.mkdtemp(prefix="chute_")
    jobs = a.jobs or p["jobs"]
    out = a.out or (None if a.preset == "ci" else f"chute_{a.preset}")
    try:
        angles = p["flow_angles"] + p["stop_angles"]
        results = run_angles(a.binary, a.backend, p, angles, work, a.reuse, jobs, budget_runs.deadline_from(a.budget_s))
        bracket_result = None
        stops = [r["theta"] for r in results if r["stopped"]]
        flows = [r["theta"] for r in results if not r["stopped"]]
        if stops and flows and max(stops) < min(flows):
            bracket_result = (max(stops), min(flows))
            if p["bracket"] > 0:
                low, high, runs = bracket(a.binary, a.backend, p, work, max(stops), min(flows), p["bracket"], a.reuse)
                results += runs
                bracket_result = (low, high)
        elif stops and flows:
            print(f"no bracket: stopped at {stops}, flowed at {flows}")
    except RuntimeError as e:
        print(e, file=sys.stderr)
        return 2
    finally:
        if not a.work:
            shutil.rmtree(work, ignore_errors=True)
    print("| theta | end | E_kin | E drift | h | bulk phi | u_surf | A | res Bagnold | res linear | res plug | t [tau] | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in sorted(results, key=lambda r: r["theta"]):
        print(describe(r))
    if bracket_result:
        print(f"flow/no-flow angle between {bracket_result[0]:.3f} and {bracket_result[1]:.3f} deg")
    if out:
        write_tables(out, p, a.preset, results, bracket_result)
        plot(out, results)
        print("tables and plots in", out)
    if a.preset == "ci" and not (a.angles or a.duration or a.height):   # the CTest's own runs only
        failures = check_ci(results)
        for f in failures:
            print("FAIL:", f)
        return 1 if failures else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
