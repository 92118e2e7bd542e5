#!/usr/bin/env python3
"""Writes the seed mixer's cases a-d (Radeke, Glasser, Khinast 2010, Tables
1-4) as grainstorm scenes, following the paper's procedure: particles are
created above the impeller (at rest), fall and settle for `settle` seconds,
are then marked by the side of the central vertical plane x = 0, and the
impeller turns from that instant for the given number of revolutions, with
the mixing analysis after every revolution.

    tools/make_mixer_cases.py [--out-dir cases/mixer] [--cases abcd]
        [--revolutions 32] [--froude | --froude-scaled] [--stiffness-scale 1]
        [--suffix ""] [--seed N]

--froude uses the paper's Froude-scaled impeller speeds (Table 2, Eq. 12)
instead of the reference 30 rpm, in the real geometry: a Froude number
(30/rpm)^2 times smaller than the real mixer's. --froude-scaled writes the
paper's scaled model instead (its Section 3: the geometry enlarged so that
one sphere size serves all cases, the speed corrected by Eq. 12): every
length times s = (30/rpm)^2 (the vessel, the impeller through the mesh's
scale, the spheres, the fill, the samples' rings and height; the samples'
mass times s^3, so they hold as many spheres), the settling time times
sqrt(s), at the Table 2 speed, so the Froude number is the real mixer's.
The springs stay: the weight on a contact grows as s^3, so the overlap
relative to a diameter grows as s^2 (which is what makes the model cheap:
contact times grow as s^1.5). With Table 4's stiffness, under the bed's
weight at its bottom: case a (s = 28.0, spheres of 84 mm, a vessel of 2.8 m) about
0.8 % of a diameter, case b (s = 64) about 10 %. --stiffness-scale below 1
makes no sense there. (The paper gives its simulated spheres a radius of
0.04 m in every case; with Table 2's speeds Eq. 12 gives that for case a
only: 42 mm, against 67 mm for case b.) --stiffness-scale multiplies Table 4's
stiffnesses (a softer, cheaper variant: the time step grows as its inverse
square root; see docs/MIXER.md for what it changes). --seed sets the random
fill's seed (default 1): another seed gives another fill of the same bed, for
averaging over runs (docs/MIXER.md, "Running the study across sessions").
"""
import argparse
import math
import os
import sys

# Table 2/3: particles, diameter [m], Froude-scaled rpm.
CASES = {
    "a": (7680, 3.0e-3, 5.6695),
    "b": (76800, 2.1e-3, 3.7500),
    "c": (768000, 0.98e-3, 2.5355),
    "d": (7680000, 0.45e-3, 1.7039),
}
DENSITY = 2500.0          # Table 4 [kg/m^3]
K_NORMAL = 1.05e5         # Table 4 [N/m]
K_TANGENTIAL = 8.25e4     # Table 4 [N/m]
VESSEL_RADIUS = 0.05      # Table 1: DS = 100 mm
SHAFT_TOP = 0.100         # impeller.stl: shaft top 100 mm above the hub's bottom face
FLOOR = -0.002            # vessel floor, 2 mm below the impeller (the paper does not say)
FILL_RADIUS = 0.047       # the creation cylinder, clear of the vessel wall
# The vessel is closed by a lid just above the fill (the paper does not say):
# the blade tips pass 2.5 mm from the wall, less than case a's diameter, and a
# sphere squeezed there at Table 4's stiffness can be thrown out of an open
# vessel (docs/MIXER.md, "Spheres thrown out of the vessel"). The lid keeps
# every sphere in the run and the tracer's share fixed.
CREATION_PACKING = 0.25   # solid fraction of the random fill the particles fall from
BED_PACKING = 0.60        # solid fraction of the settled bed (for the sample height)
# Just below the stable limit of Table 4's springs (k_t/k_n = 0.79, e = 0.78):
# 0.117 contact times, set by the tangential spring in a dense bed
# (docs/STABILITY.md; `grainstorm check` prints it).
TIME_STEP_FRACTION = 0.11
DEEP_TIME_STEP_FRACTION = 0.05  # the scaled model's deep overlaps (scene() says why)
SAMPLE_MASS = 0.46e-3     # Table 3: about 0.46 g in every case [kg]


def solid_volume(count, diameter):
    return count * math.pi / 6 * diameter**3


def units(s):
    return "real units" if s == 1 else f"the paper's scaled model: lengths x {s:.4g}, the Froude number kept"


