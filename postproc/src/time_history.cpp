#include "kinetofem/postproc/time_history.hpp"

#include <algorithm>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::post {

namespace {

std::string listed(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace

Eigen::VectorXd TimeHistory::magnitude() const { return values.rowwise().norm(); }

fem::Index nearest_node(const fem::NodeCoordinates& nodes_m, const Eigen::Vector3d& point_m) {
  require(nodes_m.rows() > 0, "nearest node: the mesh has no nodes");
  Eigen::Index best = 0;
  (nodes_m.rowwise() - point_m.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return best;
}

TimeHistory node_history(const ResultsFile& results, const std::string& body,
                         const std::string& field, fem::Index node) {
  const auto bodies = results.bodies();
  require(std::find(bodies.begin(), bodies.end(), body) != bodies.end(),
          "'{}' has no body '{}' (bodies: {})", results.path().string(), body, listed(bodies));
  const auto fields = results.series_fields(body);
  require(!fields.empty(), "body '{}' in '{}' has no time series (static fields: {})", body,
          results.path().string(), listed(results.static_fields(body)));
  require(std::find(fields.begin(), fields.end(), field) != fields.end(),
          "body '{}' has no series field '{}' (series fields: {})", body, field, listed(fields));
  const fem::NodeCoordinates nodes = results.read_mesh(body).nodes;
  require(node >= 0 && node < nodes.rows(), "body '{}' has no node {} (nodes 0..{})", body, node,
          nodes.rows() - 1);
  TimeHistory h;
  h.quantity = field;
  h.time_s = results.series_times(body);
  for (size_t k = 0; k < h.time_s.size(); ++k) {
    const FieldData step = results.read_step(body, field, fem::Index(k));
    if (k == 0) {
      h.values.resize(fem::Index(h.time_s.size()), step.values.cols());
      h.units = step.units;
      h.component_names = step.component_names;
    }
    h.values.row(fem::Index(k)) = step.values.row(node);
  }
  const Eigen::Vector3d x = nodes.row(node).transpose() * 1e3;
  h.description = fmt::format("{} at body '{}' node {} ({:.1f}, {:.1f}, {:.1f}) mm", field, body,
                              node, x.x(), x.y(), x.z());
  return h;
}

TimeHistory mechanism_history(const ResultsFile& results, const std::string& name) {
  const auto names = results.histories();
  require(std::find(names.begin(), names.end(), name) != names.end(),
          "'{}' has no mechanism history '{}' (histories: {})", results.path().string(), name,
          listed(names));
  const FieldData data = results.read_history(name);
  TimeHistory h;
  h.quantity = name;
  h.description = "mechanism history " + name;
  h.units = data.units;
  h.component_names = data.component_names;
  h.time_s = results.mechanism_time();
  h.values = data.values;
  require(h.values.rows() == fem::Index(h.time_s.size()),
          "mechanism history '{}' has {} rows for {} times", name, h.values.rows(), h.time_s.size());
  return h;
}

DisplayUnit display_unit(const std::string& si_units) {
  if (si_units == "m") return {"mm", 1e3};
  if (si_units == "Pa") return {"MPa", 1e-6};
  if (si_units == "rad") return {"deg", 180.0 / std::numbers::pi};
  return {si_units, 1.0};
}

}  // namespace kinetofem::post
