// The "spatial_linkage" case type: the TOML format mapped onto
// mech::spatial::Model (units, poses, inertias, axes, drives), its error
// messages, and the bundled case cases/spatial_linkage run through the
// case-type registry with its checks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/spatial_linkage_job.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/dynamics.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;
namespace sp = mech::spatial;
constexpr double kDeg = std::numbers::pi / 180.0;
const char* kBundledCase = "cases/spatial_linkage/case.toml";

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kinetofem_test_spatial_linkage_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A pendulum: a 100 mm bar on a revolute about the world y axis, its frame
// yawed 90 deg; `extra` is appended (line 14 on).
std::string pendulum(const std::string& joint_keys = "axis_i = [0.0, 1.0, 0.0]", const std::string& extra = "") {
  return "[case]\n"
         "type = \"spatial_linkage\"\n"
         "[[body]]\n"
         "name = \"ground\"\n"
         "fixed = true\n"
         "[[body]]\n"
         "name = \"bar\"\n"
         "mass_kg = 2.0\n"
         "com_mm = [50.0, 0.0, 0.0]\n"
         "inertia_kgm2 = [1e-4, 2e-3, 3e-3, 1e-5, 2e-5, 3e-5]\n"
         "rotation_rpy_deg = [0.0, 0.0, 90.0]\n"
         "position_mm = [10.0, 20.0, 30.0]\n"
         "[simulation]\n"
         "duration_s = 1.0\n"
         "[[joint]]\n"
         "name = \"pin\"\n"
         "type = \"revolute\"\n"
         "body_i = \"ground\"\n"
         "body_j = \"bar\"\n" +
         joint_keys + "\n" + extra;
}

