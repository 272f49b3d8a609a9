#include "kinetofem/postproc/results_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <system_error>

#include "hdf5_io.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/termination_cleanup.hpp"
#include "kinetofem/core/version.hpp"
#include "kinetofem/postproc/vtk_node_order.hpp"
#include "xdmf_document.hpp"

namespace kinetofem::post {

namespace layout {
std::string block_name(size_t index) { return fmt::format("block_{}", index); }
std::string static_name(const std::string& field) { return kStaticPrefix + field; }
std::string magnitude_name(const std::string& field) { return field + kMagnitudeSuffix; }
std::string mode_name(int i) { return kModePrefix + std::to_string(i); }
}  // namespace layout

namespace {

void require_valid_name(const std::string& name, const char* what) {
  const bool valid =
      !name.empty() && name != "." && name != ".." &&
      std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-' || c == '.';
      });
  require(valid, "{} name '{}' is not allowed (use letters, digits, '_', '-', '.')", what, name);
}

void require_components(const std::vector<std::string>& names, Eigen::Index columns,
                        const std::string& field) {
  require(names.empty() || Eigen::Index(names.size()) == columns,
          "field '{}' has {} columns but {} component names", field, columns, names.size());
}

std::string join(const std::string& a, const std::string& b) { return a + "/" + b; }

// Rows of `values` as one contiguous block: the caller's memory when its rows
// are adjacent (the usual case), else a copy in `storage`.
const double* contiguous(const Eigen::Ref<const FieldMatrix>& values, FieldMatrix& storage) {
  if (values.rows() <= 1 || values.outerStride() == values.cols()) return values.data();
  storage = values;
  return storage.data();
}

// Chunk rows for a per-step slab of N x c doubles: at most ~1 MiB per chunk,
// so a chunk fits HDF5's default chunk cache and a step is a few whole chunks.
// A non-finite result: never written (ParaView, `post` and the summaries would
// show inf or nan as if they were results). +inf is kept only where it has a
// documented meaning, "never" (a fatigue life without damage; a table's
// settling time that never comes: write_table).
struct NonFinite {
  Eigen::Index row = 0, column = 0;
  double value = 0.0;
};

template <typename Matrix>
std::optional<NonFinite> first_non_finite(const Matrix& values, bool allow_plus_infinity = false) {
  if (values.allFinite()) return std::nullopt;
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (Eigen::Index c = 0; c < values.cols(); ++c) {
      const double x = values(i, c);
      if (std::isfinite(x) || (allow_plus_infinity && x == std::numeric_limits<double>::infinity()))
        continue;
      return NonFinite{i, c, x};
    }
  return std::nullopt;
}

bool may_be_plus_infinity(const std::string& field) {
  return field == layout::kFatigueLifeCycles || field == layout::kFatigueLifeHours;
}

// "<quantity> is <value> at <location>: not written to '<file>'; <likely cause>".
[[noreturn]] void fail_non_finite(const std::string& quantity, double value, const std::string& location,
                                  const std::filesystem::path& file) {
  fail("{} is {} at {}: not written to '{}'; a non-finite result comes from an overflow or 0/0 upstream "
       "(a material constant, load, mass or dimension far outside its plausible range?)",
       quantity, value, location, file.string());
}

// A stale temporary that is a symbolic link (left by anyone who can write the
// output folder) is removed, never written through: writing would overwrite
// the link's target, and the rename would put the link under the final name.
void remove_if_symlink(const std::filesystem::path& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode))
    require(::unlink(path.c_str()) == 0, "cannot remove the stale symbolic link '{}': {}", path.string(),
            std::strerror(errno));
}

// Writes `text` to a new or truncated regular file, never through a symbolic link.
void write_text_file(const std::filesystem::path& path, const std::string& text) {
  remove_if_symlink(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
  require(fd >= 0, "cannot create '{}': {}", path.string(), std::strerror(errno));
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      fail("cannot write '{}': {}", path.string(), std::strerror(error));
    }
    written += std::size_t(n);
  }
  require(::close(fd) == 0, "cannot write '{}': {}", path.string(), std::strerror(errno));
}

std::string at_time(double time_s) { return fmt::format("t = {} s", time_s); }

hsize_t chunk_rows(fem::Index rows, int components) {
  const hsize_t limit = std::max<hsize_t>(1, (hsize_t(1) << 20) / (8 * hsize_t(components)));
  return std::max<hsize_t>(1, std::min<hsize_t>(hsize_t(rows), limit));
}

}  // namespace

namespace detail {
// The open temporary file and what the XDMF will need; shared by the writer and its bodies.
struct FileState {
  std::filesystem::path final_h5, temporary_h5, final_xdmf, temporary_xdmf;
  // Ctrl-C or SIGTERM while writing removes the temporaries (a SIGKILL cannot).
  core::RemoveOnTermination remove_h5_on_signal, remove_xdmf_on_signal;
  h5::H5Io io;
  h5::Handle file;
  h5::Handle bodies;
  h5::Handle mechanism;
  h5::Handle tables;
  std::set<std::string> table_names;
  std::vector<double> mechanism_time_s;
  bool mechanism_time_set = false;
  std::set<std::string> histories;
  std::vector<xdmf::History> xdmf_histories;  // in writing order, for the XDMF "mechanism" grid
  bool committed = false;
  // A write that failed half-way leaves the file inconsistent: commit() refuses it.
  std::string broken;

