// `kinetofem verify`: running the registry of checks and writing the report
// (Markdown and self-contained HTML) with its provenance.
#include <sys/utsname.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/version.hpp"
#include "kinetofem/postproc/markup_text.hpp"
#include "kinetofem/postproc/provenance.hpp"

namespace kinetofem::app {

void CheckRow::evaluate() {
  if (measure == ErrorMeasure::Reported) {
    error = reference != 0.0 ? computed / reference : std::nan("");
    verdict = Verdict::Reported;
    return;
  }
  const double difference = std::abs(computed - reference);
  error = measure == ErrorMeasure::Relative ? difference / std::abs(reference) : difference;
  // Written so that a NaN error (non-finite computed value, zero relative
  // reference) fails.
  verdict = std::isfinite(computed) && error <= tolerance ? Verdict::Pass : Verdict::Fail;
}

namespace {
CheckRow make_row(std::string name, std::string source, std::string unit, double reference, double computed,
                  ErrorMeasure measure, double tolerance, std::string note) {
  CheckRow row;
  row.name = std::move(name);
  row.source = std::move(source);
  row.unit = std::move(unit);
  row.reference = reference;
  row.computed = computed;
  row.measure = measure;
  row.tolerance = tolerance;
  row.note = std::move(note);
  row.evaluate();
  return row;
}
}  // namespace

CheckRow compare_absolute(std::string name, std::string source, std::string unit, double reference,
                          double computed, double tolerance, std::string note) {
  return make_row(std::move(name), std::move(source), std::move(unit), reference, computed,
                  ErrorMeasure::Absolute, tolerance, std::move(note));
}

CheckRow compare_relative(std::string name, std::string source, std::string unit, double reference,
                          double computed, double tolerance, std::string note) {
  return make_row(std::move(name), std::move(source), std::move(unit), reference, computed,
                  ErrorMeasure::Relative, tolerance, std::move(note));
}

CheckRow reported(std::string name, std::string source, std::string unit, double reference, double computed,
                  std::string note) {
  return make_row(std::move(name), std::move(source), std::move(unit), reference, computed,
                  ErrorMeasure::Reported, 0.0, std::move(note));
}

std::vector<Check> default_checks() {
  std::vector<Check> all;
  for (auto group : {mechanism_checks, dynamics_checks, fem_checks, published_checks})
    for (auto& check : group()) all.push_back(std::move(check));
  return all;
}

int VerificationReport::failures() const {
  int n = 0;
  for (const auto& r : rows) n += r.row.verdict == Verdict::Fail ? 1 : 0;
  return n;
}

namespace {

std::string machine_description() {
  struct utsname u {};
  if (uname(&u) != 0) return "unknown";
  return fmt::format("{} {} {} {}", u.sysname, u.nodename, u.release, u.machine);
}

const char* verdict_text(Verdict v) {
  switch (v) {
    case Verdict::Pass: return "PASS";
    case Verdict::Fail: return "FAIL";
    case Verdict::Reported: return "reported";
  }
  return "?";
}

std::string number(double v) {
  if (!std::isfinite(v)) return fmt::format("{}", v);
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e-3 && a < 1e6) return fmt::format("{:.7g}", v);
  return fmt::format("{:.4e}", v);
}

std::string error_text(const CheckRow& r) {
  switch (r.measure) {
    case ErrorMeasure::Absolute: return fmt::format("{:.2e} (abs.)", r.error);
    case ErrorMeasure::Relative: return fmt::format("{:.2e} (rel.)", r.error);
    case ErrorMeasure::Reported: return fmt::format("ratio {:.3f}", r.error);
  }
  return {};
}

std::string tolerance_text(const CheckRow& r) {
  if (r.measure == ErrorMeasure::Reported) return "—";
  return fmt::format("{:.1e}{}", r.tolerance, r.measure == ErrorMeasure::Relative ? " (rel.)" : "");
}

// Markdown cells must not contain '|' or newlines.
std::string md_cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\|";
    else if (c == '\n') out += ' ';
    else out += c;
  }
  return out;
}

std::string html_escape(const std::string& text) { return post::escape_markup(text, post::MarkupQuotes::Double); }

