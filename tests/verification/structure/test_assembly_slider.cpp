// Prismatic joints in the elastic assembly: a slider on its guide
// (docs/elastic_assembly.md, "Sliders").
//
// 1. A rigid slider on a cantilevered guide bar (the frame: a column held at
//    its foot, the guide its face x1), held on the slide by a rigid
//    displacement drive, loaded across the guide by P. The slider's bearing
//    spreads P uniformly over a window of contact length c centred at a on
//    the guide face, and the slider moves as the window's coupling (the
//    area-weighted mean). Reference: Timoshenko beam theory, the mean over
//    the window of the deflection under the load q = P / c on the window:
//        w(y; xi) = P y^2 (3 xi - y) / (6 E I) + P y / (kappa G A)   (y <= xi)
//    (symmetric in y, xi), integrated twice over the window (Gauss-Legendre,
//    exact for these piecewise cubics to round-off). 1 % (measured -0.92 % at
//    a = 0.5 m, -0.58 % at 0.8 m: the FE column is stiffer): the clamped foot's
//    Poisson restraint and the face load's Saint-Venant zone (the column
//    test of test_assembly_frame_part.cpp measured -0.47 % at the tip).
//    The drive carries the slide's load: its force equals the multibody
//    model's drive effort (1e-8: the same statics solved two ways).
// 2. A slider past the guide's end: Error naming the time.
// 3. Rigid bodies only, the slide held by a drive of axial stiffness k: the
//    slider moves by F / k along the slide (1e-10), the force on it -F.
// 4. A slider-crank (crank and rod elastic bars, the slider rigid on the
//    rigid ground's guide, the crank turned by a rigid angle drive): in the
//    plane it is statically determinate, so every joint's force on body_j
//    (and the guide's moment) and the drive's moment equal the multibody
//    reactions (1e-8 of the largest: the same statics, two formulations).
// 5. An elastic slider on an elastic guide link (pinned to the ground and
//    turned by a rigid angle drive), pushed along it by a displacement drive
//    (rigid, then with an axial stiffness), gravity: the condensed assembly
//    equals the monolithic sparse reference (monolithic_reference.hpp: the
//    full stiffnesses with the same ties as Lagrange constraints) at two
//    poses, 1e-8 of the largest displacement. The contact length is the
//    default, the slider's face set's extent; both poses sit on stations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../../unit/structure/structure_fixtures.hpp"
#include "monolithic_reference.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

// Ground "frame" with a guide line along +y through `line`, a rigid slider
// on it at height a, held by the displacement drive "slide".
mech::MultibodyModel slider_on_guide(double a, const Eigen::Vector2d& line, const Eigen::Vector2d& force) {
  mech::MultibodyModel m;
  m.name = "slider on a guide";
  m.characteristic_length_m = 1.0;
  m.gravity = {0.0, 0.0};
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  frame.points["line"] = line;
  mech::Body slider;
  slider.name = "slider";
  slider.mass_kg = 2.0;
  slider.inertia_kgm2 = 0.01;
  slider.pose = {line.x(), line.y() + a, 0.0};
  m.bodies = {frame, slider};
  m.joints.push_back(mech::make_prismatic("guide", "frame", "line", "slider", "origin", {0.0, 1.0}));
  mech::MotionDrive d;
  d.name = "slide";
  d.coordinate = {mech::CoordinateType::Displacement, "frame", "line", "slider", "origin", {0.0, 1.0}};
  d.law = std::make_shared<mech::Polynomial345Law>(0.0, 1.0);  // held where it is
  m.motion_drives = {d};
  m.point_forces.push_back({"load", "slider", "origin", force});
  return m;
}

