// `kinetofem post`: the summary, --all, --history, and one-line errors for a
// missing file and unknown body, field, node or history, through the same
// CLI11 registration as the program (app/main.cpp).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"
#include "post_test_results.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

// Runs `kinetofem post ARGS...`; returns stdout. Errors propagate as in main().
std::string post(std::vector<std::string> args) {
  CLI::App app{"kinetofem"};
  app.require_subcommand(1);
  app::CommandContext context;
  app::add_post_command(app, context);
  args.insert(args.begin(), {"kinetofem", "post"});
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  ::testing::internal::CaptureStdout();
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (...) {
    ::testing::internal::GetCapturedStdout();
    throw;
  }
  EXPECT_EQ(context.exit_code, 0);
  return ::testing::internal::GetCapturedStdout();
}

// The Error message of `kinetofem post ARGS...` (fails the test if none).
std::string error_of(const std::vector<std::string>& args) {
  try {
    post(args);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(PostCli, SummaryListsBodiesMaximaAndHotSpots) {
  testing::TemporaryDirectory dir;
  const std::string file = testing::write_synthetic_motion(dir.path()).string();
  const std::string out = post({file});
  EXPECT_NE(out.find("beam: 126 nodes"), std::string::npos) << out;
  EXPECT_NE(out.find("plate: 50 nodes"), std::string::npos) << out;
  EXPECT_NE(out.find("top 5 hot spots of von_mises"), std::string::npos) << out;
  EXPECT_NE(out.find("300.000"), std::string::npos) << out;
  EXPECT_NE(out.find("t = 0.2000 s"), std::string::npos) << out;
  EXPECT_NE(out.find("recomputed from series"), std::string::npos) << out;  // plate has no stored envelope
}

TEST(PostCli, AllWritesEveryCsvAndPngBesideTheResults) {
  testing::TemporaryDirectory dir;
  const auto file = testing::write_synthetic_motion(dir.path());
  post({file.string(), "--all", "--image-size", "640x480", "--hot-spots", "3"});
  const auto out = dir.path() / "motion_post";
  for (const char* name : {"hot_spots.csv", "beam_nodes.csv", "plate_nodes.csv", "mechanism.csv",
                           "von_mises_critical.png", "mechanism_loads.png", "path_H.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(out / name)) << name;
}

TEST(PostCli, HistoryAtNodePointAndOfTheMechanism) {
  testing::TemporaryDirectory dir;
  const std::string file = testing::write_synthetic_motion(dir.path()).string();
  std::string out = post({file, "--history", "50,0.4,0", "--body", "beam", "--csv", (dir / "csv").string()});
  EXPECT_NE(out.find("nearest node to (50,0.4,0) mm on 'beam': node 5"), std::string::npos) << out;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "csv" / "history_beam_von_mises_50_0.4_0.csv"));
  out = post({file, "--history", "drive_torque"});
  EXPECT_NE(out.find("time history: mechanism history drive_torque [N*m]"), std::string::npos) << out;
}

TEST(PostCli, ErrorsAreOneLineAndNameTheCulprit) {
  testing::TemporaryDirectory dir;
  const std::string file = testing::write_synthetic_motion(dir.path()).string();
  EXPECT_NE(error_of({(dir / "nope.h5").string()}).find("nope.h5: no such results file"), std::string::npos);
  // A folder or a FIFO is said to be one (a FIFO is never opened: that would wait for a writer).
  EXPECT_NE(error_of({dir.path().string()}).find(": is a directory, expected a results file"), std::string::npos);
  const std::filesystem::path fifo = dir / "fifo.h5";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(error_of({fifo.string()}).find("fifo.h5: is not a regular file (a FIFO)"), std::string::npos);
  EXPECT_NE(error_of({file, "--history", "3", "--body", "shaft"}).find("--body 'shaft'"), std::string::npos);
  EXPECT_NE(error_of({file, "--history", "3", "--body", "beam", "--field", "tresca"})
                .find("no series field 'tresca'"),
            std::string::npos);
  EXPECT_NE(error_of({file, "--history", "99999", "--body", "beam"}).find("has no node 99999"), std::string::npos);
  EXPECT_NE(error_of({file, "--history", "lever_speed"}).find("no mechanism history 'lever_speed'"),
            std::string::npos);
  EXPECT_NE(error_of({file, "--history", "1,2", "--body", "beam"}).find("expected NODE or x,y,z in mm"),
            std::string::npos);
  EXPECT_NE(error_of({file, "--history", "7"}).find("needs --body"), std::string::npos);
  EXPECT_NE(error_of({file, "--field", "tresca"}).find("--field 'tresca'"), std::string::npos);
  EXPECT_NE(error_of({file, "--image-size", "big"}).find("--image-size 'big'"), std::string::npos);
}

}  // namespace
}  // namespace kinetofem::post
