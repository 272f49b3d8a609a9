#include <cmath>

#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

double MechanismCaseSummary::value(const std::string& name) const {
  for (const auto& [key, v] : values)
    if (key == name) return v;
  fail("mechanism case summary of '{}' has no value '{}'", results_file.string(), name);
}

std::vector<KeySpec> mechanism_case_keys(const std::string& type) {
  using Type = KeySpec::Type;
  return {
      case_name_key(),
      {.path = "case.type", .type = Type::String, .allowed = {type}, .doc = "kind of analysis", .required = true},
      {.path = "case.description", .type = Type::String, .doc = "free text"},
  };
}

Log start_case_log(const CaseFile& c, const RunOptions& options, const std::string& name, const std::string& what) {
  Log log = job_log(options);
  log.info("kinetofem: case '{}' ({}), {}", name, c.path().string(), what);
  return log;
}

std::string mechanism_case_name(const CaseFile& c) {
  return case_name(c);
}

std::filesystem::path mechanism_results_path(const CaseFile&, const RunOptions& options,
                                             const std::string& name) {
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec) fail("{}: cannot create the output directory: {}", options.output_dir.string(), ec.message());
  return options.output_dir / (name + ".h5");
}

post::Provenance mechanism_provenance(const CaseFile& c, const RunOptions& options) {
  post::Provenance provenance;
  provenance.case_path = c.path().string();
  provenance.case_text = c.text();
  provenance.command_line = options.command_line;
  return provenance;
}

std::vector<double> read_numbers(const CaseFile& c, const std::string& path, std::size_t element, double to_si) {
  std::vector<double> out;
  const toml::node* node = c.node(path, element);
  if (!node) return out;
  const auto* array = node->as_array();
  require(array != nullptr, "{} must be an array of numbers", c.where(path, element));
  for (const auto& item : *array) {
    const auto v = item.is_number() ? item.value<double>() : std::nullopt;
    require(v && std::isfinite(*v), "{} must hold finite numbers only", c.where(path, element));
    c.check_number(path, element, *v);
    out.push_back(*v * to_si);
  }
  return out;
}

Eigen::Vector2d read_vector2(const CaseFile& c, const std::string& path, std::size_t element, double to_si,
                             const Eigen::Vector2d& fallback) {
  if (!c.has(path, element)) return fallback;
  const std::vector<double> v = read_numbers(c, path, element, to_si);
  require(v.size() == 2, "{} must be an array of 2 numbers [x, y], got {}", c.where(path, element), v.size());
  return {v[0], v[1]};
}

}  // namespace kinetofem::app
