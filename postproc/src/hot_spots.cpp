#include "kinetofem/postproc/hot_spots.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::post {

namespace {

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string listed(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

void require_scalar(const FieldMatrix& values, const std::string& body, const std::string& field,
                    const char* where) {
  require(values.cols() == 1, "body '{}' {} field '{}' has {} components; a scalar field is needed",
          body, where, field, values.cols());
}

// The body's envelope of `field` with its mesh read; values, steps and times still to fill.
BodyEnvelope start_envelope(const ResultsFile& results, const std::string& body, const std::string& field,
                            BodyEnvelope::Source source) {
  BodyEnvelope env;
  env.body = body;
  env.field = field;
  env.source = source;
  const fem::Mesh mesh = results.read_mesh(body);
  env.nodes_m = mesh.nodes;
  const std::string solid_prefix = layout::kSolidSetPrefix, seam_prefix = layout::kWeldSetPrefix;
  std::vector<std::pair<std::string, std::vector<fem::Index>>> solids;
  std::vector<char> in_set;
  for (const auto& [name, elements] : mesh.element_sets) {
    if (name.rfind(solid_prefix, 0) != 0) continue;
    in_set.assign(std::size_t(mesh.element_count()), 0);
    for (fem::Index e : elements) in_set[std::size_t(e)] = 1;
    std::vector<fem::Index> nodes;
    fem::Index global = 0;
    for (const auto& block : mesh.blocks)
      for (fem::Index e = 0; e < block.size(); ++e, ++global)
        if (in_set[std::size_t(global)])
          for (fem::Index n : block.element(e)) nodes.push_back(n);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    env.solid_nodes.emplace_back(name.substr(solid_prefix.size()), std::move(nodes));
  }
  for (const auto& [name, nodes] : mesh.node_sets)
    if (name.rfind(seam_prefix, 0) == 0) env.seam_nodes.emplace_back(name, nodes);
  return env;
}

}  // namespace

fem::Index BodyEnvelope::peak_node() const {
  require(max_value.size() > 0, "body '{}': empty envelope of '{}'", body, field);
  Eigen::Index node = 0;
  max_value.maxCoeff(&node);
  return node;
}

double BodyEnvelope::peak_value() const { return max_value(peak_node()); }

double BodyEnvelope::time_of(fem::Index node) const {
  const fem::Index step = max_step.at(size_t(node));
  if (step < 0 || times_s.empty()) return std::numeric_limits<double>::quiet_NaN();
  return times_s.at(size_t(step));
}

const char* BodyEnvelope::source_name() const {
  switch (source) {
    case Source::FileEnvelope: return "envelope in file";
    case Source::Series: return "recomputed from series";
    case Source::Static: return "static field";
  }
  return "";
}

BodyEnvelope envelope_from_series(const ResultsFile& results, const std::string& body,
                                  const std::string& field) {
  const auto fields = results.series_fields(body);
  require(contains(fields, field), "body '{}' in '{}' has no series field '{}' (series fields: {})",
          body, results.path().string(), field, listed(fields));
  BodyEnvelope env = start_envelope(results, body, field, BodyEnvelope::Source::Series);
  env.times_s = results.series_times(body);
  const fem::Index n = env.nodes_m.rows();
  env.max_value = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  env.max_step.assign(size_t(n), 0);
  for (size_t k = 0; k < env.times_s.size(); ++k) {
    const FieldData step = results.read_step(body, field, fem::Index(k));
    require_scalar(step.values, body, field, "series");
    env.units = step.units;
    for (fem::Index i = 0; i < n; ++i)
      if (step.values(i, 0) > env.max_value(i)) {  // strict: the first step wins a tie
        env.max_value(i) = step.values(i, 0);
        env.max_step[size_t(i)] = fem::Index(k);
      }
  }
  return env;
}

BodyEnvelope max_envelope(const ResultsFile& results, const std::string& body,
                          const std::string& field) {
  const auto envelopes = results.envelopes(body);
  if (contains(envelopes, field)) {
    const EnvelopeData data = results.read_envelope(body, field);
    if (data.operation == layout::kEnvelopeMax) {
      require_scalar(data.values, body, field, "envelope");
      BodyEnvelope env = start_envelope(results, body, field, BodyEnvelope::Source::FileEnvelope);
      env.units = data.units;
      env.times_s = data.times_s;
      require(data.values.rows() == env.nodes_m.rows(),
              "body '{}' envelope '{}' has {} rows for {} nodes", body, field, data.values.rows(),
              env.nodes_m.rows());
      env.max_value = data.values.col(0);
      env.max_step.assign(data.step.data(), data.step.data() + data.step.rows());
      for (fem::Index s : env.max_step)
        require(s >= 0 && size_t(s) < env.times_s.size(),
                "body '{}' envelope '{}': step {} outside the {} output times", body, field, s,
                env.times_s.size());
      return env;
    }
  }
  if (contains(results.series_fields(body), field)) return envelope_from_series(results, body, field);
  const auto statics = results.static_fields(body);
  require(contains(statics, field),
          "body '{}' in '{}' has no field '{}' (envelopes: {}; series fields: {}; static fields: {})",
          body, results.path().string(), field, listed(envelopes),
          listed(results.series_fields(body)), listed(statics));
  const FieldData data = results.read_static(body, field);
  require_scalar(data.values, body, field, "static");
  BodyEnvelope env = start_envelope(results, body, field, BodyEnvelope::Source::Static);
  env.units = data.units;
  env.max_value = data.values.col(0);
  env.max_step.assign(size_t(data.values.rows()), -1);
  return env;
}

std::vector<BodyEnvelope> max_envelopes(const ResultsFile& results, const std::string& field) {
  std::vector<BodyEnvelope> out;
  for (const auto& body : results.bodies()) {
    if (contains(results.envelopes(body), field) || contains(results.series_fields(body), field) ||
        contains(results.static_fields(body), field))
      out.push_back(max_envelope(results, body, field));
  }
  return out;
}

std::vector<HotSpot> find_hot_spots(const std::vector<BodyEnvelope>& envelopes,
                                    const HotSpotOptions& options) {
  require(options.count >= 0, "hot spots: count {} must not be negative", options.count);
  require(options.separation_m >= 0.0, "hot spots: separation {} m must not be negative",
          options.separation_m);
  struct Candidate {
    double value;
    size_t body;
    fem::Index node;
  };
  std::vector<Candidate> candidates;
  for (size_t b = 0; b < envelopes.size(); ++b)
    for (fem::Index n = 0; n < envelopes[b].max_value.size(); ++n)
      if (std::isfinite(envelopes[b].max_value(n))) candidates.push_back({envelopes[b].max_value(n), b, n});
  // Decreasing value; ties by body then node so the result does not depend on the sort.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.value != b.value) return a.value > b.value;
    if (a.body != b.body) return a.body < b.body;
    return a.node < b.node;
  });
  std::vector<HotSpot> spots;
  std::vector<size_t> spot_body;
  const double r2 = options.separation_m * options.separation_m;
  for (const Candidate& c : candidates) {
    if (int(spots.size()) >= options.count) break;
    const BodyEnvelope& env = envelopes[c.body];
    const Eigen::Vector3d x = env.nodes_m.row(c.node).transpose();
    bool near = false;
    for (size_t s = 0; s < spots.size() && !near; ++s)
      near = spot_body[s] == c.body && (spots[s].position_m - x).squaredNorm() <= r2;
    if (near) continue;
    HotSpot spot;
    spot.body = env.body;
    spot.node = c.node;
    spot.position_m = x;
    spot.step = env.max_step[size_t(c.node)];
    spot.time_s = env.time_of(c.node);
    spot.value = c.value;
    const auto holding = [&](const std::vector<std::pair<std::string, std::vector<fem::Index>>>& sets) {
      for (const auto& [name, nodes] : sets)
        if (std::binary_search(nodes.begin(), nodes.end(), c.node)) return name;
      return std::string();
    };
    spot.solid = holding(env.solid_nodes);
    spot.seam = holding(env.seam_nodes);
    spots.push_back(spot);
    spot_body.push_back(c.body);
  }
  return spots;
}

}  // namespace kinetofem::post
