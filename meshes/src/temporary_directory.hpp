#pragma once
// Internal: a private temporary folder for files that Gmsh reads or writes
// (Gmsh opens and writes only named files).
//
// A fresh folder `<prefix>-XXXXXX` under std::filesystem::temp_directory_path()
// ($TMPDIR, else /tmp), made by mkdtemp (unique per call, so concurrent calls
// and processes do not meet), removed with everything in it on destruction,
// also when the caller throws. The folder and the files named through
// `file()` are registered with core::RemoveOnTermination, so that a run ended
// by SIGINT, SIGTERM or SIGHUP leaves nothing behind either.
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/core/termination_cleanup.hpp"

namespace kinetofem::meshes::detail {

class TemporaryDirectory {
 public:
  // Throws Error if the folder cannot be created.
  explicit TemporaryDirectory(const std::string& prefix);
  ~TemporaryDirectory();
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // The path of the file `name` in the folder (not created), registered to
  // be removed on termination. Call it before the file is written.
  std::filesystem::path file(const std::string& name);

 private:
  std::filesystem::path path_;
  // The folder first: the handler removes the files, then the folder.
  std::vector<core::RemoveOnTermination> registered_;
};

}  // namespace kinetofem::meshes::detail
