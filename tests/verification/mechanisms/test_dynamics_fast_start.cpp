// A fast mechanism started from rest at the default tolerances (rel 1e-10,
// abs 1e-12). A seven-body toggle squeezer: a crank of 7 mm turned by a
// constant 0.033 N m torque drives, through a coupler, a 70 g yoke up a
// vertical guide near the top dead centre (the toggle); two links pull two
// jaw levers (bell cranks on ground pivots), whose tips close on a 4.5 kN/m
// spring (the squeezed part). Bodies 2-70 g, links 7-40 mm. Seven moving
// bodies plus the ground; ten lower pairs: 21 - 20 = 1 degree of freedom.
// Gravity acts along -y. From rest the crank accelerates at 1.4e4 rad/s^2:
// IDAS's own first step, h = 0.5 / ||y'||_WRMS, is then 2.3e-16 s (velocities
// at 0 weigh with 1/abs_tol = 1e12) and its corrector cannot converge there
// ("IDASolve failed with flag -4: t = 0 s" before DynamicsOptions had an
// automatic first step; measured: it needs a first step >= ~1e-11 s). The
// automatic first step (dynamics.hpp) must start it.
// References: the same run with a manual first step of 1e-10 s and a looser
// absolute tolerance (the reported work-around), the independent CVODES
// minimal-coordinate path, and the run's energy balance and constraint drift.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kMm = 1e-3, kG = 1e-3, kDeg = std::numbers::pi / 180.0;

Eigen::Vector2d polar(double length, double angle) {
  return length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

Body bar(const std::string& name, double mass, double length, const Eigen::Vector2d& origin, double angle) {
  Body b;
  b.name = name;
  b.mass_kg = mass;
  b.inertia_kgm2 = mass * length * length / 12.0;
  b.com_body = {0.5 * length, 0.0};
  b.points["end"] = {length, 0.0};
  b.pose = {origin.x(), origin.y(), angle};
  return b;
}

// Toggle squeezer; all poses consistent at phi0 (crank angle from +x).
struct Squeezer {
  double r = 7 * kMm, l = 25 * kMm;                 // crank, coupler
  double phi0 = 70 * kDeg;
  double pin_x = 4 * kMm, pin_y = 8 * kMm;          // yoke pins, yoke frame
  double pivot_x = 12 * kMm, pivot_dy = -8 * kMm;   // jaw pivots, relative to the yoke's initial slide point
  double arm = 10 * kMm, jaw = 40 * kMm;            // jaw lever: pin and tip along its axis
  double jaw_angle = 100 * kDeg;                    // right jaw; the left one mirrored
  double m_crank = 4 * kG, m_coupler = 3 * kG, m_yoke = 70 * kG, m_link = 2 * kG, m_jaw = 10 * kG;
  double torque = 0.033, stiffness = 4500.0;

  MultibodyModel model() const {
    MultibodyModel m;
    m.name = "toggle squeezer";
    m.characteristic_length_m = l;
    Body ground;
    ground.name = "ground";
    ground.fixed = true;
    const Eigen::Vector2d a = polar(r, phi0);
    const Eigen::Vector2d s(0.0, a.y() + std::sqrt(l * l - a.x() * a.x()));
    const Eigen::Vector2d pivot_r(pivot_x, s.y() + pivot_dy), pivot_l(-pivot_x, s.y() + pivot_dy);
    ground.points["jaw_r"] = pivot_r;
    ground.points["jaw_l"] = pivot_l;
    Body crank = bar("crank", m_crank, r, {0.0, 0.0}, phi0);
    Body coupler = bar("coupler", m_coupler, l, a, std::atan2(s.y() - a.y(), s.x() - a.x()));
    Body yoke;
    yoke.name = "yoke";
    yoke.mass_kg = m_yoke;
    yoke.inertia_kgm2 = m_yoke * (2 * pin_x * 2 * pin_x + pin_y * pin_y) / 12.0;
    yoke.com_body = {0.0, 0.5 * pin_y};
    yoke.points["pin_r"] = {pin_x, pin_y};
    yoke.points["pin_l"] = {-pin_x, pin_y};
    yoke.pose = {s.x(), s.y(), 0.0};
    const double jaw_l_angle = std::numbers::pi - jaw_angle;
    const Eigen::Vector2d c_r = pivot_r + polar(arm, jaw_angle), c_l = pivot_l + polar(arm, jaw_l_angle);
    const Eigen::Vector2d p_r = s + Eigen::Vector2d(pin_x, pin_y), p_l = s + Eigen::Vector2d(-pin_x, pin_y);
    const double link = (c_r - p_r).norm();
    Body link_r = bar("link_r", m_link, link, p_r, std::atan2(c_r.y() - p_r.y(), c_r.x() - p_r.x()));
    Body link_l = bar("link_l", m_link, link, p_l, std::atan2(c_l.y() - p_l.y(), c_l.x() - p_l.x()));
    Body jaw_r = bar("jaw_r", m_jaw, jaw, pivot_r, jaw_angle);
    Body jaw_l = bar("jaw_l", m_jaw, jaw, pivot_l, jaw_l_angle);
    jaw_r.points["pin"] = jaw_l.points["pin"] = {arm, 0.0};
    m.bodies = {ground, crank, coupler, yoke, link_r, link_l, jaw_r, jaw_l};
    m.joints.push_back(make_revolute("O", "ground", "origin", "crank", "origin"));
    m.joints.push_back(make_revolute("A", "crank", "end", "coupler", "origin"));
    m.joints.push_back(make_revolute("S", "coupler", "end", "yoke", "origin"));
    m.joints.push_back(make_prismatic("guide", "ground", "origin", "yoke", "origin", {0.0, 1.0}));
    m.joints.push_back(make_revolute("P_r", "yoke", "pin_r", "link_r", "origin"));
    m.joints.push_back(make_revolute("P_l", "yoke", "pin_l", "link_l", "origin"));
    m.joints.push_back(make_revolute("C_r", "link_r", "end", "jaw_r", "pin"));
    m.joints.push_back(make_revolute("C_l", "link_l", "end", "jaw_l", "pin"));
    m.joints.push_back(make_revolute("G_r", "ground", "jaw_r", "jaw_r", "origin"));
    m.joints.push_back(make_revolute("G_l", "ground", "jaw_l", "jaw_l", "origin"));
    ForceDrive motor;
    motor.name = "motor";
    motor.coordinate = crank_angle();
    motor.law_type = ForceLaw::Constant;
    motor.value = torque;
    m.force_drives.push_back(motor);
    // The squeezed part between the jaw tips, unloaded at the start.
    const double gap = ((pivot_r + polar(jaw, jaw_angle)) - (pivot_l + polar(jaw, jaw_l_angle))).norm();
    m.springs.push_back({"part", "jaw_l", "end", "jaw_r", "end", stiffness, 0.0, gap});
    return m;
  }
  static RelativeCoordinate crank_angle() {
    return {CoordinateType::Angle, "ground", "origin", "crank", "origin", {1, 0}};
  }
};

constexpr double kEnd = 5e-3;  // s
constexpr long kFrames = 51;

// Largest difference of the coordinates (m, rad) of two runs over their frames.
double max_difference(const Results& a, const Results& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < a.frames.size(); ++k)
    d = std::max(d, (a.frames[k].q - b.frames[k].q).cwiseAbs().maxCoeff());
  return d;
}

