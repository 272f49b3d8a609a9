// The crank-slider gripper of the bundled case cases/gripper_parts (SPEC §6,
// source 004) as a multibody model, read from its case file, against the
// closed form of mechanisms/crank_slider_gripper.hpp.
//
// The case's lower half is the crank-slider that eq. (6) describes: the
// rocker pivot O_l at distance e from the slider line (y = 0), rocker angle
// phi counter-clockwise from +x, pin A = O_l + r (cos phi, sin phi), rod of
// length l to the slider pin B on y = 0 with x_B > x_A. Its slider position is
//     x_B = r cos phi + sqrt(l^2 - (r sin phi - e)^2),
// and A's speed across the slider line is r cos(phi) phi', so
//     x_B' / y_A' = -tan phi - (sin phi - e/r) / sqrt(1/sigma^2 - (sin phi - e/r)^2),
// eq. (6) with sigma = r/l and gamma = e/r (the offset normalised by r: the
// source's (6) follows from its (5) only so; crank_slider_gripper.hpp). The
// jaw translates with A (parallelogram O_l A C P_l), so y_A' is the jaw's
// speed along the clamping force (+y for the lower jaw). Eq. (6) is thus the
// slider speed over the jaw speed along the clamping force, the ratio of the
// source's abstract (its text's V_out cos(alpha) / V_in is the reciprocal),
// and the one for which the virtual work of a frictionless quasi-static
// gripper gives
//     F_drive x_B' = 2 F_clamp y_A'   =>   F_clamp = (F_drive / 2) U_V
// (the slider drives two jaws, each clamped with F_clamp).
//
// References and tolerances: eq. (6) through mech::gripper_index_offset,
// 1e-9 at every output time (the model's kinematics solve to 1e-13 of the
// characteristic length; measured 1e-13); the virtual work, 1e-9 of the
// clamping force (measured 4e-15); with the bodies' inertia and weight, the
// power balance to 1e-9 of the drive's power (measured 3e-12). And the
// one-grip case grip_cycle.toml beside it, and the case through the whole
// chain (the last two tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/mechanisms/crank_slider_gripper.hpp"
#include "kinetofem/mechanisms/motion_law_factory.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/postproc/load_patterns.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::filesystem::path kCase = "cases/gripper_parts/case.toml";
const std::filesystem::path kGripCycle = "cases/gripper_parts/grip_cycle.toml";

struct GripperCase {
  mech::MultibodyModel model;
  std::vector<double> times;
  // Read from the model, not restated: crank (rocker) radius r, rod length
  // l, offset e of the rocker pivots from the slider line (m).
  double r_m = 0, l_m = 0, e_m = 0;
  double sigma() const { return r_m / l_m; }
  double gamma_r() const { return e_m / r_m; }
};

const mech::Body& body_named(const mech::MultibodyModel& m, const std::string& name) {
  const auto it = std::find_if(m.bodies.begin(), m.bodies.end(), [&](const mech::Body& b) { return b.name == name; });
  if (it == m.bodies.end()) throw std::runtime_error("no body " + name);
  return *it;
}

GripperCase read_gripper_case(const std::filesystem::path& path = kCase) {
  const CaseFile c = CaseFile::load(path, linkage_schema(), false, {});
  GripperCase g;
  g.model = read_linkage_model(c);
  g.times = mech::equally_spaced_times(c.number("simulation.duration_s"), c.integer("simulation.output_times"));
  g.r_m = body_named(g.model, "rocker_lower").points.at("A").norm();
  g.l_m = body_named(g.model, "rod_lower").points.at("B").norm();
  g.e_m = -body_named(g.model, "ground").points.at("O_lower").y();
  return g;
}

// Bodies with parts take their mass from the mesh in a run; here every
// moving body gets `mass_kg` and `inertia_kgm2` at its frame origin, and
// gravity `g`.
void set_masses(mech::MultibodyModel& m, double mass_kg, double inertia_kgm2, const Eigen::Vector2d& g) {
  for (auto& b : m.bodies) {
    if (b.fixed) continue;
    b.mass_kg = mass_kg;
    b.inertia_kgm2 = inertia_kgm2;
    b.com_body.setZero();
    b.point_masses.clear();
  }
  m.gravity = g;
}

const mech::BodyFrame& frame_body(const mech::Frame& f, const std::string& name) {
  return *std::find_if(f.bodies.begin(), f.bodies.end(), [&](const mech::BodyFrame& b) { return b.name == name; });
}

