// Stage "write the spatial mechanism" (pipeline/spatial_histories.hpp): a
// spatial multibody run as histories and as moving skeleton bodies, read back
// from the results file and compared with the run's frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/pipeline/spatial_histories.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

namespace fs = std::filesystem;
namespace spatial = mech::spatial;
namespace layout = post::layout;
using Eigen::Vector3d;
using test::error_of;

constexpr double kDeg = std::numbers::pi / 180.0;

// A crank on a revolute "hinge" about the tilted axis (1, 1, 1)/sqrt(3) at the
// ground's point "pivot", turned 90 deg in 0.5 s by "spin" (3-4-5), with a
// constant 5 N m motor "motor" on the same joint; gravity -z. The crank's
// points "mid" (0.2, 0, 0), "tip" (0.4, 0, 0) and "fin tip" (0.4, 0.1, 0); a
// body "bob" welded to the crank's tip (fixed joint "weld"), with no named
// point (its skeleton is the marker).
spatial::Model crank_model() {
  spatial::Model m;
  m.name = "tilted crank";
  m.characteristic_length_m = 0.4;
  const Vector3d pivot(0.1, 0.2, 0.3), h = Vector3d(1, 1, 1).normalized();
  spatial::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["pivot"] = pivot;
  spatial::Body crank;
  crank.name = "crank";
  crank.mass_kg = 2.0;
  crank.inertia_kgm2 = Eigen::Vector3d(0.002, 0.03, 0.03).asDiagonal();
  crank.com_body = {0.2, 0.0, 0.0};
  crank.points = {{"mid", {0.2, 0.0, 0.0}}, {"tip", {0.4, 0.0, 0.0}}, {"fin tip", {0.4, 0.1, 0.0}}};
  crank.position = pivot;
  spatial::Body bob;
  bob.name = "bob";
  bob.mass_kg = 0.5;
  bob.inertia_kgm2 = 1e-4 * Eigen::Matrix3d::Identity();
  bob.position = pivot + Vector3d(0.4, 0.0, 0.0);
  m.bodies = {ground, crank, bob};
  m.joints = {spatial::make_joint("hinge", spatial::JointType::Revolute, "ground", "pivot", "crank", "origin", h, h),
              spatial::make_joint("weld", spatial::JointType::Fixed, "crank", "tip", "bob", "origin")};
  spatial::MotionDrive spin;
  spin.name = "spin";
  spin.joint = "hinge";
  spin.coordinate = spatial::DriveCoordinate::Rotation;
  spin.law = std::make_shared<mech::Polynomial345Law>(90 * kDeg, 0.5);
  m.motion_drives = {spin};
  spatial::ForceDrive motor;
  motor.name = "motor";
  motor.joint = "hinge";
  motor.value = 5.0;
  m.force_drives = {motor};
  return m;
}

struct Written {
  spatial::Model model;
  spatial::Results results;
  fs::path file;
};

// The crank over 0 .. 0.5 s at 11 output times, written by the stage.
const Written& crank_written() {
  static const Written w = [] {
    Written out;
    out.model = crank_model();
    std::vector<double> times;
    for (int k = 0; k <= 10; ++k) times.push_back(0.05 * k);
    out.results = spatial::run_kinematics(spatial::System(out.model), times);
    out.file = test::fresh_dir(std::string("spatial_histories_") +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name()) /
               "crank.h5";
    post::ResultsWriter writer(out.file, {});
    write_spatial_mechanism_histories(writer, out.model, out.results);
    writer.commit();
    return out;
  }();
  return w;
}

Vector3d row3(const post::FieldMatrix& m, Eigen::Index r) { return m.row(r).transpose(); }