// Mean over [a - c/2, a + c/2] of the cantilever's deflection under q = P/c
// on the same window (Timoshenko), by 2 x 8-point Gauss-Legendre per half.
double window_mean_deflection(double P, double a, double c, double EI, double kGA) {
  static const double x8[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double w8[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  auto w = [&](double y, double xi) {  // unit load at xi, deflection at y
    const double lo = std::min(y, xi), hi = std::max(y, xi);
    return lo * lo * (3 * hi - lo) / (6 * EI) + lo / kGA;
  };
  // The kernel has a kink at y = xi: integrate y over [a - c/2, xi] and
  // [xi, a + c/2] separately so each piece is a polynomial.
  auto over = [&](double lo, double hi, auto f) {
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) sum += w8[k] * f(0.5 * (lo + hi) + 0.5 * (hi - lo) * x8[k]);
    return 0.5 * (hi - lo) * sum;
  };
  const double y0 = a - 0.5 * c, y1 = a + 0.5 * c;
  const double total = over(y0, y1, [&](double xi) {
    return over(y0, xi, [&](double y) { return w(y, xi); }) + over(xi, y1, [&](double y) { return w(y, xi); });
  });
  return P / c * total / c;
}

TEST(ElasticAssemblySlider, SliderOnCantileverGuideIsBeamTheory) {
  const double L = 1.0, h = 0.05, t = 0.05, c = 0.1, P = 2000.0, Q = 300.0;
  const std::vector<pipeline::Part> parts = {
      test::held_column_part({"frame", nullptr, {{"guide", "x1"}}, {}, {{"slide", "y0"}}}, L, h, t, {4, 40, 4}, 0.0)};
  const fem::IsotropicMaterial& mat = parts[0].model.material;
  const double E = mat.youngs_modulus_pa, nu = mat.poisson_ratio, G = E / (2 * (1 + nu));
  const double I = t * h * h * h / 12.0, A = h * t, kappa = 10 * (1 + nu) / (12 + 11 * nu);
  for (const double a : {0.5, 0.8}) {  // both on stations (0.05 + k 0.025)
    // P presses the slider onto the guide (-x); Q pulls along the slide.
    const mech::MultibodyModel m = slider_on_guide(a, {0.5 * h, 0.0}, {-P, Q});
    const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();
    AssemblyOptions options;
    options.points = {{"S", "slider", "origin", ""}};
    options.slides = {{"guide", c, 0.0}};
    ElasticAssembly assembly(parts, m, options);
    const PoseSolution pose = assembly.solve(frame);
    const PointResult& s = pose.point("S");
    const double expected = -window_mean_deflection(P, a, c, E * I, kappa * G * A);
    std::printf("  slider at a = %.3f m: u_x %.6e m, beam theory %.6e m, error %.3f %%; u_y %.2e m\n", a,
                s.displacement_m.x(), expected, 100 * (s.displacement_m.x() / expected - 1), s.displacement_m.y());
    EXPECT_NEAR(s.displacement_m.x(), expected, 0.01 * std::abs(expected));
    // The drive holds Q: its force on the slider is -Q, the multibody effort.
    const DriveResult& d = pose.drive("slide");
    EXPECT_TRUE(d.displacement);
    EXPECT_NEAR(d.force_on_j_n, frame.drives[0].effort, 1e-8 * Q);
    EXPECT_NEAR(d.force_on_j_n, -Q, 1e-8 * Q);
    // The guide side of the joint carries P and the moment of Q's line about
    // the slider point (none: Q acts at the slider's point).
    const JointLoad& g = pose.joint("guide");
    EXPECT_NEAR(g.force_on_j_n.x(), P, 1e-8 * P);
    EXPECT_NEAR(g.force_on_j_n.y(), 0.0, 1e-8 * P);
  }
}

TEST(ElasticAssemblySlider, SliderPastTheGuideIsAnErrorNamingTheTime) {
  const double L = 1.0, h = 0.05, c = 0.1;
  const std::vector<pipeline::Part> parts = {
      test::held_column_part({"frame", nullptr, {{"guide", "x1"}}, {}, {{"slide", "y0"}}}, L, h, h, {2, 20, 2}, 0.0)};
  const mech::MultibodyModel m = slider_on_guide(0.97, {0.5 * h, 0.0}, {-100.0, 0.0});
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();
  AssemblyOptions options;
  options.slides = {{"guide", c, 0.0}};
  ElasticAssembly assembly(parts, m, options);
  try {
    (void)assembly.solve(frame);
    FAIL() << "a slider past the guide's end solved";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("at t = 0 s: joint 'guide': the slider sits at 970.000 mm"), std::string::npos) << message;
    EXPECT_NE(message.find("beyond the guide"), std::string::npos) << message;
  }
  // A slide option for a guide that has no part is an Error too.
  const mech::MultibodyModel rigid = slider_on_guide(0.5, {0.0, 0.0}, {-100.0, 0.0});
  EXPECT_THROW(ElasticAssembly({}, rigid, options), Error);
}