def scene(case, revolutions, froude, stiffness_scale, settle, suffix, layers=1, seed=1, froude_scaled=False):
    count, diameter, froude_rpm = CASES[case]
    rpm = froude_rpm if froude or froude_scaled else 30.0
    period = 60.0 / rpm
    # The paper's scaled model (Eq. 12: the Froude number omega^2 R / g kept):
    # every length times s, times s^3 the samples' mass, times sqrt(s) the
    # settling (a fall's time); 1 in real units.
    s = (30.0 / froude_rpm) ** 2 if froude_scaled else 1.0
    settle *= math.sqrt(s)
    diameter *= s
    radius = diameter / 2
    volume = solid_volume(count, diameter)
    # Created in a cylinder above the shaft top, loose, so nothing starts inside the impeller.
    fill_bottom = s * SHAFT_TOP + radius + 0.001 * s
    fill_height = volume / CREATION_PACKING / (math.pi * (s * FILL_RADIUS)**2)
    top = fill_bottom + fill_height + 0.002 * s
    bed_height = volume / BED_PACKING / (math.pi * (s * VESSEL_RADIUS)**2)
    sample_height = round(min(bed_height, 0.08 * s), 4)
    kn, kt = K_NORMAL * stiffness_scale, K_TANGENTIAL * stiffness_scale
    # A sphere falling from the fill's top onto the floor, or onto a resting
    # sphere of its own mass, presses in by about v sqrt(m / 2 k) (the
    # undamped spring). In real units below 1 % of a diameter; in the scaled
    # model (v grows as sqrt(s), m as s^3) 22 % for case a and 58 % for case
    # b. So deep, a sphere touches more spheres than the default 12 contact
    # slots hold, and a step moves it too far for the Verlet list's margin: a
    # list kept on the last step's verdict covers a move that grows by up to
    # a tenth of the skin (0.01 diameters) in one step, and a contact of
    # overlap delta changes a move by about a dt^2 = (pi f)^2 delta / 2 per
    # step at f contact times per step, 0.06 delta at f = 0.11. Where the
    # impacts pass 30 % of a diameter the scene gets 24 slots and f = 0.05
    # (0.012 delta: overlaps up to 80 % of a diameter covered).
    impact = math.sqrt(2 * 9.81 * (top - s * FLOOR)) * math.sqrt(DENSITY * math.pi / 6 * diameter**3 / 2 / kn) / diameter
    deep = impact > 0.3
    slots = (f"contact_slots: 24            # the fill's impacts press spheres about {100 * impact:.0f} % of a diameter deep\n"
             if deep else "")
    fraction = DEEP_TIME_STEP_FRACTION if deep else TIME_STEP_FRACTION
    # Case a's few spheres rebuild their lists every dozen steps at the
    # default skin, and a build costs a small scene more than its longer
    # rows: case a soft turning ran 69-70 us a step at 0.3 against 74-76 at
    # 0.1 on one H100, and 4 % faster on one CPU thread (docs/PERFORMANCE.md,
    # "A CUDA timeline of mixer case a's step"); case b's one lane per sphere
    # ran slower at 0.3. No result depends on the skin.
    skin = "verlet_skin: 0.3             # fewer list builds: see tools/make_mixer_cases.py\n" if case == "a" else ""
    fraction_note = f"          # {100 * impact:.0f} % overlaps: see tools/make_mixer_cases.py" if deep else ""
    duration = settle + revolutions * period
    # Snapshots at multiples of the settling time, so one lands on the marking;
    # the big beds less often (case d: 250 MB each).
    snapshot_every = settle * (1 if count < 500000 else 2)
    name = f"case_{case}"
    return f"""# Seed mixer, case {case} (Radeke et al. 2010, Tables 1-4): {count:,} glass spheres of
# {diameter * 1e3:.2f} mm in the {100 * s:g} mm vessel with the four-bladed impeller at {rpm:g} rpm
# ({"Froude-scaled, Table 2" if froude or froude_scaled else "the reference speed"}), {units(s)}.
# Written by tools/make_mixer_cases.py; procedure and choices: docs/MIXER.md.
# Stiffness {"of Table 4" if stiffness_scale == 1 else f"Table 4 x {stiffness_scale:g} (a cheaper variant)"}.
# Procedure: fall from a loose fill above the shaft and settle for {settle:g} s with
# the impeller at rest; at t = {settle:g} s mark by the side of the plane x = 0 and
# start the impeller; {revolutions} revolutions; mixing statistics every revolution.
# impeller.stl: build/tools/make_impeller cases/mixer/impeller.stl

domain: {{min: [{-0.052 * s:g}, {-0.052 * s:g}, {s * (FLOOR - 0.001):g}], max: [{0.052 * s:g}, {0.052 * s:g}, {top + 0.002 * s:.4f}]}}
gravity: [0, 0, -9.81]
contact_model: linear
precision: fp32
{slots}{skin}effects: {{friction: true, rolling_resistance: false, cohesion: false}}

materials:
  - {{name: glass, density: {DENSITY:g}}}
  - {{name: steel, density: 7800}}

pairs:
  - {{materials: [glass, glass], stiffness_normal: {kn:.6g}, stiffness_tangential: {kt:.6g}, restitution: 0.78, friction: 0.5}}
  - {{materials: [glass, steel], stiffness_normal: {kn:.6g}, stiffness_tangential: {kt:.6g}, restitution: 0.78, friction: 0.2}}

walls:
  - cylinder: {{base: [0, 0, {s * FLOOR:g}], axis: [0, 0, 1], radius: {s * VESSEL_RADIUS:g}, length: {top - s * FLOOR:.4f}, caps: both}}
    material: steel
    name: vessel
  - mesh: {{stl: impeller.stl{"" if s == 1 else f", scale: {s:.6g}"}}}
    material: steel
    name: impeller
    motion: {{rotation: {{axis_point: [0, 0, 0], axis: [0, 0, 1], rpm: {rpm:g}}}, start: {settle:g}}}

particles:
  - random_fill:
      material: glass
      region: {{cylinder: {{base: [0, 0, {fill_bottom:.4f}], axis: [0, 0, 1], radius: {s * FILL_RADIUS:g}, length: {fill_height:.4f}}}}}
      count: {count}
      radius: {radius:g}
      seed: {seed}

marking: {{time: {settle:g}, plane: {{point: [0, 0, 0], normal: [1, 0, 0]}}, front: 1, back: 0}}

time_step: {{fraction_of_contact_time: {fraction:g}}}{fraction_note}
duration: {duration:.6g}                 # settling + {revolutions} revolutions
output:
  interval: {snapshot_every:g}                # snapshots at the marking and every {snapshot_every:g} s after it
  fields: [id, material, marker, radius, position, velocity]
  directory: out/mixer_{case}{suffix}
  checkpoint_minutes: 30
analysis:
  mixing:
    center: [0, 0]
    bottom: {s * FLOOR:g}
    height: {sample_height}            # about the settled bed's height
    rings: {{inner_radius: {0.012 * s:g}, outer_radius: {0.048 * s:g}, count: 3}}
    sample_mass: {SAMPLE_MASS * s**3:g}
    bulk_density: {DENSITY * BED_PACKING:g}
    start: {settle:g}
    revolution_period: {period:.6g}
""" + (f"    layers: {layers}               # samples stacked in height (docs/MIXING.md)\n" if layers > 1 else "")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out-dir", default=os.path.join(os.path.dirname(__file__), "..", "cases", "mixer"))
    p.add_argument("--cases", default="abcd")
    p.add_argument("--revolutions", type=int, default=32)
    speed = p.add_mutually_exclusive_group()
    speed.add_argument("--froude", action="store_true", help="the Table 2 speed in the real geometry")
    speed.add_argument("--froude-scaled", action="store_true", help="the paper's scaled model (Eq. 12)")
    p.add_argument("--stiffness-scale", type=float, default=1.0)
    p.add_argument("--settle", type=float, default=1.0, help="seconds of settling before marking [1.0]")
    p.add_argument("--suffix", default="", help="appended to the file names, e.g. _froude")
    p.add_argument("--layers", type=int, default=1, help="mixing samples stacked in height [1]")
    p.add_argument("--seed", type=int, default=1, help="the random fill's seed, >= 0 [1]")
    a = p.parse_args()
    if not set(a.cases) <= set(CASES) or not a.cases:
        sys.exit(f"make_mixer_cases: --cases must be letters of abcd, got '{a.cases}'")
    if a.revolutions < 1 or not a.stiffness_scale > 0 or not a.settle > 0 or a.layers < 1 or a.seed < 0:
        sys.exit("make_mixer_cases: --revolutions >= 1, --stiffness-scale > 0, --settle > 0, --layers >= 1 and --seed >= 0 are required")
    for c in a.cases:
        path = os.path.join(a.out_dir, f"case_{c}{a.suffix}.yaml")
        with open(path, "w") as f:
            f.write(scene(c, a.revolutions, a.froude, a.stiffness_scale, a.settle, a.suffix, a.layers, a.seed,
                          a.froude_scaled))
        print(path)


if __name__ == "__main__":
    main()