TEST(WriteSpatialMechanismHistories, EveryQuantityIsWrittenWithItsUnitAndComponents) {
  // Reference: the names, units and component counts of spatial_histories.hpp.
  const auto file = post::ResultsFile::open(crank_written().file);
  struct Expected {
    std::string name, unit;
    int columns;
  };
  const std::vector<Expected> expected = {
      {"body.crank.origin", "m", 3},              {"body.crank.euler_parameters", "1", 4},
      {"body.crank.rotation", "1", 9},            {"body.crank.velocity", "m/s", 3},
      {"body.crank.acceleration", "m/s^2", 3},    {"body.crank.angular_velocity", "rad/s", 3},
      {"body.crank.angular_acceleration", "rad/s^2", 3}, {"body.bob.com_position", "m", 3},
      {"body.bob.com_velocity", "m/s", 3},        {"body.ground.com_acceleration", "m/s^2", 3},
      {"joint.hinge.on_ground.force_world", "N", 3}, {"joint.hinge.on_crank.moment_world", "N*m", 3},
      {"joint.weld.on_bob.point", "m", 3},        {"drive.spin.s", "rad", 1},
      {"drive.spin.s_dot", "rad/s", 1},           {"drive.spin.s_ddot", "rad/s^2", 1},
      {"drive.spin.effort", "N*m", 1},            {"drive.spin.power", "W", 1},
      {"drive.spin.on_crank.force_world", "N", 3}, {"drive.spin.on_ground.moment_world", "N*m", 3},
      {"drive.motor.effort", "N*m", 1},           {"energy.kinetic", "J", 1},
      {"energy.potential", "J", 1},               {"check.drift_position", "m", 1},
      {"check.drift_velocity", "m/s", 1},         {"check.equilibrium_residual", "1", 1},
      {"check.redundant_rows", "1", 1}};
  const auto names = file.histories();
  for (const auto& e : expected) {
    ASSERT_NE(std::find(names.begin(), names.end(), e.name), names.end()) << e.name;
    const post::FieldData h = file.read_history(e.name);
    EXPECT_EQ(h.units, e.unit) << e.name;
    EXPECT_EQ(h.values.rows(), 11) << e.name;
    EXPECT_EQ(h.values.cols(), e.columns) << e.name;
  }
  EXPECT_EQ(file.read_history("body.crank.euler_parameters").component_names, post::kEulerParameterComponents);
  EXPECT_EQ(file.read_history("body.crank.rotation").component_names, post::kRotationComponents);
  EXPECT_EQ(file.bodies(), (std::vector<std::string>{"skeleton.bob", "skeleton.crank", "skeleton.ground"}));
}

TEST(WriteSpatialMechanismHistories, PoseAtEachTimeIsTheFrames) {
  // The histories are copies of the frames' doubles (exact); the skeleton's
  // position at each output time is origin + R x_body of its nodes, so the
  // node of "tip" is where the spatial core puts the point (System::point_world,
  // 1e-15 of the crank length: one rotation and one sum in another order).
  const Written& w = crank_written();
  const auto file = post::ResultsFile::open(w.file);
  const spatial::System system(w.model);
  const std::vector<double> t = file.mechanism_time();
  ASSERT_EQ(t.size(), w.results.frames.size());
  EXPECT_EQ(file.series_times("skeleton.crank"), t);
  EXPECT_EQ(file.geometry_field("skeleton.crank"), layout::kPosition);
  const auto origin = file.read_history("body.crank.origin").values;
  const auto p = file.read_history("body.crank.euler_parameters").values;
  const auto rotation = file.read_history("body.crank.rotation").values;
  const fem::Mesh mesh = file.read_mesh("skeleton.crank");
  const fem::Index tip = mesh.node_set("tip").front();
  for (std::size_t k = 0; k < t.size(); ++k) {
    const spatial::Frame& f = w.results.frames[k];
    const spatial::BodyState& crank = f.bodies[1];
    const auto r = Eigen::Index(k);
    EXPECT_EQ(t[k], f.t);
    EXPECT_EQ(row3(origin, r), crank.origin);
    EXPECT_EQ(Eigen::Vector4d(p.row(r).transpose()), crank.euler_parameters);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_EQ(rotation(r, 3 * i + j), crank.rotation(i, j)) << i << j;
    const post::FieldMatrix position = file.read_step("skeleton.crank", layout::kPosition, fem::Index(k)).values;
    EXPECT_LT((row3(position, tip) - system.point_world(1, "tip", f.q)).norm(), 1e-15 * 0.4) << "t = " << f.t;
    EXPECT_LT((row3(position, 0) - crank.origin).norm(), 1e-15 * 0.4);
  }
  // The crank has turned 90 deg about h at the end: the tip is at pivot + 0.4 (h x ex rotated).
  const Vector3d h = Vector3d(1, 1, 1).normalized(), pivot(0.1, 0.2, 0.3);
  const Vector3d ex = Vector3d::UnitX(), radial = ex - ex.dot(h) * h;
  const Vector3d expected_tip = pivot + 0.4 * (ex.dot(h) * h + h.cross(radial));
  const post::FieldMatrix last = file.read_step("skeleton.crank", layout::kPosition, 10).values;
  EXPECT_LT((row3(last, tip) - expected_tip).norm(), 1e-12);
}