void write_file(const std::filesystem::path& path, const std::string& text) {
  const auto tmp = std::filesystem::path(path.string() + ".tmp");
  {
    std::ofstream out(tmp, std::ios::binary);
    require(bool(out), "cannot write {}", tmp.string());
    out << text;
    out.close();
    require(bool(out), "cannot write {}", tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  require(!ec, "cannot write {}: {}", path.string(), ec.message());
}

}  // namespace

VerificationReport run_checks(const std::vector<Check>& checks, const VerifyOptions& options) {
  VerificationReport report;
  report.quick = options.quick;
  report.version = kVersion;
  report.git_commit = kGitCommit;
  report.date_utc = post::utc_now_iso8601();
  report.machine = machine_description();
  report.cores = int(std::thread::hardware_concurrency());
  report.command_line = options.command_line;
  const CheckContext context{options.output_dir, options.quick, options.quiet};
  const Stopwatch total;
  for (const Check& check : checks) {
    if (options.quick && !check.in_quick) continue;
    if (!options.quiet) std::printf("verify: %-34s ", check.id.c_str()), std::fflush(stdout);
    const Stopwatch watch;
    std::vector<CheckRow> rows;
    try {
      rows = check.run(context);
      require(!rows.empty(), "check '{}' produced no rows", check.id);
    } catch (const std::exception& e) {
      CheckRow failed;
      failed.name = check.id;
      failed.source = "—";
      failed.unit = "—";
      failed.computed = std::nan("");
      failed.note = std::string("error: ") + e.what();
      failed.evaluate();
      rows = {failed};
    }
    report.check_seconds.emplace_back(check.id, watch.seconds());
    int failed = 0;
    for (auto& row : rows) {
      failed += row.verdict == Verdict::Fail ? 1 : 0;
      report.rows.push_back({check.id, check.group, std::move(row)});
    }
    if (!options.quiet)
      std::printf("%zu rows, %s (%.2f s)\n", rows.size(), failed ? "FAIL" : "ok", watch.seconds());
  }
  report.total_seconds = total.seconds();
  return report;
}

std::string report_markdown(const VerificationReport& r) {
  std::string md = "# kinetofem verification report\n\n";
  md += fmt::format("- result: **{}** ({} rows, {} failed)\n", r.passed() ? "PASS" : "FAIL", r.rows.size(),
                    r.failures());
  md += fmt::format("- suite: {}\n", r.quick ? "quick (`--quick`: SPEC §3 runs left out)" : "full");
  md += fmt::format("- kinetofem {} (git {})\n- date: {}\n- machine: {}, {} cores\n", r.version, r.git_commit,
                    r.date_utc, r.machine, r.cores);
  if (!r.command_line.empty()) md += fmt::format("- command: `{}`\n", r.command_line);
  md += fmt::format("- wall time: {:.1f} s\n\n", r.total_seconds);
  md += "Error: |computed − reference| (abs., in the unit) or that over |reference| (rel.). "
        "PASS when error ≤ tolerance. \"reported\": informational (published vs computed, ratio), never fails.\n\n";
  md += "| group | check | reference | source | computed | unit | error | tolerance | result | why this tolerance |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& rr : r.rows) {
    const CheckRow& c = rr.row;
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", md_cell(rr.group), md_cell(c.name),
                      number(c.reference),
                      md_cell(c.source), number(c.computed), md_cell(c.unit), error_text(c), tolerance_text(c),
                      c.verdict == Verdict::Fail ? "**FAIL**" : verdict_text(c.verdict), md_cell(c.note));
  }
  md += "\n## Time per check\n\n| check | s |\n|---|---|\n";
  for (const auto& [id, s] : r.check_seconds) md += fmt::format("| {} | {:.2f} |\n", id, s);
  return md;
}

