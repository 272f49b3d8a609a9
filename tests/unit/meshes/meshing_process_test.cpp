// Gmsh in a child process (meshes/src/meshing_process.hpp): a file that
// crashes Gmsh/OpenCASCADE or keeps it busy past the time limit is an Error
// naming the file, not a crash or a hang of the caller; meshing still works
// after the caller has run OpenMP threads (fork keeps only the calling
// thread); and the private temporary folder is gone afterwards.
#include <gtest/gtest.h>
#include <omp.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geometry_text.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "mesh_test_helpers.hpp"
#include "kinetofem/testing/scoped_tmpdir.hpp"

namespace kinetofem::meshes {
namespace {

namespace fs = std::filesystem;

using kinetofem::testing::ScopedTmpdir;

bool folder_is_empty(const fs::path& dir) { return fs::directory_iterator(dir) == fs::directory_iterator(); }

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeshingProcess, ALongLoopIsStoppedAtTheTimeLimit) {
  testing::TempDir dir;
  const fs::path tmp = dir / "tmp";
  fs::create_directories(tmp);
  const fs::path file = dir / "loop.geo";
  std::ofstream(file) << "SetFactory(\"OpenCASCADE\");\nx = 0;\nFor i In {1:2000000000}\n  x = x + 1;\nEndFor\n"
                         "Box(1) = {0, 0, 0, 0.1, 0.02, 0.01};\n";
  MeshOptions options;
  options.element_size_m = 0.02;
  options.time_limit_s = 1.0;
  const ScopedTmpdir scoped(tmp);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = error_of([&] { mesh_geometry(file, options); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(message.find(file.string() + ": reading and meshing the file did not finish within the time limit "
                                         "of 1 s (mesh.time_limit_s); Gmsh was stopped"),
            std::string::npos)
      << message;
  EXPECT_LT(seconds, 5.0);
  EXPECT_TRUE(folder_is_empty(tmp)) << "the private temporary folder is left behind";
}

TEST(MeshingProcess, ACrashOfOpenCascadeIsAnErrorNamingTheFile) {
  // The slider-crank's crank.step cut after line 720 of 900 and closed with
  // ENDSEC / END-ISO-10303-21: OpenCASCADE 7.x dies of SIGSEGV reading it.
  const fs::path file = "tests/data/robustness/135_part_file_damaged_step/crank.step";
  ASSERT_TRUE(fs::is_regular_file(file));
  MeshOptions options;
  options.element_size_m = 0.02;
  const std::string message = error_of([&] { mesh_geometry(file, options); });
  EXPECT_NE(message.find(file.string() + ": Gmsh/OpenCASCADE crashed (signal 11, SIGSEGV"), std::string::npos)
      << message;
  EXPECT_NE(message.find("it is damaged or not a valid .step file"), std::string::npos) << message;
}

TEST(MeshingProcess, ErrorsOfGmshKeepTheirMessage) {
  testing::TempDir dir;
  const fs::path file = dir / "empty.geo";
  std::ofstream(file) << "// no geometry\n";
  MeshOptions options;
  options.element_size_m = 0.02;
  EXPECT_EQ(error_of([&] { mesh_geometry(file, options); }),
            file.string() + ": the geometry has no volumes to mesh");
}

TEST(MeshingProcess, MeshesAfterTheCallerRanOpenMpThreads) {
  // The parent's OpenMP pool exists when it forks; the child has one thread.
  double sum = 0.0;
#pragma omp parallel for num_threads(4) reduction(+ : sum)
  for (int i = 0; i < 1000; ++i) sum += double(i);
  ASSERT_EQ(sum, 499500.0);
  MeshOptions options;
  options.element_size_m = 0.02;
  options.order = 1;
  const auto mesh = mesh_geometry_text("lever.geo", lever_geometry_text(), options);
  EXPECT_GT(mesh.element_count(), 100);
  EXPECT_TRUE(mesh.node_sets.count("bore_A0"));
}

TEST(MeshingProcess, TheTimeLimitMustBePositive) {
  MeshOptions options;
  options.time_limit_s = 0.0;
  EXPECT_EQ(error_of([&] { options.validate(); }), "mesh option time_limit_s = 0 must be a positive time in s");
}

}  // namespace
}  // namespace kinetofem::meshes
