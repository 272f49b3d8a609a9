// PNG pictures of the elastic assembly (png_plots.hpp, 4. and 5.) on a synthetic
// results file whose step, scale and maxima are known by construction; and
// `kinetofem post --png` writing and listing them. With KINETOFEM_PNG_KEEP_DIR
// set, the pictures are written there and kept (to look at them).
//
// "assembly.h5", an L of two parts in world axes, 11 output times t = 0, 0.1, ..., 1 s:
//   assembly.a  HEX8 grid 100 x 20 x 10 mm (hex_grid(11, 3, 2)), placed as meshed;
//   assembly.b  HEX8 grid 50 x 20 x 10 mm (hex_grid(6, 3, 2)), turned +90° about z and
//               standing on a's right end: world (x, y) = (0.1 - y_b, 0.02 + x_b);
//   both moved rigidly by (0, 2 mm * k, 0) at step k (position).
//   Elastic displacement u = c_k r e, r = |p_0| / R (p_0: world position at step 0,
//   R: the largest |p_0|, at b's node 23, world (100, 70, 10) mm), e = (0.6, -0.8, 0):
//   |u| = c_k r, largest c_k at node 23 of assembly.b.
//   c_k = 0, 0.3, 0.7, 1.1, 1.5, 1.3, 1.0, 0.8, 0.6, 0.4, 0.2 mm (largest at step 4);
//   histories: assembly.max_displacement = c_k; the gripper point H (rigid path
//   point.b.H = (90, 70 + 2k) mm) with |u_H| = 0, 0.1, 0.25, 0.4, 0.55, 0.7, 0.9, 0.8, 0.5,
//   0.3, 0.1 mm (largest at step 6) and contributions part.a 0.5 u + w, part.b 0.2 u - w,
//   chain.lift 0.35 u, drive.motor -0.05 u (w perpendicular to u: they add up to u);
//   static pose study: c = 0.03 mm at the step-0 position.
//   One ordinary link "arm" with a von_mises series (50 MPa, below the assembly's 100 MPa).
// Drawing size (default oblique view, k = 0.5 at 40°): 100 + 0.5 cos 40° * 10 = 103.83 mm
// wide, so the automatic scale is the 1/2/5 factor nearest 0.08 * 103.83 / max|u| [mm].
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/png_plots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "png_inspect.hpp"
#include "post_test_results.hpp"
#include "post_test_calls.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::inspect;
using testing::PngStats;

constexpr int kSteps = 11;
constexpr double kDt = 0.1;
constexpr double kC_mm[kSteps] = {0, 0.3, 0.7, 1.1, 1.5, 1.3, 1.0, 0.8, 0.6, 0.4, 0.2};
constexpr double kH_mm[kSteps] = {0, 0.1, 0.25, 0.4, 0.55, 0.7, 0.9, 0.8, 0.5, 0.3, 0.1};
constexpr double kStatic_mm = 0.03;
constexpr fem::Index kFarNode = 23;  // of assembly.b: i = 5, j = 0, k = 1

struct Contents {
  bool point_histories = true;  // point.b.H, assembly.point.H.*
  bool static_pose = true;
};

