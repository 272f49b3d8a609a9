#include "kinetofem/postproc/fatigue_nodes.hpp"

#include <algorithm>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::post {

namespace {

bool has_field(const ResultsFile& r, const std::string& body, const char* field) {
  const auto statics = r.static_fields(body);
  return std::find(statics.begin(), statics.end(), field) != statics.end();
}

Eigen::VectorXd scalar(const ResultsFile& r, const std::string& body, const char* field, fem::Index nodes) {
  require(has_field(r, body, field), "'{}': body '{}' has {} but no {}", r.path().string(), body,
          layout::kFatigueDamage, field);
  const FieldData d = r.read_static(body, field);
  require(d.values.rows() == nodes && d.values.cols() == 1, "'{}': body '{}': {} is {} x {}, not {} x 1",
          r.path().string(), body, field, d.values.rows(), d.values.cols(), nodes);
  return d.values.col(0);
}

}  // namespace

bool has_fatigue(const ResultsFile& results) {
  for (const auto& body : results.bodies())
    if (has_field(results, body, layout::kFatigueDamage)) return true;
  return false;
}

std::vector<FatigueNode> worst_fatigue_nodes(const ResultsFile& r, int count) {
  require(count >= 0, "fatigue nodes: count {} must not be negative", count);
  std::vector<FatigueNode> all;
  for (const auto& body : r.bodies()) {
    if (!has_field(r, body, layout::kFatigueDamage)) continue;
    const fem::NodeCoordinates nodes = r.read_mesh(body).nodes;
    const fem::Index n = nodes.rows();
    const Eigen::VectorXd damage = scalar(r, body, layout::kFatigueDamage, n);
    const Eigen::VectorXd life = scalar(r, body, layout::kFatigueLifeCycles, n);
    const Eigen::VectorXd life_h = scalar(r, body, layout::kFatigueLifeHours, n);
    const Eigen::VectorXd u = scalar(r, body, layout::kFatigueUtilization, n);
    const Eigen::VectorXd category = scalar(r, body, layout::kFatigueDetailCategory, n);
    const Eigen::VectorXd range = scalar(r, body, layout::kFatigueMaxRange, n);
    for (fem::Index i = 0; i < n; ++i)
      all.push_back({body, i, nodes.row(i).transpose(), damage[i], life[i], life_h[i], u[i], category[i], range[i]});
  }
  const auto worse = [](const FatigueNode& a, const FatigueNode& b) {
    if (a.damage_per_cycle != b.damage_per_cycle) return a.damage_per_cycle > b.damage_per_cycle;
    return a.utilization > b.utilization;
  };
  const std::size_t shown = std::min(all.size(), std::size_t(count));
  std::partial_sort(all.begin(), all.begin() + std::ptrdiff_t(shown), all.end(), worse);
  all.resize(shown);
  return all;
}

}  // namespace kinetofem::post
