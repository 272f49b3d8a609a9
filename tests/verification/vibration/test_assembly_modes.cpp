// Issue 14, verification 4: the natural frequencies of the reduced elastic
// assembly (vibration/assembly_modes.hpp: one Craig-Bampton reduction per part
// with the default part-mode rule, one small eigenproblem per pose) against a
// full eigen-solve of the monolithic assembly at two poses: the first five
// frequencies within 1e-4 (relative).
//
// The monolithic reference (below) reduces nothing: every part's full
// consistent mass and stiffness (no support), the interfaces' motions
// v_k = Q_b G_k^T u (the same distributing couplings, rotated to world
// axes), the joints' constraints C v = 0 and the chain and drive springs
// (ElasticAssembly::interface_structure: the joints' definition is shared),
// each point mass m on the translation of its own coupling (fem::
// DistributingCoupling of its mount face at the mass's point), the
// constraints eliminated by an orthonormal null-space basis (QR), and a
// dense generalized eigen solve of the whole model.
// Models: the SPEC §1 lever-chain manipulator with box parts (chain spring,
// rigid lever drive, gripper 20 kg + casting 15 kg at H) and the two-link arm
// (two rigid drives, 3 kg payload) of structure_fixtures.hpp.
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

using namespace kinetofem::vibration;  // the modes under test

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kTolerance = 1e-4;  // docs/vibration.md, verification 4: first five frequencies, relative

Eigen::Matrix3d rot_z(double theta) { return Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

MatrixXd dense_of(const fem::SymmetricUpperMatrix& upper) {
  return MatrixXd(MatrixXd(upper).selfadjointView<Eigen::Upper>());
}

VectorXd monolithic_frequencies(const std::vector<pipeline::Part>& parts, const mech::MultibodyModel& model,
                                const ElasticAssembly& assembly, const mech::Frame& frame, int count) {
  std::vector<Index> offset(parts.size() + 1, 0);
  for (size_t p = 0; p < parts.size(); ++p) offset[p + 1] = offset[p] + 3 * parts[p].model.mesh.node_count();
  const Index n = offset.back();
  MatrixXd K = MatrixXd::Zero(n, n), M = MatrixXd::Zero(n, n);
  const std::vector<InterfaceInfo> infos = assembly.interfaces();
  MatrixXd U = MatrixXd::Zero(6 * Index(infos.size()), n);  // interfaces' world motions
  for (size_t p = 0; p < parts.size(); ++p) {
    const fem::Mesh& mesh = parts[p].model.mesh;
    const fem::DofMap dofs(mesh.node_count(), {});
    const Index size = 3 * mesh.node_count();
    K.block(offset[p], offset[p], size, size) =
        dense_of(fem::assemble_stiffness(mesh, parts[p].model.material, dofs).free_free);
    M.block(offset[p], offset[p], size, size) = dense_of(fem::assemble_mass(mesh, parts[p].model.material, dofs));
    int body = -1;
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == parts[p].body()) body = int(b);
    const Eigen::Matrix3d R = rot_z(frame.bodies[size_t(body)].q.z());
    const MatrixXd& G = assembly.interface_columns(parts[p].body());
    Index local = 0;
    for (size_t k = 0; k < infos.size(); ++k) {
      if (infos[k].body != parts[p].body()) continue;
      for (int half = 0; half < 2; ++half)
        U.block(6 * Index(k) + 3 * half, offset[p], 3, size) =
            R * G.middleCols(6 * local + 3 * half, 3).transpose();
      ++local;
    }
    // Point masses on the translation of their couplings.
    for (const auto& pm : parts[p].attachments.point_masses) {
      for (const mech::PointMass& mass : model.bodies[size_t(body)].point_masses) {
        if (mass.name != pm.point_mass) continue;
        const fem::DistributingCoupling coupling(mesh, pm.face_set);
        const Eigen::Vector3d X(mass.position_body.x(), mass.position_body.y(), coupling.centroid().z());
        MatrixXd Gt = MatrixXd::Zero(size, 3);
        for (int c = 0; c < 3; ++c) coupling.add(Eigen::Vector3d::Unit(c), Eigen::Vector3d::Zero(), X, Gt.col(c));
        M.block(offset[p], offset[p], size, size) += mass.mass_kg * Gt * Gt.transpose();
      }
    }
  }
  const InterfaceStructure is = assembly.interface_structure(frame);
  K += U.transpose() * is.springs * U;
  MatrixXd A = is.constraints * U;
  for (Index r = 0; r < A.rows(); ++r) A.row(r).normalize();
  Eigen::ColPivHouseholderQR<MatrixXd> qr(A.transpose());
  const MatrixXd Q = qr.householderQ();
  const MatrixXd N = Q.rightCols(n - qr.rank());
  const MatrixXd Kc = N.transpose() * K * N, Mc = N.transpose() * M * N;
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(0.5 * (Kc + Kc.transpose()),
                                                               0.5 * (Mc + Mc.transpose()), Eigen::EigenvaluesOnly);
  EXPECT_EQ(eig.info(), Eigen::Success);
  VectorXd f(count);
  for (int i = 0; i < count; ++i) f(i) = fem::frequency_hz(eig.eigenvalues()(i));
  return f;
}

