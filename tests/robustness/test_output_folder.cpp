// Faults: an output folder that cannot be written is found before any work
// (the case read, nothing meshed or solved), with a one-line error naming
// the folder. /proc/self is a folder in which no one, root included, can
// create a file, so the test holds where CI runs as root (for whom chmod
// does not stop writes).
#include <gtest/gtest.h>

#include <filesystem>

#include "run_program.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;

namespace {

const fs::path kFaults = fs::path(ROBUSTNESS_DATA_DIR) / "faults";

TEST(OutputFolder, NotWritableIsAnErrorBeforeAnyWork) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("output-folder");
  for (const std::string case_file : {"fe_static.toml", "manipulator.toml"}) {
    Program program({KINETOFEM_EXE, "run", (kFaults / case_file).string(), "-o", "/proc/self"},
                    {.working_dir = kFaults, .capture_dir = temp});
    const auto r = program.wait(120.0);
    EXPECT_TRUE(r.exited && r.exit_code == 1) << case_file << ": " << r.describe();
    EXPECT_NE(r.err.find("kinetofem: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("output folder '/proc/self' cannot be written"), std::string::npos) << r.err;
    // Nothing was meshed or solved first.
    EXPECT_EQ(r.out.find("FE model"), std::string::npos) << case_file << ": work done first:\n" << r.out;
    EXPECT_EQ(r.out.find("mesh"), std::string::npos) << case_file << ": work done first:\n" << r.out;
  }
  if (!HasFailure()) fs::remove_all(temp);
}

}  // namespace