TEST(WriteSpatialMechanismHistories, SkeletonVelocityIsTheRigidBodyVelocity) {
  // Reference: a rotation about the fixed axis h through the pivot, v = s' h x (x - pivot),
  // with s' the drive's rate; 1e-12 m/s.
  const Written& w = crank_written();
  const auto file = post::ResultsFile::open(w.file);
  const Vector3d h = Vector3d(1, 1, 1).normalized(), pivot(0.1, 0.2, 0.3);
  const auto s_dot = file.read_history("drive.spin.s_dot").values;
  const auto body_velocity = file.read_history("body.crank.velocity").values;
  const std::string speed = layout::magnitude_name(layout::kVelocity);
  for (fem::Index k : {2, 5, 7}) {
    const post::FieldMatrix x = file.read_step("skeleton.crank", layout::kPosition, k).values;
    const post::FieldMatrix v = file.read_step("skeleton.crank", layout::kVelocity, k).values;
    const post::FieldMatrix vm = file.read_step("skeleton.crank", speed, k).values;
    ASSERT_GT(s_dot(k, 0), 0.1);
    for (fem::Index n = 0; n < x.rows(); ++n) {
      const Vector3d expected = s_dot(k, 0) * h.cross(row3(x, n) - pivot);
      EXPECT_LT((row3(v, n) - expected).norm(), 1e-12) << "node " << n << ", step " << k;
      EXPECT_NEAR(vm(n, 0), expected.norm(), 1e-12);
    }
    EXPECT_LT(row3(body_velocity, k).norm(), 1e-12);  // the crank's origin is on the axis
  }
}

TEST(WriteSpatialMechanismHistories, LoadsAndDrivesAreTheFrames) {
  const Written& w = crank_written();
  const auto file = post::ResultsFile::open(w.file);
  const auto on_crank = file.read_history("joint.hinge.on_crank.force_world").values;
  const auto on_ground = file.read_history("joint.hinge.on_ground.moment_world").values;
  const auto weld_point = file.read_history("joint.weld.on_bob.point").values;
  const auto effort = file.read_history("drive.spin.effort").values;
  const auto power = file.read_history("drive.spin.power").values;
  const auto motor = file.read_history("drive.motor.effort").values;
  const auto kinetic = file.read_history("energy.kinetic").values;
  for (std::size_t k = 0; k < w.results.frames.size(); ++k) {
    const spatial::Frame& f = w.results.frames[k];
    const auto r = Eigen::Index(k);
    EXPECT_EQ(row3(on_crank, r), f.joints[0].on_j.force_world);
    EXPECT_EQ(row3(on_ground, r), f.joints[0].on_i.moment_world);
    EXPECT_EQ(row3(weld_point, r), f.joints[1].on_j.point_world);
    EXPECT_EQ(effort(r, 0), f.drives[0].effort);
    EXPECT_EQ(power(r, 0), f.drives[0].effort * f.drives[0].s_dot);
    EXPECT_EQ(motor(r, 0), 5.0);  // the constant motor
    EXPECT_EQ(kinetic(r, 0), f.kinetic_energy_J);
  }
}

