// The SPEC §1 and §2 manipulators as presets of the general motion-to-stress
// pipeline (pipeline/manipulator_preset.hpp) give the numbers the dedicated
// manipulator job of main at b7b6faa gave, before the pipeline existed.
// Reference: that program's runs of cases/lever_chain_manipulator and
// cases/lever_manipulator with --set mesh.element_size_mm=20 --set
// motion.output_times=21 (its .summary.toml at full precision; the per-link
// peaks as it printed them, 3 decimals in MPa). Tolerances: 1e-9 relative on
// the full-precision values (the same arithmetic, so equal up to round-off of
// a reordered sum), half the printed last digit on the printed ones; peak
// node and time exactly.
#include <gtest/gtest.h>

#include <filesystem>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/manipulator_job.hpp"

namespace kinetofem::app {
namespace {

struct LinkReference {
  const char* body;
  double peak_von_mises_mpa;  // printed, 3 decimals
  double time_s;
  long node;
};

struct CaseReference {
  const char* case_dir;
  double max_von_mises_mpa, static_max_von_mises_mpa, max_displacement_mm, max_drive_torque_nm;
  std::vector<LinkReference> links;
};

const CaseReference kLeverChain{"lever_chain_manipulator", 10.73643427900288, 5.2197231412081138,
                                0.012916648219638924, 231.9454758125153,
                                {{"lever", 10.736, 1.8, 86}, {"arm", 5.220, 0.0, 1683}}};
const CaseReference kLever{"lever_manipulator", 5.8919591771035096, 5.7866331994737603, 0.0066675703170025235,
                           40.225689744341537,
                           {{"lever", 3.573, 2.0, 145}, {"arm", 5.892, 1.2, 151}, {"rocker", 1.956, 2.0, 2724}}};

void check_case(const CaseReference& ref) {
  RunOptions options;
  options.case_path = std::filesystem::path("cases") / ref.case_dir / "case.toml";
  options.output_dir = std::filesystem::temp_directory_path() / (std::string("kinetofem_preset_") + ref.case_dir);
  std::filesystem::remove_all(options.output_dir);
  options.quiet = true;
  options.overrides = {"mesh.element_size_mm=20", "motion.output_times=21"};
  const CaseFile c = CaseFile::load(options.case_path, manipulator_schema(), false, options.overrides);
  const ManipulatorSummary s = run_manipulator(c, options);
  EXPECT_NEAR(s.max_von_mises_pa / 1e6, ref.max_von_mises_mpa, 1e-9 * ref.max_von_mises_mpa);
  EXPECT_NEAR(s.static_max_von_mises_pa / 1e6, ref.static_max_von_mises_mpa, 1e-9 * ref.static_max_von_mises_mpa);
  EXPECT_NEAR(s.max_displacement_m / 1e-3, ref.max_displacement_mm, 1e-9 * ref.max_displacement_mm);
  EXPECT_NEAR(s.max_drive_torque_nm, ref.max_drive_torque_nm, 1e-9 * ref.max_drive_torque_nm);
  ASSERT_EQ(s.links.size(), ref.links.size());
  for (std::size_t k = 0; k < ref.links.size(); ++k) {
    const auto& link = s.links[k];
    EXPECT_EQ(link.body, ref.links[k].body);
    EXPECT_NEAR(link.peak_von_mises_pa / 1e6, ref.links[k].peak_von_mises_mpa, 0.5e-3) << link.body;
    EXPECT_NEAR(link.peak_von_mises_time_s, ref.links[k].time_s, 1e-12) << link.body;
    EXPECT_EQ(link.peak_von_mises_node, ref.links[k].node) << link.body;
  }
}

TEST(ManipulatorPresets, LeverChainNumbersEqualTheDedicatedJobOfMain) { check_case(kLeverChain); }

TEST(ManipulatorPresets, LeverNumbersEqualTheDedicatedJobOfMain) { check_case(kLever); }

}  // namespace
}  // namespace kinetofem::app