// Gap between the jaw tips (m) in a frame.
double tip_gap(const MultibodySystem& sys, const Frame& f) {
  const int jaw_r = sys.body_index("jaw_r"), jaw_l = sys.body_index("jaw_l");
  return (sys.point_world(jaw_r, sys.named_point(jaw_r, "end"), f.q) -
          sys.point_world(jaw_l, sys.named_point(jaw_l, "end"), f.q)).norm();
}

TEST(DynamicsFastStart, DefaultTolerancesRunToTheEndAndMatchTheReference) {
  const Squeezer sq;
  const MultibodySystem sys(sq.model());
  const std::vector<double> times = equally_spaced_times(kEnd, kFrames);
  const Eigen::VectorXd q0 = assemble(sys, sys.initial_coordinates(), 0.0);
  const Accelerations acc0 = solve_accelerations(sys, q0, Eigen::VectorXd::Zero(q0.size()), 0.0);
  const int crank = sys.offset(sys.body_index("crank")) + 2;
  const DynamicsOptions defaults;
  // The automatic rule restricted to the crank angle: the automatic step takes
  // the worst of all error-tested components, so it is at most this.
  const double crank_bound =
      0.5 * std::sqrt(2 * (defaults.relative_tolerance * std::abs(q0(crank)) + defaults.absolute_tolerance) /
                      std::abs(acc0.q_ddot(crank)));

  const Results run = simulate_ggl(sys, times);  // default options: rel 1e-10, abs 1e-12, automatic first step
  DynamicsOptions manual;  // the reported work-around: manual first step, looser absolute tolerance
  manual.initial_step_s = 1e-10;
  manual.absolute_tolerance = 2e-10;
  const Results reference = simulate_ggl(sys, times, manual);
  const Results minimal = simulate_minimal(sys, Squeezer::crank_angle(), times);  // CVODES, default options

  const double diff_reference = max_difference(run, reference), diff_minimal = max_difference(run, minimal);
  double squeeze = 0.0, crank_lo = q0(crank), crank_hi = q0(crank);
  for (const Frame& f : run.frames) {
    squeeze = std::max(squeeze, tip_gap(sys, run.frames.front()) - tip_gap(sys, f));
    crank_lo = std::min(crank_lo, f.q(crank));
    crank_hi = std::max(crank_hi, f.q(crank));
  }
  std::printf("fast start: crank q'' %.4e rad/s^2 at t = 0; first steps: automatic %.3e s (crank-angle bound "
              "%.3e s), manual %.3e s, CVODES %.3e s\n"
              "crank swings over %.3e rad, tips close by up to %.3e m; max |q - q_ref| %.3e, max |q - q_minimal| "
              "%.3e\n%s%s%s",
              acc0.q_ddot(crank), run.summary.first_step_s, crank_bound, reference.summary.first_step_s,
              minimal.summary.first_step_s, crank_hi - crank_lo, squeeze, diff_reference, diff_minimal,
              run.format_checks().c_str(), reference.format_checks().c_str(), minimal.format_checks().c_str());

  // The reported case: crank angular acceleration about 1.4e4 rad/s^2 at t = 0 (this model: 1.395e4).
  EXPECT_NEAR(acc0.q_ddot(crank), 1.4e4, 0.1e4);
  // The run reaches the end time, exactly (IDA_NORMAL returns tout; the grid ends at kEnd exactly).
  ASSERT_EQ(run.frames.size(), times.size());
  EXPECT_EQ(run.frames.back().t, kEnd);
  // It is a real motion: the jaws squeeze the part (measured 0.48 mm) and the crank swings (0.017 rad).
  EXPECT_GT(squeeze, 1e-4);
  EXPECT_GT(crank_hi - crank_lo, 1e-3);
  // Automatic first step (measured 6.6e-8 s): not above the crank-angle form of the rule (equal here: the crank
  // angle is the worst component) nor the cap 1e-3 of the first output interval (1e-7 s), and far above the
  // 2.3e-16 s IDAS picks by itself and the 1e-12 s below which its corrector fails on this model (measured:
  // 1e-12 fails, 1e-11 runs).
  EXPECT_LE(run.summary.first_step_s, crank_bound * (1 + 1e-12));
  EXPECT_LE(run.summary.first_step_s, 1e-3 * (times[1] - times[0]));
  EXPECT_GT(run.summary.first_step_s, 1e-9);
  // Reference 1: the work-around run (first step 1e-10 s, abs tol 2e-10). Its own error is of the order of
  // its abs tol (measured difference 1.2e-9 m/rad); tolerance 1e-8 m (rad), 4e-7 of the 25 mm coupler.
  EXPECT_LT(diff_reference, 1e-8);
  // Reference 2: the CVODES minimal-coordinate path at the same default tolerances, an independent
  // formulation (measured difference 7.7e-11); tolerance 1e-9 m (rad).
  EXPECT_LT(diff_minimal, 1e-9);
  // Energy balance: drive work = change of kinetic + spring + gravity energy; at rel tol 1e-10 the
  // balance holds to 1e-7 of the energy scale (measured 7.4e-9; the reference run 8.0e-8).
  EXPECT_LT(run.summary.energy_balance_error, 1e-7);
  EXPECT_LT(minimal.summary.energy_balance_error, 1e-7);
  // Constraint drift: GGL enforces position and velocity constraints at every step, so the drift stays
  // at the Newton tolerance, below the 1e-12 m absolute tolerance (measured 3.1e-15 m).
  EXPECT_LT(run.summary.max_drift_position_m, 1e-12);
  EXPECT_LT(run.summary.max_equilibrium_residual, 1e-9);  // frames' reactions: round-off (measured 2e-16)
}

