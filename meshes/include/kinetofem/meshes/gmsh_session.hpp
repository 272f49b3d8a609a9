#pragma once
// GmshSession — the one owner of Gmsh's process-wide state.
//
// Gmsh keeps its models, options and ONELAB parameters in global variables
// that gmsh::initialize creates and gmsh::finalize destroys. A GmshSession is
// the only place in kinetofem that calls those two functions: construct one,
// make Gmsh calls through `call`, and the destructor finalizes Gmsh, also on
// the error path. Each session starts from Gmsh's built-in defaults (system
// gmshrc/option files are not read), so no run depends on a user's settings.
//
// NOT thread-safe, and not re-entrant: at most one session may exist in the
// process at a time (Gmsh has one global model); constructing a second one
// while the first is alive throws kinetofem::Error. The module's functions
// (read_msh, mesh_geometry, ...) each open and close their own session, so
// they must not be called while the caller holds one, nor from two threads.
//
// Error reporting in Gmsh 4.8: the API sets "General.AbortOnError" to 2, so an
// error inside Gmsh throws a std::string (the message) out of the API
// function; some API functions throw other types. Warnings and errors are
// also captured through gmsh::logger for the duration of each `call`. `call`
// turns all of these into one kinetofem::Error naming the context (usually a
// file) and the Gmsh function. Some failures are silent in Gmsh 4.8 (opening a
// missing or empty file succeeds with an empty model), so callers check
// existence and the resulting model themselves.
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace kinetofem::meshes {

class GmshSession {
 public:
  // verbose: let Gmsh print its own progress to the terminal; otherwise
  // Gmsh is silent and only its errors reach the caller (as Error).
  explicit GmshSession(bool verbose = false);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  GmshSession(GmshSession&&) = delete;
  GmshSession& operator=(GmshSession&&) = delete;

  // Runs `function` (a callable making Gmsh API calls). Any exception from
  // Gmsh, or an "Error" message Gmsh logged without throwing, is rethrown as
  // kinetofem::Error("<context>: <what> failed: <Gmsh's message>").
  // Gmsh's warnings are kept and can be read with `warnings()`.
  template <typename Function>
  decltype(auto) call(const std::string& context, const std::string& what, Function&& function);

  // Warnings Gmsh logged during the `call`s of this session, in order.
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  void begin_call();
  // Collects Gmsh's log of the call; throws if it holds an error (and
  // `exception_message`, if not empty, is what Gmsh threw).
  void end_call(const std::string& context, const std::string& what,
                const std::string* exception_message);
  [[noreturn]] void rethrow_current(const std::string& context, const std::string& what);

  std::vector<std::string> warnings_;
};

template <typename Function>
decltype(auto) GmshSession::call(const std::string& context, const std::string& what,
                                 Function&& function) {
  begin_call();
  try {
    if constexpr (std::is_void_v<decltype(function())>) {
      std::forward<Function>(function)();
      end_call(context, what, nullptr);
    } else {
      auto result = std::forward<Function>(function)();
      end_call(context, what, nullptr);
      return result;
    }
  } catch (...) {
    rethrow_current(context, what);
  }
}

}  // namespace kinetofem::meshes
