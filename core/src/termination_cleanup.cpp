#include "kinetofem/core/termination_cleanup.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <stdexcept>
#include <string>

namespace kinetofem::core {
namespace {

// Slot states: a slot is written only between kClaimed and kReady, and the
// handler reads only kReady slots.
constexpr int kFree = 0;
constexpr int kClaimed = 1;
constexpr int kReady = 2;

struct PathSlot {
  std::atomic<int> state{kFree};
  pid_t owner = 0;
  unsigned long order = 0;  // registration order: directories are removed newest first
  char path[PATH_MAX] = {};
};

struct ChildSlot {
  std::atomic<int> state{kFree};
  pid_t owner = 0;
  pid_t pid = 0;
};

// The handler's table (see the header: the documented exception to "no global state").
PathSlot g_paths[kMaxRemovedPaths];
ChildSlot g_children[kMaxKilledChildren];
std::atomic<unsigned long> g_next_order{1};

template <typename Slot>
int claim(Slot* slots, int capacity, const char* what) {
  for (int i = 0; i < capacity; ++i) {
    int expected = kFree;
    if (slots[i].state.compare_exchange_strong(expected, kClaimed)) return i;
  }
  throw std::length_error(std::string("termination clean-up: more than ") + std::to_string(capacity) +
                          " " + what + " registered at once");
}

void sleep_ms(long ms) {
  timespec t{ms / 1000, (ms % 1000) * 1000000L};
  ::nanosleep(&t, nullptr);
}

// Removes the registered paths of this process: files first (unlink fails on
// a directory), then directories newest first (rmdir fails on what is not an
// empty directory).
void remove_paths(pid_t self) {
  for (int pass = 0; pass < 2; ++pass) {
    unsigned long below = ~0UL;
    for (;;) {
      int newest = -1;
      unsigned long newest_order = 0;
      for (int i = 0; i < kMaxRemovedPaths; ++i) {
        const PathSlot& slot = g_paths[i];
        if (slot.state.load(std::memory_order_acquire) != kReady || slot.owner != self) continue;
        if (slot.order < below && slot.order > newest_order) {
          newest = i;
          newest_order = slot.order;
        }
      }
      if (newest < 0) break;
      if (pass == 0) ::unlink(g_paths[newest].path);
      else ::rmdir(g_paths[newest].path);
      below = newest_order;
    }
  }
}

// SIGTERM to every registered child of this process, then waits for them up
// to kChildGraceSeconds; SIGKILL to those still running.
void stop_children(pid_t self) {
  bool any = false;
  for (auto& slot : g_children)
    if (slot.state.load(std::memory_order_acquire) == kReady && slot.owner == self) {
      ::kill(slot.pid, SIGTERM);
      any = true;
    }
  if (!any) return;
  bool reaped[kMaxKilledChildren] = {};
  for (long waited_ms = 0;; waited_ms += 10) {
    bool running = false;
    for (int i = 0; i < kMaxKilledChildren; ++i) {
      const ChildSlot& slot = g_children[i];
      if (reaped[i] || slot.state.load(std::memory_order_acquire) != kReady || slot.owner != self) continue;
      int status = 0;
      const pid_t done = ::waitpid(slot.pid, &status, WNOHANG);
      // Gone (reaped here, or already by another waiter: ECHILD).
      if (done == slot.pid || done < 0) reaped[i] = true;
      else running = true;
    }
    if (!running) return;
    if (waited_ms >= kChildGraceSeconds * 1000L) break;
    sleep_ms(10);
  }
  for (int i = 0; i < kMaxKilledChildren; ++i) {
    const ChildSlot& slot = g_children[i];
    if (reaped[i] || slot.state.load(std::memory_order_acquire) != kReady || slot.owner != self) continue;
    ::kill(slot.pid, SIGKILL);
    int status = 0;
    ::waitpid(slot.pid, &status, 0);
  }
}

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void on_termination(int signal_number) {
  const int saved_errno = errno;
  const pid_t self = ::getpid();
  // Children first: they may be writing into the folders removed below.
  stop_children(self);
  remove_paths(self);
  // Die of the same signal, with its default action.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  sigset_t unblock;
  sigemptyset(&unblock);
  sigaddset(&unblock, signal_number);
  ::pthread_sigmask(SIG_UNBLOCK, &unblock, nullptr);
  ::raise(signal_number);
  errno = saved_errno;  // not reached for the three signals handled
}

}  // namespace

void install_termination_cleanup() {
  struct sigaction action {};
  action.sa_handler = on_termination;
  // A second signal while cleaning up waits until the clean-up is done.
  sigemptyset(&action.sa_mask);
  for (const int s : kSignals) sigaddset(&action.sa_mask, s);
  action.sa_flags = SA_RESTART;
  for (const int s : kSignals) {
    // A signal ignored by the parent (nohup, a background job) stays ignored.
    struct sigaction previous {};
    ::sigaction(s, nullptr, &previous);
    if (previous.sa_handler == SIG_IGN) continue;
    ::sigaction(s, &action, nullptr);
  }
}

TerminationEntry::~TerminationEntry() { release(); }

TerminationEntry::TerminationEntry(TerminationEntry&& other) noexcept
    : slot_(other.slot_), free_slot_(other.free_slot_) {
  other.slot_ = -1;
}

TerminationEntry& TerminationEntry::operator=(TerminationEntry&& other) noexcept {
  if (this != &other) {
    release();
    slot_ = other.slot_;
    free_slot_ = other.free_slot_;
    other.slot_ = -1;
  }
  return *this;
}

void TerminationEntry::release() noexcept {
  if (slot_ >= 0) free_slot_(slot_);
}

namespace {

int claim_path(const std::filesystem::path& path) {
  const std::string text = std::filesystem::absolute(path).string();
  if (text.size() >= PATH_MAX)
    throw std::length_error("termination clean-up: path longer than PATH_MAX: " + text.substr(0, 200));
  const int index = claim(g_paths, kMaxRemovedPaths, "temporary paths");
  PathSlot& slot = g_paths[index];
  std::memcpy(slot.path, text.c_str(), text.size() + 1);
  slot.owner = ::getpid();
  slot.order = g_next_order.fetch_add(1);
  slot.state.store(kReady, std::memory_order_release);
  return index;
}

int claim_child(pid_t pid) {
  const int index = claim(g_children, kMaxKilledChildren, "child processes");
  ChildSlot& slot = g_children[index];
  slot.owner = ::getpid();
  slot.pid = pid;
  slot.state.store(kReady, std::memory_order_release);
  return index;
}

void free_path(int index) { g_paths[index].state.store(kFree, std::memory_order_release); }
void free_child(int index) { g_children[index].state.store(kFree, std::memory_order_release); }

}  // namespace

RemoveOnTermination::RemoveOnTermination(const std::filesystem::path& path)
    : TerminationEntry(claim_path(path), &free_path) {}

KillOnTermination::KillOnTermination(pid_t pid) : TerminationEntry(claim_child(pid), &free_child) {}

}  // namespace kinetofem::core
