// build_part_models on a part welded from two solids with a material of its
// own for one: the FE model's per-solid materials and the part's mass.
//
// Geometry: two boxes 60 x 20 x 20 mm end to end along x, written with
// Gmsh's OpenCASCADE API into a temporary .brep (mm); the solid at x > 60 mm
// is "hub" (by a point inside), the other "arm" (by position, solid1).
#include <cmath>
#include <filesystem>
#include <string>

#include <unistd.h>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/pipeline/part_model.hpp"

namespace kinetofem::pipeline {
namespace {

std::filesystem::path write_two_boxes() {
  const auto dir = std::filesystem::temp_directory_path() / ("kinetofem_welded_part_model_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto file = dir / "two_boxes.brep";
  meshes::GmshSession session;
  session.call(file.string(), "writing the test boxes", [&] {
    gmsh::model::add("boxes");
    gmsh::model::occ::addBox(0, 0, 0, 60, 20, 20);
    gmsh::model::occ::addBox(60, 0, 0, 60, 20, 20);
    gmsh::model::occ::synchronize();
    gmsh::write(file.string());
  });
  return file;
}

PartSpec welded_spec(const std::filesystem::path& file) {
  PartSpec spec;
  spec.file = file;
  spec.file_options.length_unit_m = 1e-3;
  spec.file_options.solids = {{"hub", {}, Eigen::Vector3d(0.090, 0.010, 0.010)}, {"solid1", {}, {}}};
  spec.attachments.body = "arm";
  spec.label = "part 'arm' (two_boxes.brep)";
  return spec;
}

fem::IsotropicMaterial steel() {
  fem::IsotropicMaterial m;
  m.youngs_modulus_pa = 210e9;
  m.poisson_ratio = 0.3;
  m.density_kg_m3 = 7850;
  return m;
}

meshes::MeshOptions coarse() {
  meshes::MeshOptions o;
  o.element_size_m = 0.010;
  o.order = 1;
  return o;
}

TEST(WeldedPartModel, EachSolidsDensityGivesThePartsMass) {
  const auto file = write_two_boxes();
  PartSpec spec = welded_spec(file);
  spec.solid_materials = {{"hub", 70e9, 0.33, 2700.0}};
  const auto parts = build_part_models({spec}, steel(), coarse(), Log::quiet());
  ASSERT_EQ(parts.size(), 1u);
  const auto& model = parts.front().model;
  ASSERT_EQ(model.set_materials.size(), 1u);
  EXPECT_EQ(model.set_materials.front().element_set, "solid.hub");
  EXPECT_EQ(model.set_materials.front().material.youngs_modulus_pa, 70e9);
  EXPECT_EQ(model.set_materials.front().material.poisson_ratio, 0.33);
  // Reference: boxes of 24 000 mm^3 each (plane faces: the tetrahedra fill
  // them exactly), 7850 and 2700 kg/m^3; the centre of mass of the two
  // masses at x = 30 and 90 mm.
  const double v = 24000e-9;
  EXPECT_NEAR(parts.front().mass.mass_kg, (7850 + 2700) * v, 1e-9 * 10550 * v);
  EXPECT_NEAR(parts.front().mass.centre_of_mass_m.x(), (7850 * 0.030 + 2700 * 0.090) / 10550, 1e-9);
  std::filesystem::remove_all(file.parent_path());
}

TEST(WeldedPartModel, AMaterialForASolidThePartLacksIsAnError) {
  const auto file = write_two_boxes();
  PartSpec spec = welded_spec(file);
  spec.file_options.solids.clear();  // solid1 and solid2 by position
  spec.solid_materials = {{"hub", {}, {}, 2700.0}};
  try {
    build_part_models({spec}, steel(), coarse(), Log::quiet());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("part 'arm' (two_boxes.brep): a material for solid 'hub', which the part "
                                         "does not have"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(file.parent_path());
}

}  // namespace
}  // namespace kinetofem::pipeline
