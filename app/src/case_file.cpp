#include "kinetofem/app/case_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <new>

#include <unistd.h>
#include <fstream>
#include <sstream>

#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

namespace {

std::string type_name(KeySpec::Type type) {
  switch (type) {
    case KeySpec::Type::Number: return "a number";
    case KeySpec::Type::Integer: return "an integer";
    case KeySpec::Type::String: return "a string";
    case KeySpec::Type::Boolean: return "true or false";
    case KeySpec::Type::Vector3: return "an array of 3 numbers";
    case KeySpec::Type::StringList: return "an array of strings";
    case KeySpec::Type::TableArray: return "an array of tables ([[...]])";
    case KeySpec::Type::Array: return "an array";
  }
  return "?";
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + ("\"" + item + "\"");
  return out;
}

std::optional<double> numeric(const toml::node& node) {
  if (auto v = node.value<double>()) return *v;  // integers convert too
  return std::nullopt;
}

// A name as written in a message: at most 40 bytes, a control character (NUL
// included) escaped as TOML writes it, so that the message stays one line.
std::string shown_name(const std::string& name) {
  std::string out;
  for (std::size_t k = 0; k < name.size() && k < 40; ++k) {
    const auto ch = static_cast<unsigned char>(name[k]);
    out += ch < 0x20 || ch == 0x7f ? fmt::format("\\u{:04X}", unsigned(ch)) : std::string(1, name[k]);
  }
  return name.size() > 40 ? out + "..." : out;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// One segment of an override's key: "support[1]" -> {"support", 1}.
struct KeySegment {
  std::string name;
  std::optional<std::size_t> index;
};

}  // namespace

std::pair<std::string, std::string> split_override(const std::string& text) {
  const auto eq = text.find('=');
  const std::string key = eq == std::string::npos ? "" : trim(text.substr(0, eq));
  if (key.empty())
    fail("--set {}: expected KEY=VALUE (e.g. --set mesh.element_size_mm=20)", text);
  return {key, trim(text.substr(eq + 1))};
}

std::string range_text(const KeySpec& s, std::optional<double> value) {
  const bool min_declared = s.min > -1e300, max_declared = s.max < 1e300;
  const bool below = value && (s.min_exclusive ? !(*value > s.min) : !(*value >= s.min));
  const bool above = value && *value > s.max;
  const std::string lo =
      min_declared || below ? fmt::format("{}{:g}", s.min_exclusive ? ">" : ">=", s.min) : std::string();
  const std::string hi = max_declared || above ? fmt::format("<={:g}", s.max) : std::string();
  if (lo.empty() && hi.empty()) return "";
  std::string text = lo + (lo.empty() || hi.empty() ? "" : " and ") + hi;
  if (s.zero_allowed) text = "0, or " + text;
  if (!s.unit.empty()) text += " " + s.unit;
  if (!s.range_note.empty()) text += " (" + s.range_note + ")";
  return text;
}

KeySpec plausible_range(KeySpec s) {
  struct Plausible {
    const char* unit;
    double max;  // largest magnitude, in that unit
    const char* note;
  };
  // Beyond any machine this program models, and far from overflow in the
  // products the solvers form (F / (E A), m a, k x, ...).
  static constexpr Plausible kTable[] = {
      {"kg", 1e6, "a plausible mass: up to 1000 t"},
      {"kg*m^2", 1e6, "a plausible moment of inertia"},
      {"N", 1e9, "a plausible force: up to 1 GN"},
      {"N*m", 1e9, "a plausible torque: up to 1 GN*m"},
      {"MPa", 1e7, "a plausible stress or modulus: up to 10 TPa, above diamond's Young's modulus"},
      {"m/s^2", 1e4, "a plausible acceleration: up to 1000 g"},
      {"s", 1e7, "a plausible time: up to about 4 months"},
      {"h", 1e7, "a plausible time: up to about 1100 years"},
      {"1/h", 1e9, "a plausible rate"},
      {"mm", 1e6, "a plausible length: up to 1 km"},
      {"mm/s", 1e7, "a plausible speed: up to 10 km/s"},
      {"m/s", 1e4, "a plausible speed: up to 10 km/s"},
      {"deg/s", 1e7, "a plausible angular speed"},
      {"rpm", 1e6, "a plausible angular speed"},
      {"N/m", 1e12, "a plausible stiffness"},
      {"N*s/m", 1e12, "a plausible damping"},
      {"N*m/rad", 1e12, "a plausible stiffness"},
      {"N*m*s/rad", 1e12, "a plausible damping"},
      {"Hz", 1e9, "a plausible frequency"},
      {"GB", 1e6, "a plausible memory size"},
  };
  if (s.type != KeySpec::Type::Number && s.type != KeySpec::Type::Vector3 && s.type != KeySpec::Type::Array)
    return s;
  for (const Plausible& p : kTable) {
    if (s.unit != p.unit) continue;
    const bool changed = s.max >= 1e300 || s.min <= -1e300;
    if (s.max >= 1e300) s.max = p.max;
    if (s.min <= -1e300) s.min = -p.max;
    if (changed && s.range_note.empty()) s.range_note = p.note;
    break;
  }
  return s;
}

void check_file_name(const std::string& name, const std::string& at) {
  const auto refuse = [&](const std::string& why) {
    fail("{} = \"{}\" cannot be a file name in the output folder: {}", at, shown_name(name), why);
  };
  if (name.empty()) refuse("it is empty");
  if (name == "." || name == "..") refuse("\".\" and \"..\" name folders");
  for (std::size_t k = 0; k < name.size(); ++k) {
    const auto ch = static_cast<unsigned char>(name[k]);
    if (ch == '/' || ch == '\\')
      refuse(fmt::format("it holds the path separator '{}' (byte {})", char(ch), k));
    if (ch < 0x20 || ch == 0x7f)
      refuse(fmt::format("it holds the control character U+{:04X} (byte {})", unsigned(ch), k));
  }
  if (name.size() > kMaxRunNameBytes)
    refuse(fmt::format("it has {} bytes, more than {}", name.size(), kMaxRunNameBytes));
}

KeySpec case_name_key() {
  return {.path = "case.name", .type = KeySpec::Type::String,
          .doc = "name of the run; results/<name>.h5 (default: the case folder's name)", .file_name = true};
}

std::string default_case_name(const std::filesystem::path& case_path) {
  // Normalised first: "../case.toml" is in the folder above, not in one named "..".
  // (absolute() fails only without a current directory: the name then comes from the path as given.)
  std::error_code ec;
  const std::filesystem::path full = std::filesystem::absolute(case_path, ec);
  return (ec ? case_path : full).lexically_normal().parent_path().filename().string();
}

std::string case_name(const CaseFile& c) {
  if (c.has("case.name")) {
    const std::string name = c.text_value("case.name");
    check_file_name(name, c.where("case.name"));
    return name;
  }
  const std::string name = default_case_name(c.path());
  check_file_name(name, fmt::format("{}: the case folder's name (the run's name when case.name is absent)",
                                    c.path().string()));
  return name;
}

namespace {

std::vector<KeySegment> key_segments(const std::string& key, const std::string& shown) {
  std::vector<KeySegment> out;
  std::stringstream in(key);
  for (std::string part; std::getline(in, part, '.');) {
    KeySegment segment;
    const auto open = part.find('[');
    segment.name = part.substr(0, open);
    if (open != std::string::npos) {
      const auto close = part.find(']', open);
      const std::string digits = close == std::string::npos ? "" : part.substr(open + 1, close - open - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
          close + 1 != part.size())
        fail("{}: key '{}': an element of an array of tables is written name[INDEX] (e.g. force[0].total_n)",
             shown, key);
      segment.index = std::stoul(digits);
    }
    if (segment.name.empty()) fail("{}: key '{}' has an empty part", shown, key);
    out.push_back(segment);
  }
  if (out.empty()) fail("{}: empty key", shown);
  return out;
}

}  // namespace

std::string input_file_problem(const std::filesystem::path& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (ec == std::errc::too_many_symbolic_link_levels) return "is a symlink loop";
  if (st.type() == fs::file_type::not_found) {
    std::error_code link_ec;
    return fs::is_symlink(fs::symlink_status(file, link_ec)) ? "no such file (a symlink to nothing)" : "no such file";
  }
  if (ec) return "cannot be read: " + ec.message();
  if (fs::is_directory(st)) return "is a directory";
  if (fs::is_fifo(st)) return "is not a regular file (a FIFO)";
  if (fs::is_socket(st)) return "is not a regular file (a socket)";
  if (fs::is_block_file(st) || fs::is_character_file(st)) return "is not a regular file (a device)";
  if (!fs::is_regular_file(st)) return "is not a regular file";
  if (::access(file.c_str(), R_OK) != 0) return fmt::format("cannot be read: {}", std::strerror(errno));
  return "";
}

CaseFile CaseFile::load(const std::filesystem::path& path, std::vector<KeySpec> schema,
                        bool allow_unknown, const std::vector<std::string>& overrides) {
  const std::string problem = input_file_problem(path);
  if (problem == "no such file") fail("{}: case file does not exist", path.string());
  if (problem == "is a directory") fail("{}: is a directory, expected a case file (case.toml)", path.string());
  if (!problem.empty()) fail("{}: {}, expected a case file (case.toml)", path.string(), problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open case file", path.string());
  std::stringstream buffer;
  try {
    buffer << in.rdbuf();
    return parse(buffer.str(), path, std::move(schema), allow_unknown, overrides);
  } catch (const std::bad_alloc&) {
    std::error_code ec;
    fail("{}: not enough memory to read the case file ({} bytes)", path.string(), std::filesystem::file_size(path, ec));
  }
}

CaseFile CaseFile::parse(const std::string& text, const std::filesystem::path& path,
                         std::vector<KeySpec> schema, bool allow_unknown,
                         const std::vector<std::string>& overrides) {
  CaseFile c;
  c.allow_unknown_ = allow_unknown;
  c.path_ = path;
  c.text_ = text;
  c.schema_ = std::move(schema);
  for (auto& s : c.schema_) s = plausible_range(std::move(s));
  try {
    c.root_ = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    fail("{}:{}:{}: TOML syntax error: {}", path.string(), src.begin.line, src.begin.column,
         std::string(e.description()));
  }
  c.check_table(c.root_, "");
  for (const auto& o : overrides) c.apply_override(o);
  for (const auto& s : c.schema_)
    if (s.required && s.path.find("[]") == std::string::npos && !c.find(s.path, 0))
      fail("{}: required key '{}' is missing ({})", path.string(), s.path, s.doc);
  return c;
}

void CaseFile::check_table(const toml::table& table, const std::string& prefix) const {
  for (const auto& [key, node] : table) {
    const std::string path = prefix + std::string(key.str());
    const KeySpec* found = nullptr;
    bool is_parent = false;
    for (const auto& s : schema_) {
      if (s.path == path) found = &s;
      if (s.path.rfind(path + ".", 0) == 0 || s.path.rfind(path + "[].", 0) == 0) is_parent = true;
    }
    const auto line = node.source().begin.line;
    if (found && found->type == KeySpec::Type::TableArray) {
      const auto* array = node.as_array();
      if (!array || !array->is_array_of_tables())
        fail("{}:{}: key '{}' must be an array of tables ([[{}]])", path_.string(), line, path,
             path);
      for (const auto& element : *array) check_table(*element.as_table(), path + "[].");
      continue;
    }
    if (found) {
      check_value(*found, node,
                  fmt::format("{}:{}: key '{}'", path_.string(), node.source().begin.line, path));
      continue;
    }
    if (is_parent && node.is_table()) {
      check_table(*node.as_table(), path + ".");
      continue;
    }
    if (allow_unknown_) continue;
    std::vector<std::string> siblings;
    for (const auto& s : schema_)
      if (s.path.rfind(prefix, 0) == 0) {
        const std::string rest = s.path.substr(prefix.size());
        const std::string first = rest.substr(0, rest.find_first_of(".["));
        if (std::find(siblings.begin(), siblings.end(), first) == siblings.end())
          siblings.push_back(first);
      }
    fail("{}:{}: unknown key '{}' (allowed here: {})", path_.string(), line, path,
         siblings.empty() ? std::string("none") : join(siblings));
  }
}

void CaseFile::apply_override(const std::string& text) {
  const std::string shown = "--set " + text;
  const auto [key, value] = split_override(text);
  const std::vector<KeySegment> segments = key_segments(key, shown);
  std::string schema_path;
  for (const auto& segment : segments)
    schema_path += (schema_path.empty() ? "" : ".") + segment.name + (segment.index ? "[]" : "");

  // The value as TOML; a bare word that is not TOML (--set mesh.family=hex) is a string.
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + value, std::string("--set"));
  } catch (const toml::parse_error&) {
    parsed = toml::table{};
  }
  if (parsed.size() != 1 || !parsed.contains("value")) {
    if (value.find_first_of("[]{}\"'=\n") != std::string::npos)
      fail("{}: the value '{}' is not a TOML value (number, \"string\", [array], true/false)", shown,
           value);
    parsed = toml::table{{"value", value}};
  }
  toml::node& new_value = *parsed.get("value");

