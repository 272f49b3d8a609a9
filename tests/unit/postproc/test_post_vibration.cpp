// The vibration over the motion in a results file (vibration_results.hpp) and its PNG
// pictures (png_plots.hpp, 6. and 7.) on a synthetic file whose extremes, peaks and settling
// are known by construction; and `kinetofem post` printing and drawing them. With
// KINETOFEM_PNG_KEEP_DIR set, the pictures are written there and kept (to look at them).
//
// "vibration.h5":
//   mechanism times t = 0, 0.1, ..., 2 s (the stroke; the stop at 2 s);
//   history vibration.frequency (21 x 3, Hz): mode 1 = 10 + (t - 1)^2 (lowest 10 Hz at t = 1 s,
//     highest 11 Hz at t = 0 and 2 s: t = 0 first), mode 2 = 25 + 2 t, mode 3 = 40 - t;
//   table vibration.static_frequency = 9.5, 24, 41 Hz (optional: Contents::static_pose);
//   table vibration.response.time: the 21 mechanism times, then 2 + 0.005 j, j = 1 .. 600 (3 s);
//   point H: quasi-static u_qs = (0, -q(t), 0), q = 0.5 + 0.5 sin(pi t / 2) mm over the stroke
//     (peak 1 mm at t = 1 s; 0.5 mm from the stop on); with the vibration 1.2 u_qs over the
//     stroke (peak 1.2 mm, amplification 1.2), after the stop u_rest + (0, -d(tau), 0),
//     d = 0.1 mm e^(-zeta w tau) cos(w tau), w = 2 pi 10 Hz, zeta = 0.02, tau = t - 2 s;
//     settling tolerance 0.01 mm: settling time ln(10) / (zeta w) = 1.832 s;
//   point C: the same response, with settling time inf (does not settle);
//   body "beam" (an ordinary link with a von_mises series) and mode-shape bodies
//   vibration.lowest.beam, vibration.static.beam (static fields mode_1 .. mode_3 and
//   their magnitudes).
#include <cmath>
#include <cstdlib>
#include <limits>
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
#include "kinetofem/postproc/vibration_results.hpp"
#include "png_inspect.hpp"
#include "post_test_results.hpp"
#include "post_test_calls.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::inspect;
using testing::PngStats;

constexpr int kStrokeTimes = 21;
constexpr double kStop_s = 2.0;
constexpr int kAfterSamples = 600;
constexpr double kAfterDt_s = 0.005;
constexpr double kZeta = 0.02;
const double kOmega = 2 * std::numbers::pi * 10.0;
const double kSettling_s = std::log(10.0) / (kZeta * kOmega);

struct Contents {
  bool static_pose = true;
  bool response = true;
};

double quasi_static_mm(double t) {
  return 0.5 + 0.5 * std::sin(std::numbers::pi * std::min(t, kStop_s) / 2);
}

