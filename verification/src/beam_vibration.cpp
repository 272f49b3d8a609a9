#include "kinetofem/verification/beam_vibration.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/LU>

#include "kinetofem/core/error.hpp"

namespace kinetofem::verification {

namespace {

// Boundary determinant of the Timoshenko beam at circular frequency w (header).
double boundary_determinant(const TimoshenkoBeam& beam, BeamEnds ends, double w) {
  const double E = beam.youngs_modulus_pa, G = beam.shear_modulus_pa, rho = beam.density_kg_m3;
  const double A = beam.area_m2, I = beam.second_moment_m4, k = beam.shear_coefficient;
  const double L = beam.length_m;
  const double kGA = k * G * A;
  const double P = E * I * kGA;
  const double Q = w * w * (kGA * rho * I + rho * A * E * I);
  const double R = rho * A * w * w * (rho * I * w * w - kGA);
  const double disc = std::sqrt(Q * Q - 4.0 * P * R);
  const double a = std::sqrt((-Q + disc) / (2.0 * P));
  const double b = std::sqrt((Q + disc) / (2.0 * P));
  const double c = rho * w * w / (k * G);
  const double pa = (a * a + c) / a, pb = (c - b * b) / b;
  // Per basis function: w, psi, w', psi' at x.
  auto values = [&](double x) {
    std::array<std::array<double, 4>, 4> v;  // [function][w, psi, w', psi']
    const double ch = std::cosh(a * x), sh = std::sinh(a * x), cs = std::cos(b * x),
                 sn = std::sin(b * x);
    v[0] = {ch, pa * sh, a * sh, pa * a * ch};
    v[1] = {sh, pa * ch, a * ch, pa * a * sh};
    v[2] = {cs, pb * sn, -b * sn, pb * b * cs};
    v[3] = {sn, -pb * cs, b * cs, pb * b * sn};
    return v;
  };
  const auto v0 = values(0.0), vL = values(L);
  Eigen::Matrix4d D;
  for (int f = 0; f < 4; ++f) {
    if (ends == BeamEnds::ClampedFree) {
      D(0, f) = v0[size_t(f)][0];
      D(1, f) = v0[size_t(f)][1];
    } else {
      D(0, f) = v0[size_t(f)][3] * L;
      D(1, f) = v0[size_t(f)][2] - v0[size_t(f)][1];
    }
    D(2, f) = vL[size_t(f)][3] * L;
    D(3, f) = vL[size_t(f)][2] - vL[size_t(f)][1];
  }
  return D.determinant();
}

}  // namespace

double cowper_rectangle_shear_coefficient(double nu) { return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu); }

double euler_bernoulli_frequency_hz(const TimoshenkoBeam& beam, BeamEnds ends, int n) {
  static constexpr std::array<double, 3> clamped_free = {1.8751040687, 4.6940911330, 7.8547574382};
  static constexpr std::array<double, 3> free_free = {4.7300407449, 7.8532046241, 10.9956078380};
  require(n >= 1 && n <= 3, "Euler-Bernoulli frequency: mode {} not tabulated (1..3)", n);
  const double bl = (ends == BeamEnds::ClampedFree ? clamped_free : free_free)[size_t(n - 1)];
  const double L = beam.length_m;
  return bl * bl / (2.0 * std::numbers::pi * L * L) *
         std::sqrt(beam.youngs_modulus_pa * beam.second_moment_m4 /
                   (beam.density_kg_m3 * beam.area_m2));
}

std::vector<double> timoshenko_frequencies_hz(const TimoshenkoBeam& beam, BeamEnds ends,
                                              int count) {
  require(count >= 1 && beam.second_moment_m4 > 0 && beam.area_m2 > 0 && beam.length_m > 0,
          "Timoshenko beam: count {}, I {} m^4, A {} m^2, L {} m must be positive", count,
          beam.second_moment_m4, beam.area_m2, beam.length_m);
  const double w_ref = 2.0 * std::numbers::pi * euler_bernoulli_frequency_hz(beam, ends, 1);
  const double dw = 0.002 * w_ref;
  const double w_cut = std::sqrt(beam.shear_coefficient * beam.shear_modulus_pa * beam.area_m2 /
                                 (beam.density_kg_m3 * beam.second_moment_m4));
  std::vector<double> out;
  double w0 = 0.05 * w_ref, d0 = boundary_determinant(beam, ends, w0);
  while (int(out.size()) < count) {
    const double w1 = w0 + dw;
    require(w1 < w_cut, "Timoshenko beam: mode {} lies above the second spectrum's cutoff {} Hz",
            out.size() + 1, w_cut / (2.0 * std::numbers::pi));
    const double d1 = boundary_determinant(beam, ends, w1);
    if ((d0 < 0) != (d1 < 0)) {
      double lo = w0, hi = w1, dlo = d0;
      for (int it = 0; it < 200 && hi - lo > 1e-14 * hi; ++it) {
        const double mid = 0.5 * (lo + hi), dm = boundary_determinant(beam, ends, mid);
        if ((dm < 0) == (dlo < 0)) {
          lo = mid;
          dlo = dm;
        } else {
          hi = mid;
        }
      }
      out.push_back(0.5 * (lo + hi) / (2.0 * std::numbers::pi));
    }
    w0 = w1;
    d0 = d1;
  }
  return out;
}

namespace {

struct SdofState {
  double x, v;
};

SdofState sdof_during_stroke(const Sdof345& s, double t) {
  const double w = s.omega_rad_s, z = s.damping_ratio, h = s.stroke_m, T = s.duration_s;
  // Load p(t) = -a(t) = p1 t + p2 t^2 + p3 t^3.
  const double p1 = -60.0 * h / (T * T * T), p2 = 180.0 * h / (T * T * T * T),
               p3 = -120.0 * h / (T * T * T * T * T);
  const double w2 = w * w;
  const double c3 = p3 / w2;
  const double c2 = (p2 - 6.0 * z * w * c3) / w2;
  const double c1 = (p1 - 4.0 * z * w * c2 - 6.0 * c3) / w2;
  const double c0 = (-2.0 * z * w * c1 - 2.0 * c2) / w2;
  const double wd = w * std::sqrt(1.0 - z * z);
  const double A = -c0, B = (z * w * A - c1) / wd;
  const double e = std::exp(-z * w * t), cs = std::cos(wd * t), sn = std::sin(wd * t);
  const double xh = e * (A * cs + B * sn);
  const double vh = e * ((-z * w * A + wd * B) * cs + (-z * w * B - wd * A) * sn);
  return {xh + c0 + t * (c1 + t * (c2 + t * c3)), vh + c1 + t * (2.0 * c2 + 3.0 * c3 * t)};
}

}  // namespace

double Sdof345::base_acceleration_m_s2(double t) const {
  if (t <= 0.0 || t >= duration_s) return 0.0;
  const double tau = t / duration_s;
  return stroke_m / (duration_s * duration_s) * (60.0 * tau - 180.0 * tau * tau + 120.0 * tau * tau * tau);
}

double Sdof345::relative_displacement_m(double t) const {
  if (t <= 0.0) return 0.0;
  if (t <= duration_s) return sdof_during_stroke(*this, t).x;
  const SdofState end = sdof_during_stroke(*this, duration_s);
  const double w = omega_rad_s, z = damping_ratio, wd = w * std::sqrt(1.0 - z * z);
  const double s = t - duration_s;
  return std::exp(-z * w * s) *
         (end.x * std::cos(wd * s) + (end.v + z * w * end.x) / wd * std::sin(wd * s));
}

}  // namespace kinetofem::verification
