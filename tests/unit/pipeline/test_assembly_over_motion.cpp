// The stage "elastic assembly over the motion" (pipeline/assembly_over_motion.hpp):
// what it writes (bodies assembly.<b> with a moving geometry, histories of the
// tracked points, their split and compliance, chain and drive histories),
// its summary, and its errors. The lever-chain of structure_fixtures.hpp with
// box parts, 5 output times of its motion and the static pose study.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <Eigen/Geometry>

#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/histories.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "../structure/structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

using namespace kinetofem::pipeline;  // the stage under test

namespace fs = std::filesystem;

struct StageRun {
  fs::path file;
  AssemblySummary summary;
  mech::Results motion;
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
};

AssemblyOptions lever_chain_options() {
  AssemblyOptions o;
  o.chains = {{"chain", 2e6}};
  o.drives = {{"lever_drive", 5e4}};
  o.points = {{"H", "arm", "H", "x0"}};
  return o;
}

StageRun run_stage(const std::string& name) {
  StageRun r;
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  r.model = mech::make_manipulator_model(def);
  r.parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(r.model, r.parts, Log::quiet());
  r.motion = mech::run_kinematics(mech::MultibodySystem(r.model), {0.0, 0.5, 1.0, 1.5, 2.0});
  const mech::Frame statics = pipeline::solve_static_pose(r.model, {0.0});
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_assembly_stage_{}", ::getpid());
  fs::create_directories(dir);
  r.file = dir / (name + ".h5");
  post::ResultsWriter writer(r.file, {});
  pipeline::write_mechanism_histories(writer, r.model, r.motion);
  r.summary = analyse_assembly_over_motion(r.parts, r.model, r.motion.frames, statics, writer, lever_chain_options(),
                                           Log::quiet());
  writer.commit();
  return r;
}

