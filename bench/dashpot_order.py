#!/usr/bin/env python3
"""How accurately a lone normal impact comes out at a given time step, for the
code's treatment of the dashpot and for second-order alternatives.

An independent re-computation in numpy (no grainstorm binary): the relative
motion of a head-on pair, which is that of a sphere of the effective mass m*
on a fixed plane (two equal spheres of mass m: m* = m/2). The overlap x obeys
m* x'' = -f, with the clamped normal laws of src/contact/models/:

  linear  f = max(0, k x + 2 zeta sqrt(m* k) x')
  Hertz   f = max(0, 4/3 E* sqrt(R*) x^1.5 + 2 sqrt(5/6) zeta sqrt(S_n m*) x'),
          S_n = 2 E* sqrt(R* x)

and zeta from the clamped law e = exp(-2 zeta arccos(zeta) / sqrt(1 - zeta^2))
(contact/restitution.cpp). In units of the impact (approach speed 1; linear:
omega0 = 1; Hertz: the unit of time (m*/(K sqrt(v0)))^0.4 with
K = 4/3 E* sqrt(R*)) both laws have no free parameter but zeta:

  linear  x'' = -max(0, x + 2 zeta x')
  Hertz   y'' = -max(0, y^1.5 + sqrt(5) zeta y^0.25 y')

so every relative error below depends on h / t_c and e only; for Hertz it is
the same at every impact velocity, and h is given as a fraction of the
impact's own contact duration (not of the Rayleigh time the loader uses:
see the "loader's fractions" table for that mapping).

Every scheme is a leapfrog u_{n+1/2} = u_{n-1/2} + h a_n, x_{n+1} = x_n +
h u_{n+1/2} (velocity Verlet's kick-drift-kick written with half-step
velocities); they differ in the velocity the dashpot sees in a_n = -f(x_n, w_n)/m*:

  A   the code (src/integrate/velocity_verlet.hpp): w_n = u_{n-1/2}, the velocity
      after the first half kick, half a step old.
  B1  extrapolated: w_n = u_{n-1/2} + h/2 a_{n-1}, the previous step's
      acceleration carried over the missing half step.
  B2  predictor-corrector: the force of B1, then w_n = u_{n-1/2} + h/2 a_n(B1)
      and the force again (one fixed-point pass towards C).
  C   implicit (trapezoidal) dashpot: w_n = v_n solves v_n = u_{n-1/2} + h/2 a(x_n, v_n),
      i.e. velocity Verlet with the whole-step velocity in the force, solved
      exactly for the lone contact (linear in v_n; the clamp picks the branch).

Contact: it starts at the first step with x > 0 and ends at the first step at
which the unclamped force k x + c w is <= 0 (the force is zero from there on).
Observables: restitution -u_final / v0 and the contact duration, the time
during which the force acts: from the crossing of x = 0 (exact: the approach
is uniform) to the zero of the sampled unclamped force, interpolated linearly
between the last positive and the first non-positive sample (so that the step
does not quantise it; counted in whole steps it would carry up to one step,
h / t_c, of error). The exact values are e itself and, linear,
t_c = 2 arccos(zeta) / (omega0 sqrt(1 - zeta^2)); Hertz, t_c from an RK4
integration with a step of t_c / 64000.

The grid of steps does not line up with the first touch: the first contact
step finds x_1 = s h v0 with s in (0, 1]. The linear dashpot jumps from 0 to
c v0 at the touch, so the result depends on s at first order; every point is
run for N = --nphase (16) start phases s = (j + 1/2) / N and the table gives the largest
|error| over them ("max") and their mean ("mean", signed).

Extra work per contact of each option in the real kernels (the judgement of
"under 10 % more time per step"):

  A   nothing.
  B1  the force kernel needs w = v + h/2 a_prev of every particle it visits.
      The KickDrift kernel already reads the old force of its particle, so it
      can write w (24 bytes, 48 with the angular velocity for friction) next
      to v; the force kernel then reads w instead of v: no more bytes read
      per contact, one more per-particle array written and 24-48 bytes per
      particle more memory. No extra pass.
  B2  a second force pass per step (the corrector), about 2x the force time.
  C   the dashpot couples every particle to its neighbours: (M + h/2 C) v =
      M u + h/2 F_elastic is a sparse linear solve per step (for friction
      with the tangential dashpots too). A Jacobi approximation with the
      per-particle sum of damping coefficients needs a pass to form the sums
      and an iteration per sweep: several force passes.

Usage:
  bench/dashpot_order.py                # the tables
  bench/dashpot_order.py --plot FILE    # and a figure (needs matplotlib)
  bench/dashpot_order.py --nphase 32

Checking scheme A against the code: --validate re-computes the impact of
bench/accuracy_study.cpp with the law the code had when docs/ACCURACY.md's
impact figures were measured (unclamped force, zeta from
e = exp(-pi zeta / sqrt(1 - zeta^2)), the study's step fractions and start
gap, the touch time interpolated as the study does, errors against a run at
0.005 t_c), and the same study with the clamped law, which is what the
study will measure now. The code itself, for a lone sphere on a plane
(bench/impact_step.yaml: linear, e = 0.5, no gravity, 1 m/s onto a plane,
frictionless); set the fraction, run, read the rebound velocity from the
final CSV snapshot:

  for f in 0.0125 0.025 0.045 0.05 0.054 0.1 0.2; do
    sed "s/fraction_of_contact_time: [0-9.]*/fraction_of_contact_time: $f/" \
        bench/impact_step.yaml > /tmp/impact_$f.yaml
    grainstorm run /tmp/impact_$f.yaml --out /tmp/impact_$f --overwrite > /dev/null
    last=$(ls /tmp/impact_$f/particles_*.csv | tail -1)
    # columns: id, material, marker, radius, x, y, z, vx, vy, vz, ...
    awk -F, -v f=$f '$1 ~ /^ *[0-9]+$/ {printf "%s e = %.6f\n", f, $10 / 1.0}' "$last"
  done

(a fraction the loader refuses is reported as such; the sphere starts
0.1 mm above the plane at -1 m/s and the run lasts 2 ms, long after it has
left.) Compare with `--code-yaml`, which prints what scheme A gives for that
scene at those fractions.
"""
import argparse
import math
import sys