  const KeySpec* found = nullptr;
  for (const auto& s : schema_)
    if (s.path == schema_path) found = &s;
  if (!found && !allow_unknown_) {
    // The keys of the same table if it exists, else every key.
    const std::string table = schema_path.substr(0, schema_path.rfind('.') + 1);
    std::string allowed, all;
    for (const auto& s : schema_) {
      if (s.type == KeySpec::Type::TableArray) continue;
      all += (all.empty() ? "" : ", ") + s.path;
      if (!table.empty() && s.path.rfind(table, 0) == 0) allowed += (allowed.empty() ? "" : ", ") + s.path;
    }
    fail("{}: unknown key '{}' (allowed: {})", shown, key, allowed.empty() ? all : allowed);
  }
  if (found && found->type == KeySpec::Type::TableArray)
    fail("{}: key '{}' is an array of tables: set one of its keys, e.g. {}[0].KEY", shown, key, key);
  if (found) check_value(*found, new_value, fmt::format("{}: key '{}'", shown, key));

  // Walk down to the parent table, creating tables that the file lacks.
  toml::table* table = &root_;
  for (std::size_t k = 0; k + 1 < segments.size(); ++k) {
    const KeySegment& segment = segments[k];
    toml::node* child = table->get(segment.name);
    if (segment.index) {
      auto* array = child ? child->as_array() : nullptr;
      const std::size_t size = array ? array->size() : 0;
      if (*segment.index >= size)
        fail("{}: key '{}': the case has {} [[{}]] element(s) (indices 0..{}); an override cannot add one",
             shown, key, size, segment.name, size == 0 ? std::string("none") : std::to_string(size - 1));
      table = (*array)[*segment.index].as_table();
      if (!table) fail("{}: key '{}': element {} of '{}' is not a table", shown, key, *segment.index, segment.name);
      continue;
    }
    if (!child) child = table->insert(segment.name, toml::table{}).first->second.as_table();
    if (!child->is_table())
      fail("{}: key '{}': '{}' is a value in the case file, not a table", shown, key, segment.name);
    table = child->as_table();
  }
  if (segments.back().index)
    fail("{}: key '{}': an index belongs to an array of tables, not to the last part of a key", shown, key);
  const toml::node* old = table->get(segments.back().name);
  if (old && old->is_table())
    fail("{}: key '{}' is a table in the case file: set one of its keys", shown, key);
  table->insert_or_assign(segments.back().name, std::move(new_value));
  override_texts_.push_back(text);
  override_keys_.push_back(key);
}

