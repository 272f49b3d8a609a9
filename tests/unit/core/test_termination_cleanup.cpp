// install_termination_cleanup (core/termination_cleanup.hpp): a process ended
// by SIGINT/SIGTERM/SIGHUP removes its registered temporary paths, stops its
// registered children, and still dies of the signal. Each case runs in a
// forked child so that the signal ends the child, not the test.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "kinetofem/core/termination_cleanup.hpp"

namespace kinetofem::core {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kinetofem-termination-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void touch(const fs::path& file) { std::ofstream(file) << "x"; }

// Runs body() in a forked child; returns the child's wait status.
template <typename Body>
int in_child(Body body) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    try {
      body();
    } catch (...) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

class TerminationCleanup : public ::testing::TestWithParam<int> {};

TEST_P(TerminationCleanup, RemovesRegisteredFilesAndFoldersAndDiesOfTheSignal) {
  const int signal_number = GetParam();
  const fs::path dir = fresh_dir("paths");
  const fs::path folder = dir / "work";
  const fs::path inner = folder / "part.msh";
  const fs::path tmp = dir / "case.h5.tmp";
  const fs::path kept = dir / "case.h5";
  const int status = in_child([&] {
    install_termination_cleanup();
    fs::create_directories(folder);
    const RemoveOnTermination remove_folder(folder);  // registered before its file
    touch(inner);
    const RemoveOnTermination remove_inner(inner);
    touch(tmp);
    const RemoveOnTermination remove_tmp(tmp);
    touch(kept);
    { const RemoveOnTermination released(kept); }  // no longer registered
    ::raise(signal_number);
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), signal_number);
  EXPECT_FALSE(fs::exists(tmp));
  EXPECT_FALSE(fs::exists(inner));
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::exists(kept));
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Signals, TerminationCleanup, ::testing::Values(SIGINT, SIGTERM, SIGHUP));

TEST(TerminationCleanupChildren, SendsSigtermToRegisteredChildrenAndWaitsForThem) {
  const fs::path dir = fresh_dir("children");
  const fs::path marker = dir / "child-ended";
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const int status = in_child([&] {
    install_termination_cleanup();
    const pid_t grandchild = ::fork();
    if (grandchild == 0) {
      // Ends on SIGTERM after leaving a mark, as a child that cleans up would.
      install_termination_cleanup();
      touch(marker);
      const RemoveOnTermination remove_marker(marker);
      for (;;) ::pause();
    }
    const KillOnTermination stop_grandchild(grandchild);
    ::write(pipe_fds[1], &grandchild, sizeof grandchild);
    while (!fs::exists(marker)) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ::raise(SIGTERM);
  });
  pid_t grandchild = 0;
  ASSERT_EQ(::read(pipe_fds[0], &grandchild, sizeof grandchild), static_cast<ssize_t>(sizeof grandchild));
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  // The grandchild got SIGTERM (it removed its mark) and was reaped before its parent died.
  EXPECT_FALSE(fs::exists(marker));
  EXPECT_EQ(::kill(grandchild, 0), -1);
  EXPECT_EQ(errno, ESRCH);
  fs::remove_all(dir);
}

TEST(TerminationCleanupTable, AForkedChildDoesNotRemoveItsParentsFiles) {
  const fs::path dir = fresh_dir("owner");
  const fs::path parent_file = dir / "parent.tmp";
  touch(parent_file);
  const int status = in_child([&] {
    install_termination_cleanup();
    const RemoveOnTermination parent_guard(parent_file);
    const pid_t pid = ::fork();
    if (pid == 0) ::raise(SIGTERM);  // the forked copy holds the entry but does not own it
    int child_status = 0;
    ::waitpid(pid, &child_status, 0);
    if (!fs::exists(parent_file)) ::_exit(4);
  });
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  fs::remove_all(dir);
}

TEST(TerminationCleanupTable, AFullTableThrowsAndFreesOnRelease) {
  std::vector<std::unique_ptr<RemoveOnTermination>> guards;
  EXPECT_THROW(
      {
        for (int i = 0; i <= kMaxRemovedPaths; ++i)
          guards.push_back(std::make_unique<RemoveOnTermination>("/nonexistent/" + std::to_string(i)));
      },
      std::length_error);
  EXPECT_EQ(guards.size(), static_cast<std::size_t>(kMaxRemovedPaths));
  guards.clear();
  EXPECT_NO_THROW(RemoveOnTermination("/nonexistent/again"));
  // A moved guard keeps one slot.
  RemoveOnTermination a("/nonexistent/a");
  RemoveOnTermination b(std::move(a));
  b = RemoveOnTermination("/nonexistent/c");
}

}  // namespace
}  // namespace kinetofem::core
