// Unit tests of case-file reading: schema checks and their error messages.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <utility>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {
namespace {

std::string error_of(const std::string& text) {
  try {
    CaseFile::parse(text, "case.toml", fe_static_schema());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal = "[case]\ntype = \"fe_static\"\n";

TEST(CaseFile, ReadsValuesInSiUnitsAndDefaults) {
  const CaseFile c = CaseFile::parse(std::string(kMinimal) +
                                         "[geometry]\nlength_mm = 400\n[material]\nyoungs_modulus_mpa = 70000\n",
                                     "case.toml", fe_static_schema());
  EXPECT_DOUBLE_EQ(c.number("geometry.length_mm"), 0.4);
  EXPECT_DOUBLE_EQ(c.number("material.youngs_modulus_mpa"), 70e9);
  EXPECT_DOUBLE_EQ(c.number("material.poisson_ratio"), 0.3);  // default
  EXPECT_EQ(c.integer("mesh.order"), 2);
  EXPECT_EQ(c.text_value("geometry.kind"), "lever");
}

TEST(CaseFile, UnknownKeyNamesFileLineAndKey) {
  const std::string e = error_of(std::string(kMinimal) + "[material]\nyoung = 3\n");
  EXPECT_NE(e.find("case.toml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'material.young'"), std::string::npos) << e;
  EXPECT_NE(e.find("youngs_modulus_mpa"), std::string::npos) << e;  // lists what is allowed
}

TEST(CaseFile, OutOfRangeAndMistypedValuesAreErrors) {
  std::string e = error_of(std::string(kMinimal) + "[material]\npoisson_ratio = 0.5\n");
  EXPECT_NE(e.find("case.toml:4: key 'material.poisson_ratio' = 0.5 is out of range"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[geometry]\nlength_mm = -5\n");
  EXPECT_NE(e.find("geometry.length_mm"), std::string::npos) << e;
  EXPECT_NE(e.find("out of range"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[geometry]\nlength_mm = \"long\"\n");
  EXPECT_NE(e.find("must be a number"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[geometry]\nlength_mm = nan\n");
  EXPECT_NE(e.find("not a finite number"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[mesh]\norder = 3\n");
  EXPECT_NE(e.find("mesh.order"), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[[support]]\nset = \"a\"\nfixed = [\"x\", \"w\"]\n");
  EXPECT_NE(e.find("\"w\""), std::string::npos) << e;
  e = error_of(std::string(kMinimal) + "[[force]]\nset = \"a\"\ntotal_n = [1, 2]\n");
  EXPECT_NE(e.find("array of 3 numbers"), std::string::npos) << e;
}

TEST(CaseFile, SyntaxErrorGivesLineAndColumn) {
  const std::string e = error_of("[case]\ntype = \"fe_static\n");
  EXPECT_NE(e.find("case.toml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("TOML syntax error"), std::string::npos) << e;
}

TEST(CaseFile, MissingRequiredKeyIsNamed) {
  const std::string e = error_of("[material]\npoisson_ratio = 0.3\n");
  EXPECT_NE(e.find("required key 'case.type'"), std::string::npos) << e;
}

TEST(CaseFile, MissingFileIsNamed) {
  try {
    CaseFile::load("/nonexistent/case.toml", fe_static_schema());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/case.toml: case file does not exist"),
              std::string::npos);
  }
}

TEST(CaseFile, TemplateListsEveryKeyWithItsUnit) {
  const std::string t = schema_template(fe_static_schema(), "fe_static");
  EXPECT_NE(t.find("youngs_modulus_mpa = 210000"), std::string::npos) << t;
  EXPECT_NE(t.find("unit: mm"), std::string::npos);
  EXPECT_NE(t.find("[[support]]"), std::string::npos);
  // The template itself is a valid case once the required keys are filled.
}

TEST(CaseFile, EveryTemplateDefinesEachTableOnce) {
  // TOML forbids defining a table twice: a key's table may be declared in
  // several places of a schema ([solver] by the manipulator and by the shared
  // solver keys), the template must still write it once.
  for (const auto& type : case_types()) {
    const std::string& name = type.name;
    const std::string t = schema_template(type.schema(), name);
    std::set<std::string> headers;
    std::istringstream in(t);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("[", 0) == 0 && line.rfind("[[", 0) != 0) {
        EXPECT_TRUE(headers.insert(line).second) << name << ": " << line << " twice";
      }
    EXPECT_LE(headers.count("[solver]"), 1u) << name;
  }
}

TEST(CaseFile, ManipulatorTemplateWritesTheGravityTheJobUses) {
  // Found when tried: the template wrote gravity_m_s2 = [0.0, 0.0, 0.0] under a
  // comment saying the default is [0, -9.80665, 0], so a case copied from it
  // ran without gravity. Reference: standard gravity, ISO 80000-3
  // (units::kStandardGravity), along -y (SPEC §1: the mechanism in a vertical plane).
  std::vector<KeySpec> schema = manipulator_schema();
  for (auto& k : schema) k.required = false;  // the template leaves required keys out
  const CaseFile from_template = CaseFile::parse(schema_template(schema, "manipulator"), "template.toml", schema);
  const CaseFile without_key = CaseFile::parse("", "case.toml", schema);
  const Eigen::Vector3d expected(0.0, -units::kStandardGravity, 0.0);
  EXPECT_EQ(from_template.vector3("mechanism.gravity_m_s2"), expected);
  EXPECT_EQ(without_key.vector3("mechanism.gravity_m_s2"), expected);
}

TEST(CaseFile, EveryTemplateValueIsTheDefaultAnAbsentKeyGets) {
  // One value per default: a key copied from the template must mean what
  // leaving it out means, for every case type and every key with a default
  // (keys of arrays of tables are written commented out, so they are skipped).
  for (const auto& type : case_types()) {
    std::vector<KeySpec> schema = type.schema();
    for (auto& k : schema) k.required = false;  // the template leaves required keys out
    const CaseFile from_template = CaseFile::parse(schema_template(schema, type.name), "template.toml", schema, true);
    const CaseFile empty = CaseFile::parse("", "case.toml", schema, true);
    for (const KeySpec& k : schema) {
      if (k.path.find("[]") != std::string::npos || k.required) continue;
      if (!k.default_number && !k.default_text && !k.default_vector) continue;
      switch (k.type) {
        case KeySpec::Type::Number:
          EXPECT_DOUBLE_EQ(from_template.number(k.path), empty.number(k.path)) << type.name << ": " << k.path;
          break;
        case KeySpec::Type::Integer:
          EXPECT_EQ(from_template.integer(k.path), empty.integer(k.path)) << type.name << ": " << k.path;
          break;
        case KeySpec::Type::Boolean:
          EXPECT_EQ(from_template.boolean(k.path), empty.boolean(k.path)) << type.name << ": " << k.path;
          break;
        case KeySpec::Type::Vector3:
          EXPECT_EQ(from_template.vector3(k.path), empty.vector3(k.path)) << type.name << ": " << k.path;
          break;
        case KeySpec::Type::String:
          EXPECT_EQ(from_template.text_value(k.path), empty.text_value(k.path)) << type.name << ": " << k.path;
          break;
        default:
          break;
      }
    }
  }
}

}  // namespace
}  // namespace kinetofem::app
