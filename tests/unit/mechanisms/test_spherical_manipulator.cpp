// SPEC §5 spherical manipulator (spherical_manipulator.hpp): the data table,
// the sizing rules, inverse kinematics and its rates against finite
// differences, and the service-zone check.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SphericalManipulator, VariantsTableOfSpec5) {
  const SphericalVariant& a = spherical_variant('A');
  EXPECT_DOUBLE_EQ(a.r_max_m, 2.2);
  EXPECT_DOUBLE_EQ(a.r_min_m, 1.2);
  EXPECT_DOUBLE_EQ(a.m1_kg, 300);
  const SphericalVariant& d = spherical_variant('D');
  EXPECT_DOUBLE_EQ(d.height_a_m, 0.45);
  EXPECT_DOUBLE_EQ(d.k_accel, 0.2);
  EXPECT_DOUBLE_EQ(d.k_decel, 0.3);
  EXPECT_NEAR(d.tilt_max_rad, 24 * kDeg, 1e-15);
  EXPECT_DOUBLE_EQ(spherical_variant('E').speed_mps, 1.0);
  EXPECT_THROW(spherical_variant('F'), Error);
}

TEST(SphericalManipulator, SizingRules) {
  for (const SphericalVariant& v : spherical_variants()) {
    const SphericalDesign d = size_spherical_manipulator(v, 10.0);
    // SPEC §5: l1 = r_Mmax + 0.5 l2 + 0.1 m, l2 = (0.2..0.5) l1 (0.3 chosen), d2 = (0.2..0.4) l2.
    EXPECT_NEAR(d.arm_length_m, v.r_max_m + 0.5 * d.sleeve_length_m + 0.1, 1e-14);
    EXPECT_NEAR(d.sleeve_length_m, 0.3 * d.arm_length_m, 1e-14);
    EXPECT_NEAR(d.sleeve_diameter_m, 0.3 * d.sleeve_length_m, 1e-14);
    EXPECT_NEAR(d.arm_inertia_transverse, v.m3_kg * d.arm_length_m * d.arm_length_m / 12.0, 1e-12);
  }
  EXPECT_THROW(size_spherical_manipulator(spherical_variant('A'), -1.0), Error);
  SphericalSizingOptions bad;
  bad.sleeve_ratio = 0.6;
  EXPECT_THROW(size_spherical_manipulator(spherical_variant('A'), 5.0, bad), Error);
}

TEST(SphericalManipulator, InverseKinematicsAndRatesMatchFiniteDifferences) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('B'), 8.0);
  const Eigen::Vector3d m(1.3, 0.6, 1.1);
  const Eigen::Vector3d q = spherical_inverse_kinematics(d, m);
  // SPEC §5: l_BM = sqrt(x^2 + y^2 + (z - zB)^2), phi21 = asin((z - zB)/l_BM), phi10 = atan2(y, x).
  EXPECT_NEAR(q(2), std::sqrt(1.3 * 1.3 + 0.6 * 0.6 + 0.3 * 0.3), 1e-15);
  EXPECT_NEAR(q(1), std::asin(0.3 / q(2)), 1e-15);
  EXPECT_NEAR(q(0), std::atan2(0.6, 1.3), 1e-15);
  EXPECT_LT((spherical_forward_kinematics(d, q) - m).norm(), 1e-15);
  // A curved test path M(t) (not just a line) so that all rate terms act.
  auto path = [](double t) {
    return Eigen::Vector3d(1.3 + 0.4 * std::sin(t), 0.6 + 0.5 * t * t, 1.1 - 0.3 * std::cos(2 * t));
  };
  auto path_d = [](double t) { return Eigen::Vector3d(0.4 * std::cos(t), 1.0 * t, 0.6 * std::sin(2 * t)); };
  auto path_dd = [](double t) { return Eigen::Vector3d(-0.4 * std::sin(t), 1.0, 1.2 * std::cos(2 * t)); };
  const double t = 0.7, h = 1e-5;
  const SphericalJointMotion j = spherical_joint_motion(d, path(t), path_d(t), path_dd(t));
  const Eigen::Vector3d qp = spherical_inverse_kinematics(d, path(t + h)), qm = spherical_inverse_kinematics(d, path(t - h));
  const Eigen::Vector3d q0 = spherical_inverse_kinematics(d, path(t));
  // Reference: central differences of the inverse kinematics, h = 1e-5
  // (truncation ~1e-10, round-off ~1e-11 for q', ~1e-6 for q'').
  EXPECT_LT((j.qd - (qp - qm) / (2 * h)).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT((j.qdd - (qp - 2 * q0 + qm) / (h * h)).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(SphericalManipulator, ServiceZoneViolationNamesJointAndTime) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('C'), 5.0);
  try {
    check_service_zone(d, Eigen::Vector3d(0.2, 30 * kDeg, 1.5), 0.42);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("phi21"), std::string::npos) << what;
    EXPECT_NE(what.find("t = 0.42"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(check_service_zone(d, Eigen::Vector3d(0.2, 10 * kDeg, 1.5), 0.0));
}

}  // namespace
}  // namespace kinetofem::mech