std::string error_of(const std::string& text) {
  try {
    read_spatial_linkage_model(CaseFile::parse(text, "case.toml", spatial_linkage_schema()));
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SpatialLinkageCase, ReadsBodiesInSiWithTheirPoseAndInertia) {
  const sp::Model m = read_spatial_linkage_model(CaseFile::parse(pendulum(), "case.toml", spatial_linkage_schema()));
  ASSERT_EQ(m.bodies.size(), 2u);
  const sp::Body& bar = m.bodies[1];
  EXPECT_DOUBLE_EQ(bar.mass_kg, 2.0);
  EXPECT_NEAR((bar.com_body - Eigen::Vector3d(0.05, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((bar.position - Eigen::Vector3d(0.01, 0.02, 0.03)).norm(), 0.0, 1e-15);
  // Six numbers: Ixx, Iyy, Izz, Ixy, Ixz, Iyz, a symmetric tensor.
  Eigen::Matrix3d expected;
  expected << 1e-4, 1e-5, 2e-5, 1e-5, 2e-3, 3e-5, 2e-5, 3e-5, 3e-3;
  EXPECT_NEAR((bar.inertia_kgm2 - expected).norm(), 0.0, 1e-18);
  // Yaw 90 deg: the body's x axis is the world's y.
  EXPECT_NEAR((sp::rotation(bar.euler_parameters) * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0,
              1e-15);
  EXPECT_TRUE(m.bodies[0].fixed);
  EXPECT_NEAR((m.gravity - Eigen::Vector3d(0.0, 0.0, -9.80665)).norm(), 0.0, 1e-15);
}

TEST(SpatialLinkageCase, RollPitchYawIsZYXAboutTheWorldAxes) {
  // R = Rz(yaw) Ry(pitch) Rx(roll): roll 90 then yaw 90 takes the body's y
  // axis to world z (roll), which yaw leaves; the body's x goes to world y.
  const std::string text = pendulum("axis_i = [0.0, 1.0, 0.0]", "");
  std::string turned = text;
  turned.replace(turned.find("[0.0, 0.0, 90.0]"), 16, "[90.0, 0.0, 90.0]");
  const sp::Model m = read_spatial_linkage_model(CaseFile::parse(turned, "case.toml", spatial_linkage_schema()));
  const Eigen::Matrix3d r = sp::rotation(m.bodies[1].euler_parameters);
  EXPECT_NEAR((r * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((r * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
}

TEST(SpatialLinkageCase, AxisJDefaultsToAxisIsDirectionAtTheInitialPoses) {
  // The ground's y axis is the yawed bar's x axis.
  const sp::Model m = read_spatial_linkage_model(CaseFile::parse(pendulum(), "case.toml", spatial_linkage_schema()));
  ASSERT_EQ(m.joints.size(), 1u);
  EXPECT_NEAR((m.joints[0].axis_i - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.joints[0].axis_j - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-15);
}

TEST(SpatialLinkageCase, DriveReadsItsLawInTheJointsCoordinate) {
  const sp::Model m =
      read_spatial_linkage_model(CaseFile::parse(pendulum("axis_i = [0.0, 2.0, 0.0]",
                                                          "[[motion_drive]]\nname = \"turn\"\njoint = \"pin\"\nlaw = "
                                                          "\"cycloidal\"\nstroke_deg = 90.0\nduration_s = 0.5\n"),
                                                 "case.toml", spatial_linkage_schema()));
  ASSERT_EQ(m.motion_drives.size(), 1u);
  EXPECT_EQ(m.motion_drives[0].coordinate, sp::DriveCoordinate::Rotation);
  EXPECT_NEAR(m.motion_drives[0].law->at(0.5).s, 90.0 * kDeg, 1e-12);
  EXPECT_NEAR(m.joints[0].axis_i.norm(), 1.0, 1e-15);  // normalised
}

TEST(SpatialLinkageCase, BadInputsNameTheirKey) {
  EXPECT_NE(error_of(pendulum("axis_i = [0.0, 0.0, 0.0]"))
                .find("key 'joint[0].axis_i' = [0, 0, 0]: joint 'pin': the axis has zero length"),
            std::string::npos)
      << error_of(pendulum("axis_i = [0.0, 0.0, 0.0]"));
  const std::string unknown =
      error_of(pendulum("axis_i = [0.0, 1.0, 0.0]",
                        "[[motion_drive]]\nname = \"turn\"\njoint = \"pn\"\nstroke_deg = 90.0\nduration_s = 0.5\n"));
  EXPECT_NE(unknown.find("key 'motion_drive[0].joint' = \"pn\": no joint of that name (joints: pin)"),
            std::string::npos)
      << unknown;
  std::string massless = pendulum();
  massless.replace(massless.find("mass_kg = 2.0"), 13, "mass_kg = 0.0");
  EXPECT_NE(error_of(massless).find("key 'body[1].mass_kg' = 0 kg: moving body 'bar' needs a mass > 0"),
            std::string::npos)
      << error_of(massless);
  std::string flat = pendulum();
  flat.replace(flat.find("[1e-4, 2e-3, 3e-3, 1e-5, 2e-5, 3e-5]"), 36, "[0.0, 2e-3, 3e-3]");
  EXPECT_NE(error_of(flat).find("moving body 'bar' needs an inertia tensor that is positive definite"),
            std::string::npos)
      << error_of(flat);
  std::string ball = pendulum();
  ball.replace(ball.find("\"revolute\""), 10, "\"spherical\"");
  const std::string spherical_axis = error_of(ball);
  EXPECT_NE(spherical_axis.find("a spherical joint has no axis"), std::string::npos) << spherical_axis;
  EXPECT_NE(error_of(pendulum("axis_i = [0.0, 1.0, 0.0]\naxiz_j = [1.0, 0.0, 0.0]")).find("unknown key"),
            std::string::npos);
}

TEST(SpatialLinkageCase, TemplateValuesSayNothingWhereTheyDoNotApply) {
  // The template writes axis_i = [0, 0, 1] in every [[joint]]: a spherical
  // joint copied from it is no error; another axis on it is.
  std::string ball = pendulum("axis_i = [0.0, 0.0, 1.0]");
  ball.replace(ball.find("\"revolute\""), 10, "\"spherical\"");
  EXPECT_EQ(error_of(ball), "(no error)");
  // A point mass at a named point, with its own inertia added by the core.
  const sp::Model m = read_spatial_linkage_model(
      CaseFile::parse(pendulum("axis_i = [0.0, 1.0, 0.0]",
                               "[[point]]\nbody = \"bar\"\nname = \"tip\"\nat_mm = [100.0, 0.0, 0.0]\n"
                               "[[point_mass]]\nbody = \"bar\"\nname = \"gripper\"\nmass_kg = 1.0\nat_point = \"tip\"\n"
                               "inertia_kgm2 = [1e-3, 2e-3, 3e-3]\n"),
                      "case.toml", spatial_linkage_schema()));
  ASSERT_EQ(m.bodies[1].point_masses.size(), 1u);
  EXPECT_NEAR((m.bodies[1].point_masses[0].position_body - Eigen::Vector3d(0.1, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(m.bodies[1].point_masses[0].inertia_kgm2(2, 2), 3e-3);
}

TEST(SpatialLinkageCase, BundledCaseRunsWithItsChecks) {
  RunOptions options;
  options.case_path = kBundledCase;
  options.output_dir = fresh_dir("bundled");
  options.quiet = true;
  const CaseFile c = CaseFile::load(options.case_path, spatial_linkage_schema());
  const MechanismCaseSummary s = run_spatial_linkage(c, options);
  ASSERT_TRUE(fs::exists(s.results_file));
  EXPECT_TRUE(fs::exists(fs::path(s.results_file).replace_extension(".xdmf")));
  EXPECT_TRUE(fs::exists(fs::path(kBundledCase).parent_path() / "README.md"));
  EXPECT_EQ(s.value("degrees_of_freedom"), 0.0);
  EXPECT_LE(s.value("max_drift_relative"), 1e-8);
  // The balances (spatial_linkage_job.hpp): round-off, and the quadrature.
  EXPECT_LE(s.value("power_balance_error"), kPowerBalanceTolerance);
  EXPECT_LE(s.value("work_energy_error"), kWorkEnergyTolerance);
  // One turn of the crank from rest to rest: no kinetic or potential energy
  // gained, so the drive work is what the damper took (> 0).
  EXPECT_GT(s.value("drive_work_j"), 0.0);
  EXPECT_GT(s.value("peak_effort_crank_drive"), 0.0);
  const auto file = post::ResultsFile::open(s.results_file);
  EXPECT_EQ(file.mechanism_time().size(), 201u);
}

TEST(SpatialLinkageCase, BundledCaseFollowsTheClosedFormLoopEquation) {
  // The RSUR loop (cases/spatial_linkage/README.md): crank radius r about z
  // through the origin, rocker radius rho about x through D0 = (d, 0, h),
  // coupler L^2 = d^2 + r^2 + rho^2 + h^2, so that with the crank angle theta
  // and the rocker angle phi (from the world y axis about x)
  //   2 h rho sin(phi) - 2 rho r sin(theta) cos(phi) = 2 d r cos(theta).
  // The rocker's angle at every output time against it, as a residual in m^2.
  const double r = 0.05, rho = 0.12, d = 0.2, h = 0.2;
  const CaseFile c = CaseFile::load(kBundledCase, spatial_linkage_schema());
  const sp::System system(read_spatial_linkage_model(c));
  std::vector<double> times;
  for (int k = 0; k <= 40; ++k) times.push_back(0.05 * k);
  const sp::Results run = sp::run_kinematics(system, times);
  const int crank = system.body_index("crank"), rocker = system.body_index("rocker");
  for (const sp::Frame& f : run.frames) {
    const Eigen::Matrix3d rc = f.bodies[crank].rotation, rr = f.bodies[rocker].rotation;
    const double theta = std::atan2(rc(1, 0), rc(0, 0)), phi = std::atan2(rr(2, 1), rr(1, 1));
    const double residual =
        2 * h * rho * std::sin(phi) - 2 * rho * r * std::sin(theta) * std::cos(phi) - 2 * d * r * std::cos(theta);
    EXPECT_NEAR(residual, 0.0, 1e-10) << "t = " << f.t;
  }
}

TEST(SpatialLinkageCase, TranslationDriveLiftsTheSliderByMassTimesGravityPlusAcceleration) {
  // A 2 kg slider on a vertical prismatic joint, lifted 100 mm in 1 s by a
  // polynomial345 law: the drive force is m (g + a), m g at rest (t = 0 and
  // the law's midpoint, where a = 0) and m (g + 10 sqrt(3) / 3 h / T^2) at
  // the 3-4-5 law's largest acceleration, t = T (1/2 - sqrt(3) / 6).
  const std::string text =
      "[case]\ntype = \"spatial_linkage\"\n"
      "[[body]]\nname = \"ground\"\nfixed = true\n"
      "[[body]]\nname = \"slider\"\nmass_kg = 2.0\ninertia_kgm2 = [1e-3, 1e-3, 1e-3]\n"
      "[[joint]]\nname = \"guide\"\ntype = \"prismatic\"\nbody_i = \"ground\"\nbody_j = \"slider\"\n"
      "axis_i = [0.0, 0.0, 5.0]\n"
      "[[motion_drive]]\nname = \"lift\"\njoint = \"guide\"\nstroke_mm = 100.0\nduration_s = 1.0\n"
      "[simulation]\nduration_s = 1.0\noutput_times = 3\n";
  const CaseFile c = CaseFile::parse(text, "case.toml", spatial_linkage_schema());
  const sp::System system(read_spatial_linkage_model(c));
  const sp::Results run = sp::run_kinematics(system, {0.0, 0.5, 1.0});
  const double g = 9.80665, m = 2.0, h = 0.1;
  EXPECT_NEAR(run.frames[0].drives[0].effort, m * g, 1e-9);
  EXPECT_NEAR(run.frames[1].drives[0].effort, m * g, 1e-9);
  EXPECT_NEAR(run.frames[1].drives[0].s_dot, 1.875 * h, 1e-12);  // 15/8 h/T at the midpoint
  const double peak_t = 0.5 - std::sqrt(3.0) / 6.0;
  const sp::Results at_peak = sp::run_kinematics(system, {0.0, peak_t});
  EXPECT_NEAR(at_peak.frames[1].drives[0].effort, m * (g + 10.0 * std::sqrt(3.0) / 3.0 * h), 1e-9);
}

TEST(SpatialLinkageCase, FreePendulumThroughIdasConservesEnergy) {
  // A spherical pendulum (a 1 kg bob 0.5 m from a ball joint, started with a
  // sideways speed) integrated with IDAS: no drives, no dampers, so the
  // work-energy balance says dT + dV = 0. Reference: energy conservation, to
  // the integrator's tolerance (relative 1e-10).
  const std::string text =
      "[case]\ntype = \"spatial_linkage\"\n"
      "[[body]]\nname = \"ground\"\nfixed = true\n"
      "[[body]]\nname = \"bob\"\nmass_kg = 1.0\ninertia_kgm2 = [1e-3, 1e-3, 1e-3]\n"
      "position_mm = [300.0, 0.0, -400.0]\nvelocity_mm_s = [0.0, 1000.0, 0.0]\n"
      "[[point]]\nbody = \"bob\"\nname = \"pivot\"\nat_mm = [-300.0, 0.0, 400.0]\n"
      "[[joint]]\nname = \"ball\"\ntype = \"spherical\"\nbody_i = \"ground\"\nbody_j = \"bob\"\npoint_j = \"pivot\"\n"
      "[simulation]\nmethod = \"idas\"\nduration_s = 2.0\n";
  const CaseFile c = CaseFile::parse(text, "case.toml", spatial_linkage_schema());
  const sp::System system(read_spatial_linkage_model(c));
  std::vector<double> times;
  for (int k = 0; k <= 2000; ++k) times.push_back(0.001 * k);
  const sp::Results run = sp::simulate_ggl(system, times);
  const EnergyBalance b = energy_balance(system, run);
  const double scale = 1.0 * 9.80665 * 0.5;  // m g L
  EXPECT_NEAR(b.kinetic_gain_J + b.potential_gain_J, 0.0, 1e-7 * scale);
  EXPECT_EQ(b.drive_work_J, 0.0);
  EXPECT_NEAR(b.nonconservative_work_J, 0.0, 1e-7 * scale);
  EXPECT_LE(b.power_balance_error, kPowerBalanceTolerance);
  EXPECT_LE(b.work_energy_error, kWorkEnergyTolerance);
  EXPECT_GT(run.frames.back().bodies[1].com_velocity.norm(), 0.1);  // it moved
}

TEST(SpatialLinkageCase, IsARegisteredCaseTypeWithATemplate) {
  const std::string text = case_template("spatial_linkage");
  for (const char* table : {"[[body]]", "[[point]]", "[[point_mass]]", "[[joint]]", "[[motion_drive]]", "[[spring]]",
                            "[[point_force]]", "[gravity]", "[simulation]"})
    EXPECT_NE(text.find(table), std::string::npos) << table;
}

}  // namespace
}  // namespace kinetofem::app