void CaseFile::check_value(const KeySpec& s, const toml::node& node, const std::string& at) const {
  auto check_number = [&](double v) {
    if (!std::isfinite(v)) fail("{} = {} is not a finite number", at, v);
    const bool low = s.min_exclusive ? !(v > s.min) : !(v >= s.min);
    if ((low || v > s.max) && !(s.zero_allowed && v == 0.0))
      fail("{} = {:g}{} is out of range: must be {}", at, v, s.unit.empty() ? "" : " " + s.unit,
           range_text(s, v));
  };
  switch (s.type) {
    case KeySpec::Type::Number: {
      auto v = node.is_number() ? numeric(node) : std::nullopt;
      if (!v) fail("{} must be {} (in {})", at, type_name(s.type), s.unit.empty() ? "-" : s.unit);
      check_number(*v);
      return;
    }
    case KeySpec::Type::Integer: {
      if (!node.is_integer()) fail("{} must be {}", at, type_name(s.type));
      check_number(double(*node.value<std::int64_t>()));
      return;
    }
    case KeySpec::Type::Boolean:
      if (!node.is_boolean()) fail("{} must be {}", at, type_name(s.type));
      return;
    case KeySpec::Type::String: {
      if (!node.is_string()) fail("{} must be {}", at, type_name(s.type));
      const std::string v = *node.value<std::string>();
      if (!s.allowed.empty() && std::find(s.allowed.begin(), s.allowed.end(), v) == s.allowed.end())
        fail("{} = \"{}\" is not allowed: use one of {}", at, v, join(s.allowed));
      if (s.file_name) check_file_name(v, at);
      return;
    }
    case KeySpec::Type::Vector3: {
      const auto* array = node.as_array();
      if (!array || array->size() != 3) fail("{} must be {}", at, type_name(s.type));
      for (const auto& element : *array) {
        auto v = element.is_number() ? numeric(element) : std::nullopt;
        if (!v) fail("{} must be {}", at, type_name(s.type));
        check_number(*v);
      }
      return;
    }
    case KeySpec::Type::StringList: {
      const auto* array = node.as_array();
      if (!array) fail("{} must be {}", at, type_name(s.type));
      for (const auto& element : *array) {
        if (!element.is_string()) fail("{} must be {}", at, type_name(s.type));
        const std::string v = *element.value<std::string>();
        if (!s.allowed.empty() &&
            std::find(s.allowed.begin(), s.allowed.end(), v) == s.allowed.end())
          fail("{} holds \"{}\": use only {}", at, v, join(s.allowed));
      }
      return;
    }
    case KeySpec::Type::TableArray: return;
    case KeySpec::Type::Array:
      if (!node.is_array()) fail("{} must be {}", at, type_name(s.type));
      return;
  }
}

