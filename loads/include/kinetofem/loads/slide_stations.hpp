#pragma once
// Stations of a slide face: a face set along which a slider's bearing moves
// (an arm sliding in a sleeve), cut into windows so that a load entering
// where the bearing is at an output time is a combination of fixed load
// patterns (one distributing coupling per window, load_patterns.hpp): the
// load goes to the two stations that bracket the bearing, weighted linearly.
//
// Frame and units: the mesh frame (the part's body frame), m. A station's
// position s is measured along the unit `axis` from `axis_point`.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::loads {

struct SlideStations {
  std::string face_set;                // the slide face the windows are cut from
  std::vector<std::string> face_sets;  // one per station: "<face_set><infix><s in mm>mm"
  std::vector<double> s_m;             // increasing
  double window_m = 0.0;               // each window's length along the axis
};

// Cuts `face_set` into windows `window_m` long (the bearing's length) whose
// centres run from half a window inside one end of the set to half a window
// inside the other, at most `spacing_m` apart; a window holds the faces whose
// nodes all lie within half a window (and 1e-9 of it) of its centre. Adds the
// windows to mesh.face_sets, named by `infix` (the elastic assembly's guide
// stations use "@"). Throws Error naming the face set when it is missing,
// shorter than a window, or a window holds no whole face (faces longer than
// the window: mesh finer).
SlideStations add_slide_stations(fem::Mesh& mesh, const std::string& face_set, const Eigen::Vector3d& axis_point,
                                 const Eigen::Vector3d& axis, double window_m, double spacing_m,
                                 const std::string& infix = ".at_");

// The stations a bearing at s lies between, and the share of the second
// (0 at station a, 1 at b). Throws Error naming `who` and s when s lies beyond
// the first or last station by more than 1e-9 of a window.
struct StationBracket {
  int a = 0, b = 0;
  double weight_b = 0.0;
};
StationBracket bracket_station(const SlideStations& stations, double s_m, const std::string& who);

}  // namespace kinetofem::loads
