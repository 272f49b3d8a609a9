// PinMember (structure/pin_member.hpp): the Timoshenko pin of a joint whose
// bores sit at different z, against the textbook beam (Przemieniecki's
// matrix entries; the Timoshenko cantilever's tip deflection and rotation)
// and its section stresses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "kinetofem/structure/pin_member.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

PinSection steel_pin(double d = 0.02) { return {d, 210e9, 0.3}; }

// The section constants written out, not taken from PinSection.
struct Hand {
  double E, G, A, I, kappa, L;
  double phi() const { return 12 * E * I / (kappa * G * A * L * L); }
};
Hand hand(double d, double L) {
  const double nu = 0.3, E = 210e9;
  return {E, E / (2 * (1 + nu)), kPi * d * d / 4, kPi * d * d * d * d / 64, 6 * (1 + nu) / (7 + 6 * nu), L};
}

TEST(PinMember, LocalMatrixHasPrzemienieckiEntries) {
  const double d = 0.02, L = 0.05;
  const Hand h = hand(d, L);
  const Matrix12d K = PinMember::local_stiffness(L, steel_pin(d));
  const double b = h.E * h.I / ((1 + h.phi()) * L * L * L);
  // Round-off only: the same closed forms evaluated in another order.
  const double tol = 1e-12;
  EXPECT_NEAR(K(0, 0) / (h.E * h.A / L), 1.0, tol);
  EXPECT_NEAR(K(0, 6) / (-h.E * h.A / L), 1.0, tol);
  EXPECT_NEAR(K(1, 1) / (12 * b), 1.0, tol);
  EXPECT_NEAR(K(1, 5) / (6 * L * b), 1.0, tol);
  EXPECT_NEAR(K(2, 4) / (-6 * L * b), 1.0, tol);
  EXPECT_NEAR(K(5, 5) / ((4 + h.phi()) * L * L * b), 1.0, tol);
  EXPECT_NEAR(K(5, 11) / ((2 - h.phi()) * L * L * b), 1.0, tol);
  EXPECT_NEAR(K(4, 10) / ((2 - h.phi()) * L * L * b), 1.0, tol);
  EXPECT_NEAR(K(7, 11) / (-6 * L * b), 1.0, tol);
  EXPECT_NEAR(K(8, 10) / (6 * L * b), 1.0, tol);
  // Torsion released.
  EXPECT_EQ(K(3, 3), 0.0);
  EXPECT_EQ(K(9, 9), 0.0);
  EXPECT_EQ(K(3, 9), 0.0);
}

TEST(PinMember, RigidMotionsAndTheTwistDoNoWork) {
  const Vector3d a(0.1, 0.2, 0.01), b(0.1, 0.2, 0.06);
  const PinMember pin(a, b, steel_pin(), "pin 'A'");
  const Matrix12d& K = pin.stiffness();
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  // Rank 5: 6 rigid motions plus the free twist (relative rotation about the axis).
  Eigen::SelfAdjointEigenSolver<Matrix12d> eig(K);
  int zero = 0;
  for (int i = 0; i < 12; ++i) zero += std::abs(eig.eigenvalues()(i)) < 1e-9 * eig.eigenvalues().cwiseAbs().maxCoeff();
  EXPECT_EQ(zero, 7);
  const Vector3d w(0.3, -0.2, 0.5), t(1e-3, 2e-3, -1e-3);
  Vector12d u;
  u << t + w.cross(a), w, t + w.cross(b), w;
  EXPECT_LT((K * u).norm(), 1e-9 * K.norm() * u.norm());
  Vector12d twist = Vector12d::Zero();
  twist(11) = 1.0;
  EXPECT_LT((K * twist).norm(), 1e-9 * K.norm());
}

