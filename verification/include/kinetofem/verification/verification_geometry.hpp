#pragma once
// The geometry of the FE checks that Gmsh meshes, compiled into the library
// from verification/geometry/ (cmake/KinetofemEmbed.cmake); mesh them with
// meshes::mesh_geometry_text (geometry_text.hpp).
#include <string_view>

namespace kinetofem::verification {

// verification/geometry/bar.geo: bar 100 x 20 x 20 mm, sets x0, x1, origin,
// corner_y (`kinetofem verify` fem.bar_tension).
std::string_view bar_geometry_text();
// verification/geometry/beam_link.geo: link 640 x 40 x 20 mm with two pin
// bores 600 mm apart, sets link, bore_1, bore_2 (accelerated_link.hpp).
std::string_view beam_link_geometry_text();

}  // namespace kinetofem::verification
