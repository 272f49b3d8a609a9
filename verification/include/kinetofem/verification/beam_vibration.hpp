#pragma once
// Analytic references of the vibration checks
// (tests/verification/vibration/ and `kinetofem verify`).
//
// Timoshenko beam (shear deformation and rotary inertia), uniform, length
// L, E, G, density rho, area A, second moment I, shear coefficient kappa:
//   kappa G A (w'' - psi') + rho A w^2 w = 0,
//   E I psi'' + kappa G A (w' - psi) + rho I w^2 psi = 0.
// With w ~ exp(s x): E I kappa G A s^4 + w^2 (kappa G A rho I + rho A E I) s^2
//   + rho A w^2 (rho I w^2 - kappa G A) = 0, two roots s^2 = a^2 > 0 and
// s^2 = -b^2 < 0 below the second spectrum (w^2 < kappa G A / (rho I)); the
// field is a combination of cosh, sinh (a) and cos, sin (b) with psi from
// the first equation. The natural frequencies are the zeros of the 4 x 4
// boundary determinant (clamped: w = psi = 0; free: E I psi' = 0 and
// kappa G A (w' - psi) = 0), found by scanning and bisection (Huang 1961,
// "The effect of rotatory inertia and of shear deformation on the frequency
// and normal mode equations of uniform beams with simple end conditions").
//
// Euler-Bernoulli: f_n = (beta_n L)^2 / (2 pi L^2) sqrt(E I / (rho A)),
// clamped-free beta L = 1.8751, 4.6941, 7.8548; free-free 4.7300, 7.8532.
//
// Single degree of freedom under a base motion of the 3-4-5 polynomial law
// s(t) = h (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t / T (0 <= t <= T, then at
// rest): the relative displacement x of x'' + 2 zeta w x' + w^2 x = -a(t),
// x(0) = x'(0) = 0, in closed form: a cubic particular solution plus the
// damped homogeneous one during the stroke, free damped vibration after it.
#include <vector>

namespace kinetofem::verification {

struct TimoshenkoBeam {
  double length_m = 1.0;
  double youngs_modulus_pa = 210e9;
  double shear_modulus_pa = 105e9;
  double density_kg_m3 = 7850.0;
  double area_m2 = 0.005;
  double second_moment_m4 = 0.0;  // about the bending axis
  double shear_coefficient = 5.0 / 6.0;
};

enum class BeamEnds { ClampedFree, FreeFree };

// The lowest `count` bending frequencies (Hz, ascending; rigid-body modes of
// a free-free beam excluded).
std::vector<double> timoshenko_frequencies_hz(const TimoshenkoBeam& beam, BeamEnds ends, int count);

// Euler-Bernoulli n-th frequency (Hz), n = 1, 2, 3.
double euler_bernoulli_frequency_hz(const TimoshenkoBeam& beam, BeamEnds ends, int n);

// Cowper's shear coefficient of a rectangle: 10 (1 + nu) / (12 + 11 nu).
double cowper_rectangle_shear_coefficient(double poisson_ratio);

struct Sdof345 {
  double omega_rad_s = 2.0 * 3.14159265358979323846 * 5.0;
  double damping_ratio = 0.02;
  double stroke_m = 1.0;     // h
  double duration_s = 2.0;   // T
  double base_acceleration_m_s2(double t) const;
  double relative_displacement_m(double t) const;  // closed form
};

}  // namespace kinetofem::verification
