#include "kinetofem/postproc/provenance.hpp"

#include <chrono>
#include <ctime>

#include <fmt/format.h>

namespace kinetofem::post {

std::string command_line_of(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string argument = argv[i] != nullptr ? argv[i] : "";
    const bool plain = !argument.empty() &&
                       argument.find_first_of(" \t\n'\"\\$") == std::string::npos;
    if (!plain) {
      std::string quoted = "'";
      for (char c : argument) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      argument = quoted + "'";
    }
    line += (i == 0 ? "" : " ") + argument;
  }
  return line;
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}Z", utc.tm_year + 1900, utc.tm_mon + 1,
                     utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec);
}

}  // namespace kinetofem::post
