// RigidBoreCondensation (structure/rigid_bore.hpp): the rigid-bore
// (kinematic) coupling condensed onto its interfaces, on the HEX20 bar of
// structure_fixtures.hpp (300 x 40 x 20 mm, 10 x 2 x 1 cells, bores on the
// end faces x0 and x1, references at their centroids). Each behaviour is
// checked with both supports a part can have: the 3-2-1 support among all
// nodes (elastic_assembly's: it holds face nodes of both bores) and among
// the nodes off the bores (rigid_bore_support_candidates).
#include <gtest/gtest.h>

#include <memory>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/rigid_bore.hpp"
#include "structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using test::error_of;

constexpr double kLength = 0.30;  // BarSize's default

// LinearStaticAnalysis keeps a reference to its log: one that outlives it.
const Log kQuiet = Log::quiet();

enum class Support { AllNodes, OffBores };

// A supported bar and its factorization (the model must outlive the analysis).
struct SupportedBar {
  std::unique_ptr<fem::FeModel> model;
  std::unique_ptr<fem::LinearStaticAnalysis> analysis;
};

SupportedBar supported_bar(Support support, const std::vector<std::string>& bores = {"x0", "x1"}) {
  SupportedBar bar;
  bar.model = std::make_unique<fem::FeModel>();
  bar.model->mesh = test::bar_mesh();
  bar.model->material = test::steel();
  std::vector<fem::Index> candidates;
  if (support == Support::OffBores) {
    candidates = rigid_bore_support_candidates(bar.model->mesh, bores);
  } else {
    for (fem::Index n = 0; n < bar.model->mesh.node_count(); ++n) candidates.push_back(n);
  }
  bar.model->supports = fem::three_two_one_support(bar.model->mesh, candidates);
  bar.analysis = std::make_unique<fem::LinearStaticAnalysis>(*bar.model, kQuiet);
  return bar;
}

const std::vector<RigidBoreInterface> kEnds = {{"x0", {0.0, 0.0, 0.0}}, {"x1", {kLength, 0.0, 0.0}}};

// Translations in m, rotations times the bar length: F in m/N throughout.
MatrixXd in_length_units(const MatrixXd& F) {
  Eigen::VectorXd s = Eigen::VectorXd::Ones(F.rows());
  for (Eigen::Index k = 0; k < F.rows(); ++k)
    if (k % 6 >= 3) s(k) = kLength;
  return s.asDiagonal() * F * s.asDiagonal();
}

// The distributing coupling's flexibility G^T K_s^-1 G on the same faces.
MatrixXd distributing_flexibility(SupportedBar& bar, const std::vector<RigidBoreInterface>& in) {
  const fem::Mesh& mesh = bar.model->mesh;
  MatrixXd G = MatrixXd::Zero(3 * mesh.node_count(), 6 * Eigen::Index(in.size()));
  for (size_t l = 0; l < in.size(); ++l) {
    const fem::DistributingCoupling coupling(mesh, in[l].face_set);
    for (int c = 0; c < 3; ++c) {
      coupling.add(Vector3d::Unit(c), Vector3d::Zero(), in[l].reference_m, G.col(6 * Eigen::Index(l) + c));
      coupling.add(Vector3d::Zero(), Vector3d::Unit(c), in[l].reference_m, G.col(6 * Eigen::Index(l) + 3 + c));
    }
  }
  const std::vector<fem::DisplacementField> Z = bar.analysis->solve_forces(G);
  MatrixXd ZG(G.rows(), G.cols());
  for (Eigen::Index c = 0; c < G.cols(); ++c) ZG.col(c) = Eigen::Map<const Eigen::VectorXd>(Z[size_t(c)].data(), G.rows());
  return G.transpose() * ZG;
}

// Load displacement of a body force (gravity plus a rotation's inertia).
MatrixXd body_load_displacement(SupportedBar& bar) {
  const fem::RigidBodyMotionLoads motion(bar.model->mesh, bar.model->material);
  const Eigen::VectorXd f = motion.forces({0.0, -9.81, 0.0}, {3.0, 1.0, 0.5}, {0.0, 0.0, 4.0}, {1.0, -2.0, 20.0});
  const fem::DisplacementField u = bar.analysis->solve_forces(f).front();
  return Eigen::Map<const Eigen::VectorXd>(u.data(), f.size());
}

