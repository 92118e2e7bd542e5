#!/usr/bin/env python3
"""Chung & Ooi (2011) impact benchmarks 1-8: write the cases, run them, compare.

    tools/chung_ooi.py BINARY [--quick] [--write-cases] [--keep DIR]

Y.C. Chung, J.Y. Ooi, "Benchmark tests for verifying discrete element
modelling codes at particle impact level", Granular Matter 13 (2011) 643-656.

The scenes are generated from the parameter tables below, so that the tool
knows which particle is which case. --write-cases (re)writes the full scenes
to cases/validation/chung_ooi/; a full run checks that those files are what
this script generates (an edited case would otherwise be compared against the
wrong references) and runs them. --quick runs a reduced set of the same
impacts from a temporary directory (the CTest test validation_chung_ooi).

References (docs/VALIDATION.md derives them):
  tests 1-3, Hertz: t_c = 2.9432 delta_max / v (2.87 (m*^2/(R* E*^2 v))^(1/5)),
    delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),
    F_max = 4/3 E* sqrt(R*) delta_max^(3/2); rebound v' = e v.
  tests 4-8, rigid-body impact in gross sliding (Maw et al. 1976, Walton 1993):
    normal impulse J_n = (1 + e) m* g_n, tangential impulse mu J_n against
    the slip, valid while |g_t| > mu J_n (1/m1 + 1/m2 + R1^2/I1 + R2^2/I2).
    Below that (stick / micro-slip) the rebound depends on the tangential
    compliance; there is no closed form and the values are only reported.
Exit status 0 when every checked quantity is within its tolerance, 1 when one
is not, 2 on a usage or run error. Standard library only.
"""
import argparse
import glob
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE_DIR = os.path.join(ROOT, "cases", "validation", "chung_ooi")

# Tolerances (relative), set from measurement with margin: docs/VALIDATION.md.
TOL_HERTZ = 0.01        # contact time, max overlap, max force of elastic impacts
TOL_RESTITUTION = 0.01  # v_n' / (e v_n)
TOL_SLIDING = 0.01      # tangential impulse / mu J_n, from translation and from spin
SLIDING_MARGIN = 1.05   # check sliding where |g_t| exceeds the threshold by 5 %
TIME_STEP_FRACTION = 0.02

# Materials: name -> (E [Pa], nu, rho [kg/m^3], source). The paper's Table 1
# was not at hand: every value is that of an open re-implementation, named
# here and in docs/VALIDATION.md with the ones that agree.
MATERIALS = {
    "glass": (4.8e10, 0.20, 2800, "Yade examples Test1.py"),
    "limestone": (2.0e10, 0.25, 2500, "Yade examples Test1.py"),
    "al_alloy_t2": (7.0e10, 0.30, 2699, "Yade examples Test2.py"),
    "mg_alloy": (4.0e10, 0.35, 1800, "Yade examples Test2.py"),
    "alumina": (3.8e11, 0.23, 4000, "Yade examples Test3.py and Test4.py"),
    "cast_iron": (1.0e11, 0.25, 7000, "Yade examples Test3.py"),
    "al_alloy": (7.0e10, 0.33, 2700, "Yade examples Test4.py; PySPH chung tests 7-8 agree"),
    "steel": (2.08e11, 0.30, 7850, "PySPH chung test 5"),
    "polyethylene": (1.0e9, 0.40, 1400, "PySPH chung test 5"),
    "nylon": (2.5e9, 0.40, 1000, "PySPH chung test 8"),
    "copper": (1.2e11, 0.35, 8900, "PySPH chung test 7"),
}


# Scene material name -> (E, nu, rho, source): a case's own copy of a base
# material (test 3 needs one per restitution, since e belongs to a pair).
SCENE_MATERIALS = {}


def scene_material(base, suffix="", density_factor=1):
    name = base + suffix
    E, nu, rho, src = MATERIALS[base]
    if density_factor != 1:
        src += ", density x %g (PySPH's set-up)" % density_factor
    SCENE_MATERIALS[name] = (E, nu, rho * density_factor, src)
    return name


class Impact:
    """One impact: sphere 1 against the plane (partner None) or sphere 2."""

    def __init__(self, label, mat, radius, vel, spin=(0, 0, 0), e=1.0, mu=0.0,
                 partner=None):
        self.label, self.mat, self.radius = label, mat, radius
        self.vel, self.spin, self.e, self.mu = vel, spin, e, mu
        # partner: dict(mat, radius, vel, spin) or None (plane)
        self.partner = partner