  explicit FileState(const std::filesystem::path& path)
      : final_h5(path),
        temporary_h5(path.string() + ".tmp"),
        final_xdmf(std::filesystem::path(path).replace_extension(".xdmf")),
        temporary_xdmf(final_xdmf.string() + ".tmp"),
        remove_h5_on_signal(temporary_h5),
        remove_xdmf_on_signal(temporary_xdmf),
        io(final_h5.string()) {}  // messages name the results file, not its temporary

  void check_writable() const {
    require(!committed, "results file '{}' is already committed; nothing more can be written",
            final_h5.string());
    require(broken.empty(), "results file '{}' is unusable after an earlier failure: {}",
            final_h5.string(), broken);
  }

  // Runs `write`; if it throws, marks the file broken (then rethrows).
  template <typename Write>
  void guarded(Write&& write) {
    try {
      write();
    } catch (const std::exception& e) {
      broken = e.what();
      throw;
    }
  }
};
}  // namespace detail

struct BodyWriter::State {
  h5::Handle group;
  h5::Handle statics;
  h5::Handle elements;
  h5::Handle series;
  h5::Handle envelopes;
  h5::Handle time;
  std::vector<SeriesField> fields;
  std::vector<h5::Handle> datasets;  // one per series field
  std::vector<double> times_s;
  std::set<std::string> names_static, names_element, names_envelope;
  bool load_patterns_written = false;
  xdmf::Grid grid;
  std::string path;  // "/bodies/<name>"
};

// ---------------------------------------------------------------------------------------------
// BodyWriter

BodyWriter::BodyWriter(detail::FileState& file, const std::string& name, const fem::Mesh& mesh)
    : file_(file), name_(name), state_(std::make_unique<State>()) {
  const h5::H5Io& io = file_.io;
  node_count_ = mesh.node_count();
  element_count_ = mesh.element_count();
  State& s = *state_;
  s.path = fmt::format("/{}/{}", layout::kBodies, name);
  s.group = h5::make_group(io, file_.bodies.get(), name, s.path);
  h5::write_attribute(io, s.group.get(), s.path, "node_count", std::int64_t(node_count_));
  h5::write_attribute(io, s.group.get(), s.path, "element_count", std::int64_t(element_count_));

  const std::string mesh_path = join(s.path, layout::kMesh);
  h5::Handle mesh_group = h5::make_group(io, s.group.get(), layout::kMesh, mesh_path);
  const std::string nodes_path = join(mesh_path, layout::kNodes);
  const hsize_t node_dims[2] = {hsize_t(node_count_), 3};
  h5::write_dataset(io, mesh_group.get(), layout::kNodes, nodes_path, node_dims, mesh.nodes.data(),
                    "m");
  h5::write_attribute(io, mesh_group.get(), mesh_path, "node_order",
                      std::string("connectivity: Gmsh; connectivity_vtk: VTK/XDMF"));

  s.grid.name = name;
  s.grid.nodes = node_count_;
  s.grid.nodes_dataset = nodes_path;

  const std::string blocks_path = join(mesh_path, layout::kBlocks);
  h5::Handle blocks = h5::make_group(io, mesh_group.get(), layout::kBlocks, blocks_path);
  std::vector<fem::Index> mixed;
  fem::Index first_element = 0;
  for (size_t b = 0; b < mesh.blocks.size(); ++b) {
    const fem::ElementBlock& block = mesh.blocks[b];
    const std::string block_path = join(blocks_path, layout::block_name(b));
    h5::Handle group = h5::make_group(io, blocks.get(), layout::block_name(b), block_path);
    const int n = fem::nodes_per_element(block.type);
    h5::write_attribute(io, group.get(), block_path, "element_type",
                        std::string(fem::name_of(block.type)));
    h5::write_attribute(io, group.get(), block_path, "xdmf_topology",
                        std::string(xdmf_topology_name(block.type)));
    h5::write_attribute(io, group.get(), block_path, "nodes_per_element", std::int64_t(n));
    h5::write_attribute(io, group.get(), block_path, "first_element", std::int64_t(first_element));
    const hsize_t dims[2] = {hsize_t(block.size()), hsize_t(n)};
    h5::write_dataset(io, group.get(), layout::kConnectivity,
                      join(block_path, layout::kConnectivity), dims, block.connectivity.data(),
                      layout::kDimensionless);
    const std::vector<fem::Index> vtk = vtk_connectivity(block);
    const std::string vtk_path = join(block_path, layout::kConnectivityVtk);
    h5::write_dataset(io, group.get(), layout::kConnectivityVtk, vtk_path, dims, vtk.data(),
                      layout::kDimensionless);
    s.grid.blocks.push_back({block.type, block.size(), vtk_path});
    for (fem::Index e = 0; e < block.size(); ++e) {
      mixed.push_back(xdmf_mixed_code(block.type));
      mixed.insert(mixed.end(), vtk.begin() + e * n, vtk.begin() + (e + 1) * n);
    }
    first_element += block.size();
  }
  if (mesh.blocks.size() > 1) {
    // A Mixed XDMF topology: per element its XDMF type code, then its VTK-ordered nodes.
    const std::string mixed_path = join(mesh_path, layout::kMixedTopology);
    const hsize_t dims[1] = {hsize_t(mixed.size())};
    h5::write_dataset(io, mesh_group.get(), layout::kMixedTopology, mixed_path, dims, mixed.data(),
                      layout::kDimensionless);
    s.grid.mixed_dataset = mixed_path;
    s.grid.mixed_length = fem::Index(mixed.size());
  }

  const std::string node_sets_path = join(mesh_path, layout::kNodeSets);
  h5::Handle node_sets = h5::make_group(io, mesh_group.get(), layout::kNodeSets, node_sets_path);
  for (const auto& [set, nodes] : mesh.node_sets) {
    require_valid_name(set, "node set");
    const hsize_t dims[1] = {hsize_t(nodes.size())};
    h5::write_dataset(io, node_sets.get(), set, join(node_sets_path, set), dims, nodes.data(),
                      layout::kDimensionless);
  }
  const std::string element_sets_path = join(mesh_path, layout::kElementSets);
  h5::Handle element_sets =
      h5::make_group(io, mesh_group.get(), layout::kElementSets, element_sets_path);
  for (const auto& [set, elements] : mesh.element_sets) {
    require_valid_name(set, "element set");
    const hsize_t dims[1] = {hsize_t(elements.size())};
    h5::write_dataset(io, element_sets.get(), set, join(element_sets_path, set), dims,
                      elements.data(), layout::kDimensionless);
  }
  const std::string face_sets_path = join(mesh_path, layout::kFaceSets);
  h5::Handle face_sets = h5::make_group(io, mesh_group.get(), layout::kFaceSets, face_sets_path);
  for (const auto& [set, face_blocks] : mesh.face_sets) {
    require_valid_name(set, "face set");
    const std::string set_path = join(face_sets_path, set);
    h5::Handle set_group = h5::make_group(io, face_sets.get(), set, set_path);
    for (size_t b = 0; b < face_blocks.size(); ++b) {
      const std::string block_path = join(set_path, layout::block_name(b));
      h5::Handle group = h5::make_group(io, set_group.get(), layout::block_name(b), block_path);
      const fem::FaceBlock& faces = face_blocks[b];
      h5::write_attribute(io, group.get(), block_path, "face_type",
                          std::string(fem::name_of(faces.type)));
      const hsize_t dims[2] = {hsize_t(faces.size()), hsize_t(fem::nodes_per_face(faces.type))};
      h5::write_dataset(io, group.get(), layout::kConnectivity,
                        join(block_path, layout::kConnectivity), dims, faces.connectivity.data(),
                        layout::kDimensionless);
    }
  }
}