import numpy as np

FRACTIONS = [0.2, 0.1, 0.054, 0.05, 0.045, 0.025, 0.0125]
RESTITUTIONS = [0.3, 0.5, 0.7, 0.9]
SCHEMES = ["A", "B1", "B2", "C", "A+o", "B1+o", "C+o"]
SCHEME_NAMES = {
    "A": "code: dashpot sees u(n-1/2)",
    "B1": "extrapolated u(n-1/2) + h/2 a(n-1)",
    "B2": "predictor-corrector (2 force passes)",
    "C": "implicit (trapezoidal) dashpot",
    "A+o": "A with the onset correction",
    "B1+o": "B1 with the onset correction",
    "C+o": "C with the onset correction",
}


# --- damping ratio --------------------------------------------------------------

def clamped_restitution(z):
    if z == 1:
        return math.exp(-2.0)
    if z < 1:
        return math.exp(-2 * z * math.acos(z) / math.sqrt(1 - z * z))
    return math.exp(-2 * z * math.acosh(z) / math.sqrt(z * z - 1))


def zeta_clamped(e):
    """As contact/restitution.cpp: bisection of the clamped law."""
    if e == 1:
        return 0.0
    lo, hi = 0.0, 1.0
    while clamped_restitution(hi) > e:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if clamped_restitution(mid) > e:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def zeta_unclamped(e):
    """The textbook relation, which contact_time.cpp still uses for t_c."""
    le = math.log(e)
    return -le / math.sqrt(math.pi ** 2 + le * le)