void CaseFile::check_number(const std::string& path, std::size_t element, double value) const {
  KeySpec s = spec(path);
  s.type = KeySpec::Type::Number;
  const toml::value<double> node(value);
  check_value(s, node, where(path, element));
}

const KeySpec& CaseFile::spec(const std::string& path) const {
  for (const auto& s : schema_)
    if (s.path == path) return s;
  fail("internal: key '{}' is not declared in the case schema", path);
}

const toml::node* CaseFile::find(const std::string& path, std::size_t element) const {
  const auto bracket = path.find("[].");
  if (bracket == std::string::npos) return root_.at_path(path).node();
  const auto* array = root_.at_path(path.substr(0, bracket)).as_array();
  if (!array || element >= array->size()) return nullptr;
  const auto* table = (*array)[element].as_table();
  return table ? table->at_path(path.substr(bracket + 3)).node() : nullptr;
}

bool CaseFile::has(const std::string& path, std::size_t element) const {
  return find(path, element) != nullptr;
}

bool CaseFile::departs_from_default(const std::string& path, std::size_t element) const {
  if (!has(path, element)) return false;
  const KeySpec& key = spec(path);
  return !(key.type == KeySpec::Type::Number && key.default_number &&
           number(path, element) == *key.default_number * key.to_si);
}