BodyWriter::~BodyWriter() = default;

void BodyWriter::check_open() const { file_.check_writable(); }

void BodyWriter::write_static(const std::string& name, const std::string& units,
                              const Eigen::Ref<const FieldMatrix>& values,
                              const std::vector<std::string>& component_names) {
  check_open();
  require_valid_name(name, "field");
  State& s = *state_;
  require(!s.names_static.contains(name), "body '{}' already has static field '{}'", name_, name);
  require(values.rows() == node_count_,
          "static field '{}' of body '{}' has {} rows; the mesh has {} nodes", name, name_,
          values.rows(), node_count_);
  require(values.cols() > 0, "static field '{}' of body '{}' has no columns", name, name_);
  require_components(component_names, values.cols(), name);
  if (const auto bad = first_non_finite(values, may_be_plus_infinity(name)))
    fail_non_finite(fmt::format("static field '{}' ({}) of body '{}'", name, units, name_), bad->value,
                    fmt::format("node {} (component {})", bad->row, bad->column), file_.final_h5);
  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string group_path = join(s.path, layout::kStatic);
    if (!s.statics.valid()) s.statics = h5::make_group(io, s.group.get(), layout::kStatic, group_path);
    const std::string path = join(group_path, name);
    const hsize_t dims[2] = {hsize_t(values.rows()), hsize_t(values.cols())};
    FieldMatrix storage;
    h5::write_dataset(io, s.statics.get(), name, path, dims, contiguous(values, storage), units);
    h5::Handle dataset = h5::open_dataset(io, s.statics.get(), name, path);
    h5::write_attribute(io, dataset.get(), path, "location", std::string("node"));
    if (!component_names.empty())
      h5::write_attribute(io, dataset.get(), path, "components", component_names);
    s.grid.attributes.push_back({name, path, node_count_, int(values.cols()), false, false});
  });
  s.names_static.insert(name);
}