TEST(ElasticAssemblySlider, RigidSliderOnAnElasticDriveMovesByForceOverStiffness) {
  const double F = 750.0, k = 2.5e6;
  // The slide's force F along the axis (+y) and a load across it, which the
  // rigid guide takes.
  const mech::MultibodyModel m = slider_on_guide(0.3, {0.0, 0.0}, {-400.0, F});
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();
  AssemblyOptions options;
  options.points = {{"S", "slider", "origin", ""}};
  DriveHold hold{"slide"};
  hold.axial_stiffness_n_per_m = k;
  options.drives = {hold};
  ElasticAssembly assembly({}, m, options);
  const PoseSolution pose = assembly.solve(frame);
  const PointResult& s = pose.point("S");
  std::printf("  slider: u_y %.12e m, F / k %.12e m; across %.1e m\n", s.displacement_m.y(), F / k, s.displacement_m.x());
  EXPECT_NEAR(s.displacement_m.y(), F / k, 1e-10 * F / k);
  EXPECT_NEAR(s.displacement_m.x(), 0.0, 1e-10 * F / k);
  const DriveResult& d = pose.drive("slide");
  EXPECT_NEAR(d.force_on_j_n, -F, 1e-10 * F);
  EXPECT_NEAR(d.stretch_m, F / k, 1e-10 * F / k);
  // The unit-load split puts it all on the drive.
  ASSERT_EQ(s.contributions.size(), 1u);
  EXPECT_EQ(s.contributions[0].name, "drive.slide");
  EXPECT_NEAR(s.contributions[0].displacement_m.y(), F / k, 1e-10 * F / k);
}

