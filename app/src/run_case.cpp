#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <limits>

#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/app/spatial_linkage_job.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/pipeline/run_report.hpp"

namespace kinetofem::app {

namespace {

using units::kMm;
using units::kMpa;

RunSummary summary_of(const FeStaticSummary& s) {
  return {.results_file = s.results_file, .max_von_mises_pa = s.max_von_mises_pa,
          .max_displacement_m = s.max_displacement_m,
          .extra = {{"dofs", double(s.dof_count)}, {"reaction_balance", s.reaction_balance}}};
}

// The elastic assembly's key results: total deformation (max |u| over all
// nodes, world, from the rigid pose) and the tracked points' deflection.
void add_assembly_results(RunSummary& s, const std::optional<pipeline::AssemblySummary>& a) {
  if (!a) return;
  s.extra.push_back({"total_deformation_mm", a->max_displacement_m / kMm});
  if (a->has_static_study) s.extra.push_back({"static_total_deformation_mm", a->static_max_displacement_m / kMm});
  for (const auto& p : a->points) {
    s.extra.push_back({"max_deflection_" + p.name + "_mm", p.max_displacement_m / kMm});
    if (p.has_static_study) s.extra.push_back({"static_deflection_" + p.name + "_mm", p.static_displacement_m.norm() / kMm});
  }
}

// The fatigue check's key results: the shortest life (h; inf where no range
// reaches the cut-off) over the parts and per part, the largest utilization.
void add_fatigue_results(RunSummary& s, const std::vector<pipeline::PartFatigue>& parts) {
  if (parts.empty()) return;
  double min_life_s = std::numeric_limits<double>::infinity(), max_utilization = 0.0, max_damage = 0.0;
  for (const auto& p : parts) {
    min_life_s = std::min(min_life_s, p.min_life_s);
    max_utilization = std::max(max_utilization, p.max_utilization);
    max_damage = std::max(max_damage, p.max_damage_per_cycle);
  }
  s.extra.push_back({"fatigue_min_life_h", min_life_s / units::kHour});
  s.extra.push_back({"fatigue_max_utilization", max_utilization});
  s.extra.push_back({"fatigue_max_damage_per_cycle", max_damage});
  for (const auto& p : parts) {
    s.extra.push_back({"fatigue_life_h_" + p.body, p.min_life_s / units::kHour});
    s.extra.push_back({"fatigue_utilization_" + p.body, p.max_utilization});
  }
}

// Pins in contact: the largest peak contact pressure over the parts and per pin (MPa).
void add_contact_results(RunSummary& s, const std::vector<pipeline::PartSummary>& parts) {
  double largest = 0.0;
  bool any = false;
  for (const auto& p : parts)
    for (const auto& c : p.contacts) {
      any = true;
      largest = std::max(largest, c.peak_pressure_pa);
      s.extra.push_back({"contact_pressure_" + p.body + "_" + c.joint + "_mpa", c.peak_pressure_pa / kMpa});
    }
  if (any) s.extra.push_back({"max_contact_pressure_mpa", largest / kMpa});
}

// The vibration's key results (Hz, s, mm): the first natural frequency's
// range over the motion and in the static pose, per tracked point the dynamic
// amplification, the ringing after the stop and the settling time (inf: never).
void add_vibration_results(RunSummary& s, const std::optional<pipeline::VibrationSummary>& v) {
  if (!v) return;
  s.extra.push_back({"vibration_min_first_frequency_hz", v->lowest_first_hz});
  s.extra.push_back({"vibration_max_first_frequency_hz", v->highest_first_hz});
  if (v->has_static_study) s.extra.push_back({"vibration_static_first_frequency_hz", v->static_frequency_hz(0)});
  for (const auto& p : v->points) {
    s.extra.push_back({"vibration_amplification_" + p.name, p.dynamic_amplification});
    s.extra.push_back({"vibration_after_stop_" + p.name + "_mm", p.amplitude_at_stop_m / kMm});
    s.extra.push_back({"vibration_settling_time_" + p.name + "_s", p.settling_time_s});
  }
}

RunSummary summary_of(const ManipulatorSummary& s) {
  RunSummary r{.results_file = s.results_file, .max_von_mises_pa = s.max_von_mises_pa,
               .max_displacement_m = s.max_displacement_m,
               .extra = {{"static_max_von_mises_mpa", s.static_max_von_mises_pa / kMpa},
                         {"static_max_displacement_mm", s.static_max_displacement_m / kMm},
                         {"max_drive_torque_nm", s.max_drive_torque_nm},
                         {"min_chain_tension_n", s.min_chain_tension_n}}};
  add_contact_results(r, s.links);
  add_assembly_results(r, s.assembly);
  add_vibration_results(r, s.vibration);
  add_fatigue_results(r, s.fatigue);
  return r;
}

RunSummary summary_of(const LinkageRun& r) {
  const pipeline::PartExtremes pe = pipeline::part_extremes(r.parts);
  RunSummary s{.results_file = r.results_file, .max_von_mises_pa = pe.max_von_mises_pa,
               .max_displacement_m = pe.max_displacement_m,
               .extra = {{"max_abs_drive_effort", r.max_abs_drive_effort}}};
  if (!r.results.frames.empty() && !r.results.frames.front().chains.empty())
    s.extra.push_back({"min_chain_tension_n", r.min_chain_tension_n});
  add_contact_results(s, r.parts);
  add_assembly_results(s, r.assembly);
  add_vibration_results(s, r.vibration);
  add_fatigue_results(s, r.fatigue);
  return s;
}

// The output folder exists (it is made) and a file can be created in it,
// checked before any work: a folder that cannot be written must not be found
// only when the results are written after a long solve. A probe file is
// created and removed, since access() says yes to root on a read-only mount.
void require_writable_output_folder(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  require(!ec, "{}: cannot create the output directory: {}", folder.string(), ec.message());
  const std::filesystem::path probe = folder / fmt::format(".kinetofem-write-probe-{}", long(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  require(fd >= 0, "output folder '{}' cannot be written: {} (checked before any work; -o sets another)",
          folder.string(), std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

// +inf in a summary value means "never" only for a fatigue life (no damage) and a settling time.
bool summary_may_be_infinite(const std::string& key) {
  return key.starts_with("fatigue_min_life_") || key.starts_with("fatigue_life_") ||
         key.starts_with("vibration_settling_time_");
}

// Every summary value is finite (or a documented +inf). Else the run's results
// files are removed: a run with a non-finite key result leaves no results.
void require_finite_summary(const RunSummary& s) {
  std::vector<std::pair<std::string, double>> values;
  if (s.max_von_mises_pa) values.push_back({"max_von_mises_mpa", *s.max_von_mises_pa});
  if (s.max_displacement_m) values.push_back({"max_displacement_mm", *s.max_displacement_m});
  values.insert(values.end(), s.extra.begin(), s.extra.end());
  for (const auto& [key, value] : values) {
    if (std::isfinite(value) || (value > 0 && summary_may_be_infinite(key))) continue;
    std::error_code ec;
    std::filesystem::remove(s.results_file, ec);
    std::filesystem::remove(std::filesystem::path(s.results_file).replace_extension(".xdmf"), ec);
    fail("summary value '{}' of '{}' is {}: the results '{}' are removed; a non-finite result comes from an "
         "overflow or 0/0 upstream (a material constant, load, mass or dimension far outside its plausible range?)",
         key, s.name, value, s.results_file.string());
  }
}

// A mechanism-only case type's key results are its named values.
RunSummary summary_of(const MechanismCaseSummary& m) {
  return {.results_file = m.results_file,
          .max_von_mises_pa = m.max_von_mises_pa,
          .max_displacement_m = m.max_displacement_m,
          .extra = m.values};
}

// A case type's CaseType::run: its job, then its key results (the type's name
// is filled in by run_case).
template <auto Job>
RunSummary run_type(const CaseFile& c, const RunOptions& o) {
  return summary_of(Job(c, o));
}

}  // namespace

const std::vector<CaseType>& case_types() {
  static const std::vector<CaseType> types = {
      {"fe_static", "one linear-elastic part under static loads", &fe_static_schema,
       &run_type<run_fe_static>},
      {"manipulator",
       "lever-chain or lever manipulator: motion, loads on every link, stress over the motion",
       &manipulator_schema, &run_type<run_manipulator>},
      {"linkage",
       "any planar linkage (bodies, joints, chains, springs, drives): dynamics, reactions, drive efforts, and the "
       "stress of its FE parts (parametric links or CAD files) over the motion",
       &linkage_schema, &run_type<run_linkage>},
      {"lever_chain_kinematics", "SPEC §1 lever-chain: synthesis, paths of C and H, straightness, speeds for a motion law",
       &lever_chain_kinematics_schema, &run_type<run_lever_chain_kinematics>},
      {"four_bar_study", "SPEC §2 lever-chain vs equivalent four-bar over the same lever motion",
       &four_bar_study_schema, &run_type<run_four_bar_study>},
      {"q_manipulator", "SPEC §4 Q-manipulator: path of H, cusps, isokinematic equivalent",
       &q_manipulator_schema, &run_type<run_q_manipulator>},
      {"spherical_manipulator", "SPEC §5 spherical 3-DoF manipulator: straight-line motion, inverse dynamics, forward check",
       &spherical_manipulator_schema, &run_type<run_spherical_manipulator>},
      {"spatial_linkage",
       "any spatial linkage of rigid bodies (joint axes in any direction): prescribed motion or IDAS dynamics, every "
       "joint's reaction, drive efforts, energy checks, the moving skeleton",
       &spatial_linkage_schema, &run_type<run_spatial_linkage>},
      {"gripper_study", "SPEC §6 crank-slider gripper: U_V over phi, operating ranges, widest design",
       &gripper_study_schema, &run_type<run_gripper_study>},
  };
  return types;
}

const CaseType& case_type_named(const std::string& name, const std::string& context) {
  std::string known;
  for (const auto& type : case_types()) {
    if (type.name == name) return type;
    known += (known.empty() ? "\"" : ", \"") + type.name + "\"";
  }
  fail("{}case.type = \"{}\" is not a known case type (known: {})", context, name, known);
}

std::string case_template(const std::string& type) {
  const CaseType& t = case_type_named(type, "");
  return schema_template(t.schema(), "kinetofem case template: " + t.name + " — " + t.summary);
}

int run_case(const RunOptions& options) {
  // Read case.type first, then check the whole file against that type's schema.
  const CaseFile any = CaseFile::load(
      options.case_path, {{.path = "case.type", .type = KeySpec::Type::String, .required = true}},
      /*allow_unknown=*/true, options.overrides);
  const CaseType& type = case_type_named(any.text_value("case.type"), options.case_path.string() + ": ");
  const CaseFile c = CaseFile::load(options.case_path, type.schema(), /*allow_unknown=*/false, options.overrides);
  case_name(c);  // a name that cannot be a file name is refused before any work
  require_writable_output_folder(options.output_dir);
  Stopwatch clock;
  RunSummary summary = type.run(c, options);
  summary.type = type.name;
  // Key results for `kinetofem batch`: OUTPUT_DIR/<name>.summary.toml, for every case type.
  summary.name = summary.results_file.stem().string();
  summary.wall_time_s = clock.seconds();
  require_finite_summary(summary);
  write_run_summary(options.output_dir, summary);
  return 0;
}

}  // namespace kinetofem::app
