// The elastic assembly of a `linkage` case with FE parts is the manipulator
// preset's: cases/mechanisms/lever_chain_linkage (the SPEC §1 lever-chain
// manipulator written as a generic linkage of rigid bodies) given the preset's
// two parametric parts (pipeline/manipulator_preset.cpp: the lever with face
// sets bore_A0, bore_A; the arm with roller, bore_A, roller_rim, gripper_mount),
// the face keys on every joint, drive and point mass, the chain's EA and the
// gripper point H, runs the same model on the same meshes as
// cases/lever_chain_manipulator: only the case format differs, so the total
// deformation and H's deflection agree to round-off.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

// Coarse and short: TET4 at 20 mm, 11 output times over the 2 s motion.
constexpr double kElementSizeMm = 20.0;
constexpr int kOutputTimes = 11;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `from` must occur exactly once in `text`.
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "not in the case: " << from;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "twice in the case: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The linkage case with the preset's parts. arm_length_mm is given although
// 350 mm is the arm's default: the manipulator reads c = 350 mm as 350 * 1e-3 =
// 0.35000000000000003 m, the default is 0.350 m, and Gmsh meshes the arm
// differently for that last bit (another mesh of the same node count: H's
// deflection then differs by 2e-7, the arm's share of it by 1.4e-4).
std::string linkage_case_with_parts() {
  std::string t = read_text("cases/mechanisms/lever_chain_linkage/case.toml");
  t = replace_once(t, "[[point_mass]]\nbody = \"arm\"\nname = \"gripper\"",
                   "[[part]]\nbody = \"lever\"\nsource = \"lever\"\n\n"
                   "[[part]]\nbody = \"arm\"\nsource = \"arm_with_roller\"\narm_length_mm = 350.0\n\n"
                   "[[point_mass]]\nbody = \"arm\"\nname = \"gripper\"");
  t = replace_once(t, "name = \"gripper\"\nmass_kg = 20.0\nat_point = \"H\"\n",
                   "name = \"gripper\"\nmass_kg = 20.0\nat_point = \"H\"\nface = \"gripper_mount\"\n");
  t = replace_once(t, "name = \"casting\"\nmass_kg = 15.0\nat_point = \"H\"\n",
                   "name = \"casting\"\nmass_kg = 15.0\nat_point = \"H\"\nface = \"gripper_mount\"\n");
  t = replace_once(t, "name = \"A0\"\ntype = \"revolute\"\nbody_i = \"frame\"\nbody_j = \"lever\"\n",
                   "name = \"A0\"\ntype = \"revolute\"\nbody_i = \"frame\"\nbody_j = \"lever\"\nface_j = \"bore_A0\"\n");
  t = replace_once(t, "point_i = \"A\"\nbody_j = \"arm\"\n",
                   "point_i = \"A\"\nbody_j = \"arm\"\nface_i = \"bore_A\"\nface_j = \"bore_A\"\n");
  t = replace_once(t, "radius_mm = 75.0\n", "radius_mm = 75.0\nface_j = \"roller_rim\"\nea_per_strand_n = 5.0e6\n");
  t = replace_once(t, "body_j = \"lever\"\nlaw = \"polynomial345\"",
                   "body_j = \"lever\"\nface_j = \"bore_A0\"\nlaw = \"polynomial345\"");
  t = replace_once(t, "output_times = 101", "output_times = " + std::to_string(kOutputTimes));
  return t + "\n[mesh]\nelement_size_mm = " + std::to_string(kElementSizeMm) +
         "\n\n[static_study]\nenabled = true\ntime_s = 0.0\n\n[assembly]\nenabled = true\n\n"
         "[[assembly_point]]\nname = \"H\"\nbody = \"arm\"\npoint = \"H\"\nface = \"gripper_mount\"\n";
}

RunOptions quiet_options(const std::string& dir) {
  RunOptions options;
  options.output_dir = fs::temp_directory_path() / dir;
  fs::remove_all(options.output_dir);
  options.quiet = true;
  return options;
}

const pipeline::PointSummary& point(const pipeline::AssemblySummary& a, const std::string& name) {
  const auto it = std::find_if(a.points.begin(), a.points.end(), [&](const auto& p) { return p.name == name; });
  EXPECT_NE(it, a.points.end()) << "no tracked point " << name;
  return it != a.points.end() ? *it : a.points.front();
}