// World velocity of a point given in the body frame.
Eigen::Vector2d point_velocity(const mech::BodyFrame& b, const Eigen::Vector2d& p_body) {
  const double c = std::cos(b.q(2)), s = std::sin(b.q(2));
  const Eigen::Vector2d rp(c * p_body.x() - s * p_body.y(), s * p_body.x() + c * p_body.y());
  return b.q_dot.head<2>() + b.q_dot(2) * Eigen::Vector2d(-rp.y(), rp.x());
}

const mech::PointForce& force_named(const mech::MultibodyModel& m, const std::string& name) {
  return *std::find_if(m.point_forces.begin(), m.point_forces.end(),
                       [&](const mech::PointForce& f) { return f.name == name; });
}

// Rocker angle phi of the lower half in (0, 2 pi).
double phi_of(const mech::Frame& f) {
  double phi = std::fmod(frame_body(f, "rocker_lower").q(2), 2 * std::numbers::pi);
  return phi < 0 ? phi + 2 * std::numbers::pi : phi;
}

// The jaw's speed along its clamping force: the force the jaw puts on the
// object, opposite to the object's reaction the case applies at the pad.
double jaw_speed_along_clamp(const mech::MultibodyModel& m, const mech::Frame& f, const std::string& side) {
  const mech::PointForce& reaction = force_named(m, "object_on_" + side + "_jaw");
  const Eigen::Vector2d clamp_dir = -reaction.force_world.normalized();
  const mech::Body& jaw = body_named(m, reaction.body);
  return point_velocity(frame_body(f, jaw.name), jaw.points.at(reaction.point)).dot(clamp_dir);
}

TEST(GripperPartsCase, IndexFromTheModelsVelocitiesIsEquationSix) {
  GripperCase g = read_gripper_case();
  // The case's polynomial law starts and ends at rest, where the ratio is
  // 0/0; the same stroke at a constant speed has the same poses and a
  // velocity at every output time.
  mech::MotionDrive& drive = g.model.motion_drives.at(0);
  const double stroke_m = drive.law->at(g.times.back()).s - drive.law->at(0.0).s;
  const double s0 = drive.initial.value() + drive.law->at(0.0).s;
  drive.initial = s0;
  drive.law = mech::make_motion_law({.law = "constant_velocity", .speed = stroke_m / g.times.back()});
  const mech::MultibodySystem system(g.model);
  const mech::Results results = mech::run_kinematics(system, g.times);

  double max_error = 0, max_asymmetry = 0;
  for (const mech::Frame& f : results.frames) {
    const double phi = phi_of(f);
    const double slider_speed = f.drives.at(0).s_dot;
    const double u_model = slider_speed / jaw_speed_along_clamp(g.model, f, "lower");
    const double u_eq6 = mech::gripper_index_offset(phi, g.sigma(), g.gamma_r());
    max_error = std::max(max_error, std::abs(u_model - u_eq6));
    EXPECT_NEAR(u_model, u_eq6, 1e-9) << "t = " << f.t << " s, phi = " << phi / kDeg << " deg";
    // The upper half is the mirror image: the same index.
    const double u_upper = slider_speed / jaw_speed_along_clamp(g.model, f, "upper");
    max_asymmetry = std::max(max_asymmetry, std::abs(u_upper - u_model));
    EXPECT_NEAR(u_upper, u_model, 1e-9) << "t = " << f.t << " s";
  }
  // The stroke is the operating range 163 -> 139 deg (the case's initial_mm
  // and stroke_mm are x_B at those angles to 1e-6 mm: phi to about 1e-6 deg).
  EXPECT_NEAR(phi_of(results.frames.front()) / kDeg, 163.0, 1e-4);
  EXPECT_NEAR(phi_of(results.frames.back()) / kDeg, 139.0, 1e-4);
  std::printf("gripper_parts: sigma = r/l = %.6f, gamma = e/r = %.6f; U_V over %zu output times (phi %.4f..%.4f deg): "
              "max |model - eq. (6)| = %.3g, max |upper - lower| = %.3g\n",
              g.sigma(), g.gamma_r(), results.frames.size(), phi_of(results.frames.front()) / kDeg,
              phi_of(results.frames.back()) / kDeg, max_error, max_asymmetry);

  // And with the case's own law, at every output time where the slider moves.
  const GripperCase as_is = read_gripper_case();
  const mech::Results own = mech::run_kinematics(mech::MultibodySystem(as_is.model), as_is.times);
  double max_error_own = 0;
  std::size_t moving = 0;
  for (const mech::Frame& f : own.frames) {
    if (std::abs(f.drives.at(0).s_dot) < 1e-9) continue;  // the ends, at rest
    ++moving;
    const double u_model = f.drives.at(0).s_dot / jaw_speed_along_clamp(as_is.model, f, "lower");
    const double u_eq6 = mech::gripper_index_offset(phi_of(f), as_is.sigma(), as_is.gamma_r());
    max_error_own = std::max(max_error_own, std::abs(u_model - u_eq6));
    EXPECT_NEAR(u_model, u_eq6, 1e-9) << "case's law, t = " << f.t << " s";
  }
  EXPECT_EQ(moving, own.frames.size() - 2);
  std::printf("gripper_parts: the case's own law (polynomial 3-4-5): %zu output times with the slider moving, max |model - "
              "eq. (6)| = %.3g\n", moving, max_error_own);
}

