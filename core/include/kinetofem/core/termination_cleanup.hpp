#pragma once
// Clean-up when the process is ended by SIGINT, SIGTERM or SIGHUP (Ctrl-C, a
// job scheduler, a closed terminal): the temporary files and folders that are
// registered here are removed, and the registered child processes are
// stopped, before the process dies of the signal as it would have without the
// handler (its exit status still says "killed by SIGINT").
//
// Usage:
//   int main() { kinetofem::core::install_termination_cleanup(); ... }
//
//   const kinetofem::core::RemoveOnTermination remove_tmp(tmp_path);
//   ... write tmp_path, rename it to its final name ...
//   // on leaving the scope, tmp_path is no longer removed on a signal
//
// State: the one documented exception to "no global state". The handler can
// only reach a static, fixed-capacity table (paths as fixed-size character
// arrays, pids), filled and emptied by the guards below with atomic slot
// states so that the handler reads only complete entries. The handler calls
// only async-signal-safe functions (unlink, rmdir, kill, waitpid, nanosleep,
// sigaction, raise). An entry belongs to the process that registered it: a
// forked child that has not exec'd does not remove its parent's files.
#include <sys/types.h>

#include <filesystem>

namespace kinetofem::core {

// Installs SIGINT/SIGTERM/SIGHUP handlers that remove every registered path,
// send SIGTERM to every registered child process (and wait for them, at most
// kChildGraceSeconds, then SIGKILL), then re-raise the signal with its default
// action. Called once, first thing in main(); calling it again is harmless.
void install_termination_cleanup();

// How long the handler waits for registered children to end after SIGTERM
// (they remove their own temporary files) before it kills them.
inline constexpr int kChildGraceSeconds = 10;

// Capacity of the tables (paths; child processes).
inline constexpr int kMaxRemovedPaths = 64;
inline constexpr int kMaxKilledChildren = 256;

// An entry that a guard below holds in one of the handler's tables: freed
// (the handler no longer acts on it) when the guard dies, or when it is moved
// onto another guard. Movable, not copyable.
class TerminationEntry {
 public:
  TerminationEntry(TerminationEntry&& other) noexcept;
  TerminationEntry& operator=(TerminationEntry&& other) noexcept;
  TerminationEntry(const TerminationEntry&) = delete;
  TerminationEntry& operator=(const TerminationEntry&) = delete;

 protected:
  using FreeSlot = void (*)(int slot);
  TerminationEntry(int slot, FreeSlot free_slot) : slot_(slot), free_slot_(free_slot) {}
  ~TerminationEntry();

 private:
  void release() noexcept;
  int slot_ = -1;
  FreeSlot free_slot_ = nullptr;
};

// While alive, `path` (a file, or a directory that is empty once its
// registered files are gone: directories are removed with rmdir after files,
// in reverse order of registration) is removed if the process is ended by one
// of those signals. Throws std::length_error if the table is full and
// std::length_error if the path is longer than the table's entries (PATH_MAX).
// Movable, not copyable.
class RemoveOnTermination : private TerminationEntry {
 public:
  explicit RemoveOnTermination(const std::filesystem::path& path);
};

// While alive, the child `pid` gets SIGTERM (and is waited for, bounded by
// kChildGraceSeconds) if this process is ended by one of those signals.
// Throws std::length_error if the table is full. Movable, not copyable.
class KillOnTermination : private TerminationEntry {
 public:
  explicit KillOnTermination(pid_t pid);
};

}  // namespace kinetofem::core
