// Envelopes, hot spots and time histories on synthetic results files whose
// maxima are placed by hand (post_test_results.hpp): every expected number is
// exact by construction.
#include <cmath>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "post_test_results.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::SyntheticMotion;

TEST(PostEnvelope, ReadFromFileWhenStoredElseRecomputedFromSeries) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const BodyEnvelope beam = max_envelope(r, "beam");
  EXPECT_EQ(beam.source, BodyEnvelope::Source::FileEnvelope);
  EXPECT_EQ(beam.peak_node(), SyntheticMotion::kBeamPeak);
  EXPECT_DOUBLE_EQ(beam.peak_value(), 300e6);
  EXPECT_DOUBLE_EQ(beam.time_of(beam.peak_node()), 0.2);
  // The stored envelope and one recomputed from the series agree node by node.
  const BodyEnvelope again = envelope_from_series(r, "beam");
  EXPECT_EQ(again.max_value, beam.max_value);
  EXPECT_EQ(again.max_step, beam.max_step);

  const BodyEnvelope plate = max_envelope(r, "plate");
  EXPECT_EQ(plate.source, BodyEnvelope::Source::Series);
  EXPECT_EQ(plate.peak_node(), SyntheticMotion::plate_peak());
  EXPECT_DOUBLE_EQ(plate.peak_value(), 250e6);
  EXPECT_DOUBLE_EQ(plate.time_of(plate.peak_node()), 0.1);
  EXPECT_EQ(plate.units, "Pa");
}

TEST(PostEnvelope, StaticFileUsesTheStaticFieldWithoutTime) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_static(dir.path()));
  const BodyEnvelope bar = max_envelope(r, "bar");
  EXPECT_EQ(bar.source, BodyEnvelope::Source::Static);
  EXPECT_NEAR(bar.peak_value(), 25e6 * 1.1, 1e-6);  // vm = 25 MPa (1 + x/m) at x = 0.1 m
  EXPECT_NEAR(bar.nodes_m(bar.peak_node(), 0), 0.1, 1e-12);
  EXPECT_TRUE(std::isnan(bar.time_of(bar.peak_node())));
}

TEST(PostEnvelope, UnknownFieldNamesTheFieldsPresent) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  try {
    max_envelope(r, "beam", "tresca");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no field 'tresca'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("von_mises"), std::string::npos) << e.what();
  }
  EXPECT_THROW(max_envelope(r, "beam", "displacement"), Error);  // 3 components: not scalar
}

TEST(PostHotSpots, TopThreeAreSeparatedAndOrdered) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const auto spots = find_hot_spots(max_envelopes(r), {.count = 3, .separation_m = 0.010});
  ASSERT_EQ(spots.size(), 3u);
  // 290 MPa at (60, 0, 0) mm is 10 mm from the 300 MPa peak: skipped.
  EXPECT_EQ(spots[0].body, "beam");
  EXPECT_EQ(spots[0].node, SyntheticMotion::kBeamPeak);
  EXPECT_DOUBLE_EQ(spots[0].value, 300e6);
  EXPECT_DOUBLE_EQ(spots[0].time_s, 0.2);
  EXPECT_EQ(spots[0].step, 2);
  EXPECT_NEAR((spots[0].position_m - Eigen::Vector3d(0.05, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(spots[1].body, "plate");
  EXPECT_EQ(spots[1].node, SyntheticMotion::plate_peak());
  EXPECT_DOUBLE_EQ(spots[1].value, 250e6);
  EXPECT_DOUBLE_EQ(spots[1].time_s, 0.1);
  EXPECT_EQ(spots[2].body, "beam");
  EXPECT_EQ(spots[2].node, SyntheticMotion::beam_second());
  EXPECT_DOUBLE_EQ(spots[2].value, 200e6);
  EXPECT_NEAR((spots[2].position_m - Eigen::Vector3d(0.15, 0.02, 0.01)).norm(), 0.0, 1e-12);
  // The static pose field is a separate load case and never a hot spot of the motion.
  for (const auto& s : find_hot_spots(max_envelopes(r), {.count = 20})) EXPECT_NE(s.value, 1e6);
}

TEST(PostHotSpots, SeparationIsAppliedPerBodyAndCanBeSwitchedOff) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const auto envelopes = max_envelopes(r);
  const auto close = find_hot_spots(envelopes, {.count = 2, .separation_m = 0.0});
  ASSERT_EQ(close.size(), 2u);
  EXPECT_EQ(close[1].node, SyntheticMotion::kBeamNeighbour);
  EXPECT_DOUBLE_EQ(close[1].value, 290e6);
  // 25 mm: every listed beam spot keeps its beam neighbours within 25 mm off the list.
  const auto spots = find_hot_spots(envelopes, {.count = 10, .separation_m = 0.025});
  ASSERT_EQ(spots.size(), 10u);
  for (size_t i = 0; i < spots.size(); ++i) {
    if (i) {
      EXPECT_GE(spots[i - 1].value, spots[i].value);
    }
    for (size_t j = 0; j < i; ++j) {
      if (spots[i].body == spots[j].body) {
        EXPECT_GT((spots[i].position_m - spots[j].position_m).norm(), 0.025);
      }
    }
  }
  EXPECT_THROW(find_hot_spots(envelopes, {.count = -1}), Error);
}

TEST(PostTimeHistory, NodeHistoryAndNearestNode) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const fem::Index node = nearest_node(r.read_mesh("beam").nodes, {0.0512, 0.0031, -0.002});
  EXPECT_EQ(node, SyntheticMotion::kBeamPeak);
  const TimeHistory h = node_history(r, "beam", "von_mises", node);
  ASSERT_EQ(h.time_s.size(), 5u);
  ASSERT_EQ(h.values.rows(), 5);
  EXPECT_DOUBLE_EQ(h.values(2, 0), 300e6);
  EXPECT_DOUBLE_EQ(h.time_s[4], 0.4);
  EXPECT_EQ(h.units, "Pa");
  const TimeHistory u = node_history(r, "beam", "displacement", 20);  // x = 200 mm
  EXPECT_DOUBLE_EQ(u.values(4, 1), -5e-5);
  EXPECT_THROW(node_history(r, "beam", "von_mises", 99999), Error);
  EXPECT_THROW(node_history(r, "nobody", "von_mises", 0), Error);
  EXPECT_THROW(node_history(r, "beam", "stress", 0), Error);
}

