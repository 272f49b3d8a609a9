#pragma once
// CaseFile — a TOML case file read against a schema.
//
// Every key a case may hold is declared once (KeySpec: path, type, unit and
// its factor to SI, default, allowed range or values, doc). Reading a case
// checks every key present against the schema: an unknown key, a value of the
// wrong type, out of range or not finite is an Error that names the file,
// line, key and value. Values are returned in SI units: a key declared in mm
// is multiplied by 1e-3 on reading.
//
// Paths use dots; elements of an array of tables are written `name[]`
// (e.g. "support[].set"), and getters take the element's index.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <toml++/toml.h>

namespace kinetofem::app {

struct KeySpec {
  enum class Type { Number, Integer, String, Boolean, Vector3, StringList, TableArray };
  std::string path;
  Type type = Type::Number;
  std::string unit;           // as written in the case file ("mm", "MPa", "N", ...)
  double to_si = 1.0;         // factor from the file's unit to SI
  std::optional<double> default_number;
  std::optional<std::string> default_text;
  double min = -1e300, max = 1e300;  // allowed range, in the file's unit
  bool min_exclusive = false;
  std::vector<std::string> allowed;  // allowed strings (String, StringList)
  std::string doc;
  bool required = false;
};

class CaseFile {
 public:
  // Parses the file and checks it against the schema. Throws Error for a
  // missing or unreadable file, a TOML syntax error (with line and column),
  // an unknown key or a bad value.
  // allow_unknown skips the unknown-key check (to read one key, e.g. case.type,
  // before the schema of the case's type is known).
  static CaseFile load(const std::filesystem::path& path, std::vector<KeySpec> schema,
                       bool allow_unknown = false);
  static CaseFile parse(const std::string& text, const std::filesystem::path& path,
                        std::vector<KeySpec> schema, bool allow_unknown = false);

  const std::filesystem::path& path() const { return path_; }
  const std::string& text() const { return text_; }

  bool has(const std::string& path, std::size_t element = 0) const;
  // SI value of a Number key (its default if absent; Error if required and absent).
  double number(const std::string& path, std::size_t element = 0) const;
  long integer(const std::string& path, std::size_t element = 0) const;
  std::string text_value(const std::string& path, std::size_t element = 0) const;
  bool boolean(const std::string& path, std::size_t element = 0) const;
  Eigen::Vector3d vector3(const std::string& path, std::size_t element = 0) const;
  std::vector<std::string> strings(const std::string& path, std::size_t element = 0) const;
  // Number of elements of an array of tables (0 if absent).
  std::size_t count(const std::string& array_path) const;

  // "file:line: key" for messages.
  std::string where(const std::string& path, std::size_t element = 0) const;

 private:
  const KeySpec& spec(const std::string& path) const;
  const toml::node* find(const std::string& path, std::size_t element) const;
  void check_table(const toml::table& table, const std::string& prefix) const;
  void check_value(const KeySpec& spec, const toml::node& node, const std::string& shown) const;

  std::filesystem::path path_;
  std::string text_;
  toml::table root_;
  std::vector<KeySpec> schema_;
  bool allow_unknown_ = false;
};

// A commented TOML template of a schema: every key with its doc, unit,
// range and default.
std::string schema_template(const std::vector<KeySpec>& schema, const std::string& title);

}  // namespace kinetofem::app