TEST(GripperPartsCase, QuasiStaticClampingForceIsHalfTheDriveForceTimesTheIndex) {
  // Massless links and no gravity: the drive force holds the object's
  // reactions alone, at every output time (the ends at rest included).
  GripperCase g = read_gripper_case();
  set_masses(g.model, 0.0, 0.0, Eigen::Vector2d::Zero());
  const mech::MultibodySystem system(g.model);
  const mech::Results results = mech::run_kinematics(system, g.times);
  const double clamp_n = force_named(g.model, "object_on_lower_jaw").force_world.norm();
  ASSERT_DOUBLE_EQ(force_named(g.model, "object_on_upper_jaw").force_world.norm(), clamp_n);

  double max_relative = 0;
  for (const mech::Frame& f : results.frames) {
    const double phi = phi_of(f);
    const double drive_n = f.drives.at(0).effort;  // on the slider along +x
    const double predicted = 0.5 * drive_n * mech::gripper_index_offset(phi, g.sigma(), g.gamma_r());
    max_relative = std::max(max_relative, std::abs(predicted - clamp_n) / clamp_n);
    EXPECT_NEAR(predicted, clamp_n, 1e-9 * clamp_n) << "t = " << f.t << " s, phi = " << phi / kDeg << " deg";
  }
  std::printf("gripper_parts: quasi-static, clamping force %.1f N per jaw, drive %.2f..%.2f N: "
              "max |(F_drive/2) U_V - F_clamp| / F_clamp = %.3g\n",
              clamp_n, results.frames.front().drives[0].effort, results.frames.back().drives[0].effort, max_relative);
}

TEST(GripperPartsCase, WithInertiaAndWeightThePowerBalanceHolds) {
  // Every moving body 0.2 kg and 1e-4 kg m^2, gravity -y, the case's motion:
  //     F_drive x_B' + sum F_pad . v_pad + sum m g . v_com = dT/dt
  //                                        = sum (m a_com . v_com + I theta'' theta').
  GripperCase g = read_gripper_case();
  const double mass = 0.2, inertia = 1e-4;
  set_masses(g.model, mass, inertia, Eigen::Vector2d(0.0, -9.80665));
  const mech::MultibodySystem system(g.model);
  const mech::Results results = mech::run_kinematics(system, g.times);

  double max_relative = 0, max_inertia_share = 0;
  for (const mech::Frame& f : results.frames) {
    const double drive_power = f.drives.at(0).effort * f.drives.at(0).s_dot;
    double external = 0, kinetic_rate = 0;
    for (const auto& pf : g.model.point_forces) {
      const mech::Body& b = body_named(g.model, pf.body);
      external += pf.force_world.dot(point_velocity(frame_body(f, b.name), b.points.at(pf.point)));
    }
    for (const mech::BodyFrame& b : f.bodies) {
      if (body_named(g.model, b.name).fixed) continue;
      external += mass * g.model.gravity.dot(b.com_velocity);
      kinetic_rate += mass * b.com_acceleration.dot(b.com_velocity) + inertia * b.q_ddot(2) * b.q_dot(2);
    }
    const double scale = std::max(std::abs(drive_power), 1e-12);
    if (std::abs(drive_power) < 1e-6) continue;  // the ends, at rest: 0 = 0
    const double residual = drive_power + external - kinetic_rate;
    max_relative = std::max(max_relative, std::abs(residual) / scale);
    max_inertia_share = std::max(max_inertia_share, std::abs(kinetic_rate) / scale);
    EXPECT_NEAR(residual / scale, 0.0, 1e-9) << "t = " << f.t << " s";
  }
  std::printf("gripper_parts: with inertia and weight, max |power balance| / drive power = %.3g (dT/dt up to %.3g of "
              "the drive power)\n",
              max_relative, max_inertia_share);
}

