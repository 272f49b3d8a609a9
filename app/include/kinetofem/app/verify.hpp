#pragma once
// `kinetofem verify` — the verification suite run in-process by the program
// itself, against the libraries it is built from, and written as a report.
// The references (SPEC numbers, analytic solutions) and check computations
// come from the verification library (verification/, kinetofem::verification),
// the same code the tests under tests/verification/ call; the program needs no
// source tree (its case files and geometry are compiled in). Reports:
//   DIR/verification_report.md    (Markdown table)
//   DIR/verification_report.html  (self-contained HTML, pass/fail in colour)
//
// A check is a small function that computes one or more rows. A row compares
// a computed value with a reference (a SPEC number or an analytic formula,
// named in `source`): error = |computed - reference| (Absolute) or that over
// |reference| (Relative), pass when error <= tolerance. Informational rows
// (Reported: the published stress analyses of SPEC §3, whose link geometry
// is reconstructed, not published) show the ratio computed / reference and
// never fail. A check that throws gives one failing row carrying the message.
//
// The registry is a plain vector, so a caller (the unit test) can run its own
// list, e.g. with a deliberately wrong reference, and see FAIL and exit 1.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace kinetofem::app {

enum class ErrorMeasure {
  Absolute,  // |computed - reference|, in the row's unit
  Relative,  // |computed - reference| / |reference|
  Reported,  // no tolerance: computed / reference shown, never fails
};

enum class Verdict { Pass, Fail, Reported };

struct CheckRow {
  std::string name;       // what is compared
  std::string source;     // SPEC section or formula of the reference
  std::string unit;       // of reference and computed ("1" = dimensionless)
  double reference = 0.0;
  double computed = 0.0;
  ErrorMeasure measure = ErrorMeasure::Absolute;
  double tolerance = 0.0;  // on the error, in the measure's terms
  std::string note;        // optional: why the tolerance, or an error message

  // Filled by evaluate() from the fields above.
  double error = 0.0;  // Absolute/Relative error; the ratio computed/reference when Reported
  Verdict verdict = Verdict::Fail;

  // Computes error and verdict. A non-finite computed value fails.
  void evaluate();
};

// Row constructors (evaluated already).
CheckRow compare_absolute(std::string name, std::string source, std::string unit, double reference,
                          double computed, double tolerance, std::string note = {});
CheckRow compare_relative(std::string name, std::string source, std::string unit, double reference,
                          double computed, double tolerance, std::string note = {});
CheckRow reported(std::string name, std::string source, std::string unit, double reference,
                  double computed, std::string note = {});

struct CheckContext {
  std::filesystem::path output_dir;  // for checks that write files (SPEC §3 runs)
  bool quick = false;
  bool quiet = false;
};

struct Check {
  std::string id;     // "spec1.design_geometry"
  std::string group;  // section of the report: "SPEC §1", "dynamics", "FEM", ...
  bool in_quick = true;  // false: run only without --quick
  std::function<std::vector<CheckRow>(const CheckContext&)> run;
};

// The registry, by group (verify_checks_*.cpp).
std::vector<Check> mechanism_checks();  // SPEC §1, §2, §4, §5, §6
std::vector<Check> dynamics_checks();   // multibody dynamics (SUNDIALS)
std::vector<Check> fem_checks();        // FEM core and load transfer
std::vector<Check> published_checks();  // SPEC §3, informational, not in --quick
std::vector<Check> default_checks();    // all of the above, in that order

struct ReportRow {
  std::string check_id;
  std::string group;
  CheckRow row;
};

struct VerificationReport {
  std::vector<ReportRow> rows;
  std::vector<std::pair<std::string, double>> check_seconds;  // wall time per check
  bool quick = false;
  double total_seconds = 0.0;
  // Provenance.
  std::string version, git_commit, date_utc, machine, command_line;
  int cores = 0;

  int failures() const;
  bool passed() const { return failures() == 0; }
};

struct VerifyOptions {
  std::filesystem::path output_dir = "verification";
  bool quick = false;
  bool quiet = false;
  std::string command_line;
};

// Runs the checks (those with in_quick only, when quick), each timed; a
// check that throws becomes one failing row with the message.
VerificationReport run_checks(const std::vector<Check>& checks, const VerifyOptions& options);

std::string report_markdown(const VerificationReport& report);
std::string report_html(const VerificationReport& report);

// Runs the checks, writes both report files into options.output_dir, prints
// the table, returns the exit code: 0 when every row passes, 1 otherwise.
int run_verify(const VerifyOptions& options, const std::vector<Check>& checks);
int run_verify(const VerifyOptions& options);  // default_checks()

}  // namespace kinetofem::app
