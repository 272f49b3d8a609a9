#pragma once
// ResultsFile — reads a results file written by ResultsWriter (read-only).
//
// Used by the tests, by post-processing (pictures, hot spots) and by the
// batch summary. Lists come back in name order; a missing body, field or step
// is an Error naming it and what the file has instead.
//
//   auto results = post::ResultsFile::open("out/lever_run.h5");
//   for (const auto& body : results.bodies()) {
//     fem::Mesh mesh = results.read_mesh(body);
//     post::FieldData u = results.read_static(body, "displacement");  // N x 3, "m"
//     auto t = results.series_times(body);
//     post::FieldData vm = results.read_step(body, "von_mises", t.size() - 1);
//   }
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "kinetofem/postproc/load_patterns.hpp"
#include "kinetofem/postproc/provenance.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

struct FieldData {
  FieldMatrix values;                       // rows: nodes / elements / times; columns: components
  std::string units;
  std::vector<std::string> component_names;  // empty if the writer gave none
};

struct EnvelopeData {
  FieldMatrix values;  // N x c
  IndexMatrix step;    // N x c, index into times_s
  std::vector<double> times_s;  // the envelope's own output times, or else the body's series times
  std::string units;
  std::string operation;  // "max", ...
};

class ResultsFile {
 public:
  // Throws Error if the file is missing, not HDF5, or not a kinetofem results file.
  static ResultsFile open(const std::filesystem::path& path);
  ResultsFile(ResultsFile&&) noexcept;
  ResultsFile& operator=(ResultsFile&&) noexcept;
  ~ResultsFile();

  const std::filesystem::path& path() const;
  std::int64_t format_version() const;
  Provenance provenance() const;

  std::vector<std::string> bodies() const;
  fem::Mesh read_mesh(const std::string& body) const;

  std::vector<std::string> static_fields(const std::string& body) const;
  FieldData read_static(const std::string& body, const std::string& field) const;
  std::vector<std::string> element_fields(const std::string& body) const;
  FieldData read_element_field(const std::string& body, const std::string& field) const;

  std::vector<std::string> series_fields(const std::string& body) const;
  std::vector<double> series_times(const std::string& body) const;  // s; empty: no series
  // One output time of a series field: N x c.
  FieldData read_step(const std::string& body, const std::string& field, fem::Index step) const;
  // The series field that is the body's per-step geometry (N x 3, m: the nodes' coordinates at
  // each output time; SeriesField::geometry, attribute xdmf_geometry), "" if it has none.
  std::string geometry_field(const std::string& body) const;

  std::vector<std::string> envelopes(const std::string& body) const;
  EnvelopeData read_envelope(const std::string& body, const std::string& field) const;

  // The body's load patterns (load_patterns.hpp); false: the body has none
  // (a step-by-step run, or an older file).
  bool has_load_patterns(const std::string& body) const;
  LoadPatternData read_load_patterns(const std::string& body) const;

  std::vector<double> mechanism_time() const;  // s; empty: no histories
  std::vector<std::string> histories() const;
  FieldData read_history(const std::string& name) const;  // T_m x c

  // Tables (/tables/<name>, ResultsWriter::write_table): any rows x c. An absent table is an
  // Error naming the file, the table and the tables present.
  std::vector<std::string> tables() const;  // empty: none (or an older file)
  FieldData read_table(const std::string& name) const;

  // Absolute paths of every dataset in the file, and the `units` attribute of one.
  std::vector<std::string> datasets() const;
  // Any 1-D or 2-D integer dataset by absolute path (e.g. .../connectivity_vtk), rows x columns.
  IndexMatrix read_indices(const std::string& dataset) const;
  bool has_units(const std::string& dataset) const;
  std::string units_of(const std::string& dataset) const;

 private:
  struct Impl;
  explicit ResultsFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::post
