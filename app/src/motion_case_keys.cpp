#include "kinetofem/app/motion_case_keys.hpp"

#include <cstdio>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/fatigue_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/vibration_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/pipeline/part_model.hpp"

namespace kinetofem::app {

std::vector<std::string> bodies_with_parts(const std::vector<pipeline::PartSpec>& parts) {
  std::vector<std::string> bodies;
  for (const auto& p : parts) bodies.push_back(p.attachments.body);
  return bodies;
}

void read_shared_motion_keys(const CaseFile& c, const RunOptions& options, const std::string& name,
                             const AssemblyReader& read_assembly, driver::MotionStressCase& run_case) {
  run_case.label = c.path().string();
  const std::vector<std::string> bodies = bodies_with_parts(run_case.parts);
  run_case.assembly = read_assembly(bodies);
  run_case.vibration = read_vibration(c, run_case.assembly);
  run_case.fatigue = read_fatigue(c, bodies);
  // Parts in several planes: the moments between the planes are only in the
  // elastic assembly's 3D joint loads, which their fatigue check then uses.
  if (run_case.fatigue && !run_case.assembly && pipeline::parts_in_several_planes(run_case.parts))
    fail("{} = true: the parts sit in several planes (their offset_mm z differs), so their fatigue needs the elastic "
         "assembly's 3D joint loads (the moments between the planes): set assembly.enabled = true",
         c.where("fatigue.enabled"));
  run_case.material = read_material(c);
  run_case.mesh = read_part_mesh_options(c, options.output_dir);
  run_case.stress = read_stress_options(c);
  run_case.stress.callback_steps = read_field_output_steps(c, run_case.times);
  run_case.results_file = mechanism_results_path(c, options, name);
  run_case.provenance = mechanism_provenance(c, options);
}

void print_stage_summaries(const driver::MotionStressRun& run) {
  if (run.assembly) std::printf("%s", pipeline::format_assembly_summary(*run.assembly).c_str());
  if (run.vibration) std::printf("%s", pipeline::format_vibration_summary(*run.vibration).c_str());
  report_fatigue(run.fatigue, run.results_file);
}

}  // namespace kinetofem::app