std::string report_html(const VerificationReport& r) {
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>kinetofem verification report</title>\n<style>\n"
      "body{font-family:system-ui,sans-serif;margin:2em;color:#222}\n"
      "table{border-collapse:collapse;font-size:0.9em}\n"
      "th,td{border:1px solid #bbb;padding:0.3em 0.6em;text-align:left;vertical-align:top}\n"
      "th{background:#eee}td.num{text-align:right;font-family:monospace;white-space:nowrap}\n"
      "tr.pass td.verdict{background:#c8f0c8;color:#064}\n"
      "tr.fail td{background:#fde0e0}tr.fail td.verdict{background:#e33;color:#fff;font-weight:bold}\n"
      "tr.reported td.verdict{background:#dde8ff;color:#124}\n"
      ".note{color:#666;font-size:0.9em}\n.ok{color:#064}.bad{color:#c00}\n"
      "</style>\n</head>\n<body>\n<h1>kinetofem verification report</h1>\n";
  h += fmt::format("<p>Result: <strong class=\"{}\">{}</strong> ({} rows, {} failed)</p>\n",
                   r.passed() ? "ok" : "bad", r.passed() ? "PASS" : "FAIL", r.rows.size(), r.failures());
  h += "<ul>\n";
  h += fmt::format("<li>suite: {}</li>\n", r.quick ? "quick (--quick: SPEC §3 runs left out)" : "full");
  h += fmt::format("<li>kinetofem {} (git {})</li>\n<li>date: {}</li>\n<li>machine: {}, {} cores</li>\n",
                   html_escape(r.version), html_escape(r.git_commit), html_escape(r.date_utc),
                   html_escape(r.machine), r.cores);
  if (!r.command_line.empty()) h += fmt::format("<li>command: <code>{}</code></li>\n", html_escape(r.command_line));
  h += fmt::format("<li>wall time: {:.1f} s</li>\n</ul>\n", r.total_seconds);
  h += "<p>Error: |computed &minus; reference| (abs., in the unit) or that over |reference| (rel.). PASS when "
       "error &le; tolerance. &ldquo;reported&rdquo;: informational (published vs computed, ratio), never fails.</p>\n";
  h += "<table>\n<thead><tr><th>group</th><th>check</th><th>reference</th><th>source</th><th>computed</th>"
       "<th>unit</th><th>error</th><th>tolerance</th><th>result</th><th>why this tolerance</th></tr></thead>\n"
       "<tbody>\n";
  for (const auto& rr : r.rows) {
    const CheckRow& c = rr.row;
    const char* cls = c.verdict == Verdict::Pass ? "pass" : c.verdict == Verdict::Fail ? "fail" : "reported";
    h += fmt::format(
        "<tr class=\"{}\"><td>{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td><td class=\"num\">{}</td>"
        "<td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"verdict\">{}</td>"
        "<td class=\"note\">{}</td></tr>\n",
        cls, html_escape(rr.group), html_escape(c.name), html_escape(number(c.reference)), html_escape(c.source),
        html_escape(number(c.computed)), html_escape(c.unit), html_escape(error_text(c)),
        html_escape(tolerance_text(c)), verdict_text(c.verdict), html_escape(c.note));
  }
  h += "</tbody>\n</table>\n<h2>Time per check</h2>\n<table>\n<thead><tr><th>check</th><th>s</th></tr></thead>\n"
       "<tbody>\n";
  for (const auto& [id, s] : r.check_seconds)
    h += fmt::format("<tr><td>{}</td><td class=\"num\">{:.2f}</td></tr>\n", html_escape(id), s);
  h += "</tbody>\n</table>\n</body>\n</html>\n";
  return h;
}

int run_verify(const VerifyOptions& options, const std::vector<Check>& checks) {
  // Before the checks run: a folder that cannot be made is the user's error, named.
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  require(!ec, "{}: cannot create the output directory: {}", options.output_dir.string(), ec.message());
  const VerificationReport report = run_checks(checks, options);
  const std::string md = report_markdown(report);
  write_file(options.output_dir / "verification_report.md", md);
  write_file(options.output_dir / "verification_report.html", report_html(report));
  if (!options.quiet) std::printf("\n%s\n", md.c_str());
  std::printf("verification %s: %zu rows, %d failed, %.1f s; report: %s (+ .html)\n",
              report.passed() ? "PASSED" : "FAILED", report.rows.size(), report.failures(), report.total_seconds,
              (options.output_dir / "verification_report.md").string().c_str());
  return report.passed() ? 0 : 1;
}

int run_verify(const VerifyOptions& options) { return run_verify(options, default_checks()); }

}  // namespace kinetofem::app