void BodyWriter::write_element_field(const std::string& name, const std::string& units,
                                     const Eigen::Ref<const FieldMatrix>& values,
                                     const std::vector<std::string>& component_names) {
  check_open();
  require_valid_name(name, "field");
  State& s = *state_;
  require(!s.names_element.contains(name), "body '{}' already has element field '{}'", name_,
          name);
  require(values.rows() == element_count_,
          "element field '{}' of body '{}' has {} rows; the mesh has {} elements", name, name_,
          values.rows(), element_count_);
  require(values.cols() > 0, "element field '{}' of body '{}' has no columns", name, name_);
  require_components(component_names, values.cols(), name);
  if (const auto bad = first_non_finite(values, may_be_plus_infinity(name)))
    fail_non_finite(fmt::format("element field '{}' ({}) of body '{}'", name, units, name_), bad->value,
                    fmt::format("element {} (component {})", bad->row, bad->column), file_.final_h5);
  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string group_path = join(s.path, layout::kElementFields);
    if (!s.elements.valid())
      s.elements = h5::make_group(io, s.group.get(), layout::kElementFields, group_path);
    const std::string path = join(group_path, name);
    const hsize_t dims[2] = {hsize_t(values.rows()), hsize_t(values.cols())};
    FieldMatrix storage;
    h5::write_dataset(io, s.elements.get(), name, path, dims, contiguous(values, storage), units);
    h5::Handle dataset = h5::open_dataset(io, s.elements.get(), name, path);
    h5::write_attribute(io, dataset.get(), path, "location", std::string("element"));
    if (!component_names.empty())
      h5::write_attribute(io, dataset.get(), path, "components", component_names);
    s.grid.attributes.push_back({name, path, element_count_, int(values.cols()), true, false});
  });
  s.names_element.insert(name);
}

void BodyWriter::begin_series(const std::vector<SeriesField>& fields) {
  check_open();
  State& s = *state_;
  require(!s.series.valid(), "body '{}' already has a time series", name_);
  require(!fields.empty(), "time series of body '{}' has no fields", name_);
  std::set<std::string> seen;
  std::string geometry;  // the field marked `geometry`, if any
  for (const auto& field : fields) {
    require_valid_name(field.name, "field");
    require(field.name != layout::kTime, "series field name 'time' is reserved (body '{}')", name_);
    require(seen.insert(field.name).second, "series field '{}' of body '{}' declared twice",
            field.name, name_);
    require(field.components > 0, "series field '{}' of body '{}' has {} components", field.name,
            name_, field.components);
    require(field.component_names.empty() || int(field.component_names.size()) == field.components,
            "series field '{}' has {} components but {} component names", field.name,
            field.components, field.component_names.size());
    if (field.geometry) {
      require(field.components == 3,
              "series field '{}' of body '{}' is marked as the geometry but has {} components "
              "(a geometry is N x 3 coordinates, m)",
              field.name, name_, field.components);
      require(geometry.empty(),
              "series fields '{}' and '{}' of body '{}' are both marked as the geometry (at most "
              "one per body)",
              geometry, field.name, name_);
      geometry = field.name;
    }
  }
  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string series_path = join(s.path, layout::kSeries);
    s.series = h5::make_group(io, s.group.get(), layout::kSeries, series_path);

    // Extensible in time, so the number of steps need not be known in advance.
    auto make_extensible = [&](const std::string& name, const std::string& path,
                               std::vector<hsize_t> dims, std::vector<hsize_t> chunk,
                               const std::string& units) {
      std::vector<hsize_t> max_dims = dims;
      max_dims[0] = H5S_UNLIMITED;
      h5::Handle space(KF_H5(io, path, H5Screate_simple, int(dims.size()), dims.data(),
                             max_dims.data()),
                       H5Sclose);
      h5::Handle properties(KF_H5(io, path, H5Pcreate, H5P_DATASET_CREATE), H5Pclose);
      KF_H5(io, path, H5Pset_chunk, properties.get(), int(chunk.size()), chunk.data());
      h5::Handle dataset(KF_H5(io, path, H5Dcreate2, s.series.get(), name.c_str(), H5T_IEEE_F64LE,
                               space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                         H5Dclose);
      h5::write_attribute(io, dataset.get(), path, "units", units);
      return dataset;
    };

    const std::string time_path = join(series_path, layout::kTime);
    s.time = make_extensible(layout::kTime, time_path, {0}, {1024}, "s");
    for (const auto& field : fields) {
      const std::string path = join(series_path, field.name);
      const hsize_t n = hsize_t(node_count_), c = hsize_t(field.components);
      s.datasets.push_back(make_extensible(field.name, path, {0, n, c},
                                           {1, chunk_rows(node_count_, field.components), c},
                                           field.units));
      h5::write_attribute(io, s.datasets.back().get(), path, "location", std::string("node"));
      if (!field.component_names.empty())
        h5::write_attribute(io, s.datasets.back().get(), path, "components",
                            field.component_names);
      if (field.geometry) {
        h5::write_attribute(io, s.datasets.back().get(), path, layout::kXdmfGeometry,
                            std::int64_t(1));
        s.grid.geometry_series = int(s.grid.series.size());
      }
      s.grid.series.push_back({field.name, path, node_count_, field.components, false, false});
    }
  });
  s.fields = fields;
}

