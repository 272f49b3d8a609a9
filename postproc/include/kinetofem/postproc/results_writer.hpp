#pragma once
// ResultsWriter — writes the results of one run: an HDF5 file (<name>.h5) and
// beside it an XDMF 3 file (<name>.xdmf) that ParaView opens.
//
// Layout: results_layout.hpp and docs/results.md. Units: SI; every dataset
// carries a `units` attribute, given by the caller for fields.
//
// Atomic: everything is written to <name>.h5.tmp; commit() closes it, writes
// <name>.xdmf.tmp and renames both over the final names. A writer destroyed
// without commit() (an exception unwinding, an early return) removes its
// temporary files, so a results file under the final name is always complete,
// and an older one is left untouched until the new one is committed. (A
// process killed by SIGKILL cannot clean up: it leaves <name>.h5.tmp, never a
// broken <name>.h5.)
//
// Memory: time-series fields go to disk one step at a time (chunked per step,
// extensible in time), so a 100-step series of a 1 M-node body needs one
// step's matrix in memory, not the series.
//
// Usage (one body, a static solution and a time series):
//
//   post::Provenance prov{.case_path = path, .case_text = text,
//                         .command_line = post::command_line_of(argc, argv)};
//   post::ResultsWriter writer("out/lever_run.h5", prov);
//   post::BodyWriter& lever = writer.add_body("lever", mesh);
//   lever.write_static("displacement", "m", U, post::kVectorComponents);
//   lever.write_static("stress", "Pa", S, post::kVoigtComponents);
//   lever.begin_series({{"displacement", "m", 3, post::kVectorComponents},
//                       {"von_mises", "Pa", 1}});
//   for (int k = 0; k < n; ++k) {
//     ...solve at time t[k]...
//     lever.write_step(t[k], {{"displacement", U_k}, {"von_mises", vm_k}});
//   }
//   lever.write_envelope("von_mises", "Pa", vm_max, vm_max_step);
//   writer.set_mechanism_time(t_mech);
//   writer.write_history("drive_torque", "N*m", torque);  // (T_m x 1)
//   writer.write_table("vibration.response.time", "s", t_response);  // (n x 1), any n
//   writer.commit();
//
// Finite results only: every value written (fields, steps, envelopes, load patterns, histories,
// tables) is checked first; an inf or NaN is an Error naming the quantity, the body, the time
// and the node (nothing of it is written, and the unwinding run leaves no results file). +inf
// is kept where it means "never": the fatigue life fields (layout::kFatigueLifeCycles,
// kFatigueLifeHours) and tables.
//
// Names of bodies, fields, sets, histories and tables: letters, digits, '_', '-', '.'
// (they become HDF5 link names and XDMF attribute names).
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/postproc/load_patterns.hpp"
#include "kinetofem/postproc/provenance.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

namespace detail {
struct FileState;
}

// One field of a time series: name, unit, number of components, component names.
struct SeriesField {
  std::string name;
  std::string units;
  int components = 1;
  std::vector<std::string> component_names = {};
  // This N x 3 field, in m, is also the geometry of its step in the XDMF file; at most one per
  // body. Its values are the nodes' coordinates at that output time (e.g. the world coordinates
  // of the rigid configuration), so ParaView shows the body moving as it steps through time;
  // the body's mesh/nodes stay its reference (body-frame) coordinates. Recorded as the
  // attribute xdmf_geometry = 1 on the series dataset (ResultsFile::geometry_field).
  bool geometry = false;
};

// A field's values for one call of write_step. Holds a reference (an Eigen::Ref)
// to the caller's matrix: use it inside the call's braces only.
struct StepValues {
  std::string name;
  Eigen::Ref<const FieldMatrix> values;
};

// Writes the results of one body (one FE mesh). Made by ResultsWriter::add_body,
// which owns it; the reference stays valid until the writer is destroyed.
class BodyWriter {
 public:
  ~BodyWriter();
  BodyWriter(const BodyWriter&) = delete;
  BodyWriter& operator=(const BodyWriter&) = delete;

  const std::string& name() const { return name_; }
  fem::Index node_count() const { return node_count_; }
  fem::Index element_count() const { return element_count_; }

