// A `linkage` case whose crank is welded from two solids (tests/data/
// linkage_welded_part: crank.brep holds the arm and the hub, named by points
// inside them, the hub of 2700 kg/m^3, a fatigue detail on their seam) runs
// through the stress and fatigue stages: the results file holds the solids'
// element sets, the seam's face set and the element field naming each
// element's solid; the fatigue detail on the seam (36 MPa) applies to the seam's nodes.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

TEST(LinkageWeldedPart, CrankOfTwoSolidsRunsAndTheResultsNameTheSolids) {
  const auto [output_dir, run] =
      testing::run_linkage_quietly("tests/data/linkage_welded_part/case.toml", "kinetofem_linkage_welded_part");
  ASSERT_EQ(run.parts.size(), 1u);
  EXPECT_GT(run.parts.front().peak_von_mises_pa, 0.0);

  const auto results = post::ResultsFile::open(run.results_file);
  const fem::Mesh mesh = results.read_mesh("crank");
  ASSERT_TRUE(mesh.element_sets.count("solid.arm"));
  ASSERT_TRUE(mesh.element_sets.count("solid.hub"));
  ASSERT_TRUE(mesh.face_sets.count("weld.arm.hub"));
  EXPECT_FALSE(mesh.node_sets.at("weld.arm.hub").empty());

  // Each element's solid: 0 = arm, 1 = hub (alphabetical), as the element sets say.
  const post::FieldData solid = results.read_element_field("crank", post::layout::kSolid);
  ASSERT_EQ(solid.values.rows(), mesh.element_count());
  for (fem::Index e : mesh.element_sets.at("solid.arm")) EXPECT_EQ(solid.values(e, 0), 0.0);
  for (fem::Index e : mesh.element_sets.at("solid.hub")) EXPECT_EQ(solid.values(e, 0), 1.0);
  EXPECT_EQ(fem::Index(mesh.element_sets.at("solid.arm").size() + mesh.element_sets.at("solid.hub").size()),
            mesh.element_count());

  // The seam's fatigue detail (36 MPa, more severe than the default) on every seam node, the
  // part default (71 MPa) elsewhere: the detail resolved to the seam's face set.
  ASSERT_EQ(run.fatigue.size(), 1u);
  const auto& fatigue = run.fatigue.front();
  const auto& seam = mesh.node_sets.at("weld.arm.hub");
  const std::set<fem::Index> on_seam(seam.begin(), seam.end());
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    EXPECT_DOUBLE_EQ(fatigue.detail_category_pa(n), on_seam.count(n) ? 36e6 : 71e6) << "node " << n;
}

}  // namespace
}  // namespace kinetofem::app
