#include "kinetofem/meshes/gmsh_session.hpp"

#include <atomic>
#include <exception>

#include <gmsh.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes {

namespace {
// Gmsh itself is one global; this flag only detects a second session (which
// would finalize the first one's model under it). It is the sole piece of
// static state in the module, and it mirrors Gmsh's own.
std::atomic<bool> session_alive{false};

std::string trim_level(const std::string& line, const std::string& level) {
  // Gmsh's logger prefixes "Error: " / "Warning: ".
  return line.substr(level.size());
}
}  // namespace

GmshSession::GmshSession(bool verbose) {
  bool expected = false;
  require(session_alive.compare_exchange_strong(expected, true),
          "a Gmsh session is already open (Gmsh has one global state: open one session at a "
          "time, from one thread)");
  try {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    gmsh::option::setNumber("General.Verbosity", verbose ? 5 : 2);
    // 2 = throw on error (the API's default, set explicitly because the rest
    // of this class relies on it).
    gmsh::option::setNumber("General.AbortOnError", 2);
  } catch (...) {
    session_alive = false;
    fail("Gmsh could not be initialized");
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::finalize();
  } catch (...) {
    // A destructor must not throw; Gmsh's state is gone either way.
  }
  session_alive = false;
}

void GmshSession::begin_call() { gmsh::logger::start(); }

void GmshSession::end_call(const std::string& context, const std::string& what,
                           const std::string* exception_message) {
  std::vector<std::string> log;
  try {
    gmsh::logger::get(log);
    gmsh::logger::stop();
  } catch (...) {
  }
  std::string first_error;
  for (const auto& line : log) {
    if (line.rfind("Error: ", 0) == 0 && first_error.empty())
      first_error = trim_level(line, "Error: ");
    else if (line.rfind("Warning: ", 0) == 0)
      warnings_.push_back(trim_level(line, "Warning: "));
  }
  if (exception_message) {
    const std::string& message = exception_message->empty() ? first_error : *exception_message;
    fail("{}: {} failed: {}", context, what, message.empty() ? "unknown Gmsh error" : message);
  }
  require(first_error.empty(), "{}: {} failed: {}", context, what, first_error);
}

void GmshSession::rethrow_current(const std::string& context, const std::string& what) {
  std::string message;
  try {
    throw;
  } catch (const Error&) {
    throw;  // already ours (from end_call)
  } catch (const std::string& text) {
    message = text;
  } catch (const char* text) {
    message = text ? text : "";
  } catch (const std::exception& error) {
    message = error.what();
  } catch (int code) {
    message = "Gmsh error code " + std::to_string(code);
  } catch (...) {
    message = "";
  }
  end_call(context, what, &message);
  fail("{}: {} failed", context, what);  // not reached: end_call throws
}

}  // namespace kinetofem::meshes
