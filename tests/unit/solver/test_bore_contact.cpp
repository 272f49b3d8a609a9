// The contact QP (primal-dual active set, interior-point fallback) and the
// bore's contact surface.
#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/verification/accelerated_link.hpp"

namespace kinetofem::fem {
namespace {

// A random strictly convex contact problem whose resultant can be carried.
struct RandomProblem {
  Eigen::MatrixXd A, E;
  Eigen::VectorXd b, r;
};

RandomProblem random_problem(int m, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  RandomProblem p;
  Eigen::MatrixXd L(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) L(i, j) = normal(rng);
  p.A = 1e-9 * (L * L.transpose() / m + Eigen::MatrixXd::Identity(m, m));  // m/N, a compliance
  // The rigid pin map of m nodes around a unit circle, at two heights.
  p.E.resize(m, 4);
  for (int i = 0; i < m; ++i) {
    const double phi = 2 * std::numbers::pi * i / m, z = (i % 2 ? 0.01 : -0.01);
    const Eigen::Vector3d n(std::cos(phi), std::sin(phi), 0), r(0.02 * n.x(), 0.02 * n.y(), z);
    const Eigen::Vector3d arm = r.cross(n);
    p.E.row(i) << n.x(), n.y(), arm.x(), arm.y();
  }
  p.b.resize(m);
  for (int i = 0; i < m; ++i) p.b[i] = 2e-6 * normal(rng);  // some nodes closed by the other loads
  p.r = Eigen::Vector4d(1500.0, -800.0, 3.0, -1.0);
  return p;
}

void expect_kkt(const RandomProblem& p, const ContactSolution& s, double tolerance) {
  const double force_scale = s.pressure.cwiseAbs().maxCoeff(), gap_scale = p.b.cwiseAbs().maxCoeff();
  EXPECT_GE(s.pressure.minCoeff(), 0.0);                           // no tension
  EXPECT_GE(s.gap.minCoeff(), -tolerance * gap_scale);             // no penetration
  EXPECT_LE((s.pressure.cwiseProduct(s.gap)).cwiseAbs().maxCoeff(), tolerance * force_scale * gap_scale);
  EXPECT_LE((p.E.transpose() * s.pressure - p.r).norm(), 1e-10 * p.r.norm());  // the resultant carried
}

TEST(BoreContactSolver, ActiveSetMeetsTheContactConditions) {
  // KKT conditions of the QP (header): lambda >= 0, g >= 0, lambda g = 0,
  // E^T lambda = r; relative tolerance 1e-9 of the problem's scales.
  for (unsigned seed : {1u, 2u, 3u}) {
    const RandomProblem p = random_problem(48, seed);
    const ContactSolution s = solve_contact(p.A, p.b, p.E, p.r, {});
    EXPECT_EQ(s.interior_point_steps, 0) << "seed " << seed;
    expect_kkt(p, s, 1e-9);
  }
}

TEST(BoreContactSolver, InteriorPointFallbackFindsTheSameSolution) {
  // The QP is strictly convex: its solution is unique, so the interior point
  // method (forced: no active-set step allowed) and the active set agree, to
  // 1e-8 of the largest force.
  const RandomProblem p = random_problem(40, 7);
  const ContactSolution active = solve_contact(p.A, p.b, p.E, p.r, {});
  ContactSolverOptions only_interior;
  only_interior.max_active_set_steps = 0;
  const ContactSolution interior = solve_contact(p.A, p.b, p.E, p.r, {}, only_interior);
  EXPECT_GT(interior.interior_point_steps, 0);
  expect_kkt(p, interior, 1e-9);
  EXPECT_LE((active.pressure - interior.pressure).cwiseAbs().maxCoeff(), 1e-8 * active.pressure.maxCoeff());
}

TEST(BoreContactSolver, MultipliersThatMeetAStiffness) {
  // E^T p + C q = r with C symmetric positive definite (a pin's motion that
  // the rest of a structure resists): q = C^-1 (r - E^T p), so the gaps are
  // g = (A + E C^-1 E^T) p + b - E C^-1 r and the contact conditions are
  // those of that reduced problem (analytic elimination). Checked: p >= 0,
  // g >= 0, p g = 0 (1e-9 of the scales), both constraint forms (1e-10), and
  // the active set against the forced interior point (1e-8).
  const RandomProblem p = random_problem(40, 13);
  Eigen::Matrix4d L;
  L << 2, 0, 0, 0, 1, 3, 0, 0, 0, 1, 1, 0, 1, 0, 2, 1;
  // A stiffness (N/m, N m/rad) of the order of the bore's own against the
  // pin's motion (E^T A^-1 E), so that it moves the answer.
  const Eigen::DiagonalMatrix<double, 4> S(3e4, 3e4, 3e2, 3e2);
  const Eigen::Matrix4d C = S * L * L.transpose() * S;
  const ContactSolution active = solve_contact(p.A, p.b, p.E, C, p.r, {});
  ContactSolverOptions only_interior;
  only_interior.max_active_set_steps = 0;
  const ContactSolution interior = solve_contact(p.A, p.b, p.E, C, p.r, {}, only_interior);
  EXPECT_GT(interior.interior_point_steps, 0);
  for (const ContactSolution* s : {&active, &interior}) {
    const double force = s->pressure.cwiseAbs().maxCoeff(), gap = p.b.cwiseAbs().maxCoeff();
    const Eigen::Matrix4d Cinv = C.inverse();
    const Eigen::VectorXd g = (p.A + p.E * Cinv * p.E.transpose()) * s->pressure + p.b - p.E * (Cinv * p.r);
    EXPECT_GE(s->pressure.minCoeff(), 0.0);
    EXPECT_GE(g.minCoeff(), -1e-9 * gap);
    EXPECT_LE(s->pressure.cwiseProduct(g).cwiseAbs().maxCoeff(), 1e-9 * force * gap);
    EXPECT_LE((g - s->gap).cwiseAbs().maxCoeff(), 1e-10 * gap);
    EXPECT_LE((p.E.transpose() * s->pressure + C * s->pin_motion - p.r).norm(), 1e-10 * p.r.norm());
    EXPECT_LE(s->resultant_error, 1e-10);
  }
  EXPECT_LE((active.pressure - interior.pressure).cwiseAbs().maxCoeff(), 1e-8 * active.pressure.maxCoeff());
  // The stiffness changes the answer (the test can fail): without it the
  // resultant is carried by the pressure alone.
  const ContactSolution rigid = solve_contact(p.A, p.b, p.E, p.r, {});
  EXPECT_GT((rigid.pressure - active.pressure).cwiseAbs().maxCoeff(), 1e-3 * active.pressure.maxCoeff());
}

TEST(BoreContactSolver, AWarmStartGivesTheSameSolutionInFewerSteps) {
  const RandomProblem p = random_problem(48, 11);
  const ContactSolution cold = solve_contact(p.A, p.b, p.E, p.r, {});
  const ContactSolution warm = solve_contact(p.A, p.b, p.E, p.r, cold.in_contact);
  EXPECT_EQ(warm.active_set_steps, 1);
  EXPECT_LE((cold.pressure - warm.pressure).cwiseAbs().maxCoeff(), 1e-12 * cold.pressure.maxCoeff());
}

TEST(BoreContactSolver, NoLoadAndOpenGapsGiveNoContact) {
  RandomProblem p = random_problem(24, 5);
  p.b = p.b.cwiseAbs() + Eigen::VectorXd::Constant(24, 1e-6);
  p.r.setZero();
  const ContactSolution s = solve_contact(p.A, p.b, p.E, p.r, {});
  EXPECT_EQ(s.pressure.maxCoeff(), 0.0);
  EXPECT_EQ(s.gap, p.b);
}

TEST(BoreContactSolver, InconsistentSizesAreAnError) {
  const RandomProblem p = random_problem(12, 5);
  EXPECT_THROW(solve_contact(p.A, p.b.head(11), p.E, p.r, {}), Error);
  EXPECT_THROW(solve_contact(p.A, p.b, p.E, p.r, std::vector<char>(3, 1)), Error);
}

TEST(BoreContactSurface, GeometryOfABore) {
  // The beam link's bore_1: radius 8 mm, 20 mm long, axis z through (0, 0).
  // The corner areas (integrals of the corner functions) sum to the bore's
  // area (round-off); the normals are unit, radial, normal to the axis; a
  // uniform pressure p0 has the nodal forces of the consistent load of p0
  // n (so no resultant on a closed bore: 1e-12 of p0 times the area); the
  // carried resultant of a pressure's nodal forces is E^T p (1e-12).
  const Mesh mesh = verification::beam_link_mesh();
  const BoreContactSurface bore(mesh, "bore_1", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  const double area = surface_area(mesh, mesh.face_set("bore_1"));
  EXPECT_NEAR(bore.corner_area_m2().sum(), area, 1e-12 * area);
  EXPECT_GT(bore.corner_area_m2().minCoeff(), 0.0);
  EXPECT_LT(bore.size(), Index(bore.nodes().size()));  // TET10: the corners only
  EXPECT_NEAR(bore.radius_m(), 0.008, 1e-9);
  EXPECT_NEAR(bore.length_m(), 0.020, 1e-9);
  for (Eigen::Index a = 0; a < Eigen::Index(bore.nodes().size()); ++a) {
    EXPECT_NEAR(bore.normals().row(a).norm(), 1.0, 1e-14);
    EXPECT_NEAR(bore.normals()(a, 2), 0.0, 1e-14);
  }
  const double p0 = 1e6;
  Eigen::MatrixXd uniform = Eigen::MatrixXd::Zero(3 * mesh.node_count(), 1);
  bore.add_forces(Eigen::VectorXd::Constant(bore.size(), p0), uniform);
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (Index n = 0; n < mesh.node_count(); ++n) total += uniform.col(0).segment<3>(3 * n);
  EXPECT_LE(total.norm(), 1e-3 * p0 * area);  // the faceted bore closes to the mesh's accuracy
  Eigen::VectorXd pressure = Eigen::VectorXd::LinSpaced(bore.size(), 0.0, 3e6);
  Eigen::MatrixXd forces = Eigen::MatrixXd::Zero(3 * mesh.node_count(), 1);
  bore.add_forces(pressure, forces);
  Eigen::Vector3d F = Eigen::Vector3d::Zero(), M = Eigen::Vector3d::Zero();
  for (Index n = 0; n < mesh.node_count(); ++n) {
    const Eigen::Vector3d f = forces.col(0).segment<3>(3 * n);
    F += f;
    M += Eigen::Vector3d(mesh.nodes.row(n).transpose()).cross(f);
  }
  const Eigen::Vector4d carried = bore.rigid_pin_map().transpose() * pressure;
  EXPECT_LE((bore.carried(F, M) - carried).norm(), 1e-12 * carried.norm());
  EXPECT_LE((bore.pressure_resultants().transpose() * pressure - F).norm(), 1e-12 * F.norm());
  EXPECT_NEAR(F.z(), 0.0, 1e-12 * F.norm());
  EXPECT_NEAR(M.z(), 0.0, 1e-12 * M.norm());
  // Angles: the corner on +x is at 0, on +y at pi/2.
  for (Eigen::Index c = 0; c < bore.size(); ++c) {
    const Eigen::Vector3d x = mesh.nodes.row(bore.corner_nodes()[size_t(c)]).transpose();
    EXPECT_NEAR(std::atan2(x.y(), x.x()), bore.angle_rad()[c], 1e-12);
  }
}

TEST(BoreContactSurface, NodalPressureIsLinearAlongTheEdges) {
  // Corner pressures equal to the corners' x (m, as a stand-in field): at a
  // mid-edge node the mean of its edge's corners, which is the node's x to
  // the edge's sagitta on the 8 mm bore (below 0.2 mm at this mesh).
  const Mesh mesh = verification::beam_link_mesh();
  const BoreContactSurface bore(mesh, "bore_1", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  Eigen::VectorXd p(bore.size());
  for (Eigen::Index c = 0; c < bore.size(); ++c) p[c] = mesh.nodes(bore.corner_nodes()[size_t(c)], 0);
  const Eigen::VectorXd nodal = bore.nodal_pressure(p);
  for (size_t a = 0; a < bore.nodes().size(); ++a)
    EXPECT_NEAR(nodal[Eigen::Index(a)], mesh.nodes(bore.nodes()[a], 0), 2e-4) << "node " << bore.nodes()[a];
}

TEST(BoreContactSurface, StateOfAContactPatch) {
  // Pressure on the corners within 30 degrees of +y: the arc is 60 degrees
  // to the angular spacing of the corners, the peak pressure's angle within
  // it, the resultant along +y.
  const Mesh mesh = verification::beam_link_mesh();
  const BoreContactSurface bore(mesh, "bore_1", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(bore.size());
  for (Eigen::Index c = 0; c < bore.size(); ++c) {
    const double off = std::abs(bore.angle_rad()[c] - std::numbers::pi / 2);
    if (off <= std::numbers::pi / 6) pressure[c] = std::cos(3 * off);
  }
  const BoreContactState s = contact_state(bore, pressure);
  EXPECT_GT(s.corners_in_contact, 3);
  EXPECT_LE(s.arc_rad, std::numbers::pi / 3 + 1e-12);
  EXPECT_GT(s.arc_rad, std::numbers::pi / 3 - 0.5);  // the bore's corners are about 0.3 rad apart
  EXPECT_NEAR(s.peak_angle_rad, std::numbers::pi / 2, std::numbers::pi / 6);
  EXPECT_GT(s.force_n.y(), 0.0);
}

TEST(BoreContactSurface, ANodeOnTheAxisIsAnError) {
  const Mesh mesh = verification::beam_link_mesh();
  // An axis through a node of the bore: that node has no radial direction.
  const Index node = nodes_of_faces(mesh.face_set("bore_1")).front();
  EXPECT_THROW(BoreContactSurface(mesh, "bore_1", mesh.nodes.row(node).transpose(), Eigen::Vector3d::UnitZ()), Error);
  EXPECT_THROW(BoreContactSurface(mesh, "no_such_set", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()), Error);
}

}  // namespace
}  // namespace kinetofem::fem