// Largest deviation of the nodes' displacement from their best rigid motion
// about `reference`, and that motion (t, theta).
double rigid_deviation(const fem::Mesh& mesh, const std::vector<fem::Index>& nodes, const Eigen::VectorXd& u,
                       const Vector3d& reference, Eigen::Matrix<double, 6, 1>* motion = nullptr) {
  MatrixXd T(3 * Eigen::Index(nodes.size()), 6);
  Eigen::VectorXd un(T.rows());
  for (size_t i = 0; i < nodes.size(); ++i) {
    const Vector3d a = mesh.nodes.row(nodes[i]).transpose() - reference;
    Eigen::Matrix3d S;
    S << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    T.middleRows<3>(3 * Eigen::Index(i)) << Eigen::Matrix3d::Identity(), -S;
    un.segment<3>(3 * Eigen::Index(i)) = u.segment<3>(3 * nodes[i]);
  }
  const Eigen::Matrix<double, 6, 1> q = T.colPivHouseholderQr().solve(un);
  if (motion) *motion = q;
  return (T * q - un).cwiseAbs().maxCoeff();
}

class RigidBore : public ::testing::TestWithParam<Support> {};

TEST_P(RigidBore, FlexibilityIsSymmetricAndNoMoreCompliantThanTheDistributingCoupling) {
  // Reference: F_r = (T^T F_SS^-1 T)^-1 is the minimum of the complementary
  // energy over all face reactions with the given resultant, so F - F_r is
  // positive semidefinite for the distributing F on the same faces and
  // support (Loewner order; round-off of the solves ~1e-12 of the diagonal:
  // tolerance 1e-10). It must also be strictly stiffer somewhere (a rigid
  // end face does not warp): the largest eigenvalue of the scaled F - F_r
  // is 1.48 (support on all nodes) / 0.33 (off the bores) here, limit 0.1;
  // its smallest 2.2e-3 / 3.4e-3. F_r is positive definite with the support off
  // the bores; with the support on them it has one zero eigenvalue per held
  // face DoF (6: the 3-2-1 nodes a and b are end-face nodes).
  SupportedBar bar = supported_bar(GetParam());
  const RigidBoreCondensation bores(*bar.analysis, bar.model->mesh, kEnds);
  const MatrixXd Fr = bores.flexibility();
  ASSERT_EQ(Fr.rows(), 12);
  EXPECT_LT((Fr - Fr.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Fr.cwiseAbs().maxCoeff());
  // D^T Z_D from the solved columns equals F_r from the small algebra, and is symmetric.
  const MatrixXd DZ = bores.loads().transpose() * bores.load_displacement();
  EXPECT_LT((DZ - DZ.transpose()).cwiseAbs().maxCoeff(), 1e-10 * DZ.cwiseAbs().maxCoeff());
  EXPECT_LT((DZ - Fr).cwiseAbs().maxCoeff(), 1e-10 * Fr.cwiseAbs().maxCoeff());
  EXPECT_LT(bores.statistics().consistency, 1e-10);

  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(in_length_units(Fr));
  const Eigen::VectorXd ev = eig.eigenvalues();
  const long held = bores.statistics().held_face_dofs;
  EXPECT_EQ(held, GetParam() == Support::AllNodes ? 6 : 0);
  for (Eigen::Index k = 0; k < ev.size(); ++k) {
    if (k < held)
      EXPECT_LT(std::abs(ev(k)), 1e-10 * ev.maxCoeff()) << "eigenvalue " << k;
    else
      EXPECT_GT(ev(k), 1e-6 * ev.maxCoeff()) << "eigenvalue " << k;
  }

  const MatrixXd F = distributing_flexibility(bar, kEnds);
  const Eigen::VectorXd s = in_length_units(F).diagonal().cwiseSqrt().cwiseInverse();
  const MatrixXd gap = s.asDiagonal() * in_length_units(F - Fr) * s.asDiagonal();
  const Eigen::VectorXd gev = Eigen::SelfAdjointEigenSolver<MatrixXd>(gap).eigenvalues();
  std::printf("  F - F_r (scaled by F's diagonal): eigenvalues %.3e .. %.3e; held face DoFs %ld\n", gev.minCoeff(),
              gev.maxCoeff(), held);
  EXPECT_GT(gev.minCoeff(), -1e-10);
  EXPECT_GT(gev.maxCoeff(), 0.1);
}

TEST_P(RigidBore, EachColumnOfDIsItsUnitLoadOnItsBoreAndSelfEquilibratedOnTheOthers) {
  // Reference: T^T H = I, the reactions' resultant is the load (held DoFs'
  // reactions included): the unit load on the own bore, zero on the other
  // bore (which must still stay rigid, so it carries self-equilibrated
  // reactions, unlike a distributing G column); D is zero off the face
  // nodes. Tolerance: 1e-12 of the largest term summed (the unit load, or
  // the other bore's self-equilibrated nodal reactions, up to ~20 N for a
  // unit load: their sum's round-off scales with them and with the CPU's
  // BLAS kernels; 1.5e-12 was measured on an AMD EPYC for the 21.7 N ones).
  SupportedBar bar = supported_bar(GetParam());
  const RigidBoreCondensation bores(*bar.analysis, bar.model->mesh, kEnds);
  const fem::Mesh& mesh = bar.model->mesh;
  const MatrixXd& D = bores.loads();
  std::vector<char> on_face(size_t(mesh.node_count()), 0);
  for (int l = 0; l < 2; ++l)
    for (fem::Index n : bores.face_nodes(l)) on_face[size_t(n)] = 1;
  double other_bore = 0.0;
  for (int l = 0; l < 2; ++l)
    for (int j = 0; j < 6; ++j) {
      const Eigen::VectorXd column = D.col(6 * l + j);
      for (int b = 0; b < 2; ++b) {
        Eigen::VectorXd on_b = Eigen::VectorXd::Zero(column.size());  // bore b's nodes only
        for (fem::Index n : bores.face_nodes(b)) on_b.segment<3>(3 * n) = column.segment<3>(3 * n);
        Vector3d force, moment;
        fem::resultant(mesh, on_b, kEnds[size_t(b)].reference_m, force, moment);
        Eigen::Matrix<double, 6, 1> r, expected = Eigen::Matrix<double, 6, 1>::Zero();
        if (b == l) expected(j) = 1.0;
        r << force, moment;
        const double largest_term = std::max(1.0, on_b.cwiseAbs().maxCoeff());
        EXPECT_LT((r - expected).cwiseAbs().maxCoeff(), 1e-12 * largest_term)
            << "interface " << l << " column " << j << " bore " << b;
        if (b != l) other_bore = std::max(other_bore, on_b.cwiseAbs().maxCoeff());
      }
      for (fem::Index n = 0; n < mesh.node_count(); ++n) {
        if (!on_face[size_t(n)]) {
          ASSERT_EQ(column.segment<3>(3 * n).cwiseAbs().maxCoeff(), 0.0);
        }
      }
    }
  std::printf("  largest nodal load of a unit load on the other bore: %.3g N\n", other_bore);
  EXPECT_GT(other_bore, 1e-3);
}

TEST_P(RigidBore, CorrectedLoadDisplacementMovesTheBoresRigidly) {
  // With lambda = 0 and a body force, the field Z_f + c must move each
  // bore's nodes rigidly with the interface motion q = D^T Z_f (reference:
  // the constraint B u = T q; tolerance 1e-9 of the largest displacement).
  // Without the correction the faces warp (deviation checked > 1e-4), and
  // D^T c = 0 (so d = D^T (Z_f + c); tolerance 1e-10 of |d|).
  SupportedBar bar = supported_bar(GetParam());
  RigidBoreCondensation bores(*bar.analysis, bar.model->mesh, kEnds);
  const MatrixXd Zf = body_load_displacement(bar);
  const MatrixXd c = bores.correction(Zf);
  const Eigen::VectorXd u = Zf + c;
  const Eigen::VectorXd d = bores.loads().transpose() * Zf;
  EXPECT_LT((bores.loads().transpose() * c).cwiseAbs().maxCoeff(), 1e-10 * d.cwiseAbs().maxCoeff());
  EXPECT_EQ(bores.statistics().correction_solves, 1);
  const double size = u.cwiseAbs().maxCoeff();
  ASSERT_GT(size, 0.0);
  for (int l = 0; l < 2; ++l) {
    Eigen::Matrix<double, 6, 1> q;
    const double dev = rigid_deviation(bar.model->mesh, bores.face_nodes(l), u, kEnds[size_t(l)].reference_m, &q);
    const Eigen::Matrix<double, 6, 1> ql = d.segment<6>(6 * l);
    const double qdiff = (q.head<3>() - ql.head<3>()).norm() + kLength * (q.tail<3>() - ql.tail<3>()).norm();
    const double uncorrected =
        rigid_deviation(bar.model->mesh, bores.face_nodes(l), Zf.col(0), kEnds[size_t(l)].reference_m);
    std::printf("  bore %d: rigid deviation %.2e (uncorrected %.2e) of max |u| %.3e m; |q - D^T Z_f| %.2e\n", l,
                dev / size, uncorrected / size, size, qdiff / size);
    EXPECT_LT(dev, 1e-9 * size);
    EXPECT_LT(qdiff, 1e-9 * size);
    EXPECT_GT(uncorrected, 1e-4 * size);
  }
  // face_loads: K_s^-1 (f + B^T r) is the corrected field; its resultant on each bore is zero (lambda = 0).
  const MatrixXd r = bores.face_loads(MatrixXd::Zero(12, 1), Zf);
  const fem::DisplacementField ur = bar.analysis->solve_forces(r).front();
  const Eigen::Map<const Eigen::VectorXd> Zr(ur.data(), ur.size());
  EXPECT_LT((Zr - c).cwiseAbs().maxCoeff(), 1e-9 * size);
}

TEST_P(RigidBore, InterfacesOnOneFaceSetShareOneBore) {
  // A joint and its drive on one face set (elastic_assembly's J1 and d1 on
  // x0): one bore, the second interface's motion a rigid transfer of the
  // first's. Reference: the flexibility with the extra interface is X F X^T
  // of the two-interface one (X: rigid transfers; tolerance 1e-12 of |F|).
  SupportedBar bar = supported_bar(GetParam());
  const RigidBoreCondensation two(*bar.analysis, bar.model->mesh, kEnds);
  const Vector3d drive_reference(0.0, 0.01, 0.0);
  const RigidBoreCondensation three(*bar.analysis, bar.model->mesh,
                                    {kEnds[0], kEnds[1], {"x0", drive_reference}});
  EXPECT_EQ(three.statistics().bores, 2);
  EXPECT_EQ(three.statistics().face_nodes, two.statistics().face_nodes);
  MatrixXd X = MatrixXd::Zero(18, 12);
  X.topRows(12).setIdentity();
  X.block<6, 6>(12, 0).setIdentity();
  X.block<3, 3>(12, 3) << 0, 0, -drive_reference.y(), 0, 0, 0, drive_reference.y(), 0, 0;  // -skew(arm)
  const MatrixXd expected = X * two.flexibility() * X.transpose();
  EXPECT_LT((three.flexibility() - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  EXPECT_LT((three.loads().leftCols(12) - two.loads()).cwiseAbs().maxCoeff(), 1e-12 * two.loads().cwiseAbs().maxCoeff());
}

TEST_P(RigidBore, DistributingInterfacesMixWithRigidBores) {
  // A tracked point kept distributing (G_p on face y1) beside the rigid
  // bores: its load is one more load case, so Z_p = K_s^-1 G_p + c(K_s^-1
  // G_p), and the mixed flexibility [D G_p]^T [Z_D Z_p] must be symmetric
  // (reference: W symmetric; tolerance 1e-10 of its largest entry), and the
  // field of a point load must keep both bores rigid (1e-9 of max |u|).
  SupportedBar bar = supported_bar(GetParam());
  RigidBoreCondensation bores(*bar.analysis, bar.model->mesh, kEnds);
  const fem::Mesh& mesh = bar.model->mesh;
  const fem::DistributingCoupling point(mesh, "y1");
  const Vector3d xp(0.15, 0.02, 0.0);
  MatrixXd Gp = MatrixXd::Zero(3 * mesh.node_count(), 6);
  for (int c = 0; c < 3; ++c) {
    point.add(Vector3d::Unit(c), Vector3d::Zero(), xp, Gp.col(c));
    point.add(Vector3d::Zero(), Vector3d::Unit(c), xp, Gp.col(3 + c));
  }
  const std::vector<fem::DisplacementField> z = bar.analysis->solve_forces(Gp);
  MatrixXd Zp(Gp.rows(), 6);
  for (int c = 0; c < 6; ++c) Zp.col(c) = Eigen::Map<const Eigen::VectorXd>(z[size_t(c)].data(), Gp.rows());
  Zp += bores.correction(Zp);
  MatrixXd D(Gp.rows(), 18), Z(Gp.rows(), 18);
  D << bores.loads(), Gp;
  Z << bores.load_displacement(), Zp;
  const MatrixXd F = in_length_units(D.transpose() * Z);
  EXPECT_LT((F - F.transpose()).cwiseAbs().maxCoeff(), 1e-10 * F.cwiseAbs().maxCoeff());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<MatrixXd>(0.5 * (F + F.transpose())).eigenvalues().minCoeff(),
            -1e-10 * F.cwiseAbs().maxCoeff());
  const Eigen::VectorXd u = Zp.col(1);  // a unit force along y at the point, bores unloaded
  for (int l = 0; l < 2; ++l)
    EXPECT_LT(rigid_deviation(mesh, bores.face_nodes(l), u, kEnds[size_t(l)].reference_m),
              1e-9 * u.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(Supports, RigidBore, ::testing::Values(Support::AllNodes, Support::OffBores),
                         [](const auto& info) { return info.param == Support::AllNodes ? "AllNodes" : "OffBores"; });

TEST(RigidBoreErrors, FaceSetsThatShareNodesAreNamed) {
  SupportedBar bar = supported_bar(Support::AllNodes);
  const std::string e = error_of(
      [&] { RigidBoreCondensation(*bar.analysis, bar.model->mesh, {{"x0", Vector3d::Zero()}, {"y0", Vector3d::Zero()}}); });
  EXPECT_NE(e.find("face sets 'x0' and 'y0' share node"), std::string::npos) << e;
}

TEST(RigidBoreErrors, MissingFaceSetIsNamed) {
  SupportedBar bar = supported_bar(Support::AllNodes);
  const std::string e =
      error_of([&] { RigidBoreCondensation(*bar.analysis, bar.model->mesh, {{"bore", Vector3d::Zero()}}); });
  EXPECT_NE(e.find("'bore'"), std::string::npos) << e;
}

TEST(RigidBoreErrors, MeshOfAnotherModelIsRejected) {
  SupportedBar bar = supported_bar(Support::AllNodes);
  test::BarSize other;
  other.cells = {4, 2, 1};
  const fem::Mesh mesh = test::bar_mesh(other);
  const std::string e = error_of([&] { RigidBoreCondensation(*bar.analysis, mesh, kEnds); });
  EXPECT_NE(e.find("not the analysis's mesh"), std::string::npos) << e;
}

TEST(RigidBoreErrors, SupportCandidatesOffTheBoresLeaveEveryFaceDofFree) {
  const fem::Mesh mesh = test::bar_mesh();
  const std::vector<fem::Index> candidates = rigid_bore_support_candidates(mesh, {"x0", "x1"});
  const std::vector<fem::Index> x0 = fem::nodes_of_faces(mesh.face_set("x0"));
  EXPECT_EQ(candidates.size() + 2 * x0.size(), size_t(mesh.node_count()));
  for (fem::Index n : candidates) EXPECT_FALSE(std::binary_search(x0.begin(), x0.end(), n));
  EXPECT_NE(error_of([&] { rigid_bore_support_candidates(mesh, {"nope"}); }).find("'nope'"), std::string::npos);
}

}  // namespace
}  // namespace kinetofem::structure