TEST(DynamicsFastStart, ExplicitFirstStepIsUsedByBothIntegrators) {
  const Squeezer sq;
  const MultibodySystem sys(sq.model());
  const std::vector<double> times = equally_spaced_times(kEnd, 6);
  DynamicsOptions options;
  options.initial_step_s = 2e-9;
  // The integrators report the first step they took: the value given (no error-test failure on it).
  EXPECT_EQ(simulate_ggl(sys, times, options).summary.first_step_s, 2e-9);
  EXPECT_EQ(simulate_minimal(sys, Squeezer::crank_angle(), times, options).summary.first_step_s, 2e-9);
  options.initial_step_s = -1e-9;
  EXPECT_THROW(simulate_ggl(sys, times, options), Error);
  EXPECT_THROW(simulate_minimal(sys, Squeezer::crank_angle(), times, options), Error);
}

TEST(DynamicsFastStart, FirstStepOfIdasOwnSizeFailsAtTheStart) {
  // The reported failure, kept: a first step of the size IDAS picks by itself
  // here (0.5 / ||y'||_WRMS = 2.3e-16 s) stops the run at t = 0 with flag -4
  // (IDA_CONV_FAIL: the corrector does not converge, and smaller steps only worsen it).
  const Squeezer sq;
  const MultibodySystem sys(sq.model());
  DynamicsOptions options;
  options.initial_step_s = 2.3e-16;
  try {
    simulate_ggl(sys, equally_spaced_times(kEnd, 6), options);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("first step 2.3e-16 s: %s\n", what.c_str());
    EXPECT_NE(what.find("IDASolve: the corrector did not converge, repeatedly or at the smallest step (IDA_CONV_FAIL) "
                        "at t = 0 s"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("simulation.initial_step_s"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace kinetofem::mech