std::filesystem::path write_vibration(const std::filesystem::path& dir, const Contents& contents = {}) {
  const std::filesystem::path path = dir / "vibration.h5";
  Provenance prov;
  prov.case_path = "synthetic_vibration";
  ResultsWriter writer(path, prov);
  const fem::Mesh beam = testing::hex_grid(6, 3, 2, 0.01);
  {
    BodyWriter& w = writer.add_body("beam", beam);
    w.begin_series({{"displacement", "m", 3, kVectorComponents}, {"von_mises", "Pa", 1}});
    for (int k = 0; k < kStrokeTimes; ++k)
      w.write_step(0.1 * k, {{"displacement", FieldMatrix(FieldMatrix::Zero(beam.node_count(), 3))},
                             {"von_mises", FieldMatrix(FieldMatrix::Constant(beam.node_count(), 1, 40e6 + 1e6 * k))}});
  }
  for (const std::string body : {"vibration.lowest.beam", "vibration.static.beam"}) {
    BodyWriter& w = writer.add_body(body, beam);
    for (int mode = 1; mode <= 3; ++mode) {
      FieldMatrix shape = FieldMatrix::Zero(beam.node_count(), 3);
      shape.col(1) = (beam.nodes.col(0).array() / 0.05).pow(double(mode)).matrix();  // 1 at the tip
      const FieldMatrix magnitude = shape.rowwise().norm();
      w.write_static(fmt::format("mode_{}", mode), "1", shape, kVectorComponents);
      w.write_static(fmt::format("mode_{}_magnitude", mode), "1", magnitude);
    }
  }
  std::vector<double> t(kStrokeTimes);
  FieldMatrix frequency(kStrokeTimes, 3);
  for (int k = 0; k < kStrokeTimes; ++k) {
    t[size_t(k)] = 0.1 * k;
    frequency.row(k) << 10 + std::pow(t[size_t(k)] - 1, 2), 25 + 2 * t[size_t(k)], 40 - t[size_t(k)];
  }
  writer.set_mechanism_time(t);
  writer.write_history(layout::kVibrationFrequency, "Hz", frequency, {"mode_1", "mode_2", "mode_3"});
  if (contents.static_pose)
    writer.write_table(layout::kVibrationStaticFrequency, "Hz", FieldMatrix(Eigen::Vector3d(9.5, 24, 41)));
  if (contents.response) {
    const int n = kStrokeTimes + kAfterSamples;
    FieldMatrix time(n, 1), dynamic = FieldMatrix::Zero(n, 3), quasi = FieldMatrix::Zero(n, 3);
    for (int k = 0; k < n; ++k) {
      time(k, 0) = k < kStrokeTimes ? t[size_t(k)] : kStop_s + kAfterDt_s * (k - kStrokeTimes + 1);
      const double tau = time(k, 0) - kStop_s, q = quasi_static_mm(time(k, 0)) * 1e-3;
      quasi(k, 1) = -q;
      dynamic(k, 1) = tau <= 0 ? -1.2 * q : -q - 0.1e-3 * std::exp(-kZeta * kOmega * tau) * std::cos(kOmega * tau);
    }
    auto scalar = [](double v) { return FieldMatrix(FieldMatrix::Constant(1, 1, v)); };
    writer.write_table(layout::kVibrationResponseTime, "s", time);
    writer.write_table(layout::kVibrationStopTime, "s", scalar(kStop_s));
    writer.write_table(layout::kVibrationDampingRatio, "1", scalar(kZeta));
    for (const std::string point : {"H", "C"}) {
      writer.write_table("vibration.response.point." + point + ".displacement", "m", dynamic, kVectorComponents);
      writer.write_table("vibration.response.point." + point + ".quasi_static", "m", quasi, kVectorComponents);
      writer.write_table("vibration.point." + point + ".settling_time", "s",
                         scalar(point == "H" ? kSettling_s : std::numeric_limits<double>::infinity()));
      writer.write_table("vibration.point." + point + ".settling_tolerance", "m", scalar(0.01e-3));
      writer.write_table("vibration.point." + point + ".amplitude_at_stop", "m", scalar(0.1e-3));
      writer.write_table("vibration.point." + point + ".dynamic_amplification", "1", scalar(1.2));
    }
  }
  writer.commit();
  return path;
}

using testing::output_dir;

void expect_drawn(const std::filesystem::path& png, int width, int height) {
  const PngStats s = inspect(png);
  EXPECT_EQ(s.width, width) << png;
  EXPECT_EQ(s.height, height) << png;
  EXPECT_GT(s.colours, 20u) << png;  // lines in several colours, anti-aliased text
  EXPECT_GT(s.ink, 0.01) << png;
}

TEST(PostVibration, ContentsOfTheFile) {
  testing::TemporaryDirectory dir;
  const VibrationContents c = vibration_contents(ResultsFile::open(write_vibration(dir.path())));
  EXPECT_TRUE(c.frequencies);
  EXPECT_TRUE(c.static_frequencies);
  EXPECT_EQ(c.points, (std::vector<std::string>{"C", "H"}));
  EXPECT_EQ(c.bodies, (std::vector<std::string>{"vibration.lowest.beam", "vibration.static.beam"}));
  const VibrationContents none = vibration_contents(ResultsFile::open(testing::write_synthetic_motion(dir.path())));
  EXPECT_FALSE(none.frequencies);
  EXPECT_TRUE(none.points.empty());
}

TEST(PostVibration, FrequencyPictureMarksTheLowestFirstFrequency) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_vibration(dir.path()));
  const auto png = output_dir(dir) / "vibration_frequencies.png";
  const FrequencyPictureInfo info = write_frequency_picture(r, png);
  EXPECT_DOUBLE_EQ(info.lowest_first_hz, 10.0);
  EXPECT_DOUBLE_EQ(info.lowest_first_time_s, 1.0);
  EXPECT_DOUBLE_EQ(info.highest_first_hz, 11.0);
  EXPECT_EQ(info.modes, 3);
  EXPECT_DOUBLE_EQ(info.static_first_hz, 9.5);
  expect_drawn(png, 1400, 900);
}

TEST(PostVibration, FrequencyPictureWithoutTheStaticPose) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_vibration(dir.path(), {.static_pose = false, .response = false}));
  const auto png = output_dir(dir) / "vibration_frequencies_800x600.png";
  const FrequencyPictureInfo info = write_frequency_picture(r, png, {.title_name = "no static", .width_px = 800, .height_px = 600});
  EXPECT_TRUE(std::isnan(info.static_first_hz));
  expect_drawn(png, 800, 600);
}

