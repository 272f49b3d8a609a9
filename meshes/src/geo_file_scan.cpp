#include "kinetofem/meshes/geo_file_scan.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/text_file.hpp"

namespace kinetofem::meshes {

namespace {

// ---- Gmsh's lexer, as far as the scan needs it (Parser/Gmsh.l) -----------------

struct Token {
  enum class Type { Name, String, Other };
  Type type;
  std::string text;
  int line;
};

bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::vector<Token> tokens_of(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      i += 2;
      while (i < n && !(text[i] == '*' && i + 1 < n && text[i + 1] == '/')) line += text[i++] == '\n';
      i = std::min(n, i + 2);
    } else if (c == '"' || c == '\'') {
      // Gmsh keeps every character up to the same quote (no escapes).
      const int start = line;
      std::string value;
      for (++i; i < n && text[i] != c; ++i) {
        line += text[i] == '\n';
        value += text[i];
      }
      ++i;
      tokens.push_back({Token::Type::String, std::move(value), start});
    } else if (name_start(c)) {
      const std::size_t start = i;
      while (i < n && name_char(text[i])) ++i;
      tokens.push_back({Token::Type::Name, std::string(text.substr(start, i - start)), line});
    } else {
      tokens.push_back({Token::Type::Other, std::string(1, c), line});
      ++i;
    }
  }
  return tokens;
}

// Extensions Gmsh's MergeFile reads as data (CAD, mesh, post-processing);
// any other merged file is parsed as a script.
bool merged_as_data(const std::string& file_name) {
  static const std::set<std::string> data = {
      ".step", ".stp", ".iges", ".igs", ".brep", ".xao", ".stl", ".msh", ".pos", ".med", ".mmed",
      ".rmed", ".unv", ".vtk", ".bdf", ".nas", ".mesh", ".ply", ".ply2", ".off", ".p3d", ".wrl",
      ".vrml", ".inp", ".cgns", ".bmp", ".png", ".jpg", ".jpeg", ".gif", ".ppm", ".pgm", ".pbm",
      ".pnm", ".obj", ".diff", ".x_t", ".xmt_txt", ".sat", ".bin"};
  std::string extension = std::filesystem::path(file_name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return data.count(extension) > 0;
}

const std::set<std::string>& running_commands() {
  static const std::set<std::string> names = {"SystemCall", "System", "NonBlockingSystemCall",
                                              "OnelabRun"};
  return names;
}

// True when the name at k is used as a variable (assigned or indexed), not
// as a command: "System = 2;", "Save[0]".
bool used_as_variable(const std::vector<Token>& t, std::size_t k) {
  if (k + 1 >= t.size()) return false;
  const std::string& next = t[k + 1].text;
  if (t[k + 1].type != Token::Type::Other) return false;
  if (next == "=" || next == "[" || next == "," || next == ")" || next == ";") return true;
  return (next == "+" || next == "-" || next == "*" || next == "/") && k + 2 < t.size() &&
         t[k + 2].text == "=";
}

// True when the token at k can start a statement (after ";", ")" of an
// If, "}" or a keyword such as Else): "x = Save + 1" is no command.
bool at_statement_start(const std::vector<Token>& t, std::size_t k) {
  if (k == 0) return true;
  const Token& previous = t[k - 1];
  return previous.type == Token::Type::Name ||
         (previous.type == Token::Type::Other &&
          (previous.text == ";" || previous.text == ")" || previous.text == "}"));
}

// The literal at k when it is a plain string followed by `end`.
std::optional<std::string> literal_before(const std::vector<Token>& t, std::size_t k,
                                          const char* end) {
  if (k + 1 < t.size() && t[k].type == Token::Type::String && t[k + 1].type == Token::Type::Other &&
      t[k + 1].text == end)
    return t[k].text;
  return std::nullopt;
}

std::string what_it_does(GeoCommand::Kind kind) {
  switch (kind) {
    case GeoCommand::Kind::Runs: return "runs a program";
    case GeoCommand::Kind::Exits: return "ends the program (Gmsh calls exit)";
    case GeoCommand::Kind::Writes: return "writes a file";
    case GeoCommand::Kind::ReadsScript:
    case GeoCommand::Kind::ReadsData: return "reads a file";
  }
  return "reaches outside geometry";
}

// ---- files --------------------------------------------------------------------

// FNV-1a, 64 bit: a content hash that is the same in every build.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

// `path` after following symbolic links as far as they exist.
std::filesystem::path resolved(const std::filesystem::path& path) {
  std::error_code error;
  auto canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(path, error), error);
  return error ? std::filesystem::absolute(path).lexically_normal() : canonical;
}

bool inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  const auto f = resolved(file);
  const auto d = resolved(folder);
  const auto relative = f.lexically_relative(d);
  return !relative.empty() && *relative.begin() != ".." && !relative.is_absolute();
}

constexpr const char* kHowToAllow =
    "a part file may only describe geometry; if you trust this file, run with --trust-part-files";

class Scanner {
 public:
  explicit Scanner(const GeoScanPolicy& policy) : policy_(policy) {}

  GeoScan scan(const std::filesystem::path& file) {
    for (const auto& root : policy_.read_roots) roots_.push_back(root.empty() ? "." : root);
    roots_.push_back(file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path());
    visited_.insert(resolved(file).string());
    script(file);
    opened(file);
    return std::move(result_);
  }

 private:
  // Gmsh merges "<file>.opt" after opening or merging `file`.
  void opened(const std::filesystem::path& file) {
    std::filesystem::path options = file;
    options += ".opt";
    std::error_code error;
    if (std::filesystem::exists(options, error)) {
      add(options);
      if (visited_.insert(resolved(options).string()).second) script(options);
    }
  }