std::string CaseFile::where(const std::string& path, std::size_t element) const {
  const auto* node = find(path, element);
  std::string shown = path;
  const auto bracket = shown.find("[]");
  if (bracket != std::string::npos) shown.replace(bracket, 2, fmt::format("[{}]", element));
  for (std::size_t k = override_keys_.size(); k-- > 0;)
    if (override_keys_[k] == shown)
      return fmt::format("{}: key '{}' (--set {})", path_.string(), shown, override_texts_[k]);
  if (!node) return fmt::format("{}: key '{}'", path_.string(), shown);
  return fmt::format("{}:{}: key '{}'", path_.string(), node->source().begin.line, shown);
}

double CaseFile::number(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  if (const auto* node = find(path, element)) return *numeric(*node) * s.to_si;
  if (s.default_number) return *s.default_number * s.to_si;
  fail("{} is required ({}, in {})", where(path, element), s.doc, s.unit);
}

long CaseFile::integer(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  if (const auto* node = find(path, element)) return long(*node->value<std::int64_t>());
  if (s.default_number) return long(*s.default_number);
  fail("{} is required ({})", where(path, element), s.doc);
}

std::string CaseFile::text_value(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  if (const auto* node = find(path, element)) return *node->value<std::string>();
  if (s.default_text) return *s.default_text;
  fail("{} is required ({})", where(path, element), s.doc);
}

bool CaseFile::boolean(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  if (const auto* node = find(path, element)) return *node->value<bool>();
  if (s.default_number) return *s.default_number != 0.0;
  fail("{} is required ({})", where(path, element), s.doc);
}

