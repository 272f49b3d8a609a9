#include "meshing_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <new>
#include <thread>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/termination_cleanup.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "temporary_directory.hpp"

namespace kinetofem::meshes::detail {

namespace {

constexpr double kProgressIntervalS = 10.0;
// The child's exit status when it reports an error through the pipe; any
// other non-zero status (or 0 without a mesh) comes from inside Gmsh.
constexpr int kChildReportedError = 3;

// Both ends of a pipe, closed on destruction.
class Pipe {
 public:
  Pipe() { require(::pipe2(ends_, O_CLOEXEC) == 0, "cannot create a pipe: {}", std::strerror(errno)); }
  ~Pipe() {
    close_read();
    close_write();
  }
  Pipe(const Pipe&) = delete;
  Pipe& operator=(const Pipe&) = delete;
  int read_end() const { return ends_[0]; }
  int write_end() const { return ends_[1]; }
  void close_read() { close_end(ends_[0]); }
  void close_write() { close_end(ends_[1]); }

 private:
  static void close_end(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  int ends_[2] = {-1, -1};
};

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += std::size_t(n);
  }
}

// The child: runs `work`, writes its mesh to `mesh_file` or its error to the
// pipe, and ends without returning into the parent's code (no atexit
// handlers, no static destructors: _exit).
[[noreturn]] void run_child(int error_pipe, pid_t parent, const std::string& context,
                            const std::filesystem::path& mesh_file,
                            const std::function<fem::Mesh()>& work) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(kChildReportedError);  // the parent is already gone
  // A crash inside Gmsh or OpenCASCADE must end this process by its signal, so
  // that the parent can say so: a handler inherited from the parent (such as a
  // sanitizer's, which would report the library's fault and exit with status 1)
  // is reset to the default action.
  for (const int crash : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(crash, SIG_DFL);
  std::string message;
  try {
    const fem::Mesh mesh = work();
    write_msh(mesh, mesh_file, MshEncoding::Binary);
  } catch (const Error& error) {
    message = error.what();
  } catch (const std::bad_alloc&) {
    message = fmt::format("{}: reading or meshing the file ran out of memory: coarsen the mesh "
                          "(a larger element size) or allow more memory",
                          context);
  } catch (const std::exception& error) {
    message = fmt::format("{}: reading or meshing the file failed: {}", context, error.what());
  } catch (...) {
    message = fmt::format("{}: reading or meshing the file failed (an unknown exception)", context);
  }
  std::cout.flush();
  std::fflush(nullptr);
  if (message.empty()) ::_exit(0);
  write_all(error_pipe, message);
  ::_exit(kChildReportedError);
}

// Reads what is in the pipe now (non-blocking read end) into `text`; false at
// end of file or on an error.
bool read_available(int fd, std::string& text) {
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, std::size_t(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
  }
}

std::string signal_name(int signal) {
  const char* name = ::sigabbrev_np(signal);
  const char* description = ::sigdescr_np(signal);
  return fmt::format("signal {}{}{}", signal, name ? fmt::format(", SIG{}", name) : std::string(),
                     description ? fmt::format(": {}", description) : std::string());
}

}  // namespace

fem::Mesh mesh_in_child_process(const std::string& context, const std::string& extension,
                                const MeshOptions& options, const std::function<fem::Mesh()>& work) {
  TemporaryDirectory folder("kinetofem-mesh");
  const std::filesystem::path mesh_file = folder.file("mesh.msh");
  Pipe pipe;
  // Whatever the parent has buffered would otherwise be written twice, once
  // by the child.
  std::cout.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  require(pid >= 0, "{}: cannot start the meshing process: {}", context, std::strerror(errno));
  if (pid == 0) {
    pipe.close_read();
    run_child(pipe.write_end(), parent, context, mesh_file, work);
  }
  const core::KillOnTermination kill_on_termination(pid);
  pipe.close_write();
  ::fcntl(pipe.read_end(), F_SETFL, ::fcntl(pipe.read_end(), F_GETFL) | O_NONBLOCK);

  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::string message;
  bool pipe_open = true;
  bool timed_out = false;
  double next_progress_s = kProgressIntervalS;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) fail("{}: waiting for the meshing process failed: {}", context, std::strerror(errno));
    const double elapsed_s = seconds();
    if (elapsed_s > options.time_limit_s) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      timed_out = true;
      break;
    }
    if (elapsed_s >= next_progress_s) {
      fmt::print(stdout, "  meshing {}: {:.0f} s so far (time limit {:g} s, mesh.time_limit_s)\n", context,
                 elapsed_s, options.time_limit_s);
      std::fflush(stdout);
      next_progress_s += kProgressIntervalS;
    }
    if (pipe_open) {
      // Wakes at once when the child writes or ends (the pipe closes).
      pollfd event{pipe.read_end(), POLLIN, 0};
      if (::poll(&event, 1, 100) > 0) pipe_open = read_available(pipe.read_end(), message);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
  if (pipe_open) read_available(pipe.read_end(), message);

  if (timed_out)
    fail("{}: reading and meshing the file did not finish within the time limit of {:g} s "
         "(mesh.time_limit_s); Gmsh was stopped: look for a long loop in the file, or coarsen "
         "the mesh, or raise the limit",
         context, options.time_limit_s);
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (signal == SIGKILL)
      fail("{}: Gmsh was killed ({}) while reading or meshing the file: out of memory (the "
           "kernel's OOM killer) or stopped from outside",
           context, signal_name(signal));
    if (signal == SIGINT || signal == SIGTERM || signal == SIGHUP)
      fail("{}: Gmsh was stopped ({}) while reading or meshing the file", context, signal_name(signal));
    fail("{}: Gmsh/OpenCASCADE crashed ({}) reading or meshing the file: it is damaged or not a "
         "valid {} file",
         context, signal_name(signal), extension);
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == kChildReportedError && !message.empty()) throw Error(message);
  std::error_code error;
  if (code != 0 || !std::filesystem::is_regular_file(mesh_file, error))
    fail("{}: the file ended Gmsh (exit status {}) before a mesh was made: a .geo script's Exit "
         "command?",
         context, code);
  try {
    return read_msh(mesh_file);
  } catch (const Error& e) {
    fail("{}: the mesh Gmsh made could not be read back: {}", context, e.what());
  }
}

}  // namespace kinetofem::meshes::detail
