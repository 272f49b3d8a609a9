// The critical-plane search on two stress states whose principal axes turn
// over the load cycle, against their closed-form normal-stress ranges, within
// the bound of the candidate grid (critical_plane.hpp: every normal is within
// delta = 7.07 deg of a candidate at the default 10 deg spacing).
//
// 1. Rotating uniaxial stress: sigma(t) = s0 n(t) n(t)^T, n(t) = cos t e1 +
//    sin t e2 turning in a plane P of unit normal k (tilted: k = (1, 2, 3)/|.|).
//    On a plane of normal m: sigma_n = s0 (m.n)^2 = s0 (1 - (m.k)^2) cos^2(t - alpha),
//    range s0 (1 - (m.k)^2), two cycles per turn; the critical planes are all
//    m in P (range s0). A candidate lies within delta of P, so the search
//    gives a range >= s0 cos^2(delta) on a normal within delta of P.
//    sigma_1 (= s0) and the von Mises stress (= s0) are constant: the
//    principal-stress and von Mises measures see no cycle at all.
// 2. Out-of-phase bending and torsion: sigma_xx = sa cos t, sigma_xy = ta sin t
//    (90 deg phase), rotated as a whole by R. With u = R^T m:
//      sigma_n = sa ux^2 cos t + 2 ta ux uy sin t,  range = 2 sqrt(sa^2 ux^4 + 4 ta^2 ux^2 uy^2),
//    for sa^2 <= 2 ta^2 largest at uz = 0, ux^2 = 2 ta^2 / (4 ta^2 - sa^2):
//      range* = 4 ta^2 / sqrt(4 ta^2 - sa^2)  (sa = ta = 100 MPa: 230.94 MPa at
//      u = (cos 35.26 deg, +-sin 35.26 deg, 0)).
//    The search's range lies between the smallest range on the cap of radius
//    delta about u* and range*, and is the largest closed-form range among the
//    candidate planes.
// Histories sampled at 3600 steps of one period (Residue::Periodic); the
// continuous-time ranges differ from the sampled ones by < 2e-6 relative.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/critical_plane.hpp"
#include "kinetofem/fatigue/miner.hpp"

