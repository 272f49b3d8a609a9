// Unit tests of assembly, supports, solver and stress recovery on one or a
// few elements with closed-form answers.
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

#include <Eigen/Eigenvalues>

namespace kinetofem::fem {
namespace {

// A single element occupying [0,L]^3 (hexahedra) or the corner tet of it,
// nodes placed from the reference coordinates.
Mesh single_element(ElementType type, double L) {
  Mesh mesh;
  const Eigen::MatrixXd ref = reference_nodes(type);
  mesh.nodes.resize(ref.rows(), 3);
  const bool tet = corner_nodes(type) == 4;
  for (int a = 0; a < ref.rows(); ++a)
    mesh.nodes.row(a) = tet ? Eigen::RowVector3d(L * ref.row(a)) : Eigen::RowVector3d(0.5 * L * (ref.row(a).array() + 1.0).matrix());
  ElementBlock block{type, {}};
  for (int a = 0; a < ref.rows(); ++a) block.connectivity.push_back(a);
  mesh.blocks.push_back(block);
  return mesh;
}


TEST(ElementStiffness, HasExactlySixRigidBodyModes) {
  IsotropicMaterial steel;
  for (ElementType type : {ElementType::Tet4, ElementType::Tet10, ElementType::Hex8, ElementType::Hex20}) {
    Mesh mesh = single_element(type, 0.1);
    DofMap dofs(mesh.node_count(), {});
    const AssembledStiffness K = assemble_stiffness(mesh, steel, dofs);
    const Eigen::MatrixXd upper = Eigen::MatrixXd(K.free_free);
    const Eigen::MatrixXd dense = upper.selfadjointView<Eigen::Upper>();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense);
    const Eigen::VectorXd lambda = eig.eigenvalues();
    const double scale = lambda.cwiseAbs().maxCoeff();
    int zero = 0;
    for (Eigen::Index i = 0; i < lambda.size(); ++i) {
      EXPECT_GT(lambda[i], -1e-10 * scale) << name_of(type);
      if (std::abs(lambda[i]) < 1e-10 * scale) ++zero;
    }
    EXPECT_EQ(zero, 6) << name_of(type);
  }
}

TEST(ElementStiffness, InvertedElementIsRejectedWithItsIndex) {
  IsotropicMaterial steel;
  Mesh mesh = single_element(ElementType::Tet10, 0.1);
  mesh.nodes.row(3) << 0.0, 0.0, -0.1;  // apex through the base: negative volume
  DofMap dofs(mesh.node_count(), {});
  try {
    assemble_stiffness(mesh, steel, dofs);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("element 0 (TET10)"), std::string::npos) << e.what();
  }
  EXPECT_THROW(check_element_jacobians(mesh), Error);
}

TEST(StaticAnalysis, UniaxialTensionOfOneHexMatchesHookesLaw) {
  // [0,L]^3 cube, x = 0 face held in x (symmetry supports that leave
  // Poisson contraction free), traction sigma on x = L: u_x(L) = sigma L / E,
  // u_y(L) = -nu sigma L / E: exact for every element (constant strain).
  const double L = 0.2, E = 200e9, nu = 0.25, sigma = 50e6;
  for (ElementType type : {ElementType::Hex8, ElementType::Hex20, ElementType::Tet10}) {
    FeModel model;
    model.mesh = single_element(type, L);
    model.material = IsotropicMaterial{"test", E, nu, 7800};
    std::vector<Index> x0, x1, origin, y_axis;
    for (Index i = 0; i < model.mesh.node_count(); ++i) {
      const auto p = model.mesh.nodes.row(i);
      if (p[0] == 0.0) x0.push_back(i);
      if (p[0] == L) x1.push_back(i);
      if (p.norm() == 0.0) origin.push_back(i);
      if (p[0] == 0.0 && p[2] == 0.0 && p[1] > 0.0) y_axis.push_back(i);
    }
    if (corner_nodes(type) == 4) continue;  // the tet has no x = L face with area
    model.supports.push_back({"x0", x0, {true, false, false}, Eigen::Vector3d::Zero()});
    model.supports.push_back({"origin", origin, {true, true, true}, Eigen::Vector3d::Zero()});
    model.supports.push_back({"y axis", y_axis, {true, false, true}, Eigen::Vector3d::Zero()});
    // Face set x = L from the element's faces.
    FaceBlock face{face_type_of(type), {}};
    for (int f = 0; f < faces_per_element(type); ++f) {
      const auto local = element_face_nodes(type, f);
      bool on = true;
      for (int a : local) on = on && model.mesh.nodes(a, 0) == L;
      if (on)
        for (int a : local) face.connectivity.push_back(a);
    }
    model.mesh.face_sets["x1"] = {face};
    LoadCase load;
    load.tractions.push_back({"x1", Eigen::Vector3d(sigma, 0, 0)});
    Log log = Log::quiet();
    LinearStaticAnalysis analysis(model, log);
    const auto u = analysis.solve({load});
    for (Index i : x1) {
      EXPECT_NEAR(u[0](i, 0), sigma * L / E, 1e-12) << name_of(type);
      EXPECT_NEAR(u[0](i, 1), -nu * sigma * L / E * model.mesh.nodes(i, 1) / L, 1e-12);
    }
    const NodalStress s = recover_nodal_stress(model.mesh, model.material, u[0]);
    for (Index i = 0; i < model.mesh.node_count(); ++i) {
      EXPECT_NEAR(s.stress_pa(i, 0), sigma, 1e-6 * sigma) << name_of(type);
      EXPECT_NEAR(s.von_mises_pa[i], sigma, 1e-6 * sigma);
      EXPECT_NEAR(s.principal_pa(i, 0), sigma, 1e-6 * sigma);
    }
  }
}

