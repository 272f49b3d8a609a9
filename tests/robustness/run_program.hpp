#pragma once
// Starts the built `kinetofem` program as a child process for the robustness
// tests: its own working directory, stdout and stderr captured to files, an
// optional file-size limit (RLIMIT_FSIZE: a write past it fails with EFBIG,
// or kills with SIGXFSZ a program that does not ignore that signal), an
// optional address-space limit (RLIMIT_AS, as `ulimit -v`), and a
// wall-clock limit after which it is killed (a hang is a failure, not a
// stuck test). POSIX only (fork/exec), like the program's targets.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace kinetofem::test {

struct ProgramResult {
  bool timed_out = false;
  bool exited = false;   // ended by exit(), not by a signal
  int exit_code = -1;    // if exited
  int signal = 0;        // if killed by a signal
  std::string out, err;  // captured stdout and stderr
  double seconds = 0.0;

  std::string describe() const {
    std::ostringstream s;
    if (timed_out) s << "timed out after " << seconds << " s; ";
    if (exited) s << "exit code " << exit_code;
    else s << "killed by signal " << signal << " (" << strsignal(signal) << ")";
    s << "\n--- stderr ---\n" << err << "--- stdout (end) ---\n"
      << (out.size() > 2000 ? out.substr(out.size() - 2000) : out);
    return s.str();
  }
};

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

struct ProgramOptions {
  std::filesystem::path working_dir;
  std::filesystem::path capture_dir;  // receives stdout.txt, stderr.txt
  std::optional<long long> file_size_limit_bytes;
  std::optional<long long> address_space_limit_bytes;  // RLIMIT_AS (ulimit -v)
};

// A started child. wait() or kill_and_wait() reaps it.
class Program {
 public:
  Program(const std::vector<std::string>& args, const ProgramOptions& options) : options_(options) {
    const auto out = (options.capture_dir / "stdout.txt").string();
    const auto err = (options.capture_dir / "stderr.txt").string();
    argv_storage_ = args;
    std::vector<char*> argv;
    for (auto& a : argv_storage_) argv.push_back(a.data());
    argv.push_back(nullptr);
    // Emptied here, not only in the child: a caller polling stdout must not
    // see the previous run's output before the child has started.
    { std::ofstream(out, std::ios::trunc); std::ofstream(err, std::ios::trunc); }
    start_ = std::chrono::steady_clock::now();
    pid_ = ::fork();
    if (pid_ == 0) {
      // Child: only async-signal-safe calls until exec.
      if (::chdir(options.working_dir.c_str()) != 0) ::_exit(126);
      const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fo < 0 || fe < 0) ::_exit(126);
      ::dup2(fo, 1);
      ::dup2(fe, 2);
      // The program itself must cope with SIGXFSZ: start it with the default action.
      ::signal(SIGXFSZ, SIG_DFL);
      if (options.file_size_limit_bytes) {
        const rlimit limit{rlim_t(*options.file_size_limit_bytes), rlim_t(*options.file_size_limit_bytes)};
        ::setrlimit(RLIMIT_FSIZE, &limit);
      }
      if (options.address_space_limit_bytes) {
        const rlimit limit{rlim_t(*options.address_space_limit_bytes), rlim_t(*options.address_space_limit_bytes)};
        ::setrlimit(RLIMIT_AS, &limit);
      }
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
  }
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  ~Program() {
    if (pid_ > 0 && !reaped_) kill_and_wait();
  }

  pid_t pid() const { return pid_; }
  std::string stdout_text() const { return read_text(options_.capture_dir / "stdout.txt"); }

  // Waits up to timeout_s; kills the child (SIGKILL) if it is still running.
  ProgramResult wait(double timeout_s) {
    ProgramResult result;
    int status = 0;
    for (;;) {
      const pid_t done = ::waitpid(pid_, &status, WNOHANG);
      if (done == pid_) break;
      if (seconds() > timeout_s) {
        result.timed_out = true;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    reaped_ = true;
    return finish(result, status);
  }

  ProgramResult kill_and_wait() {
    ::kill(pid_, SIGKILL);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    reaped_ = true;
    return finish(ProgramResult{}, status);
  }

  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  ProgramResult finish(ProgramResult result, int status) {
    result.seconds = seconds();
    result.exited = WIFEXITED(status);
    if (result.exited) result.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    result.out = read_text(options_.capture_dir / "stdout.txt");
    result.err = read_text(options_.capture_dir / "stderr.txt");
    return result;
  }

  ProgramOptions options_;
  std::vector<std::string> argv_storage_;
  pid_t pid_ = -1;
  bool reaped_ = false;
  std::chrono::steady_clock::time_point start_;
};

// A fresh, empty directory under the system temporary directory.
inline std::filesystem::path fresh_temp_dir(const std::string& tag) {
  auto base = std::filesystem::temp_directory_path() /
              ("kinetofem-" + tag + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(base);
  std::filesystem::create_directories(base);
  return base;
}

}  // namespace kinetofem::test