std::filesystem::path write_assembly(const std::filesystem::path& dir, const Contents& contents = {}) {
  const std::filesystem::path path = dir / "assembly.h5";
  Provenance prov;
  prov.case_path = "synthetic_assembly";
  ResultsWriter writer(path, prov);
  const fem::Mesh a = testing::hex_grid(11, 3, 2, 0.01), b = testing::hex_grid(6, 3, 2, 0.01);
  fem::NodeCoordinates b_world = b.nodes;
  b_world.col(0) = 0.1 - b.nodes.col(1).array();
  b_world.col(1) = 0.02 + b.nodes.col(0).array();
  const double R = std::max(a.nodes.rowwise().norm().maxCoeff(), b_world.rowwise().norm().maxCoeff());
  const Eigen::RowVector3d e(0.6, -0.8, 0.0);
  auto write = [&](const std::string& name, const fem::Mesh& mesh, const fem::NodeCoordinates& p0) {
    const Eigen::VectorXd r = p0.rowwise().norm() / R;
    BodyWriter& w = writer.add_body(name, mesh);
    w.begin_series({{"position", "m", 3, kVectorComponents},
                    {"displacement", "m", 3, kVectorComponents},
                    {"displacement_magnitude", "m", 1},
                    {"von_mises", "Pa", 1}});
    for (int k = 0; k < kSteps; ++k) {
      FieldMatrix position = p0;
      position.col(1).array() += 0.002 * k;
      const FieldMatrix u = (kC_mm[k] * 1e-3 * r) * e, magnitude = kC_mm[k] * 1e-3 * r, vm = 100e6 * r;
      w.write_step(k * kDt, {{"position", position}, {"displacement", u}, {"displacement_magnitude", magnitude},
                             {"von_mises", vm}});
    }
    if (contents.static_pose) {
      w.write_static("static_position", "m", p0, kVectorComponents);
      w.write_static("static_displacement", "m", (kStatic_mm * 1e-3 * r) * e, kVectorComponents);
      w.write_static("static_displacement_magnitude", "m", kStatic_mm * 1e-3 * r);
      w.write_static("static_von_mises", "Pa", 50e6 * r);
    }
  };
  write("assembly.a", a, a.nodes);
  write("assembly.b", b, b_world);
  {
    const fem::Mesh arm = testing::hex_grid(6, 3, 2, 0.01);
    BodyWriter& w = writer.add_body("arm", arm);
    w.begin_series({{"displacement", "m", 3, kVectorComponents}, {"von_mises", "Pa", 1}});
    for (int k = 0; k < kSteps; ++k)
      w.write_step(k * kDt, {{"displacement", FieldMatrix(FieldMatrix::Zero(arm.node_count(), 3))},
                             {"von_mises", FieldMatrix(FieldMatrix::Constant(arm.node_count(), 1, 50e6))}});
  }
  std::vector<double> t(kSteps);
  FieldMatrix max(kSteps, 1), path_h(kSteps, 2), u_h(kSteps, 3), u_h_abs(kSteps, 1), w_h(kSteps, 3);
  for (int k = 0; k < kSteps; ++k) {
    t[size_t(k)] = k * kDt;
    max(k, 0) = kC_mm[k] * 1e-3;
    path_h.row(k) << 0.09, 0.07 + 0.002 * k;
    const double phi = (-90.0 + 40.0 * t[size_t(k)]) * std::numbers::pi / 180.0, psi = 10.0 * std::numbers::pi / 180.0;
    const double h = kH_mm[k] * 1e-3;
    u_h.row(k) << h * std::cos(phi) * std::cos(psi), h * std::sin(phi) * std::cos(psi), h * std::sin(psi);
    u_h_abs(k, 0) = h;
    w_h.row(k) << -0.3 * h * std::sin(phi), 0.3 * h * std::cos(phi), 0.0;  // perpendicular to u_h
  }
  writer.set_mechanism_time(t);
  writer.write_history("assembly.max_displacement", "m", max);
  if (contents.point_histories) {
    writer.write_history("point.b.H", "m", path_h, {"x", "y"});
    writer.write_history("assembly.point.H.displacement", "m", u_h, kVectorComponents);
    writer.write_history("assembly.point.H.displacement_magnitude", "m", u_h_abs);
    writer.write_history("assembly.point.H.from.part.a", "m", FieldMatrix(0.5 * u_h + w_h), kVectorComponents);
    writer.write_history("assembly.point.H.from.part.b", "m", FieldMatrix(0.2 * u_h - w_h), kVectorComponents);
    writer.write_history("assembly.point.H.from.chain.lift", "m", FieldMatrix(0.35 * u_h), kVectorComponents);
    writer.write_history("assembly.point.H.from.drive.motor", "m", FieldMatrix(-0.05 * u_h), kVectorComponents);
  }
  writer.commit();
  return path;
}

using testing::output_dir;
std::filesystem::path picture(const testing::TemporaryDirectory& dir, const std::string& name) {
  return output_dir(dir) / name;
}

