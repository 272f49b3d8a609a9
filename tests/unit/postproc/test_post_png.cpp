// PNG pictures: written at the requested size, decodable, and not trivial —
// many distinct colours and a good share of non-white pixels — checked by
// decoding the file with cairo, independently of how it was drawn.
#include <cmath>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/png_plots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "png_inspect.hpp"
#include "post_test_results.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::inspect;
using testing::PngStats;

TEST(PostPng, StressPictureOfTheSeries) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  StressPictureOptions o;
  o.width_px = 900;
  o.height_px = 600;
  const StressPictureInfo info = write_stress_picture(r, dir / "vm.png", o);
  EXPECT_DOUBLE_EQ(info.time_s, 0.2);  // time of the 300 MPa peak
  EXPECT_DOUBLE_EQ(info.max_value, 300e6);
  EXPECT_EQ(info.peak_body, "beam");
  EXPECT_GT(info.deformation_scale, 0.0);
  const PngStats s = inspect(dir / "vm.png");
  EXPECT_EQ(s.width, 900);
  EXPECT_EQ(s.height, 600);
  EXPECT_GT(s.colours, 200u);  // colour bar alone has 256 map colours
  EXPECT_GT(s.ink, 0.08);
}

TEST(PostPng, StressPictureOfAStaticFile) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_static(dir.path()));
  const StressPictureInfo info = write_stress_picture(r, dir / "vm.png");
  EXPECT_TRUE(std::isnan(info.time_s));
  const PngStats s = inspect(dir / "vm.png");
  EXPECT_EQ(s.width, 1400);
  EXPECT_EQ(s.height, 900);
  EXPECT_GT(s.colours, 200u);
  EXPECT_GT(s.ink, 0.08);
}

TEST(PostPng, MechanismLoadsAndPath) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  write_mechanism_loads_picture(r, dir / "loads.png");
  write_path_picture(r, dir / "path.png", "gripper_point_H", {.title_name = "synthetic", .width_px = 800, .height_px = 800});
  const PngStats loads = inspect(dir / "loads.png"), path = inspect(dir / "path.png");
  EXPECT_EQ(loads.width, 1400);
  EXPECT_EQ(loads.height, 900);
  EXPECT_EQ(path.width, 800);
  EXPECT_EQ(path.height, 800);
  // Anti-aliased lines and text in several colours: far more than a handful.
  EXPECT_GT(loads.colours, 50u);
  EXPECT_GT(path.colours, 50u);
  EXPECT_GT(loads.ink, 0.01);
  EXPECT_GT(path.ink, 0.01);
}

TEST(PostPng, MissingDataIsAnError) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_static(dir.path()));
  EXPECT_THROW(write_mechanism_loads_picture(r, dir / "loads.png"), Error);
  EXPECT_THROW(write_path_picture(r, dir / "path.png"), Error);
  StressPictureOptions o;
  o.field = "tresca";
  EXPECT_THROW(write_stress_picture(r, dir / "vm.png", o), Error);
  EXPECT_THROW(write_stress_picture(r, dir / "no_such_dir" / "vm.png"), Error);
}

}  // namespace
}  // namespace kinetofem::post
