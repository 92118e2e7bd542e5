#!/usr/bin/env python3
"""What a silo's processes and measurements cost per particle-step.

    bench/process_cost.py BINARY OUT [--variant full] [--backend cuda] [--d0 10] [--every-steps 100]
                          [--settle 0.3] [--discharge 0.2] [--budget-s S]

The silo of tools/silo_beverloo.py (variant `full`: 40 d wide, ~70k spheres),
started from one random fill of the count a bed of solid fraction 0.6 holds
up to the fill height, so that every run steps the same bed: it settles with
the gate closed until t_open (--settle), then (where the run has an outlet)
discharges for --discharge. Runs, one after the other (so that each has the
GPU alone), each to the same end time, in this order:

  static      no inlet, no outlet, the gate never opens
  outlet      the gate opens at t_open, the outlet removes what falls through
  process     as outlet, plus the inlet re-feeding the top (the validation's set-up)
  +flow       process with a flow disk at the orifice
  +solid      process with a box average of the solid fraction
  +stress     process with a box average of coordination and stress (the contact pass)
  +grid       process with a 10 x 10 x 25 grid of solid fraction and velocity (HDF5 + XDMF)
  +mesh       process with a flow through a mesh: the same disk as a fan of 64 triangles
  +all        process with all five measurements

every measurement evaluated every EVERY steps. Prints a timestamped line per
run, then a Markdown table of particle-steps per second (from each run.log)
for docs/PERFORMANCE.md. With --budget-s, a run that would end past the
budget (if it took as long as the longest so far) is skipped and named in
the table. Exit status 0, 1 when a run failed (the table names it), 2 when
none finished.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools"))
import silo_beverloo as silo  # noqa: E402


# The runs in order of interest: a budget that runs out skips the last.
KINDS = ["static", "outlet", "process", "+flow", "+solid", "+stress", "+grid", "+mesh", "+all"]


def say(text):
    """A progress line with the UTC time."""
    print("[%s] %s" % (time.strftime("%H:%M:%S", time.gmtime()), text), flush=True)


def write_disk_stl(path, radius, triangles=64):
    """A disk of `radius` at z = 0 as a fan of triangles, normals down (ASCII STL)."""
    lines = ["solid orifice"]
    for k in range(triangles):
        a0, a1 = 2 * math.pi * k / triangles, 2 * math.pi * (k + 1) / triangles
        corners = [(0.0, 0.0), (radius * math.cos(a1), radius * math.sin(a1)), (radius * math.cos(a0), radius * math.sin(a0))]
        lines += ["  facet normal 0 0 -1", "    outer loop"]
        lines += ["      vertex %.17g %.17g 0" % c for c in corners]
        lines += ["    endloop", "  endfacet"]
    with open(path, "w") as f:
        f.write("\n".join(lines + ["endsolid orifice", ""]))


def scene(g, kind, every, t_end):
    """The scene text of one run (a mesh flow reads orifice.stl beside it)."""
    g = dict(g)
    # Room above for the random fill: loose (about 30 %) over twice the fill height.
    g["top"] = g["inlet_top"] = 2.2 * g["h_fill"]
    g["hi"] = [g["hi"][0], g["hi"][1], g["top"] + silo.D]
    g["t_feed"] = None   # the inlet feeds from the start, as in the validation's set-up
    if kind == "static":
        g["t_open"] = None
    r_max = silo.D / 2 * (1 + silo.SPREAD)
    v_particle = math.pi / 6 * silo.D ** 3 * (1 + silo.SPREAD ** 2)
    count = int(0.6 * math.pi * g["r_silo"] ** 2 * g["h_fill"] / v_particle)
    text = silo.scene_head(g)
    text += f"""particles:
  - random_fill:
      material: glass
      region: {{cylinder: {{base: [0, 0, {silo.fmt(r_max)}], axis: [0, 0, 1], radius: {silo.fmt(g['r_silo'] - r_max)}, length: {silo.fmt(2.1 * g['h_fill'])}}}}}
      count: {count}
      radius: {silo.radii()}
      seed: 11