TEST(StaticAnalysis, UnsupportedModelIsAClearErrorNotNaN) {
  FeModel model;
  model.mesh = single_element(ElementType::Hex20, 0.1);
  // Only x held: y, z translations and rotations remain free.
  std::vector<Index> all(size_t(model.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = Index(i);
  model.supports.push_back({"x only", {0, 1, 2, 3}, {true, false, false}, Eigen::Vector3d::Zero()});
  Log log = Log::quiet();
  try {
    LinearStaticAnalysis analysis(model, log);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("not positive definite") != std::string::npos ||
                what.find("singular") != std::string::npos)
        << what;
  }
}

TEST(StaticAnalysis, PrescribedDisplacementGivesReactionsThatBalanceTheLoad) {
  // Whole x = L face pulled by delta: uniaxial stretch, reaction = E A delta / L.
  const double L = 0.1, E = 210e9, delta = 1e-5;
  FeModel model;
  model.mesh = single_element(ElementType::Hex20, L);
  model.material = IsotropicMaterial{"steel", E, 0.3, 7850};
  std::vector<Index> x0, x1, origin;
  for (Index i = 0; i < model.mesh.node_count(); ++i) {
    if (model.mesh.nodes(i, 0) == 0.0) x0.push_back(i);
    if (model.mesh.nodes(i, 0) == L) x1.push_back(i);
  }
  model.supports.push_back({"x0", x0, {true, false, false}, Eigen::Vector3d::Zero()});
  model.supports.push_back({"x1", x1, {true, false, false}, Eigen::Vector3d(delta, 0, 0)});
  model.supports.push_back({"origin", {0}, {true, true, true}, Eigen::Vector3d::Zero()});
  model.supports.push_back({"corner3", {3}, {true, false, true}, Eigen::Vector3d::Zero()});
  Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve({LoadCase{}});
  const Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(3 * model.mesh.node_count());
  const Eigen::VectorXd r = analysis.reactions(u[0], f_ext);
  double pull = 0;
  for (Index i : x1) pull += r[3 * i];
  EXPECT_NEAR(pull, E * L * L * delta / L, 1e-9 * E * L * delta);  // F = E A delta / L
}

TEST(Material, RejectsPoissonRatioAtOneHalf) {
  IsotropicMaterial m{"rubber", 1e6, 0.5, 1000};
  EXPECT_THROW(m.validate(), Error);
  m.poisson_ratio = 0.3;
  m.youngs_modulus_pa = -1;
  EXPECT_THROW(m.validate(), Error);
}

TEST(DofMap, ConflictingSupportsAreAnError) {
  std::vector<DisplacementSupport> supports = {{"a", {0}, {true, true, true}, Eigen::Vector3d::Zero()},
                                               {"b", {0}, {true, false, false}, Eigen::Vector3d(1, 0, 0)}};
  EXPECT_THROW(DofMap(2, supports), Error);
  DofMap ok(2, {supports[0]});
  EXPECT_EQ(ok.free_count(), 3);
  EXPECT_EQ(ok.equation(3), 0);
}

}  // namespace
}  // namespace kinetofem::fem
