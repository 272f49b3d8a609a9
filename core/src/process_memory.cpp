#include "kinetofem/core/process_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace kinetofem {

bool return_freed_memory_to_the_system() {
#if defined(__GLIBC__)
  // 65536: glibc's default number of mapped blocks.
  return mallopt(M_MMAP_MAX, 65536) == 1 && mallopt(M_MMAP_THRESHOLD, int(kLargeAllocationBytes)) == 1 &&
         mallopt(M_TRIM_THRESHOLD, int(2 * kLargeAllocationBytes)) == 1;
#else
  return true;
#endif
}

namespace {

// A number of bytes from a one-line file ("max" or absent: none).
std::optional<double> bytes_in_file(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  try {
    const double value = std::stod(text);
    // cgroup v1 writes a huge page-rounded number for "no limit".
    if (value <= 0 || value >= 1e18) return std::nullopt;
    return value;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The address space mapped by this process now (VmSize), bytes.
double mapped_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) return std::stod(line.substr(7)) * 1024.0;  // kB
  return 0.0;
}

// The process's cgroup v2 folder under /sys/fs/cgroup ("0::/path" in /proc/self/cgroup).
std::string cgroup_v2_folder() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("0::", 0) == 0) return "/sys/fs/cgroup" + line.substr(3);
  return "/sys/fs/cgroup";
}

}  // namespace

MemoryBudget memory_available_to_process() {
  constexpr double kGb = 1e9;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  MemoryBudget budget{pages > 0 && page > 0 ? double(pages) * double(page) : 8e9, "physical memory"};
  budget.limited_by = fmt::format("the physical memory of {:.3g} GB", budget.bytes / kGb);
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double in_use = mapped_bytes();
    const double left = std::max(0.0, double(limit.rlim_cur) - in_use);
    if (left < budget.bytes)
      budget = {left, fmt::format("the address-space limit (RLIMIT_AS, ulimit -v) of {:.3g} GB, {:.3g} GB of it mapped",
                                  double(limit.rlim_cur) / kGb, in_use / kGb)};
  }
  const std::string v2 = cgroup_v2_folder();
  for (const auto& [max_file, current_file] :
       {std::pair{v2 + "/memory.max", v2 + "/memory.current"},
        std::pair{std::string("/sys/fs/cgroup/memory/memory.limit_in_bytes"),
                  std::string("/sys/fs/cgroup/memory/memory.usage_in_bytes")}}) {
    const auto max = bytes_in_file(max_file);
    if (!max) continue;
    const double in_use = bytes_in_file(current_file).value_or(0.0);
    const double left = std::max(0.0, *max - in_use);
    if (left < budget.bytes)
      budget = {left, fmt::format("the cgroup memory limit ({}) of {:.3g} GB, {:.3g} GB of it in use", max_file,
                                  *max / kGb, in_use / kGb)};
  }
  return budget;
}

}  // namespace kinetofem
