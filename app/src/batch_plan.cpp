// The plan of a batch: case files and their sweeps expanded into named runs,
// each with its overrides and content hash.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/app/case_file.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/version.hpp"

namespace kinetofem::app {

namespace {

using Type = KeySpec::Type;

// The keys the batch reads; every other key is left to `kinetofem run`.
std::vector<KeySpec> plan_schema() {
  return {
      case_name_key(),
      {.path = "case.type", .type = Type::String},
      {.path = "geometry.file", .type = Type::String},
      {.path = "sweep.parameters", .type = Type::StringList},
      {.path = "sweep.values", .type = Type::Array},
      {.path = "sweep.linspace", .type = Type::Array},
  };
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot read", file.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// One value of a swept parameter: as an override's TOML value and as a label
// in the run's name.
struct SweepValue {
  std::string toml;
  std::string label;
};

struct SweepAxis {
  std::string key;
  std::vector<SweepValue> values;
};

std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::string float_toml(double v) {
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // stays a float in TOML
  return text;
}

SweepValue sweep_value(const toml::node& node, const std::string& where) {
  if (node.is_integer()) {
    const auto v = *node.value<std::int64_t>();
    return {fmt::format("{}", v), fmt::format("{}", v)};
  }
  if (node.is_floating_point()) {
    const double v = *node.value<double>();
    return {float_toml(v), fmt::format("{:.6g}", v)};
  }
  if (node.is_string()) {
    const std::string v = *node.value<std::string>();
    return {toml_string(v), v};
  }
  if (node.is_boolean()) {
    const bool v = *node.value<bool>();
    return {v ? "true" : "false", v ? "true" : "false"};
  }
  fail("{}: a swept value must be a number, a string or true/false", where);
}

// The axes of the case's [sweep] (empty if it has none).
std::vector<SweepAxis> sweep_axes(const CaseFile& c) {
  if (!c.has("sweep.parameters")) {
    require(!c.has("sweep.values") && !c.has("sweep.linspace"), "{}: [sweep] needs parameters = [\"KEY\", ...]",
            c.where("sweep.values"));
    return {};
  }
  const std::vector<std::string> keys = c.strings("sweep.parameters");
  require(!keys.empty(), "{}: is empty: name at least one key to sweep", c.where("sweep.parameters"));
  const auto* values = c.has("sweep.values") ? c.node("sweep.values")->as_array() : nullptr;
  const auto* linspace = c.has("sweep.linspace") ? c.node("sweep.linspace")->as_array() : nullptr;
  require(values || linspace, "{}: [sweep] needs values = [[...], ...] or linspace = [[start, stop, count], ...]",
          c.where("sweep.parameters"));
  const auto require_one_per_parameter = [&](const toml::array* array, const char* key) {
    if (array)
      require(array->size() == keys.size(), "{} has {} entries: one per parameter is needed ({})", c.where(key),
              array->size(), keys.size());
  };
  require_one_per_parameter(values, "sweep.values");
  require_one_per_parameter(linspace, "sweep.linspace");

  std::vector<SweepAxis> axes;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    SweepAxis axis{keys[i], {}};
    const auto* listed = values ? (*values)[i].as_array() : nullptr;
    const auto* spaced = linspace ? (*linspace)[i].as_array() : nullptr;
    if (values) require(listed, "{}: entry {} must be an array of values", c.where("sweep.values"), i);
    if (linspace) require(spaced, "{}: entry {} must be [start, stop, count]", c.where("sweep.linspace"), i);
    const bool from_values = listed && !listed->empty();
    const bool from_linspace = spaced && !spaced->empty();
    require(from_values != from_linspace,
            "{}: parameter '{}' needs its values in exactly one of sweep.values and sweep.linspace (the other "
            "entry empty: [])",
            c.where("sweep.parameters"), keys[i]);
    if (from_values) {
      for (const auto& node : *listed)
        axis.values.push_back(sweep_value(node, c.where("sweep.values") + fmt::format(" (entry {})", i)));
    } else {
      const std::string at = c.where("sweep.linspace") + fmt::format(" (entry {}, '{}')", i, keys[i]);
      require(spaced->size() == 3 && (*spaced)[0].is_number() && (*spaced)[1].is_number() &&
                  (*spaced)[2].is_integer(),
              "{}: must be [start, stop, count] (count an integer)", at);
      const double start = *(*spaced)[0].value<double>(), stop = *(*spaced)[1].value<double>();
      const auto count = *(*spaced)[2].value<std::int64_t>();
      require(count >= 1 && count <= 100000, "{}: count = {} must be between 1 and 100000", at, count);
      for (std::int64_t k = 0; k < count; ++k) {
        const double v = count == 1 ? start : start + (stop - start) * double(k) / double(count - 1);
        axis.values.push_back({float_toml(v), fmt::format("{:.6g}", v)});
      }
    }
    axes.push_back(std::move(axis));
  }
  return axes;
}

// A run's name may become a file name: keep it to letters, digits and ._+-=
std::string file_safe(const std::string& text) {
  std::string out;
  for (char ch : text)
    out += (std::isalnum(static_cast<unsigned char>(ch)) || std::string("._+-=").find(ch) != std::string::npos)
               ? ch
               : '_';
  return out;
}

BatchRun make_run(const std::filesystem::path& case_path, const std::string& text, std::string name,
                  std::vector<std::string> overrides) {
  // Re-read with the run's overrides: they may change geometry.file.
  const CaseFile c = CaseFile::parse(text, case_path, plan_schema(), /*allow_unknown=*/true, overrides);
  std::vector<std::filesystem::path> referenced;
  if (c.has("geometry.file")) referenced.push_back(case_path.parent_path() / c.text_value("geometry.file"));
  BatchRun run;
  run.name = std::move(name);
  run.case_path = case_path;
  run.overrides = std::move(overrides);
  run.hash = run_hash(run.name, text, referenced, run.overrides);
  return run;
}

// A batch larger than kMaxBatchRuns: refused as a whole, not one failed run.
struct PlanTooLarge : Error {
  using Error::Error;
};

// The runs of a sweep, from its counts before any is made; PlanTooLarge if
// they and the `planned` runs before them exceed kMaxBatchRuns. The product is
// compared by division, so that it cannot overflow.
std::size_t sweep_size(const std::vector<SweepAxis>& axes, std::size_t planned, const CaseFile& c) {
  const std::size_t room = kMaxBatchRuns - std::min(planned, kMaxBatchRuns);
  std::size_t count = 1;
  bool too_many = false;
  std::string counts;
  double product = 1.0;  // for the message only
  for (const auto& axis : axes) {
    const std::size_t n = axis.values.size();
    too_many = too_many || (n > 0 && count > room / n);
    if (!too_many) count *= n;
    product *= double(n);
    counts += (counts.empty() ? "" : " x ") + fmt::format("{}", n);
  }
  if (too_many || count > room)
    throw PlanTooLarge(fmt::format(
        "{}: [sweep] gives {} runs{}, more than the {} a batch may plan: sweep fewer values or split the batch",
        c.where("sweep.parameters"), axes.size() > 1 ? fmt::format("{} = {:g}", counts, product) : counts,
        planned > 0 ? fmt::format(" after the {} run(s) of the cases before it", planned) : std::string(),
        kMaxBatchRuns));
  return count;
}

void plan_case(const std::filesystem::path& case_path, const std::vector<std::string>& overrides,
               std::vector<BatchRun>& runs) {
  const std::string problem = input_file_problem(case_path);
  require(problem.empty(), "{}: {}", case_path.string(),
          problem == "no such file" ? std::string("case file does not exist") : problem + ", expected a case file");
  const std::string text = read_bytes(case_path);
  const CaseFile c = CaseFile::parse(text, case_path, plan_schema(), /*allow_unknown=*/true, overrides);
  const std::string base = case_name(c);
  const std::vector<SweepAxis> axes = sweep_axes(c);
  if (axes.empty()) {
    if (runs.size() >= kMaxBatchRuns)
      throw PlanTooLarge(fmt::format("{}: the batch would have more than the {} runs it may plan: split it",
                                     case_path.string(), kMaxBatchRuns));
    runs.push_back(make_run(case_path, text, base, overrides));
    return;
  }
  runs.reserve(runs.size() + sweep_size(axes, runs.size(), c));
  // Labels: the key's last part, unless two swept keys share it.
  std::vector<std::string> labels;
  for (const auto& axis : axes) labels.push_back(axis.key.substr(axis.key.rfind('.') + 1));
  for (std::size_t i = 0; i < axes.size(); ++i)
    for (std::size_t j = 0; j < axes.size(); ++j)
      if (i != j && labels[i] == axes[j].key.substr(axes[j].key.rfind('.') + 1)) labels[i] = axes[i].key;

  // Cartesian product, the last parameter varying fastest.
  std::vector<std::size_t> index(axes.size(), 0);
  while (true) {
    std::string name = base;
    std::vector<std::string> point = overrides;
    for (std::size_t i = 0; i < axes.size(); ++i) {
      const SweepValue& v = axes[i].values[index[i]];
      name += "__" + labels[i] + "=" + v.label;
      point.push_back(axes[i].key + "=" + v.toml);
    }
    name = file_safe(name);
    check_file_name(name, c.path().string() + ": the run name made of case.name and a [sweep] point");
    point.push_back("case.name=" + toml_string(name));
    runs.push_back(make_run(case_path, text, name, point));
    std::size_t k = axes.size();
    while (k > 0 && ++index[k - 1] == axes[k - 1].values.size()) index[--k] = 0;
    if (k == 0) break;
  }
}

}  // namespace

std::string run_hash(const std::string& name, const std::string& case_text,
                     const std::vector<std::filesystem::path>& referenced_files,
                     const std::vector<std::string>& overrides) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a 64
  // Each field is length-prefixed so that moving text between fields changes the hash.
  const auto add = [&h](const std::string& field) {
    const std::string framed = fmt::format("{}:", field.size()) + field;
    for (unsigned char ch : framed) {
      h ^= ch;
      h *= 1099511628211ull;
    }
  };
  add(kVersion);
  add(kGitCommit);
  add(name);
  add(case_text);
  for (const auto& file : referenced_files) {
    std::error_code ec;
    add(file.filename().string());
    add(std::filesystem::is_regular_file(file, ec) ? read_bytes(file) : std::string("<missing>"));
  }
  for (const auto& o : overrides) add(o);
  return fmt::format("{:016x}", h);
}

std::vector<BatchRun> plan_batch(const std::vector<std::filesystem::path>& cases,
                                 const std::vector<std::string>& overrides) {
  std::vector<BatchRun> runs;
  for (const auto& case_path : cases) {
    try {
      plan_case(case_path, overrides, runs);
    } catch (const PlanTooLarge&) {
      throw;
    } catch (const Error& e) {
      BatchRun run;
      run.name = file_safe(default_case_name(case_path));
      try {
        check_file_name(run.name, case_path.string());
      } catch (const Error&) {
        run.name = "unnamed_case";  // its log still needs a file name
      }
      run.case_path = case_path;
      run.overrides = overrides;
      run.plan_error = e.what();
      runs.push_back(run);
    }
  }
  std::map<std::string, std::filesystem::path> seen;
  for (const auto& run : runs) {
    const auto [it, inserted] = seen.emplace(run.name, run.case_path);
    require(inserted,
            "two runs are named '{}' ({} and {}): their results would overwrite each other; give each case its own "
            "case.name",
            run.name, it->second.string(), run.case_path.string());
  }
  return runs;
}

}  // namespace kinetofem::app
