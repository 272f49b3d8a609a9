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
//
// Overrides (`kinetofem run CASE --set key=value`): each "key=value" replaces
// or adds one key after the file is read. The value is parsed as a TOML value
// (number, "string", [array], true/false; a bare word that is not valid TOML
// is taken as a string); the key is a leaf key of the schema, an element of an
// array of tables written with its index (`force[0].total_n=[0, 5e3, 0]`).
// An override is checked like a key in the file, and its errors (and where())
// name the override ("--set mesh.element_size_mm=-2: ...").
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <toml++/toml.h>

namespace kinetofem::app {

struct KeySpec {
  // Array: any TOML array, its elements checked by the code that reads it
  // (e.g. the [sweep] table read by `kinetofem batch`).
  enum class Type { Number, Integer, String, Boolean, Vector3, StringList, TableArray, Array };
  std::string path;
  Type type = Type::Number;
  std::string unit;           // as written in the case file ("mm", "MPa", "N", ...)
  double to_si = 1.0;         // factor from the file's unit to SI
  std::optional<double> default_number;           // Vector3: the same value in all three components
  std::optional<std::array<double, 3>> default_vector;  // Vector3 of different components
  std::optional<std::string> default_text;
  // Allowed range, in the file's unit. A key that keeps a default limit gets
  // its unit's plausible range instead (plausible_range: a mass in kg, a
  // force in N, ...), so that no value in range can overflow the solution.
  double min = -1e300, max = 1e300;
  bool min_exclusive = false;
  std::vector<std::string> allowed;  // allowed strings (String, StringList)
  std::string doc;
  bool required = false;
  // 0 is allowed besides [min, max] (e.g. a density: 0 = massless, else 1..1e5 kg/m^3).
  bool zero_allowed = false;
  std::string range_note;  // why the range, shown in its message ("plausible for a solid")
  bool file_name = false;  // String: becomes a file name in the output folder (check_file_name)
};

// The longest run name in bytes: <name>.summary.toml.tmp<pid> and the other
// files a run and a batch write for it stay well inside NAME_MAX (255).
inline constexpr std::size_t kMaxRunNameBytes = 120;

// Throws Error "<at> = "<name>" cannot be a file name in the output folder:
// ..." unless `name` can name a run's files in the output folder: not empty,
// at most kMaxRunNameBytes, not "." or "..", no '/' or '\\', no control
// character (NUL included: the whole string is checked, not a C-string prefix).
void check_file_name(const std::string& name, const std::string& at);

// The spec with its unit's plausible range where it keeps a default limit
// (+-1e300): e.g. a mass at most 1e6 kg, a force at most 1e9 N in magnitude,
// a length at most 1e6 mm, a duration at most 1e7 s. Units without a
// plausible range (angles, ratios, counts) are returned unchanged. Applied by
// CaseFile to every key it reads and by schema_template.
KeySpec plausible_range(KeySpec spec);

// ">=0.001 and <=1e+07 MPa (plausible for a solid)": the range of a number
// key with its unit, for its out-of-range message ("must be ...") and the
// case template; "" for a key without limits. The default limits (+-1e300)
// are shown only when `value` lies beyond them.
std::string range_text(const KeySpec& spec, std::optional<double> value = std::nullopt);

class CaseFile {
 public:
  // Parses the file and checks it against the schema. Throws Error for a
  // missing or unreadable file, a TOML syntax error (with line and column),
  // an unknown key or a bad value.
  // allow_unknown skips the unknown-key check (to read one key, e.g. case.type,
  // before the schema of the case's type is known).
  // overrides: "key=value" strings applied in order after the file is read
  // (with allow_unknown, an override of an undeclared key is applied unchecked).
  static CaseFile load(const std::filesystem::path& path, std::vector<KeySpec> schema,
                       bool allow_unknown = false, const std::vector<std::string>& overrides = {});
  static CaseFile parse(const std::string& text, const std::filesystem::path& path,
                        std::vector<KeySpec> schema, bool allow_unknown = false,
                        const std::vector<std::string>& overrides = {});

  const std::filesystem::path& path() const { return path_; }
  // The file's text as read (without the overrides).
  const std::string& text() const { return text_; }
  // The overrides applied, as given ("key=value").
  const std::vector<std::string>& overrides() const { return override_texts_; }
  // The raw TOML node of a key (file or override), nullptr if absent: for
  // keys of Type::Array whose elements the caller checks itself.
  const toml::node* node(const std::string& path, std::size_t element = 0) const {
    return find(path, element);
  }

  bool has(const std::string& path, std::size_t element = 0) const;
  // Given with a value other than the key's default (a number at its default,
  // as `kinetofem case --template` writes it, says nothing).
  bool departs_from_default(const std::string& path, std::size_t element = 0) const;
  // SI value of a Number key (its default if absent; Error if required and absent).
  double number(const std::string& path, std::size_t element = 0) const;
  long integer(const std::string& path, std::size_t element = 0) const;
  std::string text_value(const std::string& path, std::size_t element = 0) const;
  bool boolean(const std::string& path, std::size_t element = 0) const;
  Eigen::Vector3d vector3(const std::string& path, std::size_t element = 0) const;
  std::vector<std::string> strings(const std::string& path, std::size_t element = 0) const;
  // Number of elements of an array of tables (0 if absent).
  std::size_t count(const std::string& array_path) const;

  // Error (the out-of-range message of the key) unless `value`, in the file's
  // unit, is finite and within the range of `path`: for the elements of keys of
  // Type::Array that their reader checks.
  void check_number(const std::string& path, std::size_t element, double value) const;

  // "file:line: key" for messages ("file: key 'k' (--set k=v)" for an override).
  std::string where(const std::string& path, std::size_t element = 0) const;

 private:
  const KeySpec& spec(const std::string& path) const;
  const toml::node* find(const std::string& path, std::size_t element) const;
  void check_table(const toml::table& table, const std::string& prefix) const;
  // `at` opens every message: "file:line: key 'k'" or "--set k=v: key 'k'".
  void check_value(const KeySpec& spec, const toml::node& node, const std::string& at) const;
  void apply_override(const std::string& text);

  std::filesystem::path path_;
  std::string text_;
  toml::table root_;
  std::vector<KeySpec> schema_;
  bool allow_unknown_ = false;
  std::vector<std::string> override_texts_;
  std::vector<std::string> override_keys_;  // as shown: "force[0].total_n"
};

// What keeps `file` from being read as an input file ("" if nothing): "no
// such file", "is a directory", "is not a regular file (a FIFO)", "is a
// symlink loop", "cannot be read: <reason>". A FIFO is refused before it is
// opened, which would wait for a writer forever.
std::string input_file_problem(const std::filesystem::path& file);

// The run's name: case.name, else the name of the case file's folder (as
// `kinetofem batch` names it too); either checked by check_file_name.
std::string case_name(const CaseFile& case_file);
// The key case.name, declared once for every case type and `kinetofem batch`.
KeySpec case_name_key();
std::string default_case_name(const std::filesystem::path& case_path);

// Splits "key=value" at the first '=' (key and value trimmed); Error naming
// the override if there is no '=' or no key.
std::pair<std::string, std::string> split_override(const std::string& text);

// A commented TOML template of a schema: every key with its doc, unit,
// range and default.
std::string schema_template(const std::vector<KeySpec>& schema, const std::string& title);

}  // namespace kinetofem::app