fem::Index BodyWriter::write_step(double time_s, std::initializer_list<StepValues> fields) {
  check_open();
  State& s = *state_;
  require(s.series.valid(), "body '{}': write_step before begin_series", name_);
  const fem::Index step = fem::Index(s.times_s.size());
  require(std::isfinite(time_s), "body '{}' step {}: time {} s is not finite", name_, step, time_s);
  require(s.times_s.empty() || time_s > s.times_s.back(),
          "body '{}' step {}: time {} s does not increase (previous {} s)", name_, step, time_s,
          s.times_s.empty() ? 0.0 : s.times_s.back());
  // Check everything before touching the file, so a bad call leaves it consistent.
  std::vector<const StepValues*> by_field(s.fields.size(), nullptr);
  for (const StepValues& given : fields) {
    auto it = std::find_if(s.fields.begin(), s.fields.end(),
                           [&](const SeriesField& f) { return f.name == given.name; });
    require(it != s.fields.end(), "body '{}' step {} (t = {} s): '{}' is not a declared series field",
            name_, step, time_s, given.name);
    const size_t f = size_t(it - s.fields.begin());
    require(by_field[f] == nullptr, "body '{}' step {} (t = {} s): field '{}' given twice", name_,
            step, time_s, given.name);
    require(given.values.rows() == node_count_ && given.values.cols() == it->components,
            "body '{}' step {} (t = {} s): field '{}' is {} x {}, expected {} x {}", name_, step,
            time_s, given.name, given.values.rows(), given.values.cols(), node_count_,
            it->components);
    if (const auto bad = first_non_finite(given.values, may_be_plus_infinity(given.name)))
      fail_non_finite(fmt::format("series field '{}' ({}) of body '{}' at {} (step {})", given.name, it->units,
                                  name_, at_time(time_s), step),
                      bad->value, fmt::format("node {} (component {})", bad->row, bad->column), file_.final_h5);
    by_field[f] = &given;
  }
  for (size_t f = 0; f < s.fields.size(); ++f)
    require(by_field[f] != nullptr, "body '{}' step {} (t = {} s): series field '{}' missing",
            name_, step, time_s, s.fields[f].name);

  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string time_path = join(join(s.path, layout::kSeries), layout::kTime);
    const hsize_t steps = hsize_t(step) + 1;
    KF_H5(io, time_path, H5Dset_extent, s.time.get(), &steps);
    {
      h5::Handle space(KF_H5(io, time_path, H5Dget_space, s.time.get()), H5Sclose);
      const hsize_t start = hsize_t(step), count = 1;
      KF_H5(io, time_path, H5Sselect_hyperslab, space.get(), H5S_SELECT_SET, &start, nullptr,
            &count, nullptr);
      h5::Handle memory(KF_H5(io, time_path, H5Screate_simple, 1, &count, nullptr), H5Sclose);
      KF_H5(io, time_path, H5Dwrite, s.time.get(), H5T_NATIVE_DOUBLE, memory.get(), space.get(),
            H5P_DEFAULT, &time_s);
    }
    for (size_t f = 0; f < s.fields.size(); ++f) {
      const std::string path = s.grid.series[f].dataset;
      const auto& values = by_field[f]->values;
      const hsize_t n = hsize_t(node_count_), c = hsize_t(s.fields[f].components);
      const hsize_t dims[3] = {steps, n, c};
      KF_H5(io, path, H5Dset_extent, s.datasets[f].get(), dims);
      h5::Handle space(KF_H5(io, path, H5Dget_space, s.datasets[f].get()), H5Sclose);
      const hsize_t start[3] = {hsize_t(step), 0, 0}, count[3] = {1, n, c};
      KF_H5(io, path, H5Sselect_hyperslab, space.get(), H5S_SELECT_SET, start, nullptr, count,
            nullptr);
      const hsize_t memory_count[2] = {n, c};
      h5::Handle memory(KF_H5(io, path, H5Screate_simple, 2, memory_count, nullptr), H5Sclose);
      FieldMatrix storage;
      const double* data = contiguous(values, storage);
      if (n > 0)
        KF_H5(io, path, H5Dwrite, s.datasets[f].get(), H5T_NATIVE_DOUBLE, memory.get(),
              space.get(), H5P_DEFAULT, data);
    }
  });
  s.times_s.push_back(time_s);
  s.grid.times_s.push_back(time_s);
  return step;
}

fem::Index BodyWriter::steps_written() const { return fem::Index(state_->times_s.size()); }

void BodyWriter::write_envelope(const std::string& name, const std::string& units,
                                const Eigen::Ref<const FieldMatrix>& values,
                                const Eigen::Ref<const IndexMatrix>& step,
                                const std::string& operation, const std::vector<double>& step_times_s) {
  check_open();
  require_valid_name(name, "envelope");
  require_valid_name(operation, "envelope operation");
  State& s = *state_;
  require(!s.names_envelope.contains(name), "body '{}' already has envelope '{}'", name_, name);
  require(values.rows() == node_count_ && values.cols() > 0,
          "envelope '{}' of body '{}' has {} rows; the mesh has {} nodes", name, name_,
          values.rows(), node_count_);
  require(step.rows() == values.rows() && step.cols() == values.cols(),
          "envelope '{}' of body '{}': step indices are {} x {}, values {} x {}", name, name_,
          step.rows(), step.cols(), values.rows(), values.cols());
  if (const auto bad = first_non_finite(values, may_be_plus_infinity(name)))
    fail_non_finite(fmt::format("envelope '{}' ({} {}) of body '{}'", name, operation, units, name_), bad->value,
                    fmt::format("node {} (component {})", bad->row, bad->column), file_.final_h5);
  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string group_path = join(s.path, layout::kEnvelopes);
    if (!s.envelopes.valid())
      s.envelopes = h5::make_group(io, s.group.get(), layout::kEnvelopes, group_path);
    const std::string path = join(group_path, name);
    h5::Handle group = h5::make_group(io, s.envelopes.get(), name, path);
    h5::write_attribute(io, group.get(), path, "operation", operation);
    if (step_times_s.empty()) {
      h5::write_attribute(io, group.get(), path, "step_refers_to",
                          fmt::format("{}/{}/{}", s.path, layout::kSeries, layout::kTime));
    } else {
      const hsize_t time_dims[1] = {hsize_t(step_times_s.size())};
      h5::write_dataset(io, group.get(), layout::kTime, join(path, layout::kTime), time_dims, step_times_s.data(), "s");
      h5::write_attribute(io, group.get(), path, "step_refers_to", join(path, layout::kTime));
    }
    const hsize_t dims[2] = {hsize_t(values.rows()), hsize_t(values.cols())};
    FieldMatrix storage;
    const IndexMatrix step_copy = step;
    const std::string value_path = join(path, layout::kEnvelopeValue);
    const std::string step_path = join(path, layout::kEnvelopeStep);
    h5::write_dataset(io, group.get(), layout::kEnvelopeValue, value_path, dims,
                      contiguous(values, storage), units);
    h5::write_dataset(io, group.get(), layout::kEnvelopeStep, step_path, dims, step_copy.data(),
                      layout::kDimensionless);
    const int c = int(values.cols());
    s.grid.attributes.push_back(
        {fmt::format("{}_{}", name, operation), value_path, node_count_, c, false, false});
    s.grid.attributes.push_back(
        {fmt::format("{}_{}_step", name, operation), step_path, node_count_, c, false, true});
  });
  s.names_envelope.insert(name);
}