TEST(PostVibration, PointVibrationPictureOverTheMotionAndAfterTheStop) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_vibration(dir.path()));
  const auto png = output_dir(dir) / "vibration_point_H.png";
  const PointVibrationPictureInfo info = write_point_vibration_picture(r, png, "H");
  EXPECT_NEAR(info.peak_dynamic_m, 1.2e-3, 1e-15);  // at t = 1 s, over the stroke only
  EXPECT_NEAR(info.peak_quasi_static_m, 1.0e-3, 1e-15);
  EXPECT_DOUBLE_EQ(info.dynamic_amplification, 1.2);
  EXPECT_DOUBLE_EQ(info.settling_time_s, kSettling_s);
  expect_drawn(png, 1400, 900);

  const PointVibrationData p = read_point_vibration(r, "H");
  EXPECT_EQ(p.time_s.size(), size_t(kStrokeTimes + kAfterSamples));
  EXPECT_DOUBLE_EQ(p.stop_time_s, kStop_s);
  EXPECT_DOUBLE_EQ(p.peak_dynamic_time_s, 1.0);
  EXPECT_DOUBLE_EQ(p.damping_ratio, kZeta);
  EXPECT_DOUBLE_EQ(p.settling_tolerance_m, 0.01e-3);
}

TEST(PostVibration, PointThatDoesNotSettle) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_vibration(dir.path()));
  const auto png = output_dir(dir) / "vibration_point_C.png";
  const PointVibrationPictureInfo info = write_point_vibration_picture(r, png, "C");
  EXPECT_EQ(info.settling_time_s, std::numeric_limits<double>::infinity());
  expect_drawn(png, 1400, 900);
}

TEST(PostVibration, MissingDataIsAnErrorNamingTheFileAndTheData) {
  testing::TemporaryDirectory dir;
  const auto motion = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  std::string m = testing::error_text([&] { write_frequency_picture(motion, dir / "f.png"); });
  EXPECT_NE(m.find(motion.path().string()), std::string::npos) << m;
  EXPECT_NE(m.find("no history vibration.frequency"), std::string::npos) << m;
  m = testing::error_text([&] { write_point_vibration_picture(motion, dir / "p.png", "H"); });
  EXPECT_NE(m.find(motion.path().string()), std::string::npos) << m;
  EXPECT_NE(m.find("no table vibration.response.point.H.displacement"), std::string::npos) << m;
  EXPECT_NE(m.find("points with a vibration response: none"), std::string::npos) << m;

  const auto full = ResultsFile::open(write_vibration(dir.path()));
  m = testing::error_text([&] { write_point_vibration_picture(full, dir / "p.png", "G"); });
  EXPECT_NE(m.find("points with a vibration response: C, H"), std::string::npos) << m;
  EXPECT_FALSE(std::filesystem::exists(dir / "f.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "p.png"));
}

TEST(PostVibration, StressPictureLeavesTheModeShapeBodiesOut) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(write_vibration(dir.path()));
  const StressPictureInfo info = write_stress_picture(r, dir / "vm.png");
  EXPECT_EQ(info.peak_body, "beam");
  EXPECT_DOUBLE_EQ(info.max_value, 60e6);
}

TEST(PostVibration, PostPrintsTheSummaryAndWritesThePictures) {
  testing::TemporaryDirectory dir;
  const std::filesystem::path png = dir / "png";
  const std::string out = testing::post_png(write_vibration(dir.path()), png);
  for (const char* name : {"vibration_frequencies.png", "vibration_point_H.png", "vibration_point_C.png",
                           "von_mises_critical.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(png / name)) << name;
  EXPECT_NE(out.find("first natural frequency over the motion 10.000 .. 11.000 Hz (lowest at t = 1.0000 s); static "
                     "pose 9.500 Hz"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("point H: dynamic amplification 1.200"), std::string::npos) << out;
  EXPECT_NE(out.find("settles within 0.0100 mm 1.832 s after the stop"), std::string::npos) << out;
  EXPECT_NE(out.find("point C: dynamic amplification 1.200"), std::string::npos) << out;
  EXPECT_NE(out.find("does not settle within 0.0100 mm"), std::string::npos) << out;
  EXPECT_NE(out.find("vibration_frequencies.png  (3 modes; mode 1 10.00 .. 11.00 Hz, lowest at t = 1.0000 s)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("vibration_point_H.png  (amplification 1.200, settles 1.832 s after the stop)"), std::string::npos)
      << out;
  EXPECT_NE(out.find("vibration_point_C.png  (amplification 1.200, does not settle)"), std::string::npos) << out;
  EXPECT_NE(out.find("mode shapes (world coordinates at the pose, max |u| = 1): mode_1, mode_1_magnitude"),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace kinetofem::post