# --- the laws, in units of the impact --------------------------------------------

class Law:
    """f(x, w) = K(x) + C(x) w for x > 0 (clamped at 0 unless clamp=False)."""

    def __init__(self, model, zeta, clamp=True):
        self.model, self.zeta, self.clamp = model, zeta, clamp

    def parts(self, x):
        if self.model == "linear":
            return x, 2 * self.zeta
        return x ** 1.5, math.sqrt(5.0) * self.zeta * x ** 0.25

    def force(self, x, w):
        k, c = self.parts(x)
        raw = k + c * w
        return (max(raw, 0.0) if self.clamp else raw), raw


def exact_linear(zeta):
    """Restitution, force duration, touch duration (omega0 = 1, v0 = 1)."""
    s = math.sqrt(1 - zeta * zeta)
    t_force = 2 * math.acos(zeta) / s
    return clamped_restitution(zeta), t_force, t_force + 2 * zeta


def rk4_reference(law, h=None, steps_per_tc=64000):
    """Restitution, force duration and touch duration by RK4 (any law)."""
    if h is None:
        h = 3.3 / steps_per_tc

    def acc(x, v):
        if x <= 0:
            return 0.0
        return -law.force(x, v)[0]

    x, v, t = 0.0, 1.0, 0.0
    t_force = None
    _, g_prev = law.force(1e-300, 1.0)
    while True:
        k1x, k1v = v, acc(x, v)
        k2x, k2v = v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v)
        k3x, k3v = v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v)
        k4x, k4v = v + h * k3v, acc(x + h * k3x, v + h * k3v)
        xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if xn <= 0:
            t_touch = t + h * x / (x - xn)
            if t_force is None:
                t_force = t_touch
            return -vn, t_force, t_touch
        _, g = law.force(xn, vn)
        if law.clamp and t_force is None and g <= 0:
            t_force = t + h * g_prev / (g_prev - g)
        g_prev = g
        x, v, t = xn, vn, t + h


# --- the schemes ------------------------------------------------------------------

def impact(law, scheme, h, s):
    """One impact at step h with x_1 = s h. `scheme` is A, B1, B2 or C, with
    "+o" for the onset correction. Returns (restitution, force duration, touch
    duration, steps with a force)."""
    onset = scheme.endswith("+o")
    base = scheme[:-2] if onset else scheme
    # exponent p of the dashpot coefficient's growth with the time since the touch
    p = 0.0 if law.model == "linear" else 0.25
    x, u, a_prev, t = s * h, 1.0, 0.0, 0.0
    t_start = -s * h
    t_force = t_touch = None
    samples = []  # (t, g) of the last two steps in contact, g the unclamped force
    steps_on = 0
    for _ in range(100000):
        if x > 0:
            k, c = law.parts(x)
            if onset and x - h * u <= 0:
                # First step of the contact: the overlap was negative a step
                # ago, the touch was tau = x / u before this step, and the
                # kick carries this force over [t - h/2, t + h/2]. The dashpot
                # (coefficient ~ tau^p) acted only from the touch on: weight
                # it by its integral since the touch over h times its value now.
                tau = x / u
                c *= (tau + 0.5 * h) ** (p + 1) / ((p + 1) * h * tau ** p)
            if base == "A":
                w = u
            elif base == "B1":
                w = u + 0.5 * h * a_prev
            elif base == "B2":
                w0 = u + 0.5 * h * a_prev
                w = u - 0.5 * h * (max(0.0, k + c * w0) if law.clamp else k + c * w0)
            elif base == "C":
                w = (u - 0.5 * h * k) / (1 + 0.5 * h * c)
                if law.clamp and k + c * w <= 0:
                    w = u  # the branch without force
            else:
                raise ValueError(scheme)
            g = k + c * w
            f = max(g, 0.0) if law.clamp else g
            if t_force is None and law.clamp:
                if g <= 0:
                    tp, gp = samples[-1]
                    t_force = tp + h * gp / (gp - g)
                else:
                    samples = (samples + [(t, g)])[-2:]
            if f != 0:
                steps_on += 1
        else:
            f = 0.0
        a = -f
        u += h * a
        xn = x + h * u
        if x > 0 >= xn and t_touch is None:
            t_touch = t + h * x / (x - xn)
            if t_force is None:
                # The overlap closed before a step saw the force at zero:
                # extrapolate the force's last two samples, at most to here.
                t_force = t_touch
                if law.clamp and len(samples) == 2 and samples[1][1] < samples[0][1]:
                    (t0, g0), (t1, g1) = samples
                    t_force = min(t_touch, t1 + h * g1 / (g0 - g1))
        x, t, a_prev = xn, t + h, a
        if x < 0 and u < 0 and t_touch is not None:
            return -u, t_force - t_start, t_touch - t_start, steps_on
    raise RuntimeError("no rebound")