// World position of a point given in the body frame.
Eigen::Vector2d point_position(const mech::BodyFrame& b, const Eigen::Vector2d& p_body) {
  const double c = std::cos(b.q(2)), s = std::sin(b.q(2));
  return b.q.head<2>() + Eigen::Vector2d(c * p_body.x() - s * p_body.y(), s * p_body.x() + c * p_body.y());
}

TEST(GripperPartsCase, OneGripStartsAtTheTouchAndEndsAtTheClampingForce) {
  // grip_cycle.toml: the object as a spring between the pads' grip points,
  // free length = its thickness. Its numbers (initial_mm, stroke_mm, the
  // free length; README "One grip") must put the touch at t = 0 (force 0) and
  // the clamping force at the end: checked against the spring's own law
  // T = k (L0 - L), the case's six-digit mm numbers give L at t = 0 to 1e-6 mm,
  // i.e. T(0) within k x 1e-9 m = 5e-4 N of zero. Quasi-static (massless,
  // no gravity), the drive holds the spring by the virtual work of the half
  // above: F_drive = 2 T / U_V, to 1e-9 of T at every output time but the
  // first, where T ~ 0.
  GripperCase g = read_gripper_case(kGripCycle);
  set_masses(g.model, 0.0, 0.0, Eigen::Vector2d::Zero());
  ASSERT_EQ(g.model.springs.size(), 1u);
  ASSERT_TRUE(g.model.point_forces.empty());
  const mech::Spring& object = g.model.springs[0];
  const mech::MultibodySystem system(g.model);
  const mech::Results results = mech::run_kinematics(system, g.times);

  auto compression_force = [&](const mech::Frame& f) {
    const Eigen::Vector2d pi = point_position(frame_body(f, object.body_i), body_named(g.model, object.body_i).points.at(object.point_i));
    const Eigen::Vector2d pj = point_position(frame_body(f, object.body_j), body_named(g.model, object.body_j).points.at(object.point_j));
    return object.stiffness_N_per_m * (object.free_length_m - (pj - pi).norm());
  };
  const double touch = compression_force(results.frames.front());
  const double clamp = compression_force(results.frames.back());
  EXPECT_NEAR(touch, 0.0, object.stiffness_N_per_m * 1e-9);
  EXPECT_NEAR(clamp, 500.0, 500.0 * 1e-3);  // 1 mm of squeeze at 500 N/mm, the stroke to six digits
  double max_relative = 0;
  for (std::size_t k = 1; k < results.frames.size(); ++k) {
    const mech::Frame& f = results.frames[k];
    const double force = compression_force(f);
    const double predicted = 0.5 * f.drives.at(0).effort * mech::gripper_index_offset(phi_of(f), g.sigma(), g.gamma_r());
    max_relative = std::max(max_relative, std::abs(predicted - force) / clamp);
    EXPECT_NEAR(predicted, force, 1e-9 * clamp) << "t = " << f.t << " s";
  }
  std::printf("gripper_parts grip_cycle: object force %.3g N at the touch (phi %.4f deg), %.4f N at the end (phi %.4f "
              "deg); max |(F_drive/2) U_V - T| / T_end = %.3g\n",
              touch, phi_of(results.frames.front()) / kDeg, clamp, phi_of(results.frames.back()) / kDeg, max_relative);
}