void BodyWriter::write_load_patterns(const LoadPatternData& p) {
  check_open();
  State& s = *state_;
  const Eigen::Index m = Eigen::Index(p.names.size()), T = Eigen::Index(p.time_s.size());
  require(p.coefficients.rows() == m && p.coefficients.cols() == T,
          "load patterns of body '{}': coefficients are {} x {}, expected {} patterns x {} times", name_,
          p.coefficients.rows(), p.coefficients.cols(), m, T);
  require(p.elastic_displacement_m.rows() == 3 * node_count_ && p.elastic_displacement_m.cols() == m &&
              p.stress_pa.rows() == 6 * node_count_ && p.stress_pa.cols() == m,
          "load patterns of body '{}': pattern fields do not fit its {} nodes and {} patterns", name_, node_count_, m);
  require(!s.load_patterns_written, "body '{}' already has load patterns", name_);
  // coefficients: pattern x time; displacement and stress: node-major rows x pattern.
  if (const auto bad = first_non_finite(p.coefficients))
    fail_non_finite(fmt::format("load pattern coefficients of body '{}' (pattern '{}') at {}", name_,
                                p.names[size_t(bad->row)], at_time(p.time_s[size_t(bad->column)])),
                    bad->value, fmt::format("output time {}", bad->column), file_.final_h5);
  if (const auto bad = first_non_finite(p.elastic_displacement_m))
    fail_non_finite(fmt::format("load pattern displacement (m) of body '{}' (pattern '{}')", name_,
                                p.names[size_t(bad->column)]),
                    bad->value, fmt::format("node {} (component {})", bad->row / 3, bad->row % 3), file_.final_h5);
  if (const auto bad = first_non_finite(p.stress_pa))
    fail_non_finite(fmt::format("load pattern stress (Pa) of body '{}' (pattern '{}')", name_,
                                p.names[size_t(bad->column)]),
                    bad->value, fmt::format("node {} (component {})", bad->row / 6, bad->row % 6), file_.final_h5);
  file_.guarded([&] {
    const h5::H5Io& io = file_.io;
    const std::string path = join(s.path, layout::kLoadPatterns);
    h5::Handle group = h5::make_group(io, s.group.get(), layout::kLoadPatterns, path);
    h5::write_attribute(io, group.get(), path, layout::kPatternNames, p.names);
    const hsize_t time_dims[1] = {hsize_t(T)};
    h5::write_dataset(io, group.get(), layout::kTime, join(path, layout::kTime), time_dims, p.time_s.data(), "s");
    // Column-major m x T is C-order (T, m); 3 N x m is (m, N, 3).
    const hsize_t coefficient_dims[2] = {hsize_t(T), hsize_t(m)};
    h5::write_dataset(io, group.get(), layout::kPatternCoefficients, join(path, layout::kPatternCoefficients),
                      coefficient_dims, p.coefficients.data(), "per pattern: N, N*m or m/s^2");
    const hsize_t u_dims[3] = {hsize_t(m), hsize_t(node_count_), 3};
    h5::write_dataset(io, group.get(), layout::kPatternDisplacement, join(path, layout::kPatternDisplacement), u_dims,
                      p.elastic_displacement_m.data(), "m per unit coefficient");
    const hsize_t s_dims[3] = {hsize_t(m), hsize_t(node_count_), 6};
    h5::write_dataset(io, group.get(), layout::kPatternStress, join(path, layout::kPatternStress), s_dims,
                      p.stress_pa.data(), "Pa per unit coefficient");
  });
  s.load_patterns_written = true;
}

// ---------------------------------------------------------------------------------------------
// ResultsWriter

