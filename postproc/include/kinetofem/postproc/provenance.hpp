#pragma once
// Provenance — where a results file came from: the program, the case and the run.
//
// The caller fills the case and the command line; ResultsWriter stamps the
// kinetofem version, the git commit of the build and the creation time (UTC)
// itself, so a file cannot claim a version it was not written by. ResultsFile
// reads all of it back.
#include <string>

namespace kinetofem::post {

inline constexpr const char* kSiUnitsNote =
    "SI units throughout: m, kg, s, N, Pa, rad; each dataset's 'units' attribute names its unit "
    "('1' = dimensionless or an index)";

struct Provenance {
  std::string case_path;     // the case file as given on the command line
  std::string case_text;     // its full text, so the run can be repeated from the file alone
  std::string command_line;  // the command that made the file (see command_line_of)
  std::string units_note = kSiUnitsNote;

  // Stamped by ResultsWriter (any value given is replaced); filled by ResultsFile.
  std::string kinetofem_version;
  std::string git_commit;
  std::string created_utc;  // ISO 8601, e.g. "2024-05-01T12:34:56Z"
};

// The arguments joined by spaces, each one with spaces or quotes quoted.
std::string command_line_of(int argc, const char* const* argv);

// The current time as ISO 8601 UTC, "YYYY-MM-DDThh:mm:ssZ".
std::string utc_now_iso8601();

}  // namespace kinetofem::post