# --- the study -----------------------------------------------------------------------

_HERTZ_REF = {}


def reference(model, zeta):
    if model == "linear":
        return exact_linear(zeta)
    if zeta not in _HERTZ_REF:
        _HERTZ_REF[zeta] = rk4_reference(Law("hertz", zeta))
    return _HERTZ_REF[zeta]


def phases(n):
    return [(j + 0.5) / n for j in range(n)]


def errors(model, e, scheme, frac, nphase):
    """Relative errors of restitution and force duration over the phases."""
    zeta = zeta_clamped(e)
    e_ref, tc_ref, _ = reference(model, zeta)
    law = Law(model, zeta)
    h = frac * tc_ref
    er, et = [], []
    for s in phases(nphase):
        r, tf, _, _ = impact(law, scheme, h, s)
        er.append(r / e_ref - 1)
        et.append(tf / tc_ref - 1)
    er, et = np.array(er), np.array(et)
    return {"e_max": np.abs(er).max(), "e_mean": er.mean(), "t_max": np.abs(et).max(), "t_mean": et.mean()}


def fit_order(fracs, errs):
    """Slope of log |error| against log h over the steps given."""
    f, y = np.log(np.asarray(fracs)), np.log(np.maximum(np.asarray(errs), 1e-300))
    return np.polyfit(f, y, 1)[0]


def study(nphase):
    rows = {}
    for model in ("linear", "hertz"):
        for e in RESTITUTIONS:
            for scheme in SCHEMES:
                for frac in FRACTIONS:
                    rows[model, e, scheme, frac] = errors(model, e, scheme, frac, nphase)
    return rows


def print_tables(rows, nphase):
    print(f"Lone impact, clamped laws; errors relative to the exact restitution e and contact\n"
          f"duration t_c; h = fraction x t_c (the impact's own duration); {nphase} start phases:\n"
          f"max = largest |error| over the phases, mean = their signed mean. Percent.\n")
    for key, name in SCHEME_NAMES.items():
        print(f"  {key:3s} {name}")
    order_fracs = [0.05, 0.025, 0.0125]
    for model in ("linear", "hertz"):
        print(f"\n== {model} ==")
        head = "   e  scheme " + "".join(f"{f:>17g}" for f in FRACTIONS) + "   order(max, 0.0125-0.05)"
        for what, label in (("e", "restitution"), ("t", "contact duration")):
            print(f"\n{label}: max |err| / mean err [%]")
            print(head)
            for e in RESTITUTIONS:
                for scheme in SCHEMES:
                    cells = []
                    for frac in FRACTIONS:
                        r = rows[model, e, scheme, frac]
                        cells.append(f"{100 * r[what + '_max']:8.3f}/{100 * r[what + '_mean']:+7.3f} ")
                    order = fit_order(order_fracs, [rows[model, e, scheme, f][what + "_max"] for f in order_fracs])
                    print(f"{e:4.1f}  {scheme:6s} " + "".join(cells) + f"   {order:5.2f}")
    # The criterion: both within 2 % at 0.2 t_c, worst over e and phases.
    print("\nWorst over e in {0.3, 0.5, 0.7, 0.9} and the phases, max(|err e|, |err t_c|) [%]:")
    print("model   scheme " + "".join(f"{f:>9g}" for f in FRACTIONS))
    for model in ("linear", "hertz"):
        for scheme in SCHEMES:
            cells = [max(max(rows[model, e, scheme, f]["e_max"], rows[model, e, scheme, f]["t_max"])
                         for e in RESTITUTIONS) for f in FRACTIONS]
            print(f"{model:7s} {scheme:6s} " + "".join(f"{100 * c:9.3f}" for c in cells))
    print("\nThe same for the phase-mean errors, max(|mean err e|, |mean err t_c|) [%]:")
    print("model   scheme " + "".join(f"{f:>9g}" for f in FRACTIONS))
    for model in ("linear", "hertz"):
        for scheme in SCHEMES:
            cells = [max(max(abs(rows[model, e, scheme, f]["e_mean"]), abs(rows[model, e, scheme, f]["t_mean"]))
                         for e in RESTITUTIONS) for f in FRACTIONS]
            print(f"{model:7s} {scheme:6s} " + "".join(f"{100 * c:9.3f}" for c in cells))