ResultsWriter::ResultsWriter(const std::filesystem::path& path, const Provenance& provenance) {
  require(!path.empty() && path.has_filename(), "results file path '{}' names no file",
          path.string());
  require(path.extension() != ".xdmf", "results file '{}' must be the .h5 file, not the .xdmf",
          path.string());
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  require(std::filesystem::exists(directory, ec),
          "results directory '{}' does not exist (for '{}')", directory.string(), path.string());
  require(std::filesystem::is_directory(directory, ec), "results directory '{}' is not a directory",
          directory.string());
  require(::access(directory.c_str(), W_OK) == 0, "results directory '{}' is not writable",
          directory.string());
  file_ = std::make_unique<detail::FileState>(path);
  detail::FileState& f = *file_;
  const h5::H5Io& io = f.io;
  try {
    remove_if_symlink(f.temporary_h5);
    f.file = h5::Handle(KF_H5(io, "/", H5Fcreate, f.temporary_h5.c_str(), H5F_ACC_TRUNC,
                              H5P_DEFAULT, H5P_DEFAULT),
                        H5Fclose);
  } catch (const Error& e) {
    fail("cannot create a results file in directory '{}': {}", directory.string(), e.what());
  }
  try {
    h5::Handle root = h5::open_group(io, f.file.get(), "/", "/");
    h5::write_attribute(io, root.get(), "/", "format", std::string(kFormatName));
    h5::write_attribute(io, root.get(), "/", "format_version", kFormatVersion);

    const std::string p = fmt::format("/{}", layout::kProvenance);
    h5::Handle group = h5::make_group(io, f.file.get(), layout::kProvenance, p);
    h5::write_attribute(io, group.get(), p, "kinetofem_version", std::string(kVersion));
    h5::write_attribute(io, group.get(), p, "git_commit", std::string(kGitCommit));
    h5::write_attribute(io, group.get(), p, "created_utc", utc_now_iso8601());
    h5::write_attribute(io, group.get(), p, "case_path", provenance.case_path);
    h5::write_attribute(io, group.get(), p, "command_line", provenance.command_line);
    h5::write_attribute(io, group.get(), p, "units_note", provenance.units_note);
    h5::write_string_dataset(io, group.get(), layout::kCaseText, join(p, layout::kCaseText),
                             provenance.case_text, "none");

    f.bodies = h5::make_group(io, f.file.get(), layout::kBodies, fmt::format("/{}", layout::kBodies));
  } catch (...) {
    f.bodies.reset();
    f.file.reset();
    std::filesystem::remove(f.temporary_h5, ec);
    throw;
  }
}

ResultsWriter::~ResultsWriter() {
  if (!file_ || file_->committed) return;
  bodies_.clear();
  file_->tables.reset();
  file_->mechanism.reset();
  file_->bodies.reset();
  file_->file.reset();
  std::error_code ec;
  std::filesystem::remove(file_->temporary_h5, ec);
  std::filesystem::remove(file_->temporary_xdmf, ec);
}

const std::filesystem::path& ResultsWriter::path() const { return file_->final_h5; }
bool ResultsWriter::committed() const { return file_->committed; }

BodyWriter& ResultsWriter::add_body(const std::string& name, const fem::Mesh& mesh) {
  file_->check_writable();
  require_valid_name(name, "body");
  for (const auto& body : bodies_)
    require(body->name() != name, "results file '{}' already has body '{}'",
            file_->final_h5.string(), name);
  mesh.validate();
  file_->guarded([&] {
    bodies_.push_back(std::unique_ptr<BodyWriter>(new BodyWriter(*file_, name, mesh)));
  });
  return *bodies_.back();
}

BodyWriter& ResultsWriter::body(const std::string& name) {
  for (const auto& body : bodies_)
    if (body->name() == name) return *body;
  fail("results file '{}' has no body '{}'", file_->final_h5.string(), name);
}

void ResultsWriter::set_mechanism_time(const std::vector<double>& time_s) {
  detail::FileState& f = *file_;
  f.check_writable();
  require(!f.mechanism_time_set, "mechanism time is already set in '{}'", f.final_h5.string());
  for (size_t k = 0; k < time_s.size(); ++k) {
    require(std::isfinite(time_s[k]), "mechanism time {} is not finite ({} s)", k, time_s[k]);
    require(k == 0 || time_s[k] > time_s[k - 1],
            "mechanism time does not increase at index {} ({} s after {} s)", k, time_s[k],
            k == 0 ? 0.0 : time_s[k - 1]);
  }
  f.guarded([&] {
    const std::string p = fmt::format("/{}", layout::kMechanism);
    f.mechanism = h5::make_group(f.io, f.file.get(), layout::kMechanism, p);
    const hsize_t dims[1] = {hsize_t(time_s.size())};
    h5::write_dataset(f.io, f.mechanism.get(), layout::kTime, join(p, layout::kTime), dims,
                      time_s.data(), "s");
  });
  f.mechanism_time_s = time_s;
  f.mechanism_time_set = true;
}

void ResultsWriter::write_history(const std::string& name, const std::string& units,
                                  const Eigen::Ref<const FieldMatrix>& values,
                                  const std::vector<std::string>& component_names) {
  write_history(name, units, values, component_names, /*nan_where_undefined=*/false);
}

void ResultsWriter::write_history_where_defined(const std::string& name, const std::string& units,
                                                const Eigen::Ref<const FieldMatrix>& values,
                                                const std::vector<std::string>& component_names) {
  write_history(name, units, values, component_names, /*nan_where_undefined=*/true);
}

