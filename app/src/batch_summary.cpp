// Run summaries (<name>.summary.toml) and the batch summary table.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"

namespace kinetofem::app {

namespace {
using units::kMm;
using units::kMpa;

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string md_field(const std::string& text) {
  std::string out;
  for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

std::string number_or_blank(const std::optional<double>& value, double unit, const char* format) {
  return value ? fmt::format(fmt::runtime(format), *value / unit) : "";
}
}  // namespace

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temporary =
      file.string() + fmt::format(".tmp{}", static_cast<long>(::getpid()));
  // A stale entry at the temporary name (a symbolic link above all) is removed,
  // never written through; O_EXCL | O_NOFOLLOW refuse one made in between.
  std::error_code ec;
  std::filesystem::remove(temporary, ec);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) fail("{}: cannot write ({}: {})", file.string(), temporary.filename().string(), std::strerror(errno));
  std::size_t written = 0;
  while (written < text.size()) {
    const ::ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      std::filesystem::remove(temporary, ec);
      fail("{}: write failed: {}", file.string(), std::strerror(error));
    }
    written += std::size_t(n);
  }
  if (::close(fd) != 0) {
    const int error = errno;
    std::filesystem::remove(temporary, ec);
    fail("{}: write failed: {}", file.string(), std::strerror(error));
  }
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    std::filesystem::remove(temporary, ec);
    fail("{}: cannot rename the temporary file into place", file.string());
  }
}

std::filesystem::path run_summary_path(const std::filesystem::path& output_dir,
                                       const std::string& name) {
  return output_dir / (name + ".summary.toml");
}

void write_run_summary(const std::filesystem::path& output_dir, const RunSummary& summary) {
  toml::table table{{"name", summary.name},
                    {"type", summary.type},
                    {"results_file", summary.results_file.string()},
                    {"wall_time_s", summary.wall_time_s}};
  // Only a run with FE parts has them (a mechanism-only run has no stress, not a zero one).
  if (summary.max_von_mises_pa) table.insert_or_assign("max_von_mises_mpa", *summary.max_von_mises_pa / kMpa);
  if (summary.max_displacement_m) table.insert_or_assign("max_displacement_mm", *summary.max_displacement_m / kMm);
  for (const auto& [key, value] : summary.extra) table.insert_or_assign(key, value);
  std::ostringstream text;
  text << "# Key results of `kinetofem run`, written when the run finished (read by kinetofem batch).\n"
       << table << "\n";
  write_file_atomically(run_summary_path(output_dir, summary.name), text.str());
}

std::optional<RunSummary> read_run_summary(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  toml::table table;
  try {
    table = toml::parse_file(file.string());
  } catch (const toml::parse_error&) {
    return std::nullopt;
  }
  RunSummary s;
  s.name = table["name"].value_or(std::string());
  s.type = table["type"].value_or(std::string());
  s.results_file = table["results_file"].value_or(std::string());
  s.wall_time_s = table["wall_time_s"].value_or(0.0);
  if (const auto v = table["max_von_mises_mpa"].value<double>()) s.max_von_mises_pa = *v * kMpa;
  if (const auto v = table["max_displacement_mm"].value<double>()) s.max_displacement_m = *v * kMm;
  for (const auto& [key, node] : table) {
    const std::string k(key.str());
    if (k == "name" || k == "type" || k == "results_file" || k == "wall_time_s" ||
        k == "max_von_mises_mpa" || k == "max_displacement_mm")
      continue;
    if (auto v = node.value<double>()) s.extra.emplace_back(k, *v);
  }
  return s;
}

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Done: return "done";
    case RunStatus::Skipped: return "skipped";
    case RunStatus::Failed: return "failed";
  }
  return "?";
}

std::string summary_csv(const std::vector<BatchRow>& rows) {
  std::string out =
      "case,status,wall_time_s,max_von_mises_mpa,max_displacement_mm,min_fatigue_life_h,results_file,error\n";
  for (const auto& r : rows)
    out += fmt::format("{},{},{:.2f},{},{},{},{},{}\n", csv_field(r.name), status_name(r.status),
                       r.wall_time_s, number_or_blank(r.max_von_mises_pa, kMpa, "{:.6g}"),
                       number_or_blank(r.max_displacement_m, kMm, "{:.6g}"),
                       number_or_blank(r.min_fatigue_life_s, units::kHour, "{:.6g}"),
                       csv_field(r.results_file), csv_field(r.error));
  return out;
}

std::string summary_markdown(const std::vector<BatchRow>& rows) {
  std::string out =
      "| case | status | wall time [s] | max von Mises [MPa] | max displacement [mm] | min fatigue life [h] | results "
      "| error |\n"
      "|---|---|---:|---:|---:|---:|---|---|\n";
  for (const auto& r : rows)
    out += fmt::format("| {} | {} | {:.1f} | {} | {} | {} | {} | {} |\n", md_field(r.name),
                       status_name(r.status), r.wall_time_s,
                       number_or_blank(r.max_von_mises_pa, kMpa, "{:.3f}"),
                       number_or_blank(r.max_displacement_m, kMm, "{:.5f}"),
                       number_or_blank(r.min_fatigue_life_s, units::kHour, "{:.4g}"), md_field(r.results_file),
                       md_field(r.error));
  return out;
}

}  // namespace kinetofem::app