# --- the loader's fractions ---------------------------------------------------------------

def loader_fraction_tables(nphase):
    """h as the loader derives it: linear, a fraction of the clamped contact's
    duration (contact_time.cpp; before 2026-12-02 it was the unclamped half
    period pi / (omega0 sqrt(1 - zeta_u^2))); Hertz, of the Rayleigh time, for
    accuracy_study's spheres (R = 1 mm, rho = 2500, E = 5 MPa, nu = 0.25, two
    equal spheres approaching at 1 m/s)."""
    print("\nThe loader's fractions: h / t_c(actual) for fraction_of_contact_time f")
    print("  linear: t_c(loader) = the clamped contact's duration 2 arccos(zeta) / (omega0 sqrt(1 - zeta^2))")
    r, rho, young, nu, v0 = 1e-3, 2500.0, 5e6, 0.25, 1.0
    shear = young / (2 * (1 + nu))
    t_rayleigh = math.pi * r * math.sqrt(rho / shear) / (0.1631 * nu + 0.8766)
    m_eff = 4 / 3 * math.pi * r ** 3 * rho / 2
    k_h = 4 / 3 * (young / (2 * (1 - nu * nu))) * math.sqrt(r / 2)
    unit = (m_eff / (k_h * math.sqrt(v0))) ** 0.4
    print(f"  hertz: t_c(loader) = Rayleigh time {t_rayleigh:.4g} s; unit of time of the 1 m/s impact {unit:.4g} s")
    print("   e  model   t_c(actual)/t_c(loader)")
    ratio = {}
    for e in RESTITUTIONS:
        z = zeta_clamped(e)
        lin = 1.0
        her = reference("hertz", z)[1] * unit / t_rayleigh
        ratio["linear", e], ratio["hertz", e] = lin, her
        print(f"{e:4.1f}  linear  {lin:.4f}\n{e:4.1f}  hertz   {her:.4f}")
    fracs = [0.2, 0.11, 0.1, 0.05, 0.025]
    print("\nErrors at the loader's fractions, max over the phases, restitution / contact duration [%]")
    print("model   e    scheme " + "".join(f"{f:>17g}" for f in fracs))
    for model in ("linear", "hertz"):
        for e in RESTITUTIONS:
            for scheme in SCHEMES:
                cells = []
                for f in fracs:
                    r_ = errors(model, e, scheme, f / ratio[model, e], nphase)
                    cells.append(f"{100 * r_['e_max']:7.3f}/{100 * r_['t_max']:7.3f}  ")
                print(f"{model:7s} {e:3.1f}  {scheme:6s} " + "".join(cells))