void ResultsWriter::write_history(const std::string& name, const std::string& units,
                                  const Eigen::Ref<const FieldMatrix>& values,
                                  const std::vector<std::string>& component_names,
                                  bool nan_where_undefined) {
  detail::FileState& f = *file_;
  f.check_writable();
  require_valid_name(name, "history");
  require(f.mechanism_time_set, "history '{}': set_mechanism_time must come first", name);
  require(name != layout::kTime, "history name 'time' is reserved");
  require(!f.histories.contains(name), "history '{}' is already written", name);
  require(values.rows() == Eigen::Index(f.mechanism_time_s.size()) && values.cols() > 0,
          "history '{}' has {} rows; the mechanism time grid has {}", name, values.rows(),
          f.mechanism_time_s.size());
  require_components(component_names, values.cols(), name);
  if (const auto bad = nan_where_undefined ? first_non_finite(values.array().isNaN().select(0.0, values))
                                            : first_non_finite(values))
    fail_non_finite(fmt::format("history '{}' ({}) at {}", name, units, at_time(f.mechanism_time_s[size_t(bad->row)])),
                    bad->value, fmt::format("time index {} (component {})", bad->row, bad->column), f.final_h5);
  f.guarded([&] {
    const std::string path = fmt::format("/{}/{}", layout::kMechanism, name);
    const hsize_t dims[2] = {hsize_t(values.rows()), hsize_t(values.cols())};
    FieldMatrix storage;
    h5::write_dataset(f.io, f.mechanism.get(), name, path, dims, contiguous(values, storage),
                      units);
    if (!component_names.empty()) {
      h5::Handle dataset = h5::open_dataset(f.io, f.mechanism.get(), name, path);
      h5::write_attribute(f.io, dataset.get(), path, "components", component_names);
    }
    f.xdmf_histories.push_back({name, path, fem::Index(values.rows()), int(values.cols())});
  });
  f.histories.insert(name);
}

void ResultsWriter::write_table(const std::string& name, const std::string& units,
                                const Eigen::Ref<const FieldMatrix>& values,
                                const std::vector<std::string>& component_names) {
  detail::FileState& f = *file_;
  f.check_writable();
  require_valid_name(name, "table");
  require(!f.table_names.contains(name), "table '{}' is already written", name);
  require(values.cols() > 0, "table '{}' has no columns", name);
  require_components(component_names, values.cols(), name);
  if (const auto bad = first_non_finite(values, /*allow_plus_infinity=*/true))
    fail_non_finite(fmt::format("table '{}' ({})", name, units), bad->value,
                    fmt::format("row {} (column {})", bad->row, bad->column), f.final_h5);
  f.guarded([&] {
    const std::string group_path = fmt::format("/{}", layout::kTables);
    if (!f.tables.valid()) f.tables = h5::make_group(f.io, f.file.get(), layout::kTables, group_path);
    const std::string path = join(group_path, name);
    const hsize_t dims[2] = {hsize_t(values.rows()), hsize_t(values.cols())};
    FieldMatrix storage;
    h5::write_dataset(f.io, f.tables.get(), name, path, dims, contiguous(values, storage), units);
    if (!component_names.empty()) {
      h5::Handle dataset = h5::open_dataset(f.io, f.tables.get(), name, path);
      h5::write_attribute(f.io, dataset.get(), path, "components", component_names);
    }
  });
  f.table_names.insert(name);
}

void ResultsWriter::commit() {
  detail::FileState& f = *file_;
  f.check_writable();
  f.guarded([&] {
    std::vector<xdmf::Grid> grids;
    for (const auto& body : bodies_) grids.push_back(body->state_->grid);
    // Every handle must be closed before the file: only then does closing it
    // flush everything (HDF5 keeps a file open while objects in it are open).
    for (const auto& body : bodies_) {
      BodyWriter::State& s = *body->state_;
      s.datasets.clear();
      s.time.reset();
      s.envelopes.reset();
      s.series.reset();
      s.elements.reset();
      s.statics.reset();
      s.group.reset();
    }
    f.tables.reset();
    f.mechanism.reset();
    f.bodies.reset();
    KF_H5(f.io, "/", H5Fclose, f.file.release());

    xdmf::Mechanism mechanism;
    mechanism.present = f.mechanism_time_set;
    mechanism.times_s = f.mechanism_time_s;
    mechanism.histories = f.xdmf_histories;
    const std::string text = xdmf::document(f.final_h5.filename().string(), grids, mechanism);
    write_text_file(f.temporary_xdmf, text);
    std::error_code ec;
    std::filesystem::rename(f.temporary_h5, f.final_h5, ec);
    require(!ec, "cannot rename '{}' to '{}': {}", f.temporary_h5.string(), f.final_h5.string(),
            ec.message());
  });
  f.committed = true;  // the .h5 is in place; the destructor must not remove anything now
  std::error_code ec;
  std::filesystem::rename(f.temporary_xdmf, f.final_xdmf, ec);
  if (ec) {
    std::filesystem::remove(f.temporary_xdmf, ec);
    fail("results '{}' written, but cannot rename '{}' to '{}'", f.final_h5.string(),
         f.temporary_xdmf.string(), f.final_xdmf.string());
  }
}

}  // namespace kinetofem::post