void expect_reduced_matches_monolithic(const std::vector<pipeline::Part>& parts, const mech::MultibodyModel& model,
                                       const AssemblyOptions& options, const std::vector<mech::Frame>& poses) {
  AssemblyOptions ao = options;
  ao.recover_stress = false;
  ao.superpose_loads = false;
  const ElasticAssembly assembly(parts, model, ao);
  AssemblyModesOptions mo;
  mo.modes = 5;  // the default rule: automatic cutoff = 2 x f_5
  const AssemblyModes modes(assembly, parts, model, mo, poses, Log::quiet());
  double highest = 0.0;
  for (const mech::Frame& frame : poses) {
    const PoseModes reduced = modes.modes(frame);
    const VectorXd full = monolithic_frequencies(parts, model, assembly, frame, mo.modes);
    highest = std::max(highest, reduced.frequency_hz(mo.modes - 1));
    for (int i = 0; i < mo.modes; ++i) {
      const double error = (reduced.frequency_hz(i) - full(i)) / full(i);
      std::printf("  %s pose %.4f rad: mode %d  reduced %.6f Hz  full %.6f Hz  (%+.2e)\n", model.name.c_str(),
                  frame.bodies[1].q.z(), i + 1, reduced.frequency_hz(i), full(i), error);
      EXPECT_NEAR(error, 0.0, kTolerance) << "mode " << i + 1 << " at t = " << frame.t;
      // Rayleigh-Ritz: a reduced model is stiffer, never softer, up to the
      // dense reference's own round-off (about 1e-8 relative measured on
      // these 1 200-1 300 DoF models).
      EXPECT_GE(reduced.frequency_hz(i), full(i) * (1 - 1e-7));
    }
  }
  const std::string rule = modes.check_rule(highest);
  std::printf("  %s\n", rule.c_str());
  EXPECT_NE(rule.find("holds"), std::string::npos) << rule;
  for (const auto& r : modes.reductions()) EXPECT_GT(r.first_dropped_hz, r.cutoff_hz) << r.body;
}

TEST(AssemblyModes, LeverChainManipulatorMatchesTheMonolithicAssemblyAtTwoPoses) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  AssemblyOptions options;
  options.chains = {{"chain", 5e6}};
  options.points = {{"H", "arm", "H", "x0"}};
  const std::vector<mech::Frame> poses = {pipeline::solve_static_pose(model, {0.0}),
                                          pipeline::solve_static_pose(model, {60 * test::kDeg})};
  expect_reduced_matches_monolithic(parts, model, options, poses);
}

TEST(AssemblyModes, TwoLinkArmWithPayloadMatchesTheMonolithicAssemblyAtTwoPoses) {
  mech::MultibodyModel model = test::two_link_arm();
  const std::vector<pipeline::Part> parts = test::two_link_parts();
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  AssemblyOptions options;
  const std::vector<mech::Frame> poses = {pipeline::solve_static_pose(model, {0.0, 0.0}),
                                          pipeline::solve_static_pose(model, {40 * test::kDeg, -50 * test::kDeg})};
  expect_reduced_matches_monolithic(parts, model, options, poses);
}

}  // namespace
}  // namespace kinetofem::structure
