// `kinetofem verify`: the quick suite passes and writes both reports; a check
// given a wrong reference (through the registry parameter) shows FAIL and
// makes the exit code non-zero; a throwing check is a failing row.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

VerifyOptions quiet_options(const std::string& dir) {
  VerifyOptions options;
  options.output_dir = fs::temp_directory_path() / dir;
  fs::remove_all(options.output_dir);
  options.quick = true;
  options.quiet = true;
  return options;
}

const Check& check_named(const std::vector<Check>& checks, const std::string& id) {
  for (const auto& c : checks)
    if (c.id == id) return c;
  throw Error("no check " + id);
}

TEST(Verify, QuickSuiteWritesBothReportsAndEveryRowPasses) {
  const VerifyOptions options = quiet_options("kinetofem_verify_quick");
  EXPECT_EQ(run_verify(options), 0);
  const std::string md = read_text(options.output_dir / "verification_report.md");
  const std::string html = read_text(options.output_dir / "verification_report.html");
  ASSERT_FALSE(md.empty());
  ASSERT_FALSE(html.empty());
  EXPECT_EQ(count(md, "FAIL"), 0u) << md;
  EXPECT_NE(md.find("result: **PASS**"), std::string::npos);
  // Provenance.
  EXPECT_NE(md.find("git "), std::string::npos);
  EXPECT_NE(md.find("cores"), std::string::npos);
  // Every quick check ran and has at least one row; SPEC §3 runs are left out.
  std::size_t quick_checks = 0;
  for (const Check& c : default_checks()) {
    if (!c.in_quick) {
      EXPECT_EQ(md.find("| " + c.id + " |"), std::string::npos) << c.id;
      continue;
    }
    ++quick_checks;
    EXPECT_NE(md.find("| " + c.id + " |"), std::string::npos) << c.id;
  }
  EXPECT_GE(quick_checks, 15u);
  // HTML: a document with the results table, one row per check row, every one
  // a pass; tags balanced.
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  EXPECT_GE(count(html, "<table>"), 1u);
  EXPECT_EQ(count(html, "<table>"), count(html, "</table>"));
  EXPECT_EQ(count(html, "<tr"), count(html, "</tr>"));
  EXPECT_EQ(count(html, "<td"), count(html, "</td>"));
  const std::size_t rows = count(html, "<tr class=\"");
  EXPECT_GE(rows, 50u);
  EXPECT_EQ(count(html, "<tr class=\"pass\">"), rows);
  // The Markdown's data rows (lines starting with a group name): one per HTML row.
  std::size_t md_rows = 0;
  for (const char* group : {"\n| SPEC §", "\n| dynamics |", "\n| FEM |", "\n| load transfer |"})
    md_rows += count(md, group);
  EXPECT_EQ(md_rows, rows);
}

TEST(Verify, WrongReferenceShowsFailAndExitCodeIsNonZero) {
  const std::vector<Check> all = default_checks();
  const Check& good = check_named(all, "spec1.design_geometry");
  // The test hook: the same computation against a reference 1 mm off (b0 =
  // 412.765 mm instead of the published 411.765 mm).
  Check broken = good;
  broken.id = "spec1.design_geometry_wrong_reference";
  broken.run = [run = good.run](const CheckContext& context) {
    std::vector<CheckRow> rows = run(context);
    rows.at(0).reference += 1.0;
    rows.at(0).evaluate();
    return rows;
  };
  const VerifyOptions options = quiet_options("kinetofem_verify_broken");
  EXPECT_EQ(run_verify(options, {good, broken}), 1);
  const std::string md = read_text(options.output_dir / "verification_report.md");
  const std::string html = read_text(options.output_dir / "verification_report.html");
  EXPECT_NE(md.find("result: **FAIL**"), std::string::npos) << md;
  EXPECT_EQ(count(md, "| **FAIL** |"), 1u) << md;
  EXPECT_NE(md.find("412.765"), std::string::npos) << md;
  EXPECT_EQ(count(html, "<tr class=\"fail\">"), 1u);
  EXPECT_EQ(count(html, "<tr class=\"pass\">"), 5u);  // 3 rows each; the broken check's other two pass
}

TEST(Verify, ThrowingCheckIsAFailingRowWithItsMessage) {
  const Check throwing{"throws", "test", true, [](const CheckContext&) -> std::vector<CheckRow> {
                         fail("mesh file {} not found", "x.geo");
                       }};
  const VerificationReport report = run_checks({throwing}, quiet_options("kinetofem_verify_throw"));
  ASSERT_EQ(report.rows.size(), 1u);
  EXPECT_EQ(report.rows[0].row.verdict, Verdict::Fail);
  EXPECT_NE(report.rows[0].row.note.find("mesh file x.geo not found"), std::string::npos);
  EXPECT_FALSE(report.passed());
}

TEST(Verify, RowVerdicts) {
  EXPECT_EQ(compare_absolute("a", "s", "mm", 1.0, 1.0004, 5e-4).verdict, Verdict::Pass);
  EXPECT_EQ(compare_absolute("a", "s", "mm", 1.0, 1.0006, 5e-4).verdict, Verdict::Fail);
  EXPECT_EQ(compare_relative("a", "s", "MPa", 100.0, 100.9, 0.01).verdict, Verdict::Pass);
  EXPECT_EQ(compare_relative("a", "s", "MPa", 100.0, 101.1, 0.01).verdict, Verdict::Fail);
  // A non-finite computed value fails, whatever the tolerance.
  EXPECT_EQ(compare_absolute("a", "s", "1", 0.0, std::nan(""), 1e300).verdict, Verdict::Fail);
  // Informational rows carry the ratio and never fail.
  const CheckRow r = reported("a", "s", "MPa", 23.1, 11.55);
  EXPECT_EQ(r.verdict, Verdict::Reported);
  EXPECT_DOUBLE_EQ(r.error, 0.5);
}

}  // namespace
}  // namespace kinetofem::app
