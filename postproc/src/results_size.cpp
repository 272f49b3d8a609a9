#include "kinetofem/postproc/results_size.hpp"

#include <sys/statvfs.h>

#include <limits>

#include "kinetofem/core/error.hpp"

namespace kinetofem::post {

double series_bytes(std::int64_t nodes, int values_per_node, std::int64_t written_steps) {
  return double(nodes) * double(values_per_node) * double(written_steps) * double(sizeof(double));
}

double free_bytes(const std::filesystem::path& folder) {
  struct statvfs info {};
  const std::filesystem::path at = folder.empty() ? std::filesystem::path(".") : folder;
  if (::statvfs(at.c_str(), &info) != 0) return std::numeric_limits<double>::infinity();
  return double(info.f_bavail) * double(info.f_frsize);
}

void require_free_space(const std::filesystem::path& folder, double bytes, const std::string& what,
                        const std::string& breakdown) {
  const double available = free_bytes(folder);
  require(bytes <= available,
          "{} would take about {:.3g} GB ({}), more than the {:.3g} GB free in '{}': write fields at fewer "
          "output times (output.field_every, output.field_times_s), coarsen the mesh or free space",
          what, bytes * 1e-9, breakdown, available * 1e-9, (folder.empty() ? std::filesystem::path(".") : folder).string());
}

}  // namespace kinetofem::post