TEST(AssemblyOverMotion, WritesMovingBodiesTheSplitOfHAndItsCompliance) {
  const StageRun r = run_stage("stage");
  const auto file = post::ResultsFile::open(r.file);
  // Bodies: one assembly.<b> per part, its geometry the world position of the step.
  for (const auto& part : r.parts) {
    const std::string body = "assembly." + part.body();
    ASSERT_EQ(file.series_times(body).size(), 5u) << body;
    EXPECT_EQ(file.geometry_field(body), "position");
    int b = 0;
    while (r.model.bodies[size_t(b)].name != part.body()) ++b;
    for (fem::Index k : {0, 4}) {
      const Eigen::Vector3d q = r.motion.frames[size_t(k)].bodies[size_t(b)].q;
      const Eigen::Vector3d X = part.model.mesh.nodes.row(7).transpose();
      const Eigen::Vector3d expected =
          Eigen::AngleAxisd(q.z(), Eigen::Vector3d::UnitZ()) * X + Eigen::Vector3d(q.x(), q.y(), 0.0);
      const auto position = file.read_step(body, "position", k);
      EXPECT_LT((position.values.row(7).transpose() - expected).norm(), 1e-12) << body << " step " << k;
    }
    for (const char* f : {"static_position", "static_displacement", "static_displacement_magnitude", "static_von_mises"})
      EXPECT_EQ(file.read_static(body, f).values.rows(), part.model.mesh.node_count()) << body << " " << f;
    EXPECT_EQ(file.read_envelope(body, "displacement_magnitude").values.rows(), part.model.mesh.node_count());
  }
  // H: the contributions add up to the displacement at every time (unit-load method).
  const Eigen::MatrixXd u = file.read_history("assembly.point.H.displacement").values;
  ASSERT_EQ(u.rows(), 5);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(5, 3);
  int contributors = 0;
  for (const auto& h : file.histories())
    if (h.rfind("assembly.point.H.from.", 0) == 0) sum += file.read_history(h).values, ++contributors;
  EXPECT_EQ(contributors, 4);  // part.lever, part.arm, chain.chain, drive.lever_drive
  EXPECT_LT((sum - u).norm(), 1e-10 * u.norm());
  const Eigen::MatrixXd c = file.read_history("assembly.point.H.compliance").values;
  EXPECT_EQ(file.units_of("/mechanism/assembly.point.H.compliance"), "m/N");
  for (Eigen::Index k = 0; k < 5; ++k) {
    EXPECT_NEAR(c(k, 1), c(k, 3), 1e-10 * c.row(k).norm());  // xy = yx (Maxwell-Betti)
    EXPECT_GT(c(k, 0), 0.0);
  }
  // Summary: the largest |u_H| of the histories, the static study.
  const Eigen::VectorXd magnitude = u.rowwise().norm();
  EXPECT_DOUBLE_EQ(r.summary.points.at(0).max_displacement_m, magnitude.maxCoeff());
  EXPECT_TRUE(r.summary.has_static_study);
  double static_max = 0.0;  // the total deformation: max |u| over every part's nodes
  for (const auto& part : r.parts)
    static_max = std::max(static_max,
                          file.read_static("assembly." + part.body(), "static_displacement_magnitude").values.maxCoeff());
  EXPECT_DOUBLE_EQ(r.summary.static_max_displacement_m, static_max);
  EXPECT_GT(static_max, 0.0);
  // Determinate: the chain's force is the dynamics' tension.
  EXPECT_EQ(r.summary.indeterminacy.in_plane, 0);
  EXPECT_LT(r.summary.worst_chain_mismatch, 1e-9);
  const Eigen::MatrixXd tension = file.read_history("assembly.chain.chain.tension").values;
  for (Eigen::Index k = 0; k < 5; ++k)
    EXPECT_NEAR(tension(k, 0), r.motion.frames[size_t(k)].chains[0].tension_N, 1e-8 * tension(k, 0));
  // The twist of the compliant drive is its moment over its stiffness.
  const Eigen::MatrixXd moment = file.read_history("assembly.drive.lever_drive.moment").values;
  const Eigen::MatrixXd twist = file.read_history("assembly.drive.lever_drive.twist").values;
  for (Eigen::Index k = 0; k < 5; ++k) EXPECT_NEAR(twist(k, 0) * 5e4, -moment(k, 0), 1e-8 * std::abs(moment(k, 0)) + 1e-12);
  const std::string text = format_assembly_summary(r.summary);
  EXPECT_NE(text.find("point H (arm): max |u|"), std::string::npos) << text;
  EXPECT_NE(text.find("chain.chain"), std::string::npos) << text;
  fs::remove_all(r.file.parent_path());
}

TEST(AssemblyOverMotion, NoPartIsAnErrorBeforeAnythingIsWritten) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  const mech::MultibodyModel model = mech::make_manipulator_model(def);
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(model), {0.0, 1.0});
  const fs::path file = fs::temp_directory_path() / fmt::format("kinetofem_assembly_noparts_{}.h5", ::getpid());
  post::ResultsWriter writer(file, {});
  pipeline::write_mechanism_histories(writer, model, motion);
  const std::string m = test::error_of(
      [&] { analyse_assembly_over_motion({}, model, motion.frames, std::nullopt, writer, lever_chain_options(), Log::quiet()); });
  EXPECT_NE(m.find("the linkage has no part"), std::string::npos) << m;
}

// The largest difference of two parts' stress histories over every node and
// output time, relative to the largest stress of the second.
double history_mismatch(const PartStressHistory& a, const PartStressHistory& b) {
  double diff = 0.0, peak = 0.0;
  Eigen::MatrixXd ha, hb;
  for (Eigen::Index n = 0; n < b.nodes(); ++n) {
    a.node_history(n, ha);
    b.node_history(n, hb);
    diff = std::max(diff, (ha - hb).cwiseAbs().maxCoeff());
    peak = std::max(peak, hb.cwiseAbs().maxCoeff());
  }
  return diff / peak;
}

