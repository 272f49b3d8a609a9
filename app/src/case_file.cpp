#include "kinetofem/app/case_file.hpp"

#include <cmath>
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

std::string range_text(const KeySpec& s) {
  std::string lo = s.min > -1e299 ? fmt::format("{}{:g}", s.min_exclusive ? ">" : ">=", s.min) : "";
  std::string hi = s.max < 1e299 ? fmt::format("<={:g}", s.max) : "";
  if (lo.empty() && hi.empty()) return "";
  return lo + (lo.empty() || hi.empty() ? "" : " and ") + hi;
}

}  // namespace

CaseFile CaseFile::load(const std::filesystem::path& path, std::vector<KeySpec> schema,
                        bool allow_unknown) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: case file does not exist", path.string());
  if (std::filesystem::is_directory(path, ec))
    fail("{}: is a directory, expected a case file (case.toml)", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open case file", path.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path, std::move(schema), allow_unknown);
}

CaseFile CaseFile::parse(const std::string& text, const std::filesystem::path& path,
                         std::vector<KeySpec> schema, bool allow_unknown) {
  CaseFile c;
  c.allow_unknown_ = allow_unknown;
  c.path_ = path;
  c.text_ = text;
  c.schema_ = std::move(schema);
  try {
    c.root_ = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    const auto& src = e.source();
    fail("{}:{}:{}: TOML syntax error: {}", path.string(), src.begin.line, src.begin.column,
         std::string(e.description()));
  }
  c.check_table(c.root_, "");
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
      check_value(*found, node, path);
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

void CaseFile::check_value(const KeySpec& s, const toml::node& node, const std::string& shown) const {
  const auto line = node.source().begin.line;
  const std::string at = fmt::format("{}:{}: key '{}'", path_.string(), line, shown);
  auto check_number = [&](double v) {
    if (!std::isfinite(v)) fail("{} = {} is not a finite number", at, v);
    const bool low = s.min_exclusive ? !(v > s.min) : !(v >= s.min);
    if (low || v > s.max)
      fail("{} = {:g}{} is out of range: must be {}{}", at, v, s.unit.empty() ? "" : " " + s.unit,
           range_text(s), s.unit.empty() ? "" : " " + s.unit);
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
  }
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

std::string CaseFile::where(const std::string& path, std::size_t element) const {
  const auto* node = find(path, element);
  std::string shown = path;
  const auto bracket = shown.find("[]");
  if (bracket != std::string::npos) shown.replace(bracket, 2, fmt::format("[{}]", element));
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
  std::string current_table;
  for (const auto& s : schema) {
    if (s.type == KeySpec::Type::TableArray) continue;
    const auto dot = s.path.rfind('.');
    std::string table = dot == std::string::npos ? "" : s.path.substr(0, dot);
    const std::string key = dot == std::string::npos ? s.path : s.path.substr(dot + 1);
    if (table != current_table) {
      const bool array = table.size() > 2 && table.substr(table.size() - 2) == "[]";
      out += array ? "\n[[" + table.substr(0, table.size() - 2) + "]]\n" : "\n[" + table + "]\n";
      current_table = table;
    }
    std::string info = s.doc;
    if (!s.unit.empty()) info += "; unit: " + s.unit;
    const std::string range = range_text(s);
    if (!range.empty()) info += "; " + range;
    if (!s.allowed.empty()) info += "; one of " + join(s.allowed);
    if (s.required) info += "; required";
    out += "# " + info + "\n";
    std::string value;
    if (s.default_number) {
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
  return out;
}

}  // namespace kinetofem::app