TEST(GripperPartsCase, ThroughTheWholeChainTheRodsWebCarriesItsAxialForce) {
  // The bundled case as it runs (meshes, masses from them, kinematics,
  // loads, stress over the stroke, results file). The rod is a two-force
  // member (pins A and B; its weight and inertia are below 1 % of the pin
  // force), so at mid-length, 20 mm from either boss (1.7 web widths:
  // Saint-Venant), its web is in uniform axial stress
  //     sigma_xx = N / (w t),   N = the pin force at B along the rod,
  // w x t = 12 x 8 mm (parts/rod.geo). Reference: that beam formula, 2 % (the
  // mean over the section's nodes of the 4 mm TET10 mesh; measured 6e-4).
  // And every part's loads close (the stress stage's check, 1e-6).
  const auto [output_dir, run] = testing::run_linkage_quietly(kCase, "kinetofem_gripper_parts");
  ASSERT_EQ(run.parts.size(), 8u);
  for (const auto& part : run.parts) {
    EXPECT_GT(part.peak_von_mises_pa, 0.0) << part.body;
    EXPECT_LT(part.worst_equilibrium_residual, 1e-6) << part.body;
  }
  const double l = body_named(run.model, "rod_lower").points.at("B").x(), w = 0.012, t = 0.008;
  const auto file = post::ResultsFile::open(run.results_file);
  const fem::Mesh mesh = file.read_mesh("rod_lower");
  std::vector<fem::Index> section;
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    if (std::abs(mesh.nodes(n, 0) - 0.5 * l) < 1.5e-3) section.push_back(n);
  ASSERT_GE(section.size(), 10u);
  // Every output time's stress from the part's load patterns (the case's
  // unit-load superposition; the series hold von Mises only).
  ASSERT_TRUE(file.has_load_patterns("rod_lower"));
  const post::LoadPatternData patterns = file.read_load_patterns("rod_lower");
  ASSERT_EQ(patterns.time_s.size(), run.results.frames.size());
  double worst = 0;
  std::size_t checked = 0;
  for (std::size_t k = 0; k < run.results.frames.size(); ++k) {
    const mech::Frame& frame = run.results.frames[k];
    const auto joint = std::find_if(frame.joints.begin(), frame.joints.end(),
                                    [](const mech::JointFrame& j) { return j.name == "B_lower"; });
    const double axial_n = joint->on_i.force_body.x();  // on the rod at B, along its x: tension positive
    const post::SuperposedFields fields = post::superpose(patterns, Eigen::Index(k));
    double mean = 0;
    for (fem::Index n : section) mean += fields.stress_pa(n, 0);
    mean /= double(section.size());
    const double nominal = axial_n / (w * t);
    worst = std::max(worst, std::abs(mean - nominal) / std::abs(nominal));
    EXPECT_NEAR(mean, nominal, 0.02 * std::abs(nominal)) << "t = " << frame.t << " s";
    ++checked;
  }
  std::printf("gripper_parts through the chain: rod web sigma_xx vs N/(w t) over %zu output times, %zu section nodes: "
              "worst %.3g; parts' loads close to %.2g\n",
              checked, section.size(), worst,
              std::max_element(run.parts.begin(), run.parts.end(), [](const auto& a, const auto& b) {
                return a.worst_equilibrium_residual < b.worst_equilibrium_residual;
              })->worst_equilibrium_residual);
  // The elastic assembly and the vibration (the case has both on): the
  // linkage is determinate in the plane, so each part's peak equals the
  // per-part stage's (0.1 %: the out-of-plane loads, which the per-part
  // analysis splits equally between the pins, are the only difference;
  // measured 3e-4); the pads are tracked, the jaws open under the clamping
  // force (the upper pad moves +y, the lower -y: their meshes are mirror
  // images, not copies, so 2 %), and the first frequency is positive.
  ASSERT_TRUE(run.assembly.has_value());
  EXPECT_EQ(run.assembly->indeterminacy.in_plane, 0);
  for (const auto& peak : run.assembly->parts) {
    const auto own = std::find_if(run.parts.begin(), run.parts.end(), [&](const auto& p) { return p.body == peak.body; });
    ASSERT_NE(own, run.parts.end()) << peak.body;
    EXPECT_NEAR(peak.max_von_mises_pa, own->peak_von_mises_pa, 1e-3 * own->peak_von_mises_pa) << peak.body;
  }
  ASSERT_EQ(run.assembly->points.size(), 2u);
  const Eigen::Vector3d lower = run.assembly->points[0].displacement_at_max_m, upper = run.assembly->points[1].displacement_at_max_m;
  EXPECT_LT(lower.y(), 0.0);
  EXPECT_GT(upper.y(), 0.0);
  EXPECT_NEAR(upper.y(), -lower.y(), 0.02 * std::abs(lower.y()));
  ASSERT_TRUE(run.vibration.has_value());
  EXPECT_GT(run.vibration->lowest_first_hz, 0.0);
  std::printf("gripper_parts assembly: pads %.4f / %.4f mm across, first frequency %.1f .. %.1f Hz\n", lower.y() * 1e3,
              upper.y() * 1e3, run.vibration->lowest_first_hz, run.vibration->highest_first_hz);
  std::filesystem::remove_all(output_dir);
}

}  // namespace
}  // namespace kinetofem::app