TEST(ElasticAssemblySlider, SliderCrankJointForcesAreTheMultibodyReactions) {
  const double r = 0.1, l = 0.3, crank0 = 30 * test::kDeg;
  mech::MultibodyModel m;
  m.name = "slider-crank";
  m.characteristic_length_m = l;
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body crank;
  crank.name = "crank";
  crank.mass_kg = 1.0;
  crank.inertia_kgm2 = 0.01;
  crank.points["pin"] = {r, 0.0};
  crank.pose = {0.0, 0.0, crank0};
  const Eigen::Vector2d B(r * std::cos(crank0), r * std::sin(crank0));
  const double rod0 = std::asin(-B.y() / l);
  mech::Body rod = crank;
  rod.name = "rod";
  rod.points = {{"end", {l, 0.0}}};
  rod.pose = {B.x(), B.y(), rod0};
  mech::Body slider;
  slider.name = "slider";
  slider.mass_kg = 1.5;
  slider.inertia_kgm2 = 1e-3;
  slider.pose = {B.x() + l * std::cos(rod0), 0.0, 0.0};
  m.bodies = {ground, crank, rod, slider};
  m.joints = {mech::make_revolute("O", "ground", "origin", "crank", "origin"),
              mech::make_revolute("B", "crank", "pin", "rod", "origin"),
              mech::make_revolute("C", "rod", "end", "slider", "origin"),
              mech::make_prismatic("guide", "ground", "origin", "slider", "origin", {1.0, 0.0})};
  mech::MotionDrive motor;
  motor.name = "motor";
  motor.coordinate = {mech::CoordinateType::Angle, "ground", "origin", "crank", "origin", {1, 0}};
  motor.law = std::make_shared<mech::Polynomial345Law>(90 * test::kDeg, 0.5);
  m.motion_drives = {motor};
  m.point_forces.push_back({"process_load", "slider", "origin", {-50.0, 0.0}});
  std::vector<pipeline::Part> parts = {
      test::bar_part("crank", {"crank", nullptr, {{"O", "x0"}, {"B", "x1"}}, {}, {{"motor", "x0"}}},
                     {r, 0.03, 0.02, {8, 2, 1}}),
      test::bar_part("rod", {"rod", nullptr, {{"B", "x0"}, {"C", "x1"}}, {}, {}}, {l, 0.03, 0.02, {16, 2, 1}})};
  pipeline::apply_mass_properties(m, parts, Log::quiet());
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(m), {0.1, 0.25, 0.4});
  AssemblyOptions options;
  options.points = {{"C", "slider", "origin", ""}};
  ElasticAssembly assembly(parts, m, options);
  for (const mech::Frame& frame : motion.frames) {
    const PoseSolution pose = assembly.solve(frame);
    double scale = 0.0;
    for (const mech::JointFrame& jf : frame.joints) scale = std::max(scale, jf.on_j.force_world.norm());
    double worst = 0.0;
    for (const mech::JointFrame& jf : frame.joints) {
      const JointLoad& jl = pose.joint(jf.name);
      worst = std::max(worst, (jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm() / scale);
      EXPECT_LT((jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm(), 1e-8 * scale) << jf.name << " t = " << frame.t;
    }
    const mech::JointFrame& guide = frame.joints[3];
    EXPECT_NEAR(pose.joint("guide").moment_on_j_nm.z(), guide.on_j.moment_Nm, 1e-8 * scale * l);
    EXPECT_NEAR(pose.drive("motor").moment_on_j_nm, frame.drives[0].effort, 1e-8 * scale * l);
    const PointResult& c = pose.point("C");
    std::printf("  t = %.2f s: joint forces vs multibody %.1e (of %.1f N); C moves %.3e m along the guide, %.1e "
                "across\n",
                frame.t, worst, scale, c.displacement_m.x(), c.displacement_m.y());
    // The rigid guide holds the slider on its line.
    EXPECT_LT(std::abs(c.displacement_m.y()), 1e-12);
  }
}

TEST(ElasticAssemblySlider, ElasticSliderOnElasticGuideEqualsTheMonolithicReference) {
  const double L = 0.6, H = 0.04, shoe = 0.08;
  mech::MultibodyModel m;
  m.name = "slider on a turning guide";
  m.characteristic_length_m = L;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body guide;
  guide.name = "guide";
  guide.mass_kg = 1.0;
  guide.inertia_kgm2 = 0.01;
  guide.points["top0"] = {0.0, 0.5 * H};
  guide.pose = {0.0, 0.0, 20 * test::kDeg};
  mech::Body slider = guide;
  slider.name = "slider";
  slider.points.clear();
  const double s0 = 0.2;  // a station: 0.04 + 8 x 0.02
  slider.pose = {s0 * std::cos(guide.pose.z()) - 0.5 * H * std::sin(guide.pose.z()),
                 s0 * std::sin(guide.pose.z()) + 0.5 * H * std::cos(guide.pose.z()), guide.pose.z()};
  m.bodies = {frame, guide, slider};
  m.joints = {mech::make_revolute("J1", "frame", "origin", "guide", "origin"),
              mech::make_prismatic("rail", "guide", "top0", "slider", "origin", {1.0, 0.0})};
  mech::MotionDrive turn;
  turn.name = "turn";
  turn.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "guide", "origin", {1, 0}};
  turn.law = std::make_shared<mech::Polynomial345Law>(30 * test::kDeg, 1.0);
  mech::MotionDrive push;
  push.name = "push";
  push.coordinate = {mech::CoordinateType::Displacement, "guide", "top0", "slider", "origin", {1, 0}};
  push.law = std::make_shared<mech::Polynomial345Law>(0.1, 1.0);  // to 0.3 m: station 13
  m.motion_drives = {turn, push};
  fem::Mesh shoe_mesh = test::bar_mesh({shoe, 0.03, 0.03, {4, 2, 2}});
  shoe_mesh.nodes.col(0).array() -= 0.5 * shoe;
  shoe_mesh.nodes.col(1).array() += 0.015;  // its face y0 on the guide's top, its origin at the shoe's middle
  std::vector<pipeline::Part> parts = {
      test::bar_part("guide", {"guide", nullptr, {{"J1", "x0"}, {"rail", "y1"}}, {}, {{"turn", "x0"}, {"push", "x0"}}},
                     {L, H, 0.03, {30, 2, 2}}),
      test::mesh_part("slider", {"slider", nullptr, {{"rail", "y0"}}, {}, {{"push", "x0"}}}, shoe_mesh, test::steel())};
  pipeline::apply_mass_properties(m, parts, Log::quiet());
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(m), {0.0, 1.0});
  for (const double k : {kRigid, 4e6}) {
    AssemblyOptions options;
    DriveHold hold{"push"};
    hold.axial_stiffness_n_per_m = k;
    options.drives = {hold};
    ElasticAssembly assembly(parts, m, options);
    std::map<std::string, double> springs;
    if (!std::isinf(k)) springs["push"] = k;
    for (const mech::Frame& f : motion.frames) {
      const PoseSolution pose = assembly.solve(f);
      const test::MonolithicResult ref = test::solve_monolithic(parts, m, f, springs, {{"rail", shoe}});
      EXPECT_LT(ref.relative_residual, 1e-8);
      double scale = 0.0, worst = 0.0;
      for (size_t p = 0; p < parts.size(); ++p) scale = std::max(scale, ref.displacement[p].cwiseAbs().maxCoeff());
      for (size_t p = 0; p < parts.size(); ++p)
        worst = std::max(worst, (pose.part(parts[p].body()).displacement_m - ref.displacement[p]).cwiseAbs().maxCoeff());
      std::printf("  drive %s, t = %.0f s: max |u| %.4e m, condensed vs monolithic %.2e relative\n",
                  std::isinf(k) ? "rigid" : "4e6 N/m", f.t, scale, worst / scale);
      ASSERT_GT(scale, 0.0);
      EXPECT_LT(worst / scale, 1e-8) << "t = " << f.t;
    }
  }
}

}  // namespace
}  // namespace kinetofem::structure