// Cantilever: end i clamped, end j loaded. Timoshenko beam theory: tip
// deflection P L^3/(3 E I) + P L/(kappa G A), tip rotation P L^2/(2 E I);
// tip moment M: rotation M L/(E I), deflection M L^2/(2 E I); axial P L/(E A).
// The element is exact for end loads: 1e-10 (round-off of a 5 x 5 solve).
TEST(PinMember, CantileverMatchesTimoshenkoBeamTheory) {
  const double d = 0.03, L = 0.04;
  const Hand h = hand(d, L);
  const PinMember pin(Vector3d(0.2, 0.1, -0.02), Vector3d(0.2, 0.1, -0.02 + L), steel_pin(d), "pin");
  const Eigen::Matrix<double, 6, 6> Kjj = pin.stiffness().block<6, 6>(6, 6);
  // The twist about z (component 5) is free: solve in the other five.
  const int keep[5] = {0, 1, 2, 3, 4};
  Eigen::Matrix<double, 5, 5> K5;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) K5(r, c) = Kjj(keep[r], keep[c]);
  auto solve = [&](const Eigen::Matrix<double, 5, 1>& f) { return Eigen::Matrix<double, 5, 1>(K5.fullPivLu().solve(f)); };
  const double P = 1000.0, M = 50.0;
  Eigen::Matrix<double, 5, 1> f = Eigen::Matrix<double, 5, 1>::Zero();
  f(0) = P;  // transverse x
  Eigen::Matrix<double, 5, 1> u = solve(f);
  EXPECT_NEAR(u(0) / (P * L * L * L / (3 * h.E * h.I) + P * L / (h.kappa * h.G * h.A)), 1.0, 1e-10);
  EXPECT_NEAR(u(4) / (P * L * L / (2 * h.E * h.I)), 1.0, 1e-10);  // theta_y, x grows with z
  f.setZero();
  f(3) = M;  // moment about x: bends in the y-z plane, y decreases along +z
  u = solve(f);
  EXPECT_NEAR(u(3) / (M * L / (h.E * h.I)), 1.0, 1e-10);
  EXPECT_NEAR(u(1) / (-M * L * L / (2 * h.E * h.I)), 1.0, 1e-10);
  f.setZero();
  f(2) = P;
  u = solve(f);
  EXPECT_NEAR(u(2) / (P * L / (h.E * h.A)), 1.0, 1e-10);
}

// The section of a cantilever under a tip force P: bending moment P L at the
// clamp, 0 at the tip; sigma_b = 32 P L/(pi d^3), tau = 16 P/(3 pi d^2), the
// deflection that of beam theory (as above).
TEST(PinMember, LoadsAndSectionStressesOfACantilever) {
  const double d = 0.025, L = 0.06, P = 800.0;
  const Hand h = hand(d, L);
  const PinMember pin(Vector3d(0, 0, 0.03), Vector3d(0, 0, 0.03 - L), steel_pin(d), "pin");  // axis -z
  EXPECT_NEAR(pin.axis().z(), -1.0, 1e-15);
  const double delta = P * L * L * L / (3 * h.E * h.I) + P * L / (h.kappa * h.G * h.A);
  const double theta = P * L * L / (2 * h.E * h.I);
  Vector12d u = Vector12d::Zero();
  u(7) = delta;    // y at end j
  u(9) = theta;    // rotation about x: y grows along -z, so theta_x > 0
  const PinLoads loads = pin.loads(u);
  // 1e-9: the tip motion above is beam theory's, exact for this element.
  EXPECT_NEAR(loads.force_on_j_n.y() / -P, 1.0, 1e-9);  // the pin resists the body's push
  EXPECT_NEAR(loads.force_on_j_n.norm() / P, 1.0, 1e-9);
  EXPECT_LT(loads.moment_on_j_nm.norm(), 1e-9 * P * L);
  EXPECT_NEAR(loads.force_on_i_n.y() / P, 1.0, 1e-9);
  EXPECT_NEAR(loads.moment_on_i_nm.norm() / (P * L), 1.0, 1e-9);
  EXPECT_NEAR(loads.shear_force_n / P, 1.0, 1e-9);
  EXPECT_NEAR(loads.bending_moment_i_nm / (P * L), 1.0, 1e-9);
  EXPECT_LT(loads.bending_moment_j_nm, 1e-9 * P * L);
  EXPECT_NEAR(loads.bending_stress_pa / (32 * P * L / (kPi * d * d * d)), 1.0, 1e-9);
  EXPECT_NEAR(loads.shear_stress_pa / (16 * P / (3 * kPi * d * d)), 1.0, 1e-9);
  EXPECT_NEAR(loads.deflection_m / delta, 1.0, 1e-9);
  EXPECT_NEAR(loads.axial_force_n, 0.0, 1e-9 * P);
}

TEST(PinMember, RefusesCoincidentEndsAndBadSections) {
  const Vector3d a(0, 0, 0);
  EXPECT_THROW(PinMember(a, a, steel_pin(), "pin 'A'"), Error);
  EXPECT_THROW(PinMember(a, Vector3d(0, 0, 0.01), steel_pin(0.0), "pin 'A'"), Error);
  EXPECT_THROW(PinMember(a, Vector3d(0, 0, 0.01), PinSection{0.02, 210e9, 0.5}, "pin 'A'"), Error);
}

}  // namespace
}  // namespace kinetofem::structure
