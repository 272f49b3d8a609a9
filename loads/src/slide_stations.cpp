#include "kinetofem/loads/slide_stations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"

namespace kinetofem::loads {

SlideStations add_slide_stations(fem::Mesh& mesh, const std::string& face_set, const Eigen::Vector3d& axis_point,
                                 const Eigen::Vector3d& axis, double window_m, double spacing_m,
                                 const std::string& infix) {
  require(window_m > 0 && std::isfinite(window_m) && spacing_m > 0 && std::isfinite(spacing_m),
          "slide face '{}': window {} m and station spacing {} m must be positive", face_set, window_m, spacing_m);
  require(std::abs(axis.norm() - 1.0) < 1e-12, "slide face '{}': the axis is not a unit vector", face_set);
  const std::vector<fem::FaceBlock> faces = mesh.face_set(face_set);  // throws naming the sets present
  auto along = [&](fem::Index n) { return (mesh.nodes.row(n).transpose() - axis_point).dot(axis); };
  const std::vector<fem::Index> nodes = fem::nodes_of_faces(faces);
  require(!nodes.empty(), "slide face '{}' is empty", face_set);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const fem::Index n : nodes) lo = std::min(lo, along(n)), hi = std::max(hi, along(n));
  require(hi - lo >= window_m * (1 - 1e-9),
          "slide face '{}' is {:.3f} mm long along its axis, shorter than the bearing's {:.3f} mm", face_set,
          (hi - lo) / units::kMm, window_m / units::kMm);
  SlideStations out;
  out.face_set = face_set;
  out.window_m = window_m;
  const double first = lo + 0.5 * window_m, last = hi - 0.5 * window_m;
  const int count = std::max(1, int(std::ceil((last - first) / spacing_m - 1e-9)) + 1);
  const double slack = 1e-9 * window_m;
  for (int k = 0; k < count; ++k) {
    const double s = count == 1 ? 0.5 * (first + last) : first + (last - first) * k / (count - 1);
    std::vector<fem::FaceBlock> window;
    for (const fem::FaceBlock& block : faces) {
      fem::FaceBlock kept{block.type, {}};
      for (fem::Index f = 0; f < block.size(); ++f) {
        const auto face = block.face(f);
        if (std::all_of(face.begin(), face.end(),
                        [&](fem::Index n) { return std::abs(along(n) - s) <= 0.5 * window_m + slack; }))
          kept.connectivity.insert(kept.connectivity.end(), face.begin(), face.end());
      }
      if (kept.size() > 0) window.push_back(std::move(kept));
    }
    require(!window.empty(),
            "slide face '{}': the window at {:.3f} mm holds no whole face (faces longer than the bearing's {:.3f} mm: "
            "mesh finer)",
            face_set, s / units::kMm, window_m / units::kMm);
    const std::string name = fmt::format("{}{}{:.6g}mm", face_set, infix, s / units::kMm);
    mesh.face_sets[name] = std::move(window);
    out.face_sets.push_back(name);
    out.s_m.push_back(s);
  }
  return out;
}

StationBracket bracket_station(const SlideStations& stations, double s, const std::string& who) {
  const std::vector<double>& at = stations.s_m;
  require(!at.empty(), "{}: the slide face '{}' has no stations", who, stations.face_set);
  const double slack = 1e-9 * stations.window_m;
  require(
      s >= at.front() - slack && s <= at.back() + slack,
      "{}: the bearing sits at {:.3f} mm along the slide face '{}', beyond it: its {:.3f} mm fit between {:.3f} and "
      "{:.3f} mm",
      who, s / units::kMm, stations.face_set, stations.window_m / units::kMm,
      (at.front() - 0.5 * stations.window_m) / units::kMm, (at.back() + 0.5 * stations.window_m) / units::kMm);
  StationBracket b;
  if (at.size() == 1) return b;
  const std::size_t k =
      std::min<std::size_t>(std::size_t(std::upper_bound(at.begin(), at.end(), s) - at.begin()), at.size() - 1);
  b.a = int(k == 0 ? 0 : k - 1);
  b.b = b.a + 1;
  b.weight_b = std::clamp((s - at[std::size_t(b.a)]) / (at[std::size_t(b.b)] - at[std::size_t(b.a)]), 0.0, 1.0);
  return b;
}

}  // namespace kinetofem::loads
