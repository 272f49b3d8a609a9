#include "kinetofem/postproc/vibration_results.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::post {

namespace {

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? std::string("none") : s;
}

// A table that must be there, rows x columns (rows < 0: any), in `units`.
FieldData table(const ResultsFile& results, const std::string& name, Eigen::Index rows, Eigen::Index columns,
                const std::string& units) {
  require(has(results.tables(), name), "'{}' has no table {} (vibration tables: {})", results.path().string(), name,
          [&] {
            std::vector<std::string> present;
            for (const auto& t : results.tables())
              if (starts_with(t, "vibration.")) present.push_back(t);
            return joined(present);
          }());
  FieldData d = results.read_table(name);
  require((rows < 0 || d.values.rows() == rows) && d.values.cols() == columns && d.units == units,
          "'{}': table {} is {} x {} in '{}', expected {} x {} in '{}'", results.path().string(), name, d.values.rows(),
          d.values.cols(), d.units, rows < 0 ? std::string("n") : std::to_string(rows), columns, units);
  return d;
}

double scalar(const ResultsFile& results, const std::string& name, const std::string& units) {
  return table(results, name, 1, 1, units).values(0, 0);
}

}  // namespace

bool is_vibration_body(const std::string& body) { return starts_with(body, layout::kVibrationBodyPrefix); }

VibrationContents vibration_contents(const ResultsFile& results) {
  VibrationContents c;
  c.frequencies = has(results.histories(), layout::kVibrationFrequency);
  const std::vector<std::string> tables = results.tables();
  c.static_frequencies = has(tables, layout::kVibrationStaticFrequency);
  const std::string prefix = layout::kVibrationResponsePointPrefix, suffix = ".displacement";
  for (const auto& name : tables)
    if (name.size() > prefix.size() + suffix.size() && starts_with(name, prefix) &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      c.points.push_back(name.substr(prefix.size(), name.size() - prefix.size() - suffix.size()));
  for (const auto& body : results.bodies())
    if (is_vibration_body(body)) c.bodies.push_back(body);
  return c;
}

NaturalFrequencies read_natural_frequencies(const ResultsFile& results) {
  const std::string file = results.path().string();
  require(has(results.histories(), layout::kVibrationFrequency),
          "'{}' has no history {} (no vibration over the motion in this run)", file, layout::kVibrationFrequency);
  NaturalFrequencies f;
  f.time_s = results.mechanism_time();
  const FieldData d = results.read_history(layout::kVibrationFrequency);
  require(d.units == "Hz" && d.values.cols() >= 1 && d.values.rows() >= 1 && d.values.rows() == Eigen::Index(f.time_s.size()),
          "'{}': history {} is {} x {} in '{}', expected T_m = {} rows of m >= 1 frequencies in Hz", file,
          layout::kVibrationFrequency, d.values.rows(), d.values.cols(), d.units, f.time_s.size());
  f.hz = d.values;
  Eigen::Index low = 0, high = 0;
  f.lowest_first_hz = f.hz.col(0).minCoeff(&low);
  f.highest_first_hz = f.hz.col(0).maxCoeff(&high);
  f.lowest_first_time_s = f.time_s[size_t(low)];
  f.highest_first_time_s = f.time_s[size_t(high)];
  if (has(results.tables(), layout::kVibrationStaticFrequency)) {
    const FieldData s = table(results, layout::kVibrationStaticFrequency, -1, 1, "Hz");
    f.static_hz.assign(s.values.data(), s.values.data() + s.values.size());
  }
  return f;
}

PointVibrationData read_point_vibration(const ResultsFile& results, const std::string& point) {
  const std::string file = results.path().string();
  const std::string response = layout::kVibrationResponsePointPrefix + point;
  require(has(results.tables(), response + ".displacement"),
          "'{}' has no table {}.displacement (points with a vibration response: {})", file, response,
          joined(vibration_contents(results).points));
  PointVibrationData p;
  p.point = point;
  const FieldData t = table(results, layout::kVibrationResponseTime, -1, 1, "s");
  const Eigen::Index n = t.values.rows();
  require(n >= 2, "'{}': table {} has {} times; a response needs 2", file, layout::kVibrationResponseTime, n);
  p.time_s.assign(t.values.data(), t.values.data() + n);
  p.stop_time_s = scalar(results, layout::kVibrationStopTime, "s");
  p.dynamic_m = table(results, response + ".displacement", n, 3, "m").values;
  p.quasi_static_m = table(results, response + ".quasi_static", n, 3, "m").values;
  const std::string scalars = layout::kVibrationPointPrefix + point;
  p.settling_time_s = scalar(results, scalars + ".settling_time", "s");
  p.settling_tolerance_m = scalar(results, scalars + ".settling_tolerance", "m");
  p.amplitude_at_stop_m = scalar(results, scalars + ".amplitude_at_stop", "m");
  p.dynamic_amplification = scalar(results, scalars + ".dynamic_amplification", layout::kDimensionless);
  p.damping_ratio = has(results.tables(), layout::kVibrationDampingRatio)
                        ? scalar(results, layout::kVibrationDampingRatio, layout::kDimensionless)
                        : std::numeric_limits<double>::quiet_NaN();
  // Peaks over the stroke (t <= stop time), first on a tie.
  for (Eigen::Index k = 0; k < n && p.time_s[size_t(k)] <= p.stop_time_s + 1e-9; ++k) {
    const double d = p.dynamic_m.row(k).norm(), q = p.quasi_static_m.row(k).norm();
    if (d > p.peak_dynamic_m) p.peak_dynamic_m = d, p.peak_dynamic_time_s = p.time_s[size_t(k)];
    if (q > p.peak_quasi_static_m) p.peak_quasi_static_m = q, p.peak_quasi_static_time_s = p.time_s[size_t(k)];
  }
  return p;
}

}  // namespace kinetofem::post