# --- checking scheme A against the code's own measurements ---------------------------------

def accuracy_study_impact(model, fraction, clamp):
    """bench/accuracy_study.cpp's impact in SI: two spheres R = 1 mm, rho = 2500,
    1.001 R from the origin each, approaching at 0.5 m/s each, e = 0.7; linear
    k = 2e3 N/m; Hertz E = 5e6, nu = 0.25. The step is fraction x the loader's
    t_c (linear: the unclamped half period; Hertz: the Rayleigh time). Returns
    (relative velocity after, touch time), the study's observables."""
    r, rho, e, v0, k = 1e-3, 2500.0, 0.7, 1.0, 2e3
    m = float(np.float32(4 / 3 * math.pi * r ** 3 * rho))  # the stored mass is fp32
    m_eff = m / 2
    zu = zeta_unclamped(e)
    zeta = zeta_clamped(e) if clamp else zu
    if model == "linear":
        omega0 = math.sqrt(k / m_eff)
        # the loader's t_c: the clamped contact's duration since the clamp, the
        # unclamped half period before
        t_loader = exact_linear(zeta)[1] / omega0 if clamp else math.pi / (omega0 * math.sqrt(1 - zu * zu))
        t_unit = 1 / omega0
    else:
        young, nu = 5e6, 0.25
        shear = young / (2 * (1 + nu))
        t_loader = math.pi * r * math.sqrt(rho / shear) / (0.1631 * nu + 0.8766)
        k_h = 4 / 3 * (young / (2 * (1 - nu * nu))) * math.sqrt(r / 2)
        t_unit = (m_eff / (k_h * math.sqrt(v0))) ** 0.4
    h = fraction * t_loader / t_unit  # in units of the impact (v0 = 1 m/s)
    gap0 = 0.002 * r / (v0 * t_unit)  # initial gap in the impact's length unit v0 t_unit
    # first step with overlap: x_n = n h - gap0 > 0
    n1 = math.floor(gap0 / h) + 1
    s = (n1 * h - gap0) / h
    law = Law(model, zeta, clamp=clamp)
    rest, _, touch, _ = impact(law, "A", h, s)
    return rest * v0, touch * t_unit


def validate():
    print("Scheme A against bench/accuracy_study.cpp's impact (docs/ACCURACY.md): error =")
    print("max relative error of the rebound speed and the touch time against a run at 0.005 t_c.")
    measured = {("linear", 0.025): 0.00406, ("linear", 0.05): 0.0109, ("linear", 0.1): 0.0541,
                ("linear", 0.2): 0.142, ("hertz", 0.025): 0.00167, ("hertz", 0.05): 0.00334,
                ("hertz", 0.1): 0.00811, ("hertz", 0.2): 0.0197}
    print("model   dt/t_c   code, old law (ACCURACY.md)   script A, old law   script A, clamped law (prediction)")
    for model in ("linear", "hertz"):
        ref_old = accuracy_study_impact(model, 0.005, clamp=False)
        ref_new = accuracy_study_impact(model, 0.005, clamp=True)
        for f in (0.025, 0.05, 0.1, 0.2):
            old = accuracy_study_impact(model, f, clamp=False)
            new = accuracy_study_impact(model, f, clamp=True)
            err_old = max(abs(old[i] / ref_old[i] - 1) for i in range(2))
            err_new = max(abs(new[i] / ref_new[i] - 1) for i in range(2))
            print(f"{model:7s} {f:6g}   {measured[model, f]:12.4g}                 {err_old:12.4g}"
                  f"        {err_new:12.4g}")


