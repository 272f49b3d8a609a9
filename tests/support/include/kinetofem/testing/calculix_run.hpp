#pragma once
// Running CalculiX (ccx) from a test: whether it is installed, a scratch
// folder per test for the deck and ccx's files, and one run of a job. The
// tests that need ccx skip themselves where it is missing (CI does not
// install it; `apt-get install calculix-ccx`).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <unistd.h>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::testing {

inline bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

// <tmp>/<prefix>_<pid>_<test name>, made empty at the start and removed at the
// end of the test (kept when KINETOFEM_KEEP_CCX is set, to look at the deck).
struct CcxScratchDir {
  std::filesystem::path path;
  explicit CcxScratchDir(const std::string& prefix = "kinetofem_ccx") {
    path = std::filesystem::temp_directory_path() /
           (prefix + "_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~CcxScratchDir() {
    if (!std::getenv("KINETOFEM_KEEP_CCX")) std::filesystem::remove_all(path);
  }
  CcxScratchDir(const CcxScratchDir&) = delete;
  CcxScratchDir& operator=(const CcxScratchDir&) = delete;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs ccx (one thread) on `job`.inp in `dir`; its wall time in s, or a
// negative value when it failed or wrote no .dat file (its log: <job>.log).
inline double run_ccx(const std::filesystem::path& dir, const std::string& job) {
  const auto start = std::chrono::steady_clock::now();
  const std::string command =
      "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx -i " + job + " > " + job + ".log 2>&1";
  const bool ok = std::system(command.c_str()) == 0 && std::filesystem::exists(dir / (job + ".dat"));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return ok ? seconds : -1.0;
}

// Largest von Mises stress over the integration points of a model's
// displacement field given in world axes (as the elastic assembly gives a
// part's field), turned back to the model's axes by R (model -> world): what
// ccx prints at its integration points, free of the two programs' different
// extrapolations to the nodes.
inline double peak_gauss_von_mises(const fem::FeModel& model, const fem::DisplacementField& world,
                                   const Eigen::Matrix3d& R) {
  const fem::DisplacementField body = world * R;  // rows: u_body^T = u_world^T R
  const fem::GaussPointStress gp = fem::gauss_point_stress(model.mesh, fem::element_materials(model), body);
  double peak = 0.0;
  for (Eigen::Index q = 0; q < gp.stress_pa.rows(); ++q)
    peak = std::max(peak, fem::von_mises(gp.stress_pa.row(q).transpose()));
  return peak;
}

}  // namespace kinetofem::testing