  void add(const std::filesystem::path& file) {
    const std::string key = file.lexically_normal().string();
    if (listed_.insert(key).second) result_.files_read.push_back(file.lexically_normal());
  }

  void script(const std::filesystem::path& file) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) return;  // Gmsh reports it
    const std::string name = file.string();
    const auto folder = file.parent_path();
    for (const auto& command : geo_commands(read_text_file(file))) {
      const bool reads = command.kind == GeoCommand::Kind::ReadsScript ||
                         command.kind == GeoCommand::Kind::ReadsData;
      if (!reads) {
        if (!policy_.trusted)
          fail("{}:{}: '{}' {}: {}", name, command.line, command.command,
               what_it_does(command.kind), kHowToAllow);
        continue;
      }
      if (!command.file_name) {
        if (!policy_.trusted)
          fail("{}:{}: '{}' names its file by an expression, not a plain string: kinetofem cannot "
               "check where it reads; write the file name as a string, or, if you trust this "
               "file, run with --trust-part-files",
               name, command.line, command.command);
        result_.all_files_known = false;
        continue;
      }
      const std::filesystem::path written = *command.file_name;
      const std::filesystem::path target = written.is_absolute() ? written : folder / written;
      if (!policy_.trusted &&
          std::none_of(roots_.begin(), roots_.end(),
                       [&](const auto& root) { return inside(target, root); }))
        fail("{}:{}: '{}' reads \"{}\", outside the case folder: {}", name, command.line,
             command.command, *command.file_name, kHowToAllow);
      add(target);
      if (command.kind == GeoCommand::Kind::ReadsScript &&
          visited_.insert(resolved(target).string()).second)
        script(target);
      if (command.command == "Merge" || command.command == "MergeWithBoundingBox") opened(target);
    }
  }

  const GeoScanPolicy& policy_;
  std::vector<std::filesystem::path> roots_;
  std::set<std::string> visited_;
  std::set<std::string> listed_;
  GeoScan result_;
};

}  // namespace

std::vector<GeoCommand> geo_commands(std::string_view text) {
  const auto t = tokens_of(text);
  std::vector<GeoCommand> commands;
  auto is = [&](std::size_t k, const char* s) { return k < t.size() && t[k].text == s && t[k].type != Token::Type::String; };
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k].type != Token::Type::Name) continue;
    if (k > 0 && is(k - 1, ".")) continue;  // an option's field: Mesh.Algorithm
    const std::string& name = t[k].text;
    const bool expression = name == "ShapeFromFile" || name == "ListFromFile";
    if (!expression && name != "Exit" && !at_statement_start(t, k)) continue;
    const int line = t[k].line;
    using Kind = GeoCommand::Kind;
    if (name == "Exit") {
      commands.push_back({Kind::Exits, name, line, std::nullopt});
    } else if (name == "Include" || name == "Merge" || name == "MergeWithBoundingBox") {
      if (used_as_variable(t, k)) continue;
      const auto file = literal_before(t, k + 1, ";");
      const bool script = name == "Include" || !file || !merged_as_data(*file);
      commands.push_back({script ? Kind::ReadsScript : Kind::ReadsData, name, line, file});
    } else if (name == "ShapeFromFile" || name == "ListFromFile") {
      if (!is(k + 1, "(")) continue;
      commands.push_back({Kind::ReadsData, name, line, literal_before(t, k + 2, ")")});
    } else if (running_commands().count(name)) {
      if (used_as_variable(t, k)) continue;
      commands.push_back({Kind::Runs, name, line, std::nullopt});
    } else if (name == "Save" || name == "Print" || name == "CreateDir") {
      if (used_as_variable(t, k)) continue;
      const bool view = name == "Save" && k + 1 < t.size() && t[k + 1].text == "View" &&
                        t[k + 1].type == Token::Type::Name;
      commands.push_back({Kind::Writes, view ? "Save View" : name, line,
                          view ? std::nullopt : literal_before(t, k + 1, ";")});
    } else if (name == "Printf" && is(k + 1, "(")) {
      // Printf(...) > "file"; or >> "file": a write; without them, the console.
      int depth = 0;
      std::size_t close = k + 1;
      for (; close < t.size(); ++close) {
        if (is(close, "(")) ++depth;
        if (is(close, ")") && --depth == 0) break;
      }
      if (is(close + 1, ">")) {
        const bool append = is(close + 2, ">");
        commands.push_back({Kind::Writes, append ? "Printf >>" : "Printf >", line,
                            literal_before(t, close + (append ? 3 : 2), ";")});
      }
    }
  }
  return commands;
}

GeoScan scan_geo_file(const std::filesystem::path& file, const GeoScanPolicy& policy) {
  return Scanner(policy).scan(file);
}

std::optional<std::string> geometry_inputs_key(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".geo") return std::string();
  GeoScanPolicy everything;
  everything.trusted = true;
  const GeoScan scan = scan_geo_file(file, everything);
  if (!scan.all_files_known) return std::nullopt;
  std::string key;
  const auto folder = file.parent_path();
  for (const auto& input : scan.files_read) {
    std::error_code error;
    const std::string name = input.lexically_relative(folder).string();
    if (!std::filesystem::is_regular_file(input, error)) {
      key += fmt::format("\ninput {}:{} missing", name.size(), name);
      continue;
    }
    const std::string content = read_text_file(input);
    key += fmt::format("\ninput {}:{} {} {:016x}", name.size(), name, content.size(), fnv1a(content));
  }
  return key;
}

}  // namespace kinetofem::meshes