"""
    if kind != "static" and kind != "outlet":
        text += silo.inlet_section(g)
    if kind != "static":
        text += silo.outlet_section(g)
    flows, averages = [], []
    half, r = 0.5 * g["r_silo"], g["r_silo"]
    box = "{min: %s, max: %s}" % (silo.vec([-half, -half, 0.35 * g["h_fill"]]), silo.vec([half, half, 0.75 * g["h_fill"]]))
    if kind in ("+flow", "+all"):
        flows.append("    - {name: orifice, plane: {point: [0, 0, 0], normal: [0, 0, -1]}, radius: %s, every: %r}\n"
                     % (silo.fmt(g["d0"] / 2), every))
    if kind in ("+mesh", "+all"):
        flows.append("    - {name: orifice_mesh, mesh: {stl: orifice.stl}, every: %r}\n" % every)
    if kind in ("+solid", "+all"):
        averages.append("    - {name: bulk, box: %s, quantities: [solid_fraction], every: %r}\n" % (box, every))
    if kind in ("+stress", "+all"):
        averages.append("    - {name: stress, box: %s, quantities: [coordination, stress], every: %r}\n" % (box, every))
    if kind in ("+grid", "+all"):
        averages.append("    - {name: grid, box: {min: %s, max: %s}, bins: [10, 10, 25], quantities: [solid_fraction, "
                        "velocity], every: %r}\n" % (silo.vec([-r, -r, 0]), silo.vec([r, r, g["h_fill"]]), every))
    if flows or averages:
        text += "measurements:\n"
        if flows:
            text += "  flows:\n" + "".join(flows)
        if averages:
            text += "  averages:\n" + "".join(averages)
    text += "time_step: {fraction_of_contact_time: 0.1}\nduration: %r\noutput: {interval: 0}\n" % t_end
    return text, count


def time_step(binary, path):
    out = subprocess.run([binary, "check", path], stdout=subprocess.PIPE, text=True, check=True).stdout
    return float(re.search(r"^time step:\s+(\S+)", out, re.M).group(1))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("binary")
    p.add_argument("out")
    p.add_argument("--variant", default="full", choices=sorted(silo.VARIANTS))
    p.add_argument("--backend", default="cuda")
    p.add_argument("--d0", type=float, default=10.0, help="orifice diameter in particle diameters")
    p.add_argument("--every-steps", type=int, default=100)
    p.add_argument("--discharge", type=float, default=0.2, help="simulated seconds after the gate opens")
    p.add_argument("--settle", type=float, default=0.3, help="simulated seconds before the gate opens")
    p.add_argument("--budget-s", type=float, help="wall seconds for the runs: a run that would pass them is skipped")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    g = silo.geometry(args.variant, args.d0)
    g["t_open"] = args.settle   # the random fill has fallen (0.21 s from its top) and about settled by then
    t_end = g["t_open"] + args.discharge
    probe = os.path.join(args.out, "probe.yaml")
    with open(probe, "w") as f:
        f.write(scene(g, "static", 1.0, t_end)[0])
    every = args.every_steps * time_step(args.binary, probe) * (1 + 1e-9)
    rows, skipped, failed = [], [], []
    write_disk_stl(os.path.join(args.out, "orifice.stl"), g["d0"] / 2)
    start = time.time()
    longest = 0.0
    for kind in KINDS:
        # A run is not started when one as long as the longest so far would pass the budget.
        if args.budget_s and time.time() - start + longest > args.budget_s:
            say("%s: skipped (the budget of %.0f s would not hold it)" % (kind, args.budget_s))
            skipped.append(kind)
            continue
        name = kind.replace("+", "with_")
        path = os.path.join(args.out, name + ".yaml")
        text, count = scene(g, kind, every, t_end)
        with open(path, "w") as f:
            f.write(text)
        run_dir = os.path.join(args.out, name)
        t0 = time.time()
        proc = subprocess.run([args.binary, "run", path, "--backend", args.backend, "--out", run_dir, "--overwrite"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        longest = max(longest, time.time() - t0)
        log = open(os.path.join(run_dir, "run.log")).read() if os.path.exists(os.path.join(run_dir, "run.log")) else ""
        done = re.search(r"^done: (\d+) steps, t = \S+ s, (\S+) particle-steps/s", log, re.M)
        wall = re.search(r"total wall (\S+)", log)
        end = re.search(r"^particles at the end: (\d+)", log, re.M)
        meas = re.findall(r"^measurement (.*)$", log, re.M)
        if proc.returncode != 0 or not done:
            say("%s failed (exit %d):\n%s" % (kind, proc.returncode, proc.stdout[-2000:]))
            failed.append(kind)
            continue
        rows.append((kind, count, int(end.group(1)) if end else count, int(done.group(1)), float(wall.group(1)),
                     float(done.group(2)), "; ".join(meas)))
        say("%s: %s particle-steps/s, %.0f s" % (kind, done.group(2), time.time() - t0))
    if not rows:
        print("no run finished")
        return 2
    base = {r[0]: r[5] for r in rows}
    base_static, base_process = base.get("static", float("nan")), base.get("process", float("nan"))
    print()
    print("silo %s (D0 = %g d, %d spheres at the start), backend %s, %d steps, measurements every %d steps"
          % (args.variant, args.d0, rows[0][1], args.backend, rows[0][3], args.every_steps))
    print()
    print("| run | particles at the end | wall s | particle-steps/s | vs static | vs process | measurement times (run.log) |")
    print("|---|---|---|---|---|---|---|")
    for kind, _, end, _, wall, rate, meas in rows:
        print("| %s | %d | %.1f | %.3g | %.2f | %.2f | %s |" % (kind, end, wall, rate, rate / base_static,
                                                              rate / base_process, meas or "-"))
    for kind in skipped:
        print("| %s | skipped: the budget | | | | | |" % kind)
    for kind in failed:
        print("| %s | failed (its log: %s) | | | | | |" % (kind, os.path.join(args.out, kind.replace("+", "with_"))))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
