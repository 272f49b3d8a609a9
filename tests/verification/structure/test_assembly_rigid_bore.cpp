// Verification of the rigid-bore condensation (structure/rigid_bore.hpp).
//
// 1 Monolithic reference. The part's FULL stiffness K (no support
//   eliminated), its 3-2-1 support as Lagrange constraints S u = 0, each bore
//   as Lagrange constraints B u = T q with the bore motion q as unknowns and
//   the interface load lambda imposed on the multipliers (T^T r = lambda),
//   solved directly (Eigen SparseLU on the symmetric augmented system, three
//   refinement steps). Nothing of the condensation is reused (no K_s^-1, no
//   F_SS, no projection for held face DoFs). Arbitrary interface loads plus
//   a body force (gravity and a rotation's inertia), on a randomly distorted
//   HEX20 bar, with the support among all nodes (it holds face DoFs of both
//   bores) and off the bores. Both solve the same discrete model exactly:
//   tolerance 1e-8 relative (condition ~1e10).
// 2 Cantilever: bore x0 held, a force at bore x1. Each bore's nodes move
//   rigidly (1e-9 of the displacement), the held one not at all, both
//   supports give the same field (1e-9), and the tip deflection is
//   Timoshenko's within 3 %.
// 3 Cost on a finer bar (timings printed; a 30 000-node case is DISABLED_,
//   run it with --gtest_also_run_disabled_tests).
#include <gtest/gtest.h>

#include <memory>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/rigid_bore.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// LinearStaticAnalysis keeps a reference to its log: one that outlives it.
const Log kQuiet = Log::quiet();

enum class Support { AllNodes, OffBores };

struct SupportedPart {
  std::unique_ptr<fem::FeModel> model;  // outlives the analysis
  std::unique_ptr<fem::LinearStaticAnalysis> analysis;
};

SupportedPart supported(fem::Mesh mesh, Support support, const std::vector<std::string>& bores) {
  SupportedPart part;
  part.model = std::make_unique<fem::FeModel>();
  part.model->mesh = std::move(mesh);
  part.model->material = test::steel();
  std::vector<fem::Index> candidates;
  if (support == Support::OffBores) {
    candidates = rigid_bore_support_candidates(part.model->mesh, bores);
  } else {
    for (fem::Index n = 0; n < part.model->mesh.node_count(); ++n) candidates.push_back(n);
  }
  part.model->supports = fem::three_two_one_support(part.model->mesh, candidates);
  part.analysis = std::make_unique<fem::LinearStaticAnalysis>(*part.model, kQuiet);
  return part;
}

Eigen::Matrix<double, 3, 6> rigid_rows(const Vector3d& arm) {
  Eigen::Matrix<double, 3, 6> T;
  Eigen::Matrix3d S;
  S << 0, -arm.z(), arm.y(), arm.z(), 0, -arm.x(), -arm.y(), arm.x(), 0;
  T << Eigen::Matrix3d::Identity(), -S;
  return T;
}

VectorXd solve(fem::LinearStaticAnalysis& analysis, const VectorXd& f) {
  const fem::DisplacementField u = analysis.solve_forces(f).front();
  return Eigen::Map<const VectorXd>(u.data(), u.size());
}

// Deviation of the nodes' displacement from their best rigid motion.
double rigid_deviation(const fem::Mesh& mesh, const std::vector<fem::Index>& nodes, const VectorXd& u) {
  MatrixXd T(3 * Eigen::Index(nodes.size()), 6);
  VectorXd un(T.rows());
  for (size_t i = 0; i < nodes.size(); ++i) {
    T.middleRows<3>(3 * Eigen::Index(i)) = rigid_rows(mesh.nodes.row(nodes[i]).transpose());
    un.segment<3>(3 * Eigen::Index(i)) = u.segment<3>(3 * nodes[i]);
  }
  return (T * T.colPivHouseholderQr().solve(un) - un).cwiseAbs().maxCoeff();
}

struct Monolithic {
  VectorXd u;       // 3N
  VectorXd q;       // 6 per interface
  VectorXd loads;   // B^T r, 3N
  double relative_residual = 0.0;
};