Eigen::Vector3d CaseFile::vector3(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  if (const auto* node = find(path, element)) {
    const auto& array = *node->as_array();
    return Eigen::Vector3d(*numeric(array[0]), *numeric(array[1]), *numeric(array[2])) * s.to_si;
  }
  if (s.default_vector) return Eigen::Vector3d((*s.default_vector)[0], (*s.default_vector)[1], (*s.default_vector)[2]) * s.to_si;
  if (s.default_number) return Eigen::Vector3d::Constant(*s.default_number * s.to_si);
  fail("{} is required ({}, in {})", where(path, element), s.doc, s.unit);
}

std::vector<std::string> CaseFile::strings(const std::string& path, std::size_t element) const {
  const KeySpec& s = spec(path);
  std::vector<std::string> out;
  if (const auto* node = find(path, element)) {
    for (const auto& item : *node->as_array()) out.push_back(*item.value<std::string>());
    return out;
  }
  if (s.default_text) {
    std::stringstream in(*s.default_text);
    for (std::string item; std::getline(in, item, ',');) out.push_back(item);
    return out;
  }
  fail("{} is required ({})", where(path, element), s.doc);
}

std::size_t CaseFile::count(const std::string& array_path) const {
  const auto* array = root_.at_path(array_path).as_array();
  return array ? array->size() : 0;
}

std::string schema_template(const std::vector<KeySpec>& schema, const std::string& title) {
  std::string out = "# " + title + "\n# Every key with its unit, allowed values and default.\n";
  const auto table_of = [](const KeySpec& s) {
    const auto dot = s.path.rfind('.');
    return dot == std::string::npos ? std::string() : s.path.substr(0, dot);
  };
  // Each table once, in the order of its first key (a table's keys may be
  // declared in several places, e.g. [solver] by the case type and the shared
  // solver keys): TOML forbids defining a table twice.
  std::vector<std::string> tables;
  for (const auto& s : schema)
    if (s.type != KeySpec::Type::TableArray && std::find(tables.begin(), tables.end(), table_of(s)) == tables.end())
      tables.push_back(table_of(s));
  std::vector<KeySpec> plausible;
  for (const auto& s : schema) plausible.push_back(plausible_range(s));
  for (const auto& table : tables) {
    const bool array = table.size() > 2 && table.substr(table.size() - 2) == "[]";
    // A table inside an array's element ("transmission[].input") follows its
    // array's header, so TOML puts it in that last element: [transmission.input].
    std::string header = table;
    for (auto at = header.find("[]."); at != std::string::npos; at = header.find("[]."))
      header.erase(at, 2);
    out += array ? "\n[[" + table.substr(0, table.size() - 2) + "]]\n" : "\n[" + header + "]\n";
    for (const auto& s : plausible) {
      if (s.type == KeySpec::Type::TableArray || table_of(s) != table) continue;
      const auto dot = s.path.rfind('.');
      const std::string key = dot == std::string::npos ? s.path : s.path.substr(dot + 1);
      std::string info = s.doc;
      if (!s.unit.empty()) info += "; unit: " + s.unit;
      const std::string range = range_text(s);
      if (!range.empty()) info += "; range: " + range;
      if (!s.allowed.empty()) info += "; one of " + join(s.allowed);
      if (s.required) info += "; required";
      out += "# " + info + "\n";
      std::string value;
      if (s.default_vector) {
        value = fmt::format("[{:g}, {:g}, {:g}]", (*s.default_vector)[0], (*s.default_vector)[1], (*s.default_vector)[2]);
      } else if (s.default_number) {
        if (s.type == KeySpec::Type::Vector3)
          value = fmt::format("[{0:g}, {0:g}, {0:g}]", *s.default_number);
        else if (s.type == KeySpec::Type::Boolean)
          value = *s.default_number != 0 ? "true" : "false";
        else
          value = fmt::format("{:g}", *s.default_number);
      } else if (s.default_text) {
        if (s.type == KeySpec::Type::StringList) {
          std::stringstream in(*s.default_text);
          std::vector<std::string> items;
          for (std::string item; std::getline(in, item, ',');) items.push_back(item);
          value = "[" + join(items) + "]";
        } else {
          value = "\"" + *s.default_text + "\"";
        }
      }
      out += (value.empty() ? "# " + key + " = " : key + " = " + value) + "\n";
    }
  }
  return out;
}

}  // namespace kinetofem::app