def code_yaml_prediction():
    """What scheme A gives for bench/impact_step.yaml (sphere on a plane,
    linear, e = 0.5, k = 1000 N/m, R = 1 mm, rho = 2500, 1 m/s, starting
    0.1 mm above the plane; frictionless, no gravity)."""
    r, rho, e, v0, k, z0 = 1e-3, 2500.0, 0.5, 1.0, 1000.0, 1.1e-3
    m = float(np.float32(4 / 3 * math.pi * r ** 3 * rho))
    omega0 = math.sqrt(k / m)
    zeta = zeta_clamped(e)
    tc = exact_linear(zeta)[1] / omega0
    t_loader = tc  # the loader's t_c is the clamped contact's duration
    gap0 = (z0 - r) * omega0 / v0
    print(f"bench/impact_step.yaml: t_c(loader) = {t_loader:.6g} s, t_c(actual) = {tc:.6g} s")
    print("fraction  h/t_c(actual)  rebound speed (scheme A)  e error")
    for f in FRACTIONS:
        h = f * t_loader * omega0
        n1 = math.floor(gap0 / h) + 1
        s = (n1 * h - gap0) / h
        rest = impact(Law("linear", zeta), "A", h, s)[0]
        print(f"{f:8g}  {f * t_loader / tc:13.4f}  {rest * v0:.6f} m/s            {100 * (rest / e - 1):+.3f} %")


def plot(rows, path):
    """Per scheme, the worst over e of the largest |error| over the phases
    (solid) and of the phase-mean error (dotted), against h / t_c."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    fr = np.array(FRACTIONS)
    for i, model in enumerate(("linear", "hertz")):
        for j, (what, label) in enumerate((("e", "restitution"), ("t", "contact duration"))):
            ax = axes[j][i]
            for n, scheme in enumerate(SCHEMES):
                worst = [max(rows[model, e, scheme, f][what + "_max"] for e in RESTITUTIONS) for f in FRACTIONS]
                mean = [max(abs(rows[model, e, scheme, f][what + "_mean"]) for e in RESTITUTIONS) for f in FRACTIONS]
                line, = ax.loglog(fr, np.maximum(worst, 1e-7), "o-", color=f"C{n}", ms=3, lw=1.2,
                                  label=f"{scheme}: {SCHEME_NAMES[scheme]}")
                ax.loglog(fr, np.maximum(mean, 1e-7), ":", color=line.get_color(), lw=1)
            ax.axhline(0.02, color="grey", lw=0.6)
            ax.set_title(f"{model}: {label} (solid: worst phase, dotted: phase mean; worst e)", fontsize=9)
            ax.set_xlabel("h / t_c (the impact's own contact duration)")
            ax.set_ylabel("relative error")
            ax.grid(True, which="both", lw=0.3)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    print(f"wrote {path}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--plot", metavar="FILE")
    ap.add_argument("--nphase", type=int, default=16)
    ap.add_argument("--validate", action="store_true", help="only the check against the code's measurements")
    ap.add_argument("--code-yaml", action="store_true", help="only the prediction for bench/impact_step.yaml")
    args = ap.parse_args()
    if args.validate:
        validate()
        return
    if args.code_yaml:
        code_yaml_prediction()
        return
    # The Hertz reference: restitution must be e (the clamped law), and the
    # undamped duration 2.94324 y_max.
    y_max = (5 / 4) ** 0.4
    ref0 = rk4_reference(Law("hertz", 0.0))
    print(f"Hertz reference: undamped duration {ref0[1]:.6f} (2.94324 y_max = {2.94324 * y_max:.6f}), "
          f"e = {ref0[0]:.6f}")
    for e in RESTITUTIONS:
        r = reference("hertz", zeta_clamped(e))
        print(f"  e = {e}: zeta = {zeta_clamped(e):.4f}, RK4 restitution {r[0]:.6f}, duration {r[1]:.6f}, "
              f"linear duration {exact_linear(zeta_clamped(e))[1]:.6f} (units of the impact)")
    rows = study(args.nphase)
    print()
    print_tables(rows, args.nphase)
    loader_fraction_tables(args.nphase)
    print()
    validate()
    if args.plot:
        plot(rows, args.plot)


if __name__ == "__main__":
    sys.exit(main())