void expect_drawn(const std::filesystem::path& png, int width, int height, size_t min_colours, double min_ink) {
  const PngStats s = inspect(png);
  EXPECT_EQ(s.width, width) << png;
  EXPECT_EQ(s.height, height) << png;
  EXPECT_GT(s.colours, min_colours) << png;
  EXPECT_GT(s.ink, min_ink) << png;
}

TEST(PostPngAssembly, AutomaticStepIsTheLargestDeflectionOfH) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path()));
  const auto png = picture(dir, "assembly_max_H.png");
  const AssemblyPictureInfo info = write_assembly_picture(r, png);
  EXPECT_EQ(info.step, 6);
  EXPECT_DOUBLE_EQ(info.time_s, 0.6);
  EXPECT_EQ(info.chosen_by, "largest |u| of H");
  EXPECT_DOUBLE_EQ(info.max_value, 1.0e-3);
  EXPECT_EQ(info.max_body, "assembly.b");
  EXPECT_EQ(info.max_node, kFarNode);
  EXPECT_DOUBLE_EQ(info.deformation_scale, 10.0);  // 0.08 * 103.83 / 1.0 = 8.3 -> 10
  expect_drawn(png, 1400, 900, 200, 0.05);         // the colour bar alone has 256 map colours
}

TEST(PostPngAssembly, WithoutPointHistoriesTheLargestMaxDisplacement) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path(), {.point_histories = false, .static_pose = false}));
  const auto png = picture(dir, "assembly_max.png");
  const AssemblyPictureInfo info = write_assembly_picture(r, png, {{.title_name = "", .width_px = 900, .height_px = 700}});
  EXPECT_EQ(info.step, 4);
  EXPECT_EQ(info.chosen_by, "largest assembly.max_displacement");
  EXPECT_DOUBLE_EQ(info.max_value, 1.5e-3);
  EXPECT_DOUBLE_EQ(info.deformation_scale, 5.0);  // 0.08 * 103.83 / 1.5 = 5.5 -> 5
  expect_drawn(png, 900, 700, 200, 0.05);
}

TEST(PostPngAssembly, GivenStepAndScale) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path()));
  AssemblyPictureOptions o;
  o.pose = AssemblyPictureOptions::Pose::Step;
  o.step = 2;
  o.deformation_scale = 30;
  o.oblique_depth = 0;  // plain x-y view
  const auto png = picture(dir, "assembly_step2_plain.png");
  const AssemblyPictureInfo info = write_assembly_picture(r, png, o);
  EXPECT_EQ(info.step, 2);
  EXPECT_DOUBLE_EQ(info.time_s, 0.2);
  EXPECT_DOUBLE_EQ(info.max_value, 0.7e-3);
  EXPECT_DOUBLE_EQ(info.deformation_scale, 30.0);
  expect_drawn(png, 1400, 900, 200, 0.05);
}

TEST(PostPngAssembly, StaticPoseStudy) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path()));
  AssemblyPictureOptions o;
  o.pose = AssemblyPictureOptions::Pose::Static;
  const auto png = picture(dir, "assembly_static.png");
  const AssemblyPictureInfo info = write_assembly_picture(r, png, o);
  EXPECT_TRUE(std::isnan(info.time_s));
  EXPECT_EQ(info.step, -1);
  EXPECT_DOUBLE_EQ(info.max_value, kStatic_mm * 1e-3);
  EXPECT_EQ(info.max_body, "assembly.b");
  EXPECT_DOUBLE_EQ(info.deformation_scale, 200.0);  // 0.08 * 103.83 / 0.03 = 277 -> 200
  expect_drawn(png, 1400, 900, 200, 0.05);
}

TEST(PostPngAssembly, PointDeflectionOverTheMotion) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path()));
  const auto png = picture(dir, "deflection_H.png");
  const PointDeflectionInfo info = write_point_deflection_picture(r, png);
  EXPECT_DOUBLE_EQ(info.max_m, 0.9e-3);
  EXPECT_DOUBLE_EQ(info.time_s, 0.6);
  EXPECT_EQ(info.contributors, (std::vector<std::string>{"chain.lift", "drive.motor", "part.a", "part.b"}));
  expect_drawn(png, 1400, 900, 50, 0.01);
}