TEST(LinkageAssembly, LeverChainLinkageWithThePresetsPartsEqualsTheManipulatorCase) {
  RunOptions linkage_options = quiet_options("kinetofem_linkage_assembly");
  linkage_options.case_path = "cases/mechanisms/lever_chain_linkage/case.toml";
  const CaseFile linkage_case = CaseFile::parse(linkage_case_with_parts(), linkage_options.case_path, linkage_schema());
  const LinkageRun linkage = run_linkage(linkage_case, linkage_options);

  RunOptions manipulator_options = quiet_options("kinetofem_linkage_assembly_manipulator");
  manipulator_options.case_path = "cases/lever_chain_manipulator/case.toml";
  manipulator_options.overrides = {"mesh.element_size_mm=" + std::to_string(kElementSizeMm),
                                   "motion.output_times=" + std::to_string(kOutputTimes)};
  const CaseFile manipulator_case = CaseFile::load(manipulator_options.case_path, manipulator_schema(), false,
                                                   manipulator_options.overrides);
  const ManipulatorSummary manipulator = run_manipulator(manipulator_case, manipulator_options);

  ASSERT_TRUE(linkage.assembly.has_value());
  ASSERT_TRUE(manipulator.assembly.has_value());
  const pipeline::AssemblySummary& l = *linkage.assembly;
  const pipeline::AssemblySummary& m = *manipulator.assembly;
  const double tol = 1e-6;
  const auto relative = [](double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); };
  std::printf("  total deformation over the motion: linkage %.9e m, manipulator %.9e m (rel. %.1e)\n",
              l.max_displacement_m, m.max_displacement_m, relative(l.max_displacement_m, m.max_displacement_m));
  std::printf("  total deformation, static study:   linkage %.9e m, manipulator %.9e m (rel. %.1e)\n",
              l.static_max_displacement_m, m.static_max_displacement_m,
              relative(l.static_max_displacement_m, m.static_max_displacement_m));

  EXPECT_GT(m.max_displacement_m, 0.0);
  EXPECT_NEAR(l.max_displacement_m, m.max_displacement_m, tol * m.max_displacement_m);
  EXPECT_EQ(l.max_displacement_body, m.max_displacement_body);
  EXPECT_NEAR(l.max_displacement_time_s, m.max_displacement_time_s, 1e-12);
  ASSERT_TRUE(l.has_static_study);
  ASSERT_TRUE(m.has_static_study);
  EXPECT_GT(m.static_max_displacement_m, 0.0);
  EXPECT_NEAR(l.static_max_displacement_m, m.static_max_displacement_m, tol * m.static_max_displacement_m);

  const pipeline::PointSummary& hl = point(l, "H");
  const pipeline::PointSummary& hm = point(m, "H");
  std::printf("  H's largest deflection:            linkage %.9e m, manipulator %.9e m (rel. %.1e)\n",
              hl.max_displacement_m, hm.max_displacement_m, relative(hl.max_displacement_m, hm.max_displacement_m));
  std::printf("  H's static deflection:             linkage %.9e m, manipulator %.9e m (rel. %.1e)\n",
              hl.static_displacement_m.norm(), hm.static_displacement_m.norm(),
              relative(hl.static_displacement_m.norm(), hm.static_displacement_m.norm()));
  EXPECT_GT(hm.max_displacement_m, 0.0);
  EXPECT_NEAR(hl.max_displacement_m, hm.max_displacement_m, tol * hm.max_displacement_m);
  EXPECT_NEAR(hl.max_displacement_time_s, hm.max_displacement_time_s, 1e-12);
  EXPECT_LT((hl.static_displacement_m - hm.static_displacement_m).norm(), tol * hm.static_displacement_m.norm());
  EXPECT_NEAR(hl.max_compliance_m_per_n, hm.max_compliance_m_per_n, tol * hm.max_compliance_m_per_n);

  // The linkage's results file holds the assembly beside the parts.
  const auto file = post::ResultsFile::open(linkage.results_file);
  const auto bodies = file.bodies();
  for (const std::string body : {"assembly.lever", "assembly.arm"}) {
    EXPECT_NE(std::find(bodies.begin(), bodies.end(), body), bodies.end()) << body;
    EXPECT_EQ(file.series_times(body).size(), std::size_t(kOutputTimes)) << body;
  }
  const auto histories = file.histories();
  for (const std::string h : {"assembly.point.H.displacement", "assembly.point.H.displacement_magnitude",
                              "assembly.point.H.rotation", "assembly.point.H.compliance"}) {
    const bool written = std::find(histories.begin(), histories.end(), h) != histories.end();
    EXPECT_TRUE(written) << h;
    if (written) {
      EXPECT_EQ(file.read_history(h).values.rows(), kOutputTimes) << h;
    }
  }
  EXPECT_TRUE(std::any_of(histories.begin(), histories.end(),
                          [](const std::string& h) { return h.starts_with("assembly.point.H.from."); }));
}

}  // namespace
}  // namespace kinetofem::app