TEST(PostTimeHistory, MechanismHistoryAndMagnitude) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const TimeHistory h = mechanism_history(r, "reaction_A0_on_lever");
  ASSERT_EQ(h.values.cols(), 2);
  EXPECT_EQ(h.units, "N");
  EXPECT_NEAR(h.magnitude()(10), 500.0, 1e-9);  // (300, 400) sin(pi/2)
  EXPECT_THROW(mechanism_history(r, "nothing"), Error);
  EXPECT_EQ(display_unit("Pa").label, "MPa");
  EXPECT_DOUBLE_EQ(display_unit("m").factor, 1e3);
  EXPECT_EQ(display_unit("N*m").label, "N*m");
}

}  // namespace
}  // namespace kinetofem::post

// A welded part: two TET4 of two solids sharing the face (1, 2, 3), the seam.
// Hot spots name the solid of their node and the seam when it lies on one.
namespace kinetofem::post {
namespace {

TEST(PostHotSpots, NameTheSolidAndTheWeldSeamOfAWeldedPart) {
  testing::TemporaryDirectory dir;
  fem::Mesh mesh;
  mesh.nodes.resize(5, 3);
  mesh.nodes << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  fem::ElementBlock tets;
  tets.type = fem::ElementType::Tet4;
  tets.connectivity = {0, 1, 2, 3, 4, 3, 2, 1};
  mesh.blocks.push_back(tets);
  mesh.element_sets = {{"solid.plate", {0}}, {"solid.hub", {1}}};
  mesh.node_sets = {{"weld.hub.plate", {1, 2, 3}}};
  const auto path = dir / "welded.h5";
  {
    ResultsWriter writer(path, Provenance{});
    BodyWriter& w = writer.add_body("arm", mesh);
    FieldMatrix vm(5, 1);
    vm << 1e6, 5e6, 2e6, 2e6, 3e6;  // the peak on the seam (node 1), the next in the hub only (node 4)
    w.write_static("von_mises", "Pa", vm);
    writer.commit();
  }
  const auto spots = find_hot_spots(max_envelopes(ResultsFile::open(path)), {.count = 3, .separation_m = 0.0});
  ASSERT_EQ(spots.size(), 3u);
  EXPECT_EQ(spots[0].node, 1);
  EXPECT_EQ(spots[0].solid, "hub");  // on the seam: the solid first by name
  EXPECT_EQ(spots[0].seam, "weld.hub.plate");
  EXPECT_EQ(spots[1].node, 4);
  EXPECT_EQ(spots[1].solid, "hub");
  EXPECT_EQ(spots[1].seam, "");
  EXPECT_EQ(spots[2].solid, "hub");
}

// The results layout names the solids and seams as the meshes module makes them.
TEST(PostHotSpots, SolidAndSeamPrefixesAreThoseOfTheMeshes) {
  EXPECT_STREQ(layout::kSolidSetPrefix, meshes::kSolidSetPrefix);
  EXPECT_STREQ(layout::kWeldSetPrefix, meshes::kWeldSetPrefix);
}

}  // namespace
}  // namespace kinetofem::post
