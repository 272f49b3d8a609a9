#pragma once
// What a Gmsh .geo script does besides describing geometry, found from its
// text before Gmsh sees it: the files it reads (for the mesh cache key) and
// the commands that reach outside geometry (refused unless the user trusts
// the file).
//
// Gmsh 4.8's .geo language can run programs (SystemCall, System,
// NonBlockingSystemCall, OnelabRun), end the process (Exit: exit(0) inside
// the library, so kinetofem would stop with no message and status 0), write
// files (Save, Save View, Print, Printf(...) > or >> a file, CreateDir) and
// read files (Include, Merge, MergeWithBoundingBox, ShapeFromFile,
// ListFromFile; a file name relative to the folder of the script that names
// it). Opening or merging a file also merges "<file>.opt" when it exists,
// which is parsed as a script too. A case received from someone else must
// not be able to do any of this by naming a part file, so an untrusted
// script may only read files inside the allowed folders, by file names
// written as plain strings, and may not run, exit or write at all
// (docs/robustness.md, "Trust").
//
// The scan is lexical: comments (// and /* */) and strings ("..." and
// '...', as Gmsh's lexer reads them) are skipped; a refused command is
// refused wherever it stands, also in a branch that would not run. Included
// and merged scripts are scanned the same way, recursively.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kinetofem::meshes {

// One command of a script that matters beyond geometry.
struct GeoCommand {
  enum class Kind {
    ReadsScript,  // Include, or Merge of a file Gmsh parses as a script
    ReadsData,    // Merge of a CAD or mesh file, ShapeFromFile, ListFromFile
    Runs,         // SystemCall, System, NonBlockingSystemCall, OnelabRun
    Exits,        // Exit
    Writes,       // Save, Save View, Print, Printf > / >>, CreateDir
  };
  Kind kind;
  std::string command;  // as written: "SystemCall", "Printf >", "Save View"
  int line = 0;         // 1-based line of the command in its script
  // The file name for reads and writes when it is a plain string literal;
  // nullopt when it is an expression (StrCat, a variable, ...).
  std::optional<std::string> file_name;
};

// The commands of one script's text (no file access, no recursion).
std::vector<GeoCommand> geo_commands(std::string_view text);

struct GeoScanPolicy {
  // Folders the script (and what it includes) may read from: the case
  // folder. The script's own folder is always allowed.
  std::vector<std::filesystem::path> read_roots;
  // Let the script run programs, exit, write files and read anywhere: a
  // trust decision of the person running kinetofem (--trust-part-files).
  bool trusted = false;
};

struct GeoScan {
  // Every file Gmsh will read besides the script itself, resolved as Gmsh
  // resolves them, in the order found, each once.
  std::vector<std::filesystem::path> files_read;
  // False when a read names its file by an expression (possible only when
  // trusted): the files read are then not all known.
  bool all_files_known = true;
};

// Scans `file` and everything it includes or merges. Throws Error, one line
// "FILE:LINE: ..." naming the command and how to allow it, at the first
// refused command unless policy.trusted.
GeoScan scan_geo_file(const std::filesystem::path& file, const GeoScanPolicy& policy);

// Text for the mesh cache key of `file` (a .geo script): every file it reads
// (by name relative to the script's folder) with its size and a content
// hash, "<file>.opt" included. nullopt when the files read are not all
// known. Empty for other files (a CAD file is imported by OpenCASCADE alone).
std::optional<std::string> geometry_inputs_key(const std::filesystem::path& file);

}  // namespace kinetofem::meshes
