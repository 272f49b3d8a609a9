// Unit tests of case-file reading: schema checks and their error messages.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/material.hpp"

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

// case.name becomes file names in the output folder: anything that could leave
// it, collide after a C-string cut or exceed NAME_MAX is refused while reading.
TEST(CaseFile, CaseNameMustBeAFileNameInTheOutputFolder) {
  const auto name_error = [](const std::string& toml_name) {
    return error_of("[case]\ntype = \"fe_static\"\nname = " + toml_name + "\n");
  };
  EXPECT_EQ(name_error("\"lever_1\""), "");
  EXPECT_EQ(name_error("\"r.v2+x=1\""), "");
  std::string e = name_error("\"../../x\"");
  EXPECT_NE(e.find("case.toml:3: key 'case.name' = \"../../x\" cannot be a file name in the output folder: it holds "
                   "the path separator '/' (byte 2)"),
            std::string::npos)
      << e;
  e = name_error("\"a\\\\b\"");
  EXPECT_NE(e.find("path separator '\\'"), std::string::npos) << e;
  // The NUL is inside the string: the whole std::string is checked, not the prefix "r".
  e = name_error("\"r\\u0000x\"");
  EXPECT_NE(e.find("= \"r\\u0000x\" cannot be a file name in the output folder: it holds the control character "
                   "U+0000 (byte 1)"),
            std::string::npos)
      << e;
  EXPECT_NE(name_error("\"a\\tb\"").find("control character U+0009"), std::string::npos);
  EXPECT_NE(name_error("\"\"").find("it is empty"), std::string::npos);
  EXPECT_NE(name_error("\"..\"").find("\".\" and \"..\" name folders"), std::string::npos);
  EXPECT_NE(name_error("\".\"").find("\".\" and \"..\" name folders"), std::string::npos);
  EXPECT_EQ(name_error("\"" + std::string(kMaxRunNameBytes, 'n') + "\""), "");
  e = name_error("\"" + std::string(kMaxRunNameBytes + 1, 'n') + "\"");
  EXPECT_NE(e.find("it has 121 bytes, more than 120"), std::string::npos) << e;
  // An override is checked the same way.
  try {
    CaseFile::parse(kMinimal, "case.toml", fe_static_schema(), false, {"case.name=\"../x\""});
    ADD_FAILURE() << "an override case.name = \"../x\" was accepted";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("--set case.name=\"../x\": key 'case.name' = \"../x\" cannot be"),
              std::string::npos)
        << err.what();
  }
}

// Without case.name the run is named after the case file's folder, normalised
// first ("sub/../case.toml" is in the folder above sub) and checked the same way.
TEST(CaseFile, DefaultCaseNameIsTheNormalisedFolderName) {
  EXPECT_EQ(default_case_name("/data/runs/lever/case.toml"), "lever");
  EXPECT_EQ(default_case_name("/data/runs/lever/sub/../case.toml"), "lever");
  const CaseFile at_root = CaseFile::parse(kMinimal, "/case.toml", fe_static_schema());
  try {
    case_name(at_root);
    ADD_FAILURE() << "a case in / got a name";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("/case.toml: the case folder's name"), std::string::npos) << err.what();
  }
}

