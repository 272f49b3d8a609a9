#pragma once
// Calls shared by the post-processing tests: the message of the Error a call
// throws, `kinetofem post FILE --png DIR` run through the program's own
// CLI11 registration (as a user runs it), its stdout returned, and where a
// test's pictures go.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post::testing {

// The what() of the kinetofem::Error `call` throws; a test failure and "" if none.
std::string error_text(const auto& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// `kinetofem post FILE --png DIR --image-size 800x600`; the exit code must be 0.
inline std::string post_png(const std::filesystem::path& file, const std::filesystem::path& png_dir) {
  CLI::App app{"kinetofem"};
  app::CommandContext context;
  app::add_post_command(app, context);
  const std::string f = file.string(), d = png_dir.string();
  const char* argv[] = {"kinetofem", "post", f.c_str(), "--png", d.c_str(), "--image-size", "800x600"};
  ::testing::internal::CaptureStdout();
  try {
    app.parse(7, argv);
  } catch (...) {
    ::testing::internal::GetCapturedStdout();
    throw;
  }
  EXPECT_EQ(context.exit_code, 0);
  return ::testing::internal::GetCapturedStdout();
}

// KINETOFEM_PNG_KEEP_DIR (kept, to look at the pictures) or the test's temporary directory.
inline std::filesystem::path output_dir(const TemporaryDirectory& dir) {
  const char* keep = std::getenv("KINETOFEM_PNG_KEEP_DIR");
  if (!keep || !*keep) return dir.path();
  std::filesystem::create_directories(keep);
  return keep;
}

}  // namespace kinetofem::post::testing
