#include "kinetofem/meshes/lever.hpp"

#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geometry_text.hpp"

namespace kinetofem::meshes {

void LeverDimensions::validate() const {
  for (const auto& [name, value] :
       {std::pair{"length_m", length_m}, {"width_m", width_m}, {"thickness_m", thickness_m},
        {"bore_diameter_m", bore_diameter_m}, {"boss_diameter_m", boss_diameter_m},
        {"boss_length_m", boss_length_m}})
    require(std::isfinite(value) && value > 0, "lever dimension {} = {} must be positive", name,
            value);
  require(bore_diameter_m < width_m,
          "lever bore_diameter_m = {} must be smaller than width_m = {} (the plate would be cut "
          "apart at the bores)",
          bore_diameter_m, width_m);
  require(width_m < boss_diameter_m, "lever width_m = {} must be smaller than boss_diameter_m = {}",
          width_m, boss_diameter_m);
  require(thickness_m <= boss_length_m,
          "lever thickness_m = {} must not exceed boss_length_m = {}", thickness_m, boss_length_m);
  require(length_m > boss_diameter_m,
          "lever length_m = {} must exceed boss_diameter_m = {} (the bosses would overlap)",
          length_m, boss_diameter_m);
}

double LeverDimensions::volume_m3() const {
  const double pi = std::numbers::pi;
  const double big_r = boss_diameter_m / 2, r = bore_diameter_m / 2, c = width_m / 2;
  const double strip = 2 * (c * std::sqrt(big_r * big_r - c * c) + big_r * big_r * std::asin(c / big_r));
  return width_m * length_m * thickness_m + 2 * pi * big_r * big_r * boss_length_m -
         thickness_m * strip - 2 * pi * r * r * boss_length_m;
}

fem::Mesh mesh_lever(const LeverDimensions& dimensions, const MeshOptions& options) {
  dimensions.validate();
  return mesh_geometry_text("lever.geo", lever_geometry_text(), options,
      {{"Lever/a", dimensions.length_m},
       {"Lever/w", dimensions.width_m},
       {"Lever/t", dimensions.thickness_m},
       {"Lever/d_bore", dimensions.bore_diameter_m},
       {"Lever/D_boss", dimensions.boss_diameter_m},
       {"Lever/L_boss", dimensions.boss_length_m}});
}

}  // namespace kinetofem::meshes