// One formatter for every range message: it shows the limit the value
// crossed, also a default one, and a unit's plausible range where a key
// declares no upper limit of its own.
TEST(CaseFile, RangeMessagesShowTheLimitThatWasCrossed) {
  using Type = KeySpec::Type;
  const std::vector<KeySpec> schema = {
      {.path = "a.ratio", .type = Type::Number, .min = 0, .min_exclusive = true},
      {.path = "a.mass_kg", .type = Type::Number, .unit = "kg", .min = 0},
      {.path = "a.force_n", .type = Type::Vector3, .unit = "N"},
      {.path = "a.density", .type = Type::Number, .unit = "kg/m^3", .min = 1, .max = 1e5, .zero_allowed = true},
  };
  const auto error = [&](const std::string& text) {
    try {
      CaseFile::parse(text, "c.toml", schema);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error("[a]\nratio = 1e301\n"), "c.toml:2: key 'a.ratio' = 1e+301 is out of range: must be >0 and <=1e+300");
  EXPECT_EQ(error("[a]\nratio = 0\n"), "c.toml:2: key 'a.ratio' = 0 is out of range: must be >0");
  EXPECT_EQ(error("[a]\nmass_kg = 1e300\n"),
            "c.toml:2: key 'a.mass_kg' = 1e+300 kg is out of range: must be >=0 and <=1e+06 kg (a plausible mass: up "
            "to 1000 t)");
  EXPECT_EQ(error("[a]\nforce_n = [0, 2e9, 0]\n"),
            "c.toml:2: key 'a.force_n' = 2e+09 N is out of range: must be >=-1e+09 and <=1e+09 N (a plausible force: "
            "up to 1 GN)");
  EXPECT_EQ(error("[a]\ndensity = 0\n"), "");
  EXPECT_EQ(error("[a]\ndensity = 0.5\n"),
            "c.toml:2: key 'a.density' = 0.5 kg/m^3 is out of range: must be 0, or >=1 and <=100000 kg/m^3");
  // The template states the same ranges.
  const std::string tmpl = schema_template(schema, "t");
  EXPECT_NE(tmpl.find("range: >=0 and <=1e+06 kg (a plausible mass: up to 1000 t)"), std::string::npos) << tmpl;
  // Young's modulus and Poisson's ratio: plausible for a solid, and the ratio's range is the solver's.
  EXPECT_NE(error_of(std::string(kMinimal) + "[material]\nyoungs_modulus_mpa = 1e-300\n")
                .find("= 1e-300 MPa is out of range: must be >=0.001 and <=1e+07 MPa"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "[material]\npoisson_ratio = -1\n").find("must be >-1 and <=0.4999"),
            std::string::npos);
  fem::IsotropicMaterial lowest;
  lowest.poisson_ratio = std::nextafter(-1.0, 0.0);
  EXPECT_NO_THROW(lowest.validate());
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

// An input path that is not a regular file says what it is: a FIFO (which
// would block the reader forever), a directory, a symlink loop.
TEST(CaseFile, InputPathThatIsNotARegularFileSaysWhatItIs) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kinetofem_input_kinds_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "folder.toml");
  ASSERT_EQ(::mkfifo((dir / "fifo.toml").c_str(), 0600), 0);
  std::filesystem::create_symlink("loop_b.toml", dir / "loop_a.toml");
  std::filesystem::create_symlink("loop_a.toml", dir / "loop_b.toml");
  std::filesystem::create_symlink("nothing.toml", dir / "dangling.toml");
  std::ofstream(dir / "plain.toml") << kMinimal;
  EXPECT_EQ(input_file_problem(dir / "plain.toml"), "");
  EXPECT_EQ(input_file_problem(dir / "none.toml"), "no such file");
  EXPECT_EQ(input_file_problem(dir / "dangling.toml"), "no such file (a symlink to nothing)");
  EXPECT_EQ(input_file_problem(dir / "folder.toml"), "is a directory");
  EXPECT_EQ(input_file_problem(dir / "fifo.toml"), "is not a regular file (a FIFO)");
  EXPECT_EQ(input_file_problem(dir / "loop_a.toml"), "is a symlink loop");
  const auto load_error = [](const std::filesystem::path& file) {
    try {
      CaseFile::load(file, fe_static_schema());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(load_error(dir / "fifo.toml"), (dir / "fifo.toml").string() + ": is not a regular file (a FIFO), expected a case file (case.toml)");
  EXPECT_EQ(load_error(dir / "loop_a.toml"), (dir / "loop_a.toml").string() + ": is a symlink loop, expected a case file (case.toml)");
  EXPECT_EQ(load_error(dir / "folder.toml"), (dir / "folder.toml").string() + ": is a directory, expected a case file (case.toml)");
  std::filesystem::remove_all(dir);
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