def angles(step):
    return [a for a in range(step, 90, step)]


def build_tests(quick):
    """test number -> (title, list of Impact, kind 'hertz' | 'oblique')."""
    t = {}
    S = scene_material
    deg = math.radians
    # Test 1: two identical spheres, 10 m/s each, elastic (R = 10 mm).
    mats = ["glass"] if quick else ["glass", "limestone"]
    t[1] = ("elastic normal impact of two identical spheres",
            [Impact(m, S(m), 0.010, (10, 0, 0),
                    partner=dict(mat=S(m), radius=0.010, vel=(-10, 0, 0), spin=(0, 0, 0)))
             for m in mats], "hertz")
    # Test 2: sphere on a rigid plane, 0.2 m/s, elastic (R = 0.1 m).
    mats = ["al_alloy_t2"] if quick else ["al_alloy_t2", "mg_alloy"]
    t[2] = ("elastic normal impact of a sphere with a rigid plane",
            [Impact(m, S(m), 0.10, (0, 0, -0.2)) for m in mats], "hertz")
    # Test 3: sphere on a rigid plane, 3.9 m/s, restitution 0.1-1 (R = 2.5 mm).
    es = [0.2, 0.6] if quick else [0.1, 0.2, 0.4, 0.6, 0.8, 1.0]
    mats = ["alumina"] if quick else ["alumina", "cast_iron"]
    t[3] = ("normal impact with different coefficients of restitution",
            [Impact("%s e=%.1f" % (m, e), S(m, "_e%02d" % round(10 * e)), 0.0025, (0, 0, -3.9), e=e)
             for m in mats for e in es], "hertz")
    # Test 4: |v| = 3.9 m/s at incident angles 5-85 deg, e = 0.98, mu = 0.092.
    ths = [10, 45, 70] if quick else angles(5)
    mats = ["alumina"] if quick else ["alumina", "al_alloy"]
    t[4] = ("oblique impact on a plane, constant resultant velocity",
            [Impact("%s %2d deg" % (m, th), S(m), 0.0025, (0, 3.9 * math.sin(deg(th)), -3.9 * math.cos(deg(th))),
                    e=0.98, mu=0.092) for m in mats for th in ths], "oblique")
    # Test 5: v_n = 5 m/s, tangential v_t = psi mu v_n, elastic, mu = 0.3, R = 10 um.
    psis = [2, 12] if quick else [0.5, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 17, 20]
    mats = ["steel"] if quick else ["steel", "polyethylene"]
    t[5] = ("oblique impact on a plane, constant normal velocity",
            [Impact("%s psi=%g" % (m, p), S(m), 1e-5, (0, p * 0.3 * 5.0, -5.0), e=1.0, mu=0.3)
             for m in mats for p in psis], "oblique")
    # Spins of tests 6-8: w = v_n tan(theta) / R, theta = 5-85 deg: 0.175-22.9 rad/s.
    ths = [20, 80] if quick else angles(5)
    spins = [0.2 * math.tan(deg(th)) / 0.1 for th in ths]
    # Test 6: v_n = 0.2 m/s, spin w about x (the contact point slips along y at
    # w R), no tangential velocity, e = 0.5, mu = 0.4, R = 0.1 m.
    mats = ["al_alloy"] if quick else ["al_alloy", "nylon"]
    t[6] = ("impact on a plane, constant normal velocity, varying spin",
            [Impact("%s w=%.3f" % (m, w), S(m), 0.1, (0, 0, -0.2), spin=(w, 0, 0), e=0.5, mu=0.4)
             for m in mats for w in spins], "oblique")
    # Test 7: two identical spheres, 0.2 m/s each, both spinning at w about the
    # same axis z (their contact points then slip at 2 w R), e = 0.5, mu = 0.4.
    mats = ["al_alloy"] if quick else ["al_alloy", "copper"]
    t[7] = ("two identical spheres, constant normal velocity, varying spin",
            [Impact("%s w=%.3f" % (m, w), S(m), 0.1, (0.2, 0, 0), spin=(0, 0, w), e=0.5, mu=0.4,
                    partner=dict(mat=S(m), radius=0.1, vel=(-0.2, 0, 0), spin=(0, 0, w)))
             for m in mats for w in spins], "oblique")
    # Test 8: sphere (R = 0.1 m) at 0.2 m/s with spin w about z against a
    # sphere of 5 R and 1000 x the density at rest, e = 0.5, mu = 0.4.
    mats = ["al_alloy"] if quick else ["al_alloy", "nylon"]
    t[8] = ("two differently sized spheres, constant normal velocity, varying spin",
            [Impact("%s w=%.3f" % (m, w), S(m), 0.1, (0.2, 0, 0), spin=(0, 0, w), e=0.5, mu=0.4,
                    partner=dict(mat=S(m, "_heavy", 1000), radius=0.5, vel=(0, 0, 0), spin=(0, 0, 0)))
             for m in mats for w in spins], "oblique")
    for _, imps, _ in t.values():
        for imp in imps:
            imp.plane = rigid_material(imps)
    return t


