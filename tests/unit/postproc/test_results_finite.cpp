// ResultsWriter refuses non-finite results: an inf or NaN in a field, a step,
// an envelope, the load patterns or a history is an error naming the quantity,
// the body and the time, and the run that unwinds leaves no results file.
// +inf is kept where it has a documented meaning ("never": a fatigue life
// with no damage, a settling time that never comes).
#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "post_test_calls.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::error_text;
using testing::TemporaryDirectory;

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNan = std::numeric_limits<double>::quiet_NaN();

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

FieldMatrix smooth(const fem::Mesh& mesh, int components) {
  FieldMatrix f(mesh.node_count(), components);
  for (Eigen::Index i = 0; i < f.rows(); ++i)
    for (int c = 0; c < components; ++c) f(i, c) = 1e-3 * (i + 1) + c;
  return f;
}

TEST(ResultsFinite, StaticFieldWithInfIsAnErrorAndLeavesNoFile) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  FieldMatrix u = smooth(mesh, 3);
  u(3, 1) = kInf;
  const std::string m = error_text([&] {
    ResultsWriter writer(dir / "run.h5", Provenance{});
    writer.add_body("lever", mesh).write_static("displacement", "m", u, kVectorComponents);
    writer.commit();
  });
  EXPECT_TRUE(contains(m, "static field 'displacement'")) << m;
  EXPECT_TRUE(contains(m, "body 'lever'")) << m;
  EXPECT_TRUE(contains(m, "is inf at node 3 (component 1)")) << m;
  EXPECT_TRUE(contains(m, "plausible range")) << m;  // the likely cause
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  EXPECT_FALSE(std::filesystem::exists(dir / "run.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "run.h5.tmp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "run.xdmf"));
}

TEST(ResultsFinite, SeriesStepWithNanNamesTheFieldBodyAndTime) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  ResultsWriter writer(dir / "run.h5", Provenance{});
  BodyWriter& body = writer.add_body("crank", mesh);
  body.begin_series({{"von_mises", "Pa", 1}});
  FieldMatrix vm = smooth(mesh, 1);
  body.write_step(0.0, {{"von_mises", vm}});
  vm(7, 0) = kNan;
  const std::string m = error_text([&] { body.write_step(0.5, {{"von_mises", vm}}); });
  EXPECT_TRUE(contains(m, "series field 'von_mises'")) << m;
  EXPECT_TRUE(contains(m, "body 'crank'")) << m;
  EXPECT_TRUE(contains(m, "t = 0.5 s")) << m;
  EXPECT_TRUE(contains(m, "is nan at node 7")) << m;
}

TEST(ResultsFinite, ElementFieldEnvelopeAndLoadPatternsAreChecked) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  ResultsWriter writer(dir / "run.h5", Provenance{});
  BodyWriter& body = writer.add_body("lever", mesh);
  std::string m = error_text([&] { body.write_element_field("volume", "m^3", FieldMatrix::Constant(1, 1, -kInf)); });
  EXPECT_TRUE(contains(m, "element field 'volume'")) << m;
  EXPECT_TRUE(contains(m, "is -inf at element 0")) << m;

  FieldMatrix peak = smooth(mesh, 1);
  peak(2, 0) = kNan;
  m = error_text([&] { body.write_envelope("von_mises", "Pa", peak, IndexMatrix::Zero(mesh.node_count(), 1)); });
  EXPECT_TRUE(contains(m, "envelope 'von_mises'")) << m;
  EXPECT_TRUE(contains(m, "is nan at node 2")) << m;

  LoadPatternData p;
  p.names = {"gravity"};
  p.time_s = {0.0, 1.0};
  p.coefficients = Eigen::MatrixXd::Constant(1, 2, 1.0);
  p.elastic_displacement_m = Eigen::MatrixXd::Zero(3 * mesh.node_count(), 1);
  p.stress_pa = Eigen::MatrixXd::Zero(6 * mesh.node_count(), 1);
  p.coefficients(0, 1) = kInf;
  m = error_text([&] { body.write_load_patterns(p); });
  EXPECT_TRUE(contains(m, "load pattern coefficients")) << m;
  EXPECT_TRUE(contains(m, "body 'lever'")) << m;
  EXPECT_TRUE(contains(m, "t = 1 s")) << m;
  p.coefficients(0, 1) = 1.0;
  p.stress_pa(6 * 4 + 2, 0) = kNan;
  m = error_text([&] { body.write_load_patterns(p); });
  EXPECT_TRUE(contains(m, "load pattern stress")) << m;
  EXPECT_TRUE(contains(m, "is nan at node 4 (component 2)")) << m;
}

TEST(ResultsFinite, HistoryWithInfNamesTheQuantityAndTime) {
  TemporaryDirectory dir;
  ResultsWriter writer(dir / "run.h5", Provenance{});
  writer.set_mechanism_time({0.0, 0.25, 0.5});
  FieldMatrix torque = FieldMatrix::Constant(3, 1, 2.0);
  torque(2, 0) = kInf;
  const std::string m = error_text([&] { writer.write_history("drive.lever_drive.effort", "N*m", torque); });
  EXPECT_TRUE(contains(m, "history 'drive.lever_drive.effort'")) << m;
  EXPECT_TRUE(contains(m, "t = 0.5 s")) << m;
  EXPECT_TRUE(contains(m, "is inf")) << m;
  // NaN marks the times where a history has no value (a linkage that does not assemble there)
  // only when the writer is told so; inf never.
  FieldMatrix angle = FieldMatrix::Constant(3, 1, 0.5);
  angle(1, 0) = kNan;
  EXPECT_TRUE(contains(error_text([&] { writer.write_history("four_bar.transmission_angle", "rad", angle); }), "is nan"));
  writer.write_history_where_defined("four_bar.transmission_angle", "rad", angle);
  angle(0, 0) = kInf;
  const std::string m2 = error_text([&] { writer.write_history_where_defined("four_bar.mu", "rad", angle); });
  EXPECT_TRUE(contains(m2, "history 'four_bar.mu' (rad) at t = 0 s is inf")) << m2;
}

TEST(ResultsFinite, DocumentedInfinitiesAreKeptNanIsNot) {
  TemporaryDirectory dir;
  const fem::Mesh mesh = testing::single_tet10();
  {
    ResultsWriter writer(dir / "run.h5", Provenance{});
    BodyWriter& body = writer.add_body("lever", mesh);
    FieldMatrix life = FieldMatrix::Constant(mesh.node_count(), 1, kInf);  // no damage anywhere
    body.write_static(layout::kFatigueLifeCycles, "cycles", life);
    body.write_static(layout::kFatigueLifeHours, "h", life);
    writer.write_table("point.H.settling_time", "s", FieldMatrix::Constant(1, 1, kInf));
    FieldMatrix nan_life = life;
    nan_life(0, 0) = kNan;
    std::string m = error_text([&] { body.write_static("fatigue_damage", "1", nan_life); });
    EXPECT_TRUE(contains(m, "field 'fatigue_damage'")) << m;
    EXPECT_TRUE(contains(m, "is nan at node 0")) << m;
    m = error_text([&] { writer.write_table("point.H.amplification", "1", FieldMatrix::Constant(1, 1, kNan)); });
    EXPECT_TRUE(contains(m, "table 'point.H.amplification'")) << m;
    EXPECT_TRUE(contains(m, "is nan")) << m;
    writer.commit();
  }
  const ResultsFile file = ResultsFile::open(dir / "run.h5");
  EXPECT_EQ(file.read_static("lever", layout::kFatigueLifeCycles).values(0, 0), kInf);
}

}  // namespace
}  // namespace kinetofem::post
