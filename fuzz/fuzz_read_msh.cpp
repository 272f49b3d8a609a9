// libFuzzer target: bytes written to a temporary .msh file and read with
// meshes::read_msh (its own checks, then Gmsh's reader, then the conversion
// to fem::Mesh and its validation). A crash inside libgmsh is Gmsh's (third
// party): read_msh should reject such a file before Gmsh sees it where a
// cheap check can tell (docs/robustness.md lists what was found).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/msh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                            ("kinetofem-fuzz-" + std::to_string(::getpid()) + ".msh");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const auto mesh = kinetofem::meshes::read_msh(file);
    (void)mesh.node_count();
  } catch (const kinetofem::Error&) {
    // bad input, properly reported
  }
  return 0;
}