// The monolithic reference (see the file comment). One interface per face set.
Monolithic solve_monolithic(const fem::FeModel& model, const std::vector<RigidBoreInterface>& in, const VectorXd& f,
                            const VectorXd& lambda) {
  using SpMat = Eigen::SparseMatrix<double>;
  using Triplet = Eigen::Triplet<double>;
  const fem::Mesh& mesh = model.mesh;
  const Eigen::Index ndof = 3 * mesh.node_count();
  const fem::AssembledStiffness K = fem::assemble_stiffness(mesh, model.material, fem::DofMap(mesh.node_count(), {}));
  const SpMat upper(K.free_free);
  const SpMat full = SpMat(upper.selfadjointView<Eigen::Upper>());
  const double sigma = full.diagonal().cwiseAbs().maxCoeff();  // balances the constraint rows against K

  std::vector<Triplet> t;
  for (int k = 0; k < full.outerSize(); ++k)
    for (SpMat::InnerIterator it(full, k); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
  // Bores: rows and columns [ndof, ndof + 3k) are r, then 6 per interface q.
  std::vector<std::vector<fem::Index>> nodes;
  Eigen::Index k3 = 0;
  for (const auto& i : in) {
    nodes.push_back(fem::nodes_of_faces(mesh.face_set(i.face_set)));
    k3 += 3 * Eigen::Index(nodes.back().size());
  }
  const Eigen::Index o_r = ndof, o_q = ndof + k3, o_s = o_q + 6 * Eigen::Index(in.size());
  auto sym = [&](Eigen::Index a, Eigen::Index b, double v) {
    t.emplace_back(a, b, v);
    t.emplace_back(b, a, v);
  };
  Eigen::Index row = o_r;
  for (size_t l = 0; l < in.size(); ++l)
    for (fem::Index n : nodes[l]) {
      const Eigen::Matrix<double, 3, 6> T = rigid_rows(mesh.nodes.row(n).transpose() - in[l].reference_m);
      for (int c = 0; c < 3; ++c, ++row) {
        sym(row, 3 * n + c, -sigma);  // -B u (+ T q) = 0;  K u - B^T r ... = f
        for (int j = 0; j < 6; ++j)
          if (T(c, j) != 0.0) sym(row, o_q + 6 * Eigen::Index(l) + j, sigma * T(c, j));  // T^T r = lambda
      }
    }
  Eigen::Index s = o_s;
  for (const fem::DisplacementSupport& sup : model.supports)
    for (fem::Index n : sup.nodes)
      for (int c = 0; c < 3; ++c)
        if (sup.fixed[size_t(c)]) sym(s++, 3 * n + c, sigma);  // S u = 0
  const Eigen::Index size = s;
  SpMat A(size, size);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  VectorXd rhs = VectorXd::Zero(size);
  rhs.head(ndof) = f;
  rhs.segment(o_q, lambda.size()) = lambda;
  Eigen::SparseLU<SpMat> lu;
  lu.compute(A);
  require(lu.info() == Eigen::Success, "monolithic rigid-bore reference: SparseLU failed: {}", lu.lastErrorMessage());
  VectorXd x = lu.solve(rhs);
  for (int refine = 0; refine < 3; ++refine) x += lu.solve(VectorXd(rhs - A * x));
  Monolithic out;
  out.relative_residual = (A * x - rhs).norm() / rhs.norm();
  out.u = x.head(ndof);
  out.q = x.segment(o_q, 6 * Eigen::Index(in.size()));
  out.loads = VectorXd::Zero(ndof);
  row = o_r;
  for (size_t l = 0; l < in.size(); ++l)
    for (fem::Index n : nodes[l])
      for (int c = 0; c < 3; ++c, ++row) out.loads(3 * n + c) += sigma * x(row);  // r = sigma r~
  return out;
}

// A distorted HEX20 bar 300 x 40 x 20 mm (faces stay plane), centred in y and z.
fem::Mesh distorted_bar() {
  testing::BoxMeshOptions box;
  box.length_m = {0.30, 0.04, 0.02};
  box.divisions = {10, 3, 2};
  box.type = fem::ElementType::Hex20;
  box.random_perturbation = 0.15;
  box.mid_node_perturbation = 0.05;
  box.seed = 7;
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(1).array() -= 0.02;
  mesh.nodes.col(2).array() -= 0.01;
  return mesh;
}

// Translations in m plus rotations times the length: one scale for q.
double motion_norm(const VectorXd& q, double length) {
  double s = 0.0;
  for (Eigen::Index k = 0; k < q.size(); ++k) s = std::max(s, std::abs(q(k)) * (k % 6 >= 3 ? length : 1.0));
  return s;
}

class RigidBoreMonolithic : public ::testing::TestWithParam<Support> {};

TEST_P(RigidBoreMonolithic, InterfaceMotionFieldAndReactionsEqualTheMonolithicSolution) {
  const std::vector<RigidBoreInterface> in = {{"x0", {0.0, 0.003, -0.002}}, {"x1", {0.31, -0.004, 0.0}}};
  SupportedPart part = supported(distorted_bar(), GetParam(), {"x0", "x1"});
  RigidBoreCondensation bores(*part.analysis, part.model->mesh, in);
  // Loads: arbitrary interface loads (not in equilibrium: the support takes
  // the rest) and a body force of about the same size (a 1.9 kg bar at 20
  // rad/s, 500 rad/s^2, plus gravity).
  VectorXd lambda(12);
  lambda << 120.0, -300.0, 40.0, 2.0, -5.0, 8.0, -50.0, 200.0, 10.0, -3.0, 4.0, -6.0;
  const fem::RigidBodyMotionLoads motion(part.model->mesh, part.model->material);
  const VectorXd f = motion.forces({0.0, -9.81, 0.0}, {5.0, -2.0, 1.0}, {0.0, 3.0, 20.0}, {40.0, -10.0, 500.0});

  const VectorXd Zf = solve(*part.analysis, f);
  const VectorXd c = bores.correction(Zf);
  const VectorXd q = bores.flexibility() * lambda + bores.loads().transpose() * Zf;
  const VectorXd u = bores.load_displacement() * lambda + Zf + c;
  const VectorXd r = bores.face_loads(lambda, Zf);

  const Monolithic ref = solve_monolithic(*part.model, in, f, lambda);
  EXPECT_LT(ref.relative_residual, 1e-10);  // the reference itself
  const double us = ref.u.cwiseAbs().maxCoeff(), qs = motion_norm(ref.q, 0.3), rs = ref.loads.cwiseAbs().maxCoeff();
  const double eu = (u - ref.u).cwiseAbs().maxCoeff() / us, eq = motion_norm(q - ref.q, 0.3) / qs,
               er = (r - ref.loads).cwiseAbs().maxCoeff() / rs;
  const double uncorrected = (u - c - ref.u).cwiseAbs().maxCoeff() / us;
  std::printf(
      "  support %s: %ld face nodes, %ld free / %ld held face DoFs; max |u| %.4e m; condensed vs monolithic: field "
      "%.2e, interface motion %.2e, face reactions %.2e (field without the correction %.2e); reference residual "
      "%.1e\n",
      GetParam() == Support::AllNodes ? "on all nodes" : "off the bores", bores.statistics().face_nodes,
      bores.statistics().free_face_dofs, bores.statistics().held_face_dofs, us, eu, eq, er, uncorrected,
      ref.relative_residual);
  ::testing::Test::RecordProperty("field_relative_error", std::to_string(eu));
  EXPECT_LT(eu, 1e-8);
  EXPECT_LT(eq, 1e-8);
  EXPECT_LT(er, 1e-8);
  EXPECT_GT(uncorrected, 1e-4);  // the correction matters here: the test would see it missing
}

INSTANTIATE_TEST_SUITE_P(Supports, RigidBoreMonolithic, ::testing::Values(Support::AllNodes, Support::OffBores),
                         [](const auto& info) { return info.param == Support::AllNodes ? "AllNodes" : "OffBores"; });

// The cantilever (world = body frame): bore 0 held, P along y at bore 1.
struct Cantilever {
  SupportedPart part;
  std::vector<std::vector<fem::Index>> faces;  // per bore
  VectorXd u;                                  // 3N, m
};

Cantilever cantilever(Support support, double P, double L) {
  Cantilever out;
  out.part = supported(test::bar_mesh(), support, {"x0", "x1"});
  const std::vector<RigidBoreInterface> in = {{"x0", Vector3d::Zero()}, {"x1", {L, 0.0, 0.0}}};
  const RigidBoreCondensation bores(*out.part.analysis, out.part.model->mesh, in);
  VectorXd lambda(12);
  lambda << 0.0, -P, 0.0, 0.0, 0.0, -P * L,  // the clamp's reaction on the part
      0.0, P, 0.0, 0.0, 0.0, 0.0;
  const VectorXd q = bores.flexibility() * lambda;
  out.u = bores.load_displacement() * lambda;
  // The rigid motion (t, w) about the origin, bore 0's reference, that holds bore 0: (t, w) = -q_0.
  const Vector3d t = -q.head<3>(), w = -q.segment<3>(3);
  const fem::Mesh& mesh = out.part.model->mesh;
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    out.u.segment<3>(3 * n) += t + w.cross(mesh.nodes.row(n).transpose());
  out.faces = {bores.face_nodes(0), bores.face_nodes(1)};
  return out;
}

TEST(RigidBoreCantilever, BothBoresMoveRigidlyAndTheTipDeflectsAsTimoshenko) {
  // References: the rigid-bore constraint itself (tolerance 1e-9 of max |u|:
  // round-off of the face solves; the held bore's motion likewise), the
  // same field from either support (1e-9), and Timoshenko beam theory for
  // the tip, delta = P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6, within
  // 3 % (the clamp's Poisson restraint and the coarse 10 x 2 x 1 HEX20 mesh).
  const double P = 100.0, L = 0.30, H = 0.04, B = 0.02;
  const fem::IsotropicMaterial steel = test::steel();
  const double E = steel.youngs_modulus_pa, G = steel.shear_modulus_pa();
  const double I = B * H * H * H / 12, delta_beam = P * L * L * L / (3 * E * I) + P * L / (5.0 / 6.0 * G * B * H);
  std::vector<VectorXd> fields;
  for (Support support : {Support::AllNodes, Support::OffBores}) {
    const Cantilever c = cantilever(support, P, L);
    const fem::Mesh& mesh = c.part.model->mesh;
    const double size = c.u.cwiseAbs().maxCoeff();
    double held = 0.0, tip = 0.0;
    for (fem::Index n : c.faces[0]) held = std::max(held, c.u.segment<3>(3 * n).cwiseAbs().maxCoeff());
    for (fem::Index n : c.faces[1]) tip += c.u(3 * n + 1) / double(c.faces[1].size());
    const double dev0 = rigid_deviation(mesh, c.faces[0], c.u), dev1 = rigid_deviation(mesh, c.faces[1], c.u);
    std::printf(
        "  support %s: tip deflection %.6e m, Timoshenko %.6e m (%+.3f %%); held bore |u| %.1e, rigid deviation "
        "bore 0 %.1e, bore 1 %.1e (of max |u| %.4e m)\n",
        support == Support::AllNodes ? "on all nodes" : "off the bores", tip, delta_beam,
        100 * (tip / delta_beam - 1), held / size, dev0 / size, dev1 / size, size);
    EXPECT_LT(held, 1e-9 * size);
    EXPECT_LT(dev0, 1e-9 * size);
    EXPECT_LT(dev1, 1e-9 * size);
    EXPECT_NEAR(tip / delta_beam, 1.0, 0.03);
    fields.push_back(c.u);
  }
  const double diff = (fields[0] - fields[1]).cwiseAbs().maxCoeff() / fields[1].cwiseAbs().maxCoeff();
  std::printf("  the two supports' fields differ by %.1e\n", diff);
  EXPECT_LT(diff, 1e-9);
}

// ---------------------------------------------------------------------------

void report_cost(const std::array<int, 3>& cells, const Eigen::Vector3d& size_m, bool third_bore, int poses) {
  testing::BoxMeshOptions box;
  box.length_m = size_m;
  box.divisions = cells;
  box.type = fem::ElementType::Hex20;
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(1).array() -= 0.5 * size_m.y();
  mesh.nodes.col(2).array() -= 0.5 * size_m.z();
  std::vector<std::string> sets = {"x0", "x1"};
  std::vector<RigidBoreInterface> in = {{"x0", Vector3d::Zero()}, {"x1", {size_m.x(), 0.0, 0.0}}};
  if (third_bore) {
    // A bore on the top face (z1) in the middle: its faces with centroid x within 0.58 .. 0.62 L.
    fem::FaceBlock mid;
    for (const fem::FaceBlock& block : mesh.face_set("z1")) {
      mid.type = block.type;
      for (fem::Index f = 0; f < block.size(); ++f) {
        double x = 0.0;
        for (fem::Index n : block.face(f)) x += mesh.nodes(n, 0) / double(block.face(f).size());
        if (x > 0.58 * size_m.x() && x < 0.62 * size_m.x())
          mid.connectivity.insert(mid.connectivity.end(), block.face(f).begin(), block.face(f).end());
      }
    }
    mesh.face_sets["mid"] = {mid};
    sets.push_back("mid");
    in.push_back({"mid", {0.6 * size_m.x(), 0.0, 0.5 * size_m.z()}});
  }
  Stopwatch clock;
  SupportedPart part = supported(std::move(mesh), Support::AllNodes, sets);
  const double factor_s = clock.seconds();
  const fem::CholmodStatistics& st = part.analysis->solver_statistics();
  const Log log;
  RigidBoreCondensation bores(*part.analysis, part.model->mesh, in, log);
  const RigidBoreStatistics& s = bores.statistics();

  const fem::RigidBodyMotionLoads motion(part.model->mesh, part.model->material);
  MatrixXd F(3 * part.model->mesh.node_count(), poses);
  for (int p = 0; p < poses; ++p)
    F.col(p) = motion.forces({0.0, -9.81, 0.0}, Vector3d::Zero(), {0.0, 0.0, 1.0 + p}, {0.0, 0.0, 10.0 * p});
  clock.restart();
  const std::vector<fem::DisplacementField> Z = part.analysis->solve_forces(F);
  const double load_solve_s = clock.seconds();
  MatrixXd Zf(F.rows(), poses);
  for (int p = 0; p < poses; ++p) Zf.col(p) = Eigen::Map<const VectorXd>(Z[size_t(p)].data(), F.rows());
  const MatrixXd c = bores.correction(Zf);
  std::printf(
      "  %ld nodes (%ld DoFs), nnz(L) %.3g, support + factorization %.2f s; %d bores, %ld face nodes, %ld face DoFs "
      "solved: F_SS %.2f s (%.2f ms per column), factor %.3f s, Z_D %.3f s, setup %.2f s, ~%.1f MB dense; "
      "%d poses: load solve %.3f s, correction %.3f s; |D^T Z_D - F_r| %.1e\n",
      long(part.model->mesh.node_count()), long(3 * part.model->mesh.node_count()), st.factor_nonzeros, factor_s,
      s.bores, s.face_nodes, s.free_face_dofs, s.face_solve_seconds, 1e3 * s.face_solve_seconds / double(s.free_face_dofs),
      s.factor_seconds, s.interface_solve_seconds, s.setup_seconds, s.working_bytes * 1e-6, poses, load_solve_s,
      s.correction_seconds, s.consistency);
  EXPECT_LT(s.consistency, 1e-9);
  const VectorXd u = Zf.col(poses - 1) + c.col(poses - 1);
  for (int l = 0; l < int(in.size()); ++l)
    EXPECT_LT(rigid_deviation(part.model->mesh, bores.face_nodes(l), u), 1e-9 * u.cwiseAbs().maxCoeff());
}

TEST(RigidBoreCost, FinerBarSetupAndCorrection) { report_cost({40, 6, 3}, {0.30, 0.04, 0.02}, false, 21); }

// 29 821 nodes (89 463 DoFs), bores of 181, 181 and 149 nodes: the estimate in the report.
TEST(RigidBoreCost, DISABLED_ThirtyThousandNodesThreeBores) {
  report_cost({120, 10, 5}, {1.2, 0.1, 0.05}, true, 32);
}

}  // namespace
}  // namespace kinetofem::structure
