#pragma once
// Compound pendulum: a uniform rod (mass m, length l) pinned at one end to
// the ground, released from rest at `amplitude` from the downward vertical,
// as a model of the multibody core (IDAS GGL and CVODES minimal-coordinate
// paths).
//
// Reference (exact): the simple pendulum's T = 4 sqrt(L/g) K(sin(a/2))
// (Landau & Lifshitz, Mechanics, sec. 11, problem 1) with the equivalent
// length L = I_O / (m d) of the compound pendulum:
//   T = 4 sqrt(I_O / (m g d)) K(sin(amplitude / 2)),
// d = l/2 the pivot-to-centre distance, I_O = m l^2/12 + m d^2 = m l^2/3,
// K the complete elliptic integral of the first kind (std::comp_ellint_1,
// modulus k). At T/2 the rod is at its other extreme (omega = 0).
#include <vector>

#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"

namespace kinetofem::verification {

inline constexpr double kPendulumGravity = units::kStandardGravity;

struct Rod {
  double mass_kg = 2.0, length_m = 1.0;
  double inertia_about_centre() const { return mass_kg * length_m * length_m / 12.0; }
  double weight_n() const { return mass_kg * kPendulumGravity; }
};

// The rod's body-frame origin at the pivot (the ground origin), its centre
// at (l/2, 0); gravity (0, -g).
mech::MultibodyModel compound_pendulum(const Rod& rod, double amplitude_rad);

// T of the header (s).
double compound_pendulum_period_s(const Rod& rod, double amplitude_rad);

// The period from the frame nearest T/2: the zero of omega one Newton step
// away, t* = t - omega/alpha, doubled.
double period_from_half_swing(const mech::Frame& half);

// IDAS (GGL) at t = 0, T/4, T/2, T; frames[2] is the half swing.
struct PendulumRun {
  double exact_period_s = 0.0;
  double computed_period_s = 0.0;
  mech::Results results;
};
PendulumRun run_compound_pendulum(const Rod& rod, double amplitude_rad);

// IDAS (absolute coordinates + multipliers, index-2 GGL) against CVODES (the
// pivot angle as the one minimal coordinate, ODE) at t = 0, 0.1, .., 2 s:
// max pivot-angle difference over the amplitude, max pivot-force difference
// over the weight. Issue 3: both to 1e-6.
struct PendulumAgreement {
  double angle = 0.0, force = 0.0;
  mech::Results ggl, minimal;
};
PendulumAgreement idas_vs_cvodes(const Rod& rod, double amplitude_rad);

}  // namespace kinetofem::verification