namespace kinetofem::fatigue {
namespace {

constexpr int kSteps = 3600;
constexpr double kPi = std::numbers::pi;

Eigen::Matrix<double, 6, 1> voigt(const Eigen::Matrix3d& s) {
  Eigen::Matrix<double, 6, 1> v;
  v << s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(2, 0);  // (xx, yy, zz, xy, yz, zx)
  return v;
}

double time_at(int j) { return 2.0 * kPi * j / kSteps; }

TEST(CriticalPlaneRotating, RotatingUniaxialStressFindsItsPlaneWithinTheGridBound) {
  const double s0 = 200 * units::kMpa;
  const Eigen::Vector3d k = Eigen::Vector3d(1, 2, 3).normalized();
  const Eigen::Vector3d e1 = k.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d e2 = k.cross(e1);
  StressHistory history(6, kSteps);
  for (int j = 0; j < kSteps; ++j) {
    const Eigen::Vector3d n = std::cos(time_at(j)) * e1 + std::sin(time_at(j)) * e2;
    history.col(j) = voigt(s0 * n * n.transpose());
  }
  const SnCurve curve({.detail_category_mpa = 71});
  const FatigueOptions options{.residue = Residue::Periodic};
  const auto start = std::chrono::steady_clock::now();
  const NodeFatigue r = assess_node(history, curve, options);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const CandidatePlanes planes = hemisphere_planes(10.0);
  const double delta = planes.covering_radius_deg * units::kDeg;
  EXPECT_NEAR(planes.covering_radius_deg, 7.0744, 1e-4);
  EXPECT_EQ(r.planes_searched, 226);

  const Eigen::Vector3d m = r.normal;
  const double off_plane = std::asin(std::abs(m.dot(k)));
  EXPECT_LE(off_plane, delta);
  // Closed form on the found plane, sampled and continuous.
  double lo = 1e300, hi = -1e300;
  for (int j = 0; j < kSteps; ++j) {
    const double c = m.dot(e1) * std::cos(time_at(j)) + m.dot(e2) * std::sin(time_at(j));
    lo = std::min(lo, s0 * c * c);
    hi = std::max(hi, s0 * c * c);
  }
  EXPECT_NEAR(r.max_range_pa, hi - lo, 1e-9 * s0);
  const double continuous = s0 * (1.0 - m.dot(k) * m.dot(k));
  EXPECT_NEAR(r.max_range_pa, continuous, 2e-6 * s0);
  EXPECT_GE(r.max_range_pa, s0 * std::cos(delta) * std::cos(delta) * (1.0 - 2e-6));
  EXPECT_LE(r.max_range_pa, s0);
  // Two equal cycles per turn: D = 2 / N(range).
  EXPECT_NEAR(total_count(r.cycles), 2.0, 1e-12);
  const double d = 2.0 / curve.endurance(r.max_range_pa);
  EXPECT_NEAR(r.damage, d, 1e-6 * d);
  std::printf("rotating uniaxial: range %.6f MPa (s0 200, bound %.4f MPa), plane %.3f deg off P "
              "(bound %.3f), D %.6e, %.2f ms for %d planes x %d steps\n",
              r.max_range_pa / units::kMpa, s0 * std::pow(std::cos(delta), 2) / units::kMpa,
              off_plane / units::kDeg, delta / units::kDeg, r.damage, ms, r.planes_searched,
              kSteps);

  // Constant sigma_1 and von Mises: no cycle, no damage.
  const NodeFatigue principal =
      assess_node(history, curve,
                  {.measure = StressMeasure::MaxPrincipal, .residue = Residue::Periodic});
  const NodeFatigue mises =
      assess_node(history, curve,
                  {.measure = StressMeasure::SignedVonMises, .residue = Residue::Periodic});
  EXPECT_LT(principal.max_range_pa, 1e-6 * s0);
  EXPECT_LT(mises.max_range_pa, 1e-6 * s0);
  EXPECT_EQ(principal.damage, 0.0);
  EXPECT_EQ(mises.damage, 0.0);
}

TEST(CriticalPlaneRotating, OutOfPhaseBendingTorsionWithinTheGridBound) {
  const double sa = 100 * units::kMpa, ta = 100 * units::kMpa;
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(23.0 * units::kDeg, Eigen::Vector3d(1, 1, 1).normalized())
          .toRotationMatrix();
  StressHistory history(6, kSteps);
  for (int j = 0; j < kSteps; ++j) {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    s(0, 0) = sa * std::cos(time_at(j));
    s(0, 1) = s(1, 0) = ta * std::sin(time_at(j));
    history.col(j) = voigt(rot * s * rot.transpose());
  }
  const auto range_of = [&](const Eigen::Vector3d& m) {  // continuous closed form
    const Eigen::Vector3d u = rot.transpose() * m;
    const double ux2 = u.x() * u.x(), uy2 = u.y() * u.y();
    return 2.0 * std::sqrt(sa * sa * ux2 * ux2 + 4.0 * ta * ta * ux2 * uy2);
  };
  const auto sampled_range_of = [&](const Eigen::Vector3d& m) {
    const Eigen::Vector3d u = rot.transpose() * m;
    double lo = 1e300, hi = -1e300;
    for (int j = 0; j < kSteps; ++j) {
      const double v = sa * u.x() * u.x() * std::cos(time_at(j)) +
                       2.0 * ta * u.x() * u.y() * std::sin(time_at(j));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    return hi - lo;
  };
  const double exact = 4.0 * ta * ta / std::sqrt(4.0 * ta * ta - sa * sa);
  EXPECT_NEAR(exact / units::kMpa, 230.940, 1e-3);
  const double alpha = std::acos(std::sqrt(2.0 * ta * ta / (4.0 * ta * ta - sa * sa)));
  const Eigen::Vector3d u_star(std::cos(alpha), std::sin(alpha), 0.0);
  EXPECT_NEAR(range_of(rot * u_star), exact, 1e-12 * exact);

  const SnCurve curve({.detail_category_mpa = 80});
  const CandidatePlanes planes = hemisphere_planes(10.0);
  const NodeFatigue r = assess_node(history, curve, {.residue = Residue::Periodic}, planes);
  const double delta = planes.covering_radius_deg * units::kDeg;

  // The smallest closed-form range on the cap of radius delta about u*.
  const Eigen::Vector3d a = Eigen::Vector3d::UnitZ(), b = u_star.cross(a);
  double cap_min = 1e300;
  for (int i = 0; i <= 40; ++i) {
    const double rho = delta * i / 40.0;
    for (int j = 0; j < 360; ++j) {
      const double phi = 2.0 * kPi * j / 360.0;
      const Eigen::Vector3d u =
          std::cos(rho) * u_star + std::sin(rho) * (std::cos(phi) * a + std::sin(phi) * b);
      cap_min = std::min(cap_min, range_of(rot * u));
    }
  }
  EXPECT_LE(r.max_range_pa, exact * (1.0 + 1e-12));
  EXPECT_GE(r.max_range_pa, cap_min * (1.0 - 1e-4));
  EXPECT_NEAR(r.max_range_pa, sampled_range_of(r.normal), 1e-9 * exact);
  EXPECT_NEAR(r.max_range_pa, range_of(r.normal), 2e-6 * exact);
  // The search picked the candidate of the largest closed-form range.
  double best = 0.0;
  for (Eigen::Index p = 0; p < planes.normals.rows(); ++p) {
    best = std::max(best, sampled_range_of(planes.normals.row(p).transpose()));
  }
  EXPECT_NEAR(r.max_range_pa, best, 1e-9 * exact);
  // One cycle per period.
  EXPECT_NEAR(total_count(r.cycles), 1.0, 1e-12);
  const double d = 1.0 / curve.endurance(r.max_range_pa);
  EXPECT_NEAR(r.damage, d, 1e-9 * d);
  const Eigen::Vector3d u = rot.transpose() * r.normal;
  const Eigen::Vector3d u_mirror(u_star.x(), -u_star.y(), 0.0);  // the other critical plane
  const double cos_off = std::max(std::abs(u.dot(u_star)), std::abs(u.dot(u_mirror)));
  const double off = std::acos(std::min(1.0, cos_off));
  std::printf("bending-torsion: range %.4f MPa (exact %.4f, cap minimum %.4f), critical normal "
              "%.2f deg from u*, D %.6e\n",
              r.max_range_pa / units::kMpa, exact / units::kMpa, cap_min / units::kMpa,
              off / units::kDeg, r.damage);
}

}  // namespace
}  // namespace kinetofem::fatigue
