// A model that no support holds along some direction: the error names the
// free directions (robustness catalogue, tests/data/robustness/*rigid_body*);
// the factor-memory limit prints small limits readably.
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::fem {
namespace {

// One HEX8 element on [0, 0.1]^3 m, steel.
FeModel one_hex() {
  FeModel model;
  const Eigen::MatrixXd ref = reference_nodes(ElementType::Hex8);
  model.mesh.nodes.resize(ref.rows(), 3);
  for (int a = 0; a < ref.rows(); ++a)
    model.mesh.nodes.row(a) = Eigen::RowVector3d(0.05 * (ref.row(a).array() + 1.0).matrix());
  ElementBlock block{ElementType::Hex8, {}};
  for (int a = 0; a < ref.rows(); ++a) block.connectivity.push_back(a);
  model.mesh.blocks.push_back(block);
  return model;
}

std::string analysis_error(const FeModel& model, CholmodOptions options = {}) {
  const Log log = Log::quiet();
  try {
    LinearStaticAnalysis analysis(model, log, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(UnsupportedDirection, NamesTheDirectionsNoSupportHolds) {
  FeModel model = one_hex();
  model.supports.push_back({"x only", {0, 1, 2, 3}, {true, false, false}, Eigen::Vector3d::Zero()});
  const std::string what = analysis_error(model);
  EXPECT_NE(what.find("not positive definite"), std::string::npos) << what;
  EXPECT_NE(what.find("no support fixes displacements along y, z"), std::string::npos) << what;
}

TEST(UnsupportedDirection, EveryDirectionHeldButRotationFreeKeepsTheGeneralMessage) {
  FeModel model = one_hex();
  // One node fixed in x, y, z: translations held, rotations about it free.
  model.supports.push_back({"one node", {0}, {true, true, true}, Eigen::Vector3d::Zero()});
  const std::string what = analysis_error(model);
  EXPECT_NE(what.find("rigid-body mode left unsupported"), std::string::npos) << what;
  EXPECT_EQ(what.find("no support fixes"), std::string::npos) << what;
}

TEST(FactorMemoryLimit, SmallLimitIsPrintedWithItsDigits) {
  FeModel model = one_hex();
  model.supports.push_back({"face", {0, 1, 2, 3}, {true, true, true}, Eigen::Vector3d::Zero()});
  CholmodOptions options;
  options.max_factor_bytes = 10.0;  // 1e-8 GB: any factor is larger
  const std::string what = analysis_error(model, options);
  EXPECT_NE(what.find("more than the 1e-08 GB allowed"), std::string::npos) << what;
}

}  // namespace
}  // namespace kinetofem::fem