TEST(PostPngAssembly, ContentsOfTheFile) {
  testing::TemporaryDirectory dir;
  const AssemblyContents full = assembly_contents(ResultsFile::open(write_assembly(dir.path())));
  EXPECT_EQ(full.bodies, (std::vector<std::string>{"assembly.a", "assembly.b"}));
  EXPECT_TRUE(full.has_static);
  EXPECT_EQ(full.points, std::vector<std::string>{"H"});
  EXPECT_TRUE(assembly_contents(ResultsFile::open(testing::write_synthetic_motion(dir.path()))).bodies.empty());
}

TEST(PostPngAssembly, StressPictureLeavesTheAssemblyOut) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_assembly(dir.path()));
  const StressPictureInfo info = write_stress_picture(r, dir / "vm.png");  // assembly.* reach 100 MPa
  EXPECT_EQ(info.peak_body, "arm");
  EXPECT_DOUBLE_EQ(info.max_value, 50e6);
}

TEST(PostPngAssembly, MissingDataIsAnErrorNamingTheFile) {
  testing::TemporaryDirectory dir;
  const auto motion = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  const std::string motion_file = motion.path().string();
  std::string message = testing::error_text([&] { write_assembly_picture(motion, dir / "a.png"); });
  EXPECT_NE(message.find(motion_file), std::string::npos) << message;
  EXPECT_NE(message.find("no elastic assembly"), std::string::npos) << message;
  message = testing::error_text([&] { write_point_deflection_picture(motion, dir / "d.png"); });
  EXPECT_NE(message.find("assembly.point.H.displacement"), std::string::npos) << message;

  const auto bare = ResultsFile::open(write_assembly(dir.path(), {.point_histories = false, .static_pose = false}));
  AssemblyPictureOptions o;
  o.pose = AssemblyPictureOptions::Pose::Static;
  message = testing::error_text([&] { write_assembly_picture(bare, dir / "s.png", o); });
  EXPECT_NE(message.find(bare.path().string()), std::string::npos) << message;
  EXPECT_NE(message.find("no static pose study"), std::string::npos) << message;
  o.pose = AssemblyPictureOptions::Pose::Step;
  o.step = kSteps;
  message = testing::error_text([&] { write_assembly_picture(bare, dir / "s.png", o); });
  EXPECT_NE(message.find("step 11 is outside the 11 output times"), std::string::npos) << message;
  message = testing::error_text([&] { write_point_deflection_picture(bare, dir / "d.png"); });
  EXPECT_NE(message.find("tracked points of the elastic assembly: none"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.png"));
}

TEST(PostPngAssembly, PostPngWritesAndListsTheAssemblyPictures) {
  testing::TemporaryDirectory dir;
  const std::filesystem::path png = picture(dir, "post_png");
  const std::string out = testing::post_png(write_assembly(output_dir(dir)), png);
  for (const char* name : {"assembly_static.png", "assembly_max_H.png", "deflection_H.png", "von_mises_critical.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(png / name)) << name;
  EXPECT_NE(out.find("assembly_static.png  (static pose study, deformation x200)"), std::string::npos) << out;
  EXPECT_NE(out.find("assembly_max_H.png  (t = 0.6000 s, largest |u| of H, deformation x10)"), std::string::npos) << out;
  EXPECT_NE(out.find("deflection_H.png  (max |u| 0.900 mm at t = 0.6000 s)"), std::string::npos) << out;

  std::filesystem::create_directories(dir / "bare");
  const std::string bare = testing::post_png(write_assembly(dir / "bare", {.point_histories = false, .static_pose = false}),
                                    dir / "png_bare");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "png_bare" / "assembly_max.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "png_bare" / "assembly_static.png"));
  EXPECT_EQ(bare.find("deflection_"), std::string::npos) << bare;
}

}  // namespace
}  // namespace kinetofem::post
