#pragma once
// PNG pictures of a results file, drawn with cairo (image surface, ARGB32).
//
// 1. write_stress_picture — a scalar field (von Mises) on the deformed
//    boundary surface of every body at the critical time (the output time of
//    the largest envelope value over all bodies; a body without a series shows
//    its static field). One panel per body, in its own body frame, all at one
//    scale in mm. View: oblique (cabinet-like) projection of the x-y plane,
//        X = x + k z cos(a),  Y = y + k z sin(a)   (k = oblique_depth, a = oblique_angle),
//    i.e. seen along v = (-k cos a, -k sin a, 1) from +z; boundary faces
//    facing away from the viewer are culled and the rest drawn far to near
//    (painter's algorithm), each quadratic face split into flat triangles,
//    shaded lightly for depth. Deformed position = x + scale * u; the scale
//    is stated in the title. Colour map "turbo" from 0 to the largest shown
//    value, colour bar labelled in MPa; the peak is marked.
// 2. write_mechanism_loads_picture — mechanism histories over time: every
//    history in N (joint reactions as magnitudes |R|, chain tension) in one
//    panel, every history in N*m (drive torque) in a second one.
// 3. write_path_picture — a 2-component history in m (the gripper point H) as
//    an x-y path in mm, equal aspect, start and end marked, dots at tenths of
//    the motion time.
//
// Every function throws Error naming the file or the missing data.
#include <filesystem>
#include <string>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

class ResultsFile;

struct PictureOptions {
  std::string title_name;  // case name in the titles; empty: the results file's stem
  int width_px = 1400;
  int height_px = 900;
};

struct StressPictureOptions : PictureOptions {
  std::string field = "von_mises";  // scalar, Pa
  std::string displacement_field = "displacement";
  double deformation_scale = 0.0;    // 0: automatic (a "nice" 1/2/5 x 10^k factor)
  double oblique_depth = 0.5;        // k
  double oblique_angle_deg = 40.0;   // a
};

struct StressPictureInfo {
  double time_s;             // NaN: static fields
  double deformation_scale;  // as drawn
  double max_value;          // of the shown field, its units (Pa)
  std::string peak_body;
  fem::Index peak_node;
};

StressPictureInfo write_stress_picture(const ResultsFile& results, const std::filesystem::path& png,
                                       const StressPictureOptions& options = {});

// Throws Error if the file has no history in N or N*m.
void write_mechanism_loads_picture(const ResultsFile& results, const std::filesystem::path& png,
                                   const PictureOptions& options = {});

void write_path_picture(const ResultsFile& results, const std::filesystem::path& png,
                        const std::string& history = "gripper_point_H",
                        const PictureOptions& options = {});

}  // namespace kinetofem::post
