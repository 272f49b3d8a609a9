// The case files compiled into the program (embedded_cases.hpp) are those of
// cases/ byte for byte, and valid manipulator cases.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/embedded_cases.hpp"
#include "kinetofem/app/fatigue_keys.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/app/vibration_keys.hpp"

namespace kinetofem::app {
namespace {

// The tests run from the source root (kinetofem_test_dir).
std::string source_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  EXPECT_TRUE(bool(in)) << file;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(EmbeddedCases, AreTheCaseFilesAndParse) {
  const std::pair<std::string_view, const char*> cases[] = {
      {lever_chain_manipulator_case_text(), "lever_chain_manipulator"},
      {lever_manipulator_case_text(), "lever_manipulator"}};
  for (const auto& [text, name] : cases) {
    const std::string path = std::string("cases/") + name + "/case.toml";
    EXPECT_EQ(text, source_text(path)) << path;
    const CaseFile c = CaseFile::parse(std::string(text), path, manipulator_schema());
    EXPECT_EQ(c.text_value("case.name"), name);
  }
}

TEST(EmbeddedCases, StagesSwitchOffFromTheCommandLineWithTheirSettingsLeftInTheFile) {
  // `kinetofem run case.toml --set vibration.enabled=false`: the stage is off
  // on purpose, its other keys stay unused without an error (a key in a table
  // without `enabled` at all is still an error: bad input 127).
  const std::string text(lever_manipulator_case_text());
  const CaseFile off = CaseFile::parse(text, "case.toml", manipulator_schema(), false,
                                       {"vibration.enabled=false", "fatigue.enabled=false"});
  EXPECT_FALSE(read_vibration(off, structure::AssemblyOptions{}).has_value());
  EXPECT_FALSE(read_fatigue(off, {"lever", "arm", "rocker"}).has_value());
  const CaseFile on = CaseFile::parse(text, "case.toml", manipulator_schema());
  EXPECT_TRUE(read_vibration(on, structure::AssemblyOptions{}).has_value());
  EXPECT_TRUE(read_fatigue(on, {"lever", "arm", "rocker"}).has_value());
}

}  // namespace
}  // namespace kinetofem::app
