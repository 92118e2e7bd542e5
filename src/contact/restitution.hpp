#pragma once
// The damping ratio a normal restitution coefficient asks for, for the
// clamped spring-dashpots of contact/models/ (linear and Hertz-Mindlin).
#include "core/types.hpp"

namespace gs {

// Normal restitution of a lone impact whose normal force is max(0, spring +
// dashpot) with damping ratio zeta: the contact ends when the force returns to
// zero, before the overlap does, and the sphere leaves at the speed it has then.
//   linear, m x'' = -(k x + 2 zeta sqrt(m k) x'), solved in closed form
//   (Schwager & Poeschel 2007, Phys. Rev. E 75):
//     e = exp(-2 zeta arccos(zeta) / sqrt(1 - zeta^2))      zeta < 1,
//     e = exp(-2)                                           zeta = 1,
//     e = exp(-2 zeta arccosh(zeta) / sqrt(zeta^2 - 1))     zeta > 1.
// The Hertz contact with the Tsuji-type dashpot of contact/models/hertz_mindlin.hpp gives the
// same e: in units of the impact it reads y'' = -(y^1.5 + sqrt(5) zeta y^0.25 y'),
// and with w = y^1.25 its phase-plane equation v dv/dw = -4/5 (w + sqrt(5) zeta v)
// is that of the linear oscillator with the same zeta, from the same start
// (w = 0, v = 1) to the same end (force zero: w + sqrt(5) zeta v = 0).
// tests/contact/test_restitution.cpp checks both against direct integration.
double clamped_restitution(double damping_ratio);

// Damping ratio zeta in [0, inf) that makes the clamped contact of `model`
// rebound at `restitution` e in (0, 1]; e = 1 gives 0, e = exp(-2) gives 1,
// smaller e an overdamped contact. Inverted by bisection to rounding.
double damping_ratio(ContactModel model, double restitution);

}  // namespace gs
