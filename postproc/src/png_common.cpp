#include "png_common.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::post::drawing {

std::string case_name(const ResultsFile& results, const PictureOptions& options) {
  return options.title_name.empty() ? results.path().stem().string() : options.title_name;
}

double round_down_125(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x))), f = x / mag;
  return (f >= 5 ? 5.0 : f >= 2 ? 2.0 : 1.0) * mag;
}

double nearest_125(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x))), f = x / mag;
  return (f < std::sqrt(2.0) ? 1.0 : f < std::sqrt(10.0) ? 2.0 : f < std::sqrt(50.0) ? 5.0 : 10.0) * mag;
}

bool is_assembly_body(const std::string& body) {
  return body.rfind(std::string_view(layout::kAssemblyBodyPrefix), 0) == 0;
}

std::string value_text(double v) {
  return v == 0.0 || std::abs(v) >= 0.01 ? fmt::format("{:.2f}", v) : fmt::format("{:.3e}", v);
}

std::string mm_text(double metres) {
  const double mm = metres * 1e3;
  const int decimals = mm > 0 ? std::clamp(2 - int(std::floor(std::log10(mm))), 2, 6) : 2;
  return fmt::format("{:.{}f} mm", mm, decimals);
}

std::string point_history(const std::string& point, const std::string& what) {
  return layout::kAssemblyPointPrefix + point + "." + what;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? std::string("none") : s;
}

size_t nearest_index(const std::vector<double>& times, double t) {
  size_t k = 0;
  for (size_t i = 1; i < times.size(); ++i)
    if (std::abs(times[i] - t) < std::abs(times[k] - t)) k = i;
  return k;
}

size_t argmax(const Eigen::VectorXd& v) {
  Eigen::Index i = 0;
  v.maxCoeff(&i);
  return size_t(i);
}

std::optional<TimeHistory> point_magnitude(const ResultsFile& results, const std::string& point) {
  const auto histories = results.histories();
  if (has(histories, point_history(point, "displacement_magnitude")))
    return mechanism_history(results, point_history(point, "displacement_magnitude"));
  if (!has(histories, point_history(point, "displacement"))) return std::nullopt;
  TimeHistory h = mechanism_history(results, point_history(point, "displacement"));
  h.values = FieldMatrix(h.magnitude());
  return h;
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace kinetofem::post::drawing
