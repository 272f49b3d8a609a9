#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

const std::vector<CaseType>& case_types() {
  static const std::vector<CaseType> types = {
      {"fe_static", "one linear-elastic part under static loads", &fe_static_schema,
       [](const CaseFile& c, const RunOptions& o) { run_fe_static(c, o); return 0; }},
      {"manipulator",
       "lever-chain or lever manipulator: motion, loads on every link, stress over the motion",
       &manipulator_schema,
       [](const CaseFile& c, const RunOptions& o) { run_manipulator(c, o); return 0; }},
      {"linkage", "any planar linkage (bodies, joints, chains, springs, drives): dynamics, reactions, drive efforts",
       &linkage_schema, [](const CaseFile& c, const RunOptions& o) { run_linkage(c, o); return 0; }},
      {"lever_chain_kinematics", "SPEC §1 lever-chain: synthesis, paths of C and H, straightness, speeds for a motion law",
       &lever_chain_kinematics_schema, [](const CaseFile& c, const RunOptions& o) { run_lever_chain_kinematics(c, o); return 0; }},
      {"four_bar_study", "SPEC §2 lever-chain vs equivalent four-bar over the same lever motion",
       &four_bar_study_schema, [](const CaseFile& c, const RunOptions& o) { run_four_bar_study(c, o); return 0; }},
      {"q_manipulator", "SPEC §4 Q-manipulator: path of H, cusps, isokinematic equivalent",
       &q_manipulator_schema, [](const CaseFile& c, const RunOptions& o) { run_q_manipulator(c, o); return 0; }},
      {"spherical_manipulator", "SPEC §5 spherical 3-DoF manipulator: straight-line motion, inverse dynamics, forward check",
       &spherical_manipulator_schema, [](const CaseFile& c, const RunOptions& o) { run_spherical_manipulator(c, o); return 0; }},
      {"gripper_study", "SPEC §6 crank-slider gripper: U_V over phi, operating ranges, widest design",
       &gripper_study_schema, [](const CaseFile& c, const RunOptions& o) { run_gripper_study(c, o); return 0; }},
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
  return type.run(c, options);
}

}  // namespace kinetofem::app