// The lever-chain lies in one plane (box parts symmetric about z = 0, masses
// at z = 0) and is statically determinate: the assembly's joint loads are the
// multibody reactions (docs/elastic_assembly.md), so each part's stress in
// the assembly is the per-part stage's (the same loads on the same mesh), at
// every node and output time, superposed or pose by pose; and so is the
// fatigue damage computed from it.
TEST(AssemblyOverMotion, PartStressHistoriesEqualThePerPartStagesOnAPlanarDeterminateLinkage) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(model), {0.0, 0.4, 0.8, 1.2, 1.6, 2.0});
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_assembly_history_{}", ::getpid());
  fs::create_directories(dir);
  post::ResultsWriter writer(dir / "history.h5", {});
  pipeline::write_mechanism_histories(writer, model, motion);
  std::vector<PartStressHistory> per_part(parts.size());
  for (size_t p = 0; p < parts.size(); ++p)
    analyse_part_over_motion(parts[p], model, motion.frames, std::nullopt, writer, {}, Log::quiet(), nullptr,
                             &per_part[p]);
  FatigueSettings fatigue;
  fatigue.detail_category_mpa = 36.0;
  fatigue.design_cycles = 1e9;  // some ranges above the cut-off: a damage to compare
  for (const bool superposed : {true, false}) {
    AssemblyOptions options = lever_chain_options();
    options.superpose_loads = superposed;
    options.keep_part_stress = true;
    ElasticAssembly assembly(parts, model, options, Log::quiet());
    std::vector<PartStressHistory> from_assembly;
    post::ResultsWriter assembly_writer(dir / fmt::format("assembly_{}.h5", superposed), {});
    pipeline::write_mechanism_histories(assembly_writer, model, motion);
    analyse_assembly_over_motion(assembly, parts, model, motion.frames, std::nullopt, assembly_writer, options,
                                 Log::quiet(), &from_assembly);
    ASSERT_EQ(from_assembly.size(), parts.size());
    for (size_t p = 0; p < parts.size(); ++p) {
      const PartStressHistory& h = from_assembly[p];
      EXPECT_EQ(h.source, StressHistorySource::ElasticAssembly);
      EXPECT_EQ(h.superposed(), superposed) << parts[p].body();
      ASSERT_EQ(h.times(), Eigen::Index(motion.frames.size()));
      ASSERT_EQ(h.nodes(), parts[p].model.mesh.node_count());
      EXPECT_LT(history_mismatch(h, per_part[p]), 1e-8) << parts[p].body() << (superposed ? " superposed" : " pose by pose");
      const PartFatigue a = assess_part_fatigue(parts[p], h, fatigue, Log::quiet());
      const PartFatigue b = assess_part_fatigue(parts[p], per_part[p], fatigue, Log::quiet());
      EXPECT_EQ(a.stress_source, StressHistorySource::ElasticAssembly);
      EXPECT_NEAR(a.max_utilization, b.max_utilization, 1e-6 * b.max_utilization) << parts[p].body();
      EXPECT_GT(b.max_utilization, 0.0);
    }
  }
  fs::remove_all(dir);
}

TEST(AssemblyOverMotion, StressHistoriesNeedTheAssemblyToKeepThePartsStress) {
  const StageRun r = run_stage("no_kept_stress");
  ElasticAssembly assembly(r.parts, r.model, lever_chain_options(), Log::quiet());
  post::ResultsWriter writer(r.file.parent_path() / "second.h5", {});
  pipeline::write_mechanism_histories(writer, r.model, r.motion);
  std::vector<PartStressHistory> histories;
  const std::string m = test::error_of([&] {
    analyse_assembly_over_motion(assembly, r.parts, r.model, r.motion.frames, std::nullopt, writer,
                                 lever_chain_options(), Log::quiet(), &histories);
  });
  EXPECT_NE(m.find("keep_part_stress"), std::string::npos) << m;
  fs::remove_all(r.file.parent_path());
}

}  // namespace
}  // namespace kinetofem::structure