  // A nodal field, N x c (N = node count), at /bodies/<body>/static/<name>.
  void write_static(const std::string& name, const std::string& units,
                    const Eigen::Ref<const FieldMatrix>& values,
                    const std::vector<std::string>& component_names = {});
  // An element field, E x c (E = element count, elements in block order).
  void write_element_field(const std::string& name, const std::string& units,
                           const Eigen::Ref<const FieldMatrix>& values,
                           const std::vector<std::string>& component_names = {});

  // Declares the fields of the body's time series (once per body). Throws Error naming the
  // body and field for a field marked `geometry` that does not have 3 components, or for a
  // second such field.
  void begin_series(const std::vector<SeriesField>& fields);
  // Writes output time `time_s` (s, strictly increasing): every declared field,
  // each N x c. Returns the step index k (0, 1, ...).
  fem::Index write_step(double time_s, std::initializer_list<StepValues> fields);
  fem::Index steps_written() const;

  // The body's motion as load patterns and their coefficient histories
  // (load_patterns.hpp), at /bodies/<body>/load_patterns (once per body).
  // Throws Error naming the body for sizes that do not fit its mesh.
  void write_load_patterns(const LoadPatternData& patterns);

  // Per-node extreme of a field over the series: values N x c and, for each
  // entry, the step (index into series/time) where it occurred.
  // `operation` names the extreme ("max", "min", "max_abs").
  // `step_times_s`: the times the steps index (s), when the envelope covers
  // more output times than the series holds (fields written at some output
  // times only); stored as the envelope's own `time`. Empty: the series' times.
  void write_envelope(const std::string& name, const std::string& units,
                      const Eigen::Ref<const FieldMatrix>& values,
                      const Eigen::Ref<const IndexMatrix>& step, const std::string& operation = layout::kEnvelopeMax,
                      const std::vector<double>& step_times_s = {});

 private:
  friend class ResultsWriter;
  struct State;
  BodyWriter(detail::FileState& file, const std::string& name, const fem::Mesh& mesh);
  void check_open() const;

  detail::FileState& file_;
  std::string name_;
  fem::Index node_count_ = 0;
  fem::Index element_count_ = 0;
  std::unique_ptr<State> state_;
};

class ResultsWriter {
 public:
  // Starts <path>.tmp (path ends in .h5; the XDMF file is path with .xdmf).
  // Throws Error naming the directory if it does not exist or cannot be written.
  ResultsWriter(const std::filesystem::path& path, const Provenance& provenance);
  // Without commit(): removes the temporary files; never throws.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  const std::filesystem::path& path() const;

  // Writes the body's mesh (validated first) and returns its writer.
  BodyWriter& add_body(const std::string& name, const fem::Mesh& mesh);
  // The writer of a body added before (e.g. to add a later stage's fields);
  // Error naming the body if there is none.
  BodyWriter& body(const std::string& name);

  // Time histories of the mechanism: the time grid (s) first, then any number
  // of quantities, each T_m x c, at /mechanism/<name>.
  void set_mechanism_time(const std::vector<double>& time_s);
  void write_history(const std::string& name, const std::string& units,
                     const Eigen::Ref<const FieldMatrix>& values,
                     const std::vector<std::string>& component_names = {});
  // A history that has no value at some times (a linkage that does not assemble there): NaN
  // marks those times, and is the one non-finite value allowed (inf still is an Error).
  void write_history_where_defined(const std::string& name, const std::string& units,
                                   const Eigen::Ref<const FieldMatrix>& values,
                                   const std::vector<std::string>& component_names = {});

  // A table of any size (rows x c) at /tables/<name>, e.g. a history on its own time grid
  // (its time is another table) or a few scalars. Not in the XDMF file.
  // Error naming the table for a bad name, a second table of that name, no columns, or a
  // count of component names other than c. Values may be +inf (a settling time that never comes),
  // never NaN or -inf.
  void write_table(const std::string& name, const std::string& units,
                   const Eigen::Ref<const FieldMatrix>& values,
                   const std::vector<std::string>& component_names = {});

  // Finishes the file and the XDMF and moves them to their final names.
  // Throws if a time step is incomplete; after commit() nothing more can be written.
  void commit();
  bool committed() const;

 private:
  void write_history(const std::string& name, const std::string& units,
                     const Eigen::Ref<const FieldMatrix>& values,
                     const std::vector<std::string>& component_names, bool nan_where_undefined);

  std::unique_ptr<detail::FileState> file_;
  std::vector<std::unique_ptr<BodyWriter>> bodies_;
};

}  // namespace kinetofem::post
