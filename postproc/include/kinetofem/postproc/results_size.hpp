#pragma once
// The size of a results file, estimated before the work, and the check that
// it fits the free space of the output folder's file system: a run asked for
// fields at 100 000 output times must be refused with the numbers before it
// fills the disk, not fail when the disk is full after hours of work.
//
// Units: bytes. The estimate counts the nodal time series only (8-byte
// doubles, one value per node, component and written output time): meshes,
// envelopes and histories are small beside them.
#include <cstdint>
#include <filesystem>
#include <string>

namespace kinetofem::post {

// nodes x values per node (components of every series field) x written output times x 8.
double series_bytes(std::int64_t nodes, int values_per_node, std::int64_t written_steps);

// The bytes an unprivileged writer may still use on the file system holding
// `folder` (statvfs: f_bavail x f_frsize); +inf when it cannot be asked.
double free_bytes(const std::filesystem::path& folder);

// Throws Error when `bytes` exceed free_bytes(folder): "<what> would take about X GB
// (<breakdown>), more than the Y GB free in '<folder>'", with what to change.
void require_free_space(const std::filesystem::path& folder, double bytes, const std::string& what,
                        const std::string& breakdown);

}  // namespace kinetofem::post