TEST(SpatialSkeletonMesh, BonesFollowTheShortestTreeThroughTheNamedPoints) {
  // Crank: origin, then "fin tip", "mid", "tip" in name order; the shortest tree is
  // origin - mid - tip - fin tip (0.2 + 0.2 + 0.1 m), 3 bones of 4 TET4 and 4 nodes each.
  const spatial::Model model = crank_model();
  const fem::Mesh mesh = spatial_skeleton_mesh(model, 1);
  ASSERT_EQ(mesh.blocks.size(), 1u);
  EXPECT_EQ(mesh.blocks[0].type, fem::ElementType::Tet4);
  EXPECT_EQ(mesh.node_count(), 4 + 3 * 4);
  EXPECT_EQ(mesh.element_count(), 3 * 4);
  EXPECT_EQ(mesh.node_set("origin"), std::vector<fem::Index>{0});
  EXPECT_EQ(mesh.node_set("fin_tip"), std::vector<fem::Index>{1});  // "fin tip", its space made '_'
  EXPECT_EQ(mesh.node_set("mid"), std::vector<fem::Index>{2});
  EXPECT_EQ(mesh.node_set("tip"), std::vector<fem::Index>{3});
  EXPECT_EQ(Vector3d(mesh.nodes.row(3).transpose()), Vector3d(0.4, 0.0, 0.0));
  // Each bone's tips are two of the named nodes: origin-mid, mid-tip, tip-fin tip.
  std::vector<std::pair<fem::Index, fem::Index>> tips;
  double volume = 0.0;
  for (fem::Index e = 0; e < mesh.element_count(); ++e) {
    const auto n = mesh.blocks[0].element(e);
    auto x = [&](int i) -> Vector3d { return mesh.nodes.row(n[size_t(i)]).transpose(); };
    const double v = (x(1) - x(0)).cross(x(2) - x(0)).dot(x(3) - x(0)) / 6.0;
    EXPECT_GT(v, 0.0) << "element " << e;  // positive volume: VTK's orientation
    volume += v;
    if (e % 4 == 0) tips.emplace_back(std::min(n[0], n[1]), std::max(n[0], n[1]));
  }
  EXPECT_EQ(tips, (std::vector<std::pair<fem::Index, fem::Index>>{{0, 2}, {2, 3}, {1, 3}}));
  // Octahedra: volume (1/3) length (2 w^2), w = min(0.1 length, 0.02 * 0.4 m).
  auto octahedron = [](double length) {
    const double w = std::min(kSkeletonWidthPerLength * length, kSkeletonWidthPerModel * 0.4);
    return length * 2.0 * w * w / 3.0;
  };
  EXPECT_NEAR(volume, 2 * octahedron(0.2) + octahedron(0.1), 1e-15);
}

TEST(SpatialSkeletonMesh, ABodyWithoutPointsIsAMarkerAndCoincidentPointsShareANode) {
  spatial::Model model = crank_model();
  const fem::Mesh bob = spatial_skeleton_mesh(model, 2);
  EXPECT_EQ(bob.node_count(), 3 + 4);  // origin, the marker's two tips and its ring
  EXPECT_EQ(bob.element_count(), 4);
  const double half = kSkeletonWidthPerModel * 0.4;
  EXPECT_EQ(Vector3d(bob.nodes.row(2).transpose()), Vector3d(0.0, 0.0, half));
  model.bodies[1].points["at origin"] = Vector3d(0.0, 0.0, 1e-12);
  model.bodies[1].points["twin"] = Vector3d(0.4, 0.0, 0.0);
  const fem::Mesh crank = spatial_skeleton_mesh(model, 1);
  EXPECT_EQ(crank.node_set("at_origin"), std::vector<fem::Index>{0});
  EXPECT_EQ(crank.node_set("twin"), crank.node_set("tip"));
  EXPECT_EQ(crank.node_count(), 4 + 3 * 4);
}

TEST(WriteSpatialMechanismHistories, SetsTheTimeGridForTheCallersHistories) {
  // The caller's own histories on the same output times follow; a second time grid is an Error.
  const Written& w = crank_written();
  const fs::path file = test::fresh_dir("spatial_histories_caller") / "crank.h5";
  post::ResultsWriter writer(file, {});
  write_spatial_mechanism_histories(writer, w.model, w.results);
  EXPECT_NE(error_of([&] { writer.set_mechanism_time({0.0, 1.0}); }).find("already set"), std::string::npos);
  writer.write_history("caller.quantity", "m", post::FieldMatrix::Zero(Eigen::Index(w.results.frames.size()), 1));
  writer.commit();
  const auto names = post::ResultsFile::open(file).histories();
  EXPECT_NE(std::find(names.begin(), names.end(), "caller.quantity"), names.end());
  // The skeletons are blocks of the XDMF file that ParaView opens.
  std::ifstream xdmf(fs::path(file).replace_extension(".xdmf"));
  std::stringstream text;
  text << xdmf.rdbuf();
  EXPECT_NE(text.str().find(R"(<Grid Name="skeleton.crank" GridType="Collection" CollectionType="Temporal">)"),
            std::string::npos);
}

TEST(WriteSpatialMechanismHistories, NoFramesIsAnError) {
  const spatial::Model model = crank_model();
  post::ResultsWriter writer(test::fresh_dir("spatial_histories_empty") / "empty.h5", {});
  EXPECT_NE(error_of([&] { write_spatial_mechanism_histories(writer, model, {}); }).find("no output frames"),
            std::string::npos);
}

}  // namespace
}  // namespace kinetofem::pipeline