# ---------------------------------------------------------------- geometry


def add(a, b, s=1.0):
    return tuple(x + s * y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    return math.sqrt(dot(a, a))


def material(name):
    return SCENE_MATERIALS[name][:3]


def rigid_material(imps):
    """The plane of a scene: 1000 x the stiffest sphere's E (as Yade's tests
    make their planes); nu 0.25, density unused."""
    return 1000 * max(material(i.mat)[0] for i in imps), 0.25, 7800.0


def e_star(m1, m2):
    return 1 / ((1 - m1[1] ** 2) / m1[0] + (1 - m2[1] ** 2) / m2[0])


def sphere_mass(r, rho):
    return 4 / 3 * math.pi * r ** 3 * rho


def rayleigh_time(r, mat):
    E, nu, rho = mat
    return math.pi * r * math.sqrt(rho / (E / (2 * (1 + nu)))) / (0.1631 * nu + 0.8766)


# Hertz: t_c = 2 delta_max / v * int_0^1 (1 - x^(5/2))^(-1/2) dx = 2.94324 delta_max / v.
HERTZ_TIME = 2 * 0.4 * math.gamma(0.4) * math.gamma(0.5) / math.gamma(0.9)


# int delta F dt / (delta_max int F dt) over an elastic Hertz impact: with
# y = delta / delta_max, dt ~ dy / sqrt(1 - y^(5/2)), int y^a dt ~ B((a+1)/2.5, 1/2).
LEVER_MEAN = (math.gamma(1.4) * math.gamma(0.5) / math.gamma(1.9)) / 2.0


def bodies(imp):
    """(m1, I1, R1, mat1, m2, I2, R2, mat2) with m2 = inf for the plane."""
    m1mat = material(imp.mat)
    m1 = sphere_mass(imp.radius, m1mat[2])
    if imp.partner is None:
        return m1, 0.4 * m1 * imp.radius ** 2, imp.radius, m1mat, math.inf, math.inf, 0.0, imp.plane
    p = imp.partner
    m2mat = material(p["mat"])
    m2 = sphere_mass(p["radius"], m2mat[2])
    return m1, 0.4 * m1 * imp.radius ** 2, imp.radius, m1mat, m2, 0.4 * m2 * p["radius"] ** 2, p["radius"], m2mat


def normal(imp):
    """Unit normal from sphere 1 towards its partner."""
    return (0, 0, -1) if imp.partner is None else (1, 0, 0)


def hertz(imp):
    """Elastic Hertz contact time, max overlap and max force of the impact."""
    m1, _, R1, mat1, m2, _, R2, mat2 = bodies(imp)
    n = normal(imp)
    v2 = (0, 0, 0) if imp.partner is None else imp.partner["vel"]
    v = dot(add(imp.vel, v2, -1), n)
    ms = m1 if math.isinf(m2) else m1 * m2 / (m1 + m2)
    rs = R1 if imp.partner is None else R1 * R2 / (R1 + R2)
    es = e_star(mat1, mat2)
    d = (15 * ms * v * v / (16 * es * math.sqrt(rs))) ** 0.4
    return HERTZ_TIME * d / v, d, 4 / 3 * es * math.sqrt(rs) * d ** 1.5, v


def sliding(imp):
    """Rigid-body gross-sliding rebound of sphere 1 (and its partner).

    Returns (v1', w1', v2', w2', threshold ratio |g_t| / (mu J_n K)); the state
    after a contact that slides from start to end."""
    m1, I1, R1, _, m2, I2, R2, _ = bodies(imp)
    n = normal(imp)
    v2, w2 = ((0, 0, 0), (0, 0, 0)) if imp.partner is None else (imp.partner["vel"], imp.partner["spin"])
    r1, r2 = tuple(R1 * c for c in n), tuple(-R2 * c for c in n)
    g = add(add(imp.vel, cross(imp.spin, r1)), add(v2, cross(w2, r2)), -1)
    gn = dot(g, n)
    gt = add(g, n, -gn)
    ms = m1 if math.isinf(m2) else m1 * m2 / (m1 + m2)
    jn = (1 + imp.e) * ms * gn
    inv = lambda x: 0.0 if math.isinf(x) else 1 / x  # noqa: E731
    k = 1 / m1 + inv(m2) + R1 * R1 / I1 + (R2 * R2 * inv(I2) if imp.partner else 0)
    gt_abs = norm(gt)
    ratio = gt_abs / (imp.mu * jn * k) if imp.mu > 0 else math.inf
    t = tuple(c / gt_abs for c in gt) if gt_abs > 0 else (0, 0, 0)
    imp1 = add(tuple(-jn * c for c in n), t, -imp.mu * jn)  # impulse on sphere 1
    v1p = add(imp.vel, imp1, 1 / m1)
    w1p = add(imp.spin, cross(r1, imp1), 1 / I1)
    v2p = add(v2, imp1, -inv(m2))
    w2p = add(w2, cross(r2, imp1), -inv(I2)) if imp.partner else w2
    return v1p, w1p, v2p, w2p, ratio


# ---------------------------------------------------------------- scenes


def layout(imps):
    """Initial (position, radius, material, velocity, spin) of every particle,
    impacts spaced along x (planes) or y (sphere pairs) so that none interact."""
    parts = []
    size = max(max(i.radius, i.partner["radius"] if i.partner else 0) for i in imps)
    spacing = 6 * size
    for k, imp in enumerate(imps):
        gap = 1e-3 * imp.radius
        if imp.partner is None:
            parts.append(((k * spacing, 0, imp.radius + gap), imp.radius, imp.mat, imp.vel, imp.spin))
        else:
            p = imp.partner
            y = k * spacing
            parts.append(((-imp.radius - gap / 2, y, 0), imp.radius, imp.mat, imp.vel, imp.spin))
            parts.append(((p["radius"] + gap / 2, y, 0), p["radius"], p["mat"], p["vel"], p["spin"]))
    return parts, spacing


def duration(imps):
    longest = 0
    for imp in imps:
        tc, _, _, v = hertz(imp)
        longest = max(longest, 1e-3 * imp.radius / v + 1.5 * tc)
    return longest


def fmt(x):
    return "%.10g" % x


def vec(v):
    return "[" + ", ".join(fmt(c) for c in v) + "]"


def scene_text(number, title, imps, kind, quick):
    parts, spacing = layout(imps)
    mats = []
    for p in parts:
        if p[2] not in mats:
            mats.append(p[2])
    plane = any(i.partner is None for i in imps)
    end = duration(imps)
    speed = max(norm(p[3]) + norm(p[4]) * p[1] for p in parts)
    reach = speed * end + 2 * max(p[1] for p in parts)
    lo = [min(p[0][a] for p in parts) - reach for a in range(3)]
    hi = [max(p[0][a] for p in parts) + reach for a in range(3)]
    if plane:
        lo[2] = -max(p[1] for p in parts)
    t_r = min(rayleigh_time(p[1], material(p[2])) for p in parts)
    lines = [
        "# Chung & Ooi (2011) benchmark test %d: %s." % (number, title),
        "# Y.C. Chung, J.Y. Ooi, Granular Matter 13 (2011) 643-656. Written by",
        "# tools/chung_ooi.py%s; docs/VALIDATION.md gives the" % (" (--quick set)" if quick else " --write-cases"),
        "# references, the measured agreement and the source of every parameter:",
    ]
    for m in mats:
        lines.append("#   %s: %s" % (m, SCENE_MATERIALS[m][3]))
    lines.append("# One run holds every case of the test, %g m apart so that none interact;" % spacing)
    lines.append("# particle ids follow the case order of the tool (sphere 1, then its partner).")
    if plane:
        lines.append("# The rigid plane: 1000 x the stiffest sphere's E (as Yade's tests 2-4).")
    lines += [
        "domain: {min: %s, max: %s}" % (vec(lo), vec(hi)),
        "gravity: [0, 0, 0]",
        "contact_model: hertz_mindlin",
        "precision: fp64",
        "effects: {friction: %s, rolling_resistance: false, cohesion: false}" % ("true" if kind == "oblique" else "false"),
        "materials:",
    ]
    for m in mats:
        E, nu, rho = material(m)
        lines.append("  - {name: %s, density: %s, youngs_modulus: %s, poisson_ratio: %s}" % (m, fmt(rho), fmt(E), fmt(nu)))
    if plane:
        E, nu, rho = imps[0].plane
        lines.append("  - {name: rigid, density: %s, youngs_modulus: %s, poisson_ratio: %s}" % (fmt(rho), fmt(E), fmt(nu)))
    lines.append("pairs:")
    # Per-pair restitution and friction: test 3 needs one material per
    # restitution, so each case's own pair carries its e and mu; pairs that
    # never touch get e = 1.
    own = {}
    for imp in imps:
        other = imp.partner["mat"] if imp.partner else "rigid"
        own[tuple(sorted((imp.mat, other)))] = imp
    for a in range(len(mats)):
        for b in range(a, len(mats)):
            key = tuple(sorted((mats[a], mats[b])))
            imp = own.get(key)
            lines.append(pair_line(key, imp, kind))
    if plane:
        for m in mats:
            key = tuple(sorted((m, "rigid")))
            lines.append(pair_line(key, own.get(key), kind))
        lines.append("walls:")
        lines.append("  - {name: plane, plane: {point: [0, 0, 0], normal: [0, 0, 1]}, material: rigid}")
    lines.append("particles:")
    lines.append("  - list:")
    for p in parts:
        lines.append("      - {position: %s, radius: %s, material: %s, velocity: %s, angular_velocity: %s}"
                     % (vec(p[0]), fmt(p[1]), p[2], vec(p[3]), vec(p[4])))
    lines.append("time_step: {fraction_of_contact_time: %g}   # of the Rayleigh time %.4g s" % (TIME_STEP_FRACTION, t_r))
    lines.append("duration: %s" % fmt(end))
    # Normal impacts: a snapshot every step (an interval below the step rounds
    # to one step) to resolve the contact; oblique ones need the end state only.
    lines.append("output: {format: csv, interval: %s}" % ("1e-15" if kind == "hertz" else "0"))
    return "\n".join(lines) + "\n"


def pair_line(key, imp, kind):
    e = imp.e if imp else 1.0
    mu = imp.mu if imp else 0.0
    fr = ", friction: %s" % fmt(mu) if kind == "oblique" else ""
    return "  - {materials: [%s, %s], restitution: %s%s}" % (key[0], key[1], fmt(e), fr)


# ---------------------------------------------------------------- running


def read_csv(path):
    with open(path) as f:
        head = f.readline().split()
        t = float(head[head.index("time") + 1])
        cols = f.readline().lstrip("#").replace(",", " ").split()
        rows = {}
        for line in f:
            vals = line.replace(",", " ").split()
            if vals:
                row = dict(zip(cols, (float(v) for v in vals)))
                rows[int(row["id"])] = row
    return t, rows


def run_scene(binary, scene, out):
    r = subprocess.run([binary, "run", scene, "--out", out, "--backend", "cpu"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        sys.stderr.write(r.stdout)
        raise RuntimeError("%s failed with exit code %d" % (scene, r.returncode))
    return sorted(glob.glob(os.path.join(out, "particles_*.csv")))


def V(row, k):
    return tuple(row[k + c] for c in "xyz")


class Table:
    def __init__(self):
        self.rows, self.failed, self.checked = [], 0, 0

    def add(self, test, case, qty, meas, ref=None, tol=None):
        if ref is None:
            self.rows.append((test, case, qty, "%.5g" % meas, "-", "-", "-", "info"))
            return
        if tol is None and abs(ref) < 1e-3 * abs(meas):
            # An info value whose sliding reference is ~0 (at the threshold).
            self.rows.append((test, case, qty, "%.5g" % meas, "%.5g" % ref, "-", "-", "info"))
            return
        err = (meas - ref) / abs(ref)
        ok = tol is None or abs(err) <= tol
        if tol is not None:
            self.checked += 1
            self.failed += not ok
        self.rows.append((test, case, qty, "%.5g" % meas, "%.5g" % ref, "%+.3f %%" % (100 * err),
                          "-" if tol is None else "%g %%" % (100 * tol),
                          ("ok" if ok else "FAIL") if tol is not None else "info"))

    def print(self):
        head = ("test", "case", "quantity", "measured", "reference", "error", "tol", "result")
        w = [max(len(str(r[i])) for r in self.rows + [head]) for i in range(len(head))]
        line = lambda r: "| " + " | ".join(str(c).ljust(w[i]) for i, c in enumerate(r)) + " |"  # noqa: E731
        print(line(head))
        print("|" + "|".join("-" * (x + 2) for x in w) + "|")
        for r in self.rows:
            print(line(r))


def with_ids(imps):
    """Each impact with the ids of its sphere and of its partner sphere (None
    against the plane), in the order the scene lists them."""
    ids = 0
    for imp in imps:
        yield imp, ids, (ids + 1 if imp.partner else None)
        ids += 2 if imp.partner else 1


def analyse_hertz(number, imps, files, table):
    snaps = [read_csv(f) for f in files]
    for imp, i1, i2 in with_ids(imps):
        m1, _, R1, _, m2, _, R2, _ = bodies(imp)
        n = normal(imp)

        def overlap(rows):
            p1 = V(rows[i1], "")
            if i2 is None:
                return R1 - p1[2]
            return R1 + R2 - norm(add(V(rows[i2], ""), p1, -1))

        def rel_vn(rows):
            v1 = V(rows[i1], "v")
            v2 = (0, 0, 0) if i2 is None else V(rows[i2], "v")
            return dot(add(v1, v2, -1), n)

        ts = [s[0] for s in snaps]
        ov = [overlap(s[1]) for s in snaps]
        # Contact start and end: the overlap's zero crossings, interpolated.
        inside = [k for k, d in enumerate(ov) if d > 0]
        k0, k1 = inside[0], inside[-1]
        if ov[-1] > 0 and imp.e == 1.0:
            raise RuntimeError("test %d, %s: still in contact at the end of the run" % (number, imp.label))
        # Force on sphere 1 from its velocity change between steps (velocity
        # Verlet: m (v_n+1 - v_n) / dt is the mean of two steps' forces).
        fmax = max(m1 * abs(dot(add(V(b[1][i1], "v"), V(a[1][i1], "v"), -1), n)) / (b[0] - a[0])
                   for a, b in zip(snaps, snaps[1:]))
        tc, dmax, fref, v = hertz(imp)
        e_meas = -rel_vn(snaps[-1][1]) / rel_vn(snaps[0][1])
        if imp.e == 1.0:
            t0 = ts[k0 - 1] + (ts[k0] - ts[k0 - 1]) * (-ov[k0 - 1]) / (ov[k0] - ov[k0 - 1])
            t1 = ts[k1] + (ts[k1 + 1] - ts[k1]) * ov[k1] / (ov[k1] - ov[k1 + 1])
            table.add(number, imp.label, "contact time [s]", t1 - t0, tc, TOL_HERTZ)
            table.add(number, imp.label, "max overlap [m]", max(ov), dmax, TOL_HERTZ)
            table.add(number, imp.label, "max force [N]", fmax, fref, TOL_HERTZ)
        else:
            # Damped: the contact ends when the force returns to zero, before
            # the overlap does; only the restitution has a closed form.
            table.add(number, imp.label, "max overlap [m]", max(ov))
        table.add(number, imp.label, "restitution", e_meas, imp.e, TOL_RESTITUTION)


def analyse_oblique(number, imps, files, table):
    _, first = read_csv(files[0])
    _, last = read_csv(files[-1])
    for imp, i1, i2 in with_ids(imps):
        m1, I1, R1, _, m2, _, R2, _ = bodies(imp)
        n = normal(imp)
        v1, w1 = V(first[i1], "v"), V(first[i1], "w")
        v1p, w1p = V(last[i1], "v"), V(last[i1], "w")
        v2p = (0, 0, 0) if i2 is None else V(last[i2], "v")
        v2 = (0, 0, 0) if i2 is None else V(first[i2], "v")
        pv1, pw1, _, _, ratio = sliding(imp)
        # The tangential direction: the initial slip (y in every test).
        t = (0, 1, 0)
        r1 = tuple(R1 * c for c in n)
        # Plotted quantities: restitution, tangential velocity of the centre,
        # spin, contact-point tangential velocity after impact.
        en = dot(add(v1p, v2p, -1), n) / dot(add(v1, v2, -1), n)
        spin_axis = (1, 0, 0) if imp.partner is None else (0, 0, 1)
        ut = dot(add(v1p, cross(w1p, r1)), t)
        regime = "sliding" if ratio > 1 else "stick/micro-slip"
        case = "%s (%s, slip/threshold %.2f)" % (imp.label, regime, ratio)
        slide = ratio > 1
        table.add(number, case, "v_n'/v_n", -en, imp.e, TOL_RESTITUTION)
        table.add(number, case, "v_t' [m/s]", dot(v1p, t), dot(pv1, t) if slide else None)
        table.add(number, case, "w' [rad/s]", dot(w1p, spin_axis), dot(pw1, spin_axis) if slide else None)
        table.add(number, case, "u_t' contact pt [m/s]", ut,
                  dot(add(pv1, cross(pw1, r1)), t) if slide else None)
        if slide:
            tol = TOL_SLIDING if ratio > SLIDING_MARGIN else None
            # Tangential impulse over mu J_n, once from the centre's velocity
            # change and once from the spin change (the lever is R).
            jt_v = m1 * dot(add(v1p, v1, -1), t)
            jt_w = I1 * dot(add(w1p, w1, -1), spin_axis)
            pjt_v = m1 * dot(add(pv1, v1, -1), t)
            pjt_w = I1 * dot(add(pw1, w1, -1), spin_axis)
            table.add(number, case, "J_t/(mu J_n) from v_t", jt_v / pjt_v, 1.0, tol)
            # The model's torque acts at the contact point, R - delta from the
            # centre on a plane and R - delta/2 against a sphere, not at R: in
            # an elastic Hertz impact the force-weighted mean overlap is
            # LEVER_MEAN delta_max (an approximation for e < 1, where
            # delta_max / R is below 0.3 % in these tests).
            _, dmax, _, _ = hertz(imp)
            lever = 1 - LEVER_MEAN * dmax * (1.0 if imp.partner is None else 0.5) / R1
            table.add(number, case, "J_t/(mu J_n) from w", jt_w / pjt_w, lever, tol)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary", nargs="?", help="the grainstorm executable")
    ap.add_argument("--quick", action="store_true", help="reduced set (CTest)")
    ap.add_argument("--write-cases", action="store_true", help="write the full scenes to " + CASE_DIR)
    ap.add_argument("--keep", help="run in this directory and keep the output")
    args = ap.parse_args()
    tests = build_tests(args.quick)
    if args.write_cases:
        os.makedirs(CASE_DIR, exist_ok=True)
        for n, (title, imps, kind) in build_tests(False).items():
            with open(os.path.join(CASE_DIR, "test%d.yaml" % n), "w") as f:
                f.write(scene_text(n, title, imps, kind, False))
        print("wrote %s/test1..8.yaml" % CASE_DIR)
        if not args.binary:
            return 0
    if not args.binary:
        ap.error("BINARY is required unless --write-cases")
    work = args.keep or tempfile.mkdtemp(prefix="chung_ooi_")
    os.makedirs(work, exist_ok=True)
    table = Table()
    started = time.time()
    try:
        for n, (title, imps, kind) in tests.items():
            text = scene_text(n, title, imps, kind, args.quick)
            if args.quick:
                scene = os.path.join(work, "test%d.yaml" % n)
                with open(scene, "w") as f:
                    f.write(text)
            else:
                scene = os.path.join(CASE_DIR, "test%d.yaml" % n)
                with open(scene) as f:
                    if f.read() != text:
                        print("error: %s differs from what this tool generates; run --write-cases" % scene)
                        return 2
            out = os.path.join(work, "out%d" % n)
            shutil.rmtree(out, ignore_errors=True)
            files = run_scene(args.binary, scene, out)
            (analyse_hertz if kind == "hertz" else analyse_oblique)(n, imps, files, table)
    except (RuntimeError, OSError, ValueError, IndexError, KeyError) as err:
        print("error: %s" % err)
        return 2
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    table.print()
    print("\n%d quantities checked, %d outside tolerance; %.1f s" % (table.checked, table.failed,
                                                                      time.time() - started))
    return 1 if table.failed else 0


if __name__ == "__main__":
    sys.exit(main())
