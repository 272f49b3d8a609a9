#pragma once
// Mechanism-only case types of the SPEC mechanisms (no FE): each reads a small
// schema, runs the closed-form model of mechanisms/, prints the key published
// numbers of SPEC next to the computed ones and writes its histories (or
// curves over the study's sample parameter) under /mechanism of
// results/<name>.h5 (+ .xdmf).
//
//   lever_chain_kinematics  SPEC §1  mechanisms/lever_chain.hpp
//   four_bar_study          SPEC §2  mechanisms/four_bar.hpp
//   q_manipulator           SPEC §4  mechanisms/q_manipulator.hpp
//   spherical_manipulator   SPEC §5  mechanisms/spherical_manipulator.hpp
//   gripper_study           SPEC §6  mechanisms/crank_slider_gripper.hpp
//
// The results writer's /mechanism/time grid is in seconds. Studies whose
// parameter is an angle (four_bar_study over the lever motion is timed; the
// gripper's crank angle and the Q-manipulator's lever angle are not) sweep it
// at a constant rate stated in the case (default 1 rad/s), so t is a real time
// of that sweep and the parameter itself is written as a history.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/postproc/provenance.hpp"

namespace kinetofem::app {

// The key numbers of a run (SI), by name, for tests and batch summaries.
struct MechanismCaseSummary {
  std::filesystem::path results_file;
  std::vector<std::pair<std::string, double>> values;
  // Over the FE parts, for a case type that has them; empty otherwise.
  std::optional<double> max_von_mises_pa, max_displacement_m;
  // Error naming the key if absent.
  double value(const std::string& name) const;
};

const std::vector<KeySpec>& lever_chain_kinematics_schema();
MechanismCaseSummary run_lever_chain_kinematics(const CaseFile& case_file, const RunOptions& options);

const std::vector<KeySpec>& four_bar_study_schema();
MechanismCaseSummary run_four_bar_study(const CaseFile& case_file, const RunOptions& options);

const std::vector<KeySpec>& q_manipulator_schema();
MechanismCaseSummary run_q_manipulator(const CaseFile& case_file, const RunOptions& options);

const std::vector<KeySpec>& spherical_manipulator_schema();
MechanismCaseSummary run_spherical_manipulator(const CaseFile& case_file, const RunOptions& options);

const std::vector<KeySpec>& gripper_study_schema();
MechanismCaseSummary run_gripper_study(const CaseFile& case_file, const RunOptions& options);

// ---- helpers shared by the mechanism case types (mechanism_case_common.cpp) ----

// The [case] keys every mechanism case type declares (type restricted to `type`).
std::vector<KeySpec> mechanism_case_keys(const std::string& type);
// The console of a case's run (job_log), after its first line:
// "kinetofem: case '<name>' (<case file>), <what>".
Log start_case_log(const CaseFile& case_file, const RunOptions& options, const std::string& name,
                   const std::string& what);
// case.name, or the case folder's name (case_name(): checked as a file name).
std::string mechanism_case_name(const CaseFile& case_file);
// options.output_dir / <name>.h5, creating the directory (Error naming it).
std::filesystem::path mechanism_results_path(const CaseFile& case_file, const RunOptions& options,
                                             const std::string& name);
post::Provenance mechanism_provenance(const CaseFile& case_file, const RunOptions& options);
// A key of KeySpec::Type::Array holding exactly 2 finite numbers, times to_si;
// `fallback` when absent. Error naming file, line and key otherwise.
Eigen::Vector2d read_vector2(const CaseFile& case_file, const std::string& path, std::size_t element,
                             double to_si, const Eigen::Vector2d& fallback = Eigen::Vector2d::Zero());
// A key of KeySpec::Type::Array holding finite numbers (any count), times to_si.
std::vector<double> read_numbers(const CaseFile& case_file, const std::string& path, std::size_t element,
                                 double to_si);

}  // namespace kinetofem::app
