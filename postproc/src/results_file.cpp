#include "kinetofem/postproc/results_file.hpp"

#include "hdf5_io.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::post {

namespace {

std::string names_or_none(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string text;
  for (const auto& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string join(const std::string& a, const std::string& b) { return a + "/" + b; }

fem::ElementType element_type_named(const std::string& name, const std::string& where) {
  for (auto type : fem::all_element_types)
    if (name == fem::name_of(type)) return type;
  fail("unknown element type '{}' at '{}'", name, where);
}

fem::FaceType face_type_named(const std::string& name, const std::string& where) {
  for (auto type : fem::all_face_types)
    if (name == fem::name_of(type)) return type;
  fail("unknown face type '{}' at '{}'", name, where);
}

}  // namespace

struct ResultsFile::Impl {
  std::filesystem::path path;
  h5::H5Io io;
  h5::Handle file;
  std::int64_t version = 0;

  explicit Impl(const std::filesystem::path& p) : path(p), io(p.string()) {}

  // Whether the absolute path exists, component by component (H5Lexists
  // fails rather than answering false when an intermediate group is missing).
  bool exists(const std::string& absolute) const {
    std::string prefix;
    size_t start = 1;
    while (start <= absolute.size()) {
      const size_t end = std::min(absolute.find('/', start), absolute.size());
      prefix += '/';
      prefix.append(absolute, start, end - start);
      if (KF_H5(io, prefix, H5Lexists, file.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
      start = end + 1;
    }
    return true;
  }

  std::vector<std::string> children_of(const std::string& group, h5::ChildKind kind) const {
    if (!exists(group)) return {};
    h5::Handle handle = h5::open_group(io, file.get(), group, group);
    return h5::children(io, handle.get(), group, kind);
  }

  std::string body_path(const std::string& body) const {
    const std::string p = fmt::format("/{}/{}", layout::kBodies, body);
    if (!exists(p))
      fail("results file '{}' has no body '{}' (bodies: {})", path.string(), body,
           names_or_none(children_of(fmt::format("/{}", layout::kBodies), h5::ChildKind::Group)));
    return p;
  }

  // A dataset that must be there; the error lists what the group holds instead.
  h5::Handle dataset(const std::string& group, const std::string& name, const char* what) const {
    const std::string p = join(group, name);
    if (!exists(p))
      fail("results file '{}' has no {} '{}' at '{}' (present: {})", path.string(), what, name,
           group, names_or_none(children_of(group, h5::ChildKind::Any)));
    return h5::open_dataset(io, file.get(), p, p);
  }

  FieldMatrix matrix(hid_t dataset, const std::string& p, std::span<const hsize_t> start = {},
                     std::span<const hsize_t> count = {}) const {
    std::vector<hsize_t> dims = start.empty() ? h5::dataset_dims(io, dataset, p)
                                              : std::vector<hsize_t>(count.begin(), count.end());
    const std::vector<double> values = h5::read_doubles(io, dataset, p, start, count);
    // The last dimension is the components; everything before it, the rows.
    const hsize_t columns = dims.size() >= 2 ? dims.back() : 1;
    const hsize_t rows = columns == 0 ? 0 : values.size() / columns;
    FieldMatrix m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns));
    std::copy(values.begin(), values.end(), m.data());
    return m;
  }

  FieldData field(const std::string& group, const std::string& name, const char* what) const {
    const std::string p = join(group, name);
    h5::Handle d = dataset(group, name, what);
    FieldData out;
    out.values = matrix(d.get(), p);
    out.units = h5::read_string_attribute(io, d.get(), p, "units");
    if (h5::has_attribute(io, d.get(), p, "components"))
      out.component_names = h5::read_strings_attribute(io, d.get(), p, "components");
    return out;
  }

  std::vector<std::int64_t> int64s(const std::string& p) const {
    h5::Handle d = h5::open_dataset(io, file.get(), p, p);
    return h5::read_int64s(io, d.get(), p);
  }

  // Indices read from the file (node numbers, element numbers, steps), each in
  // 0 .. count - 1: a damaged file must be an error naming the dataset, not a
  // read out of bounds in whatever uses the index.
  std::vector<std::int64_t> indices(const std::string& p, std::int64_t count, const char* what) const {
    std::vector<std::int64_t> values = int64s(p);
    for (size_t k = 0; k < values.size(); ++k)
      if (values[k] < 0 || values[k] >= count)
        fail("'{}': dataset '{}' entry {} is {} {}, outside 0 .. {} ({} {}s): the results file is damaged",
             path.string(), p, k, what, values[k], count - 1, count, what);
    return values;
  }
};

ResultsFile::ResultsFile(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ResultsFile::ResultsFile(ResultsFile&&) noexcept = default;
ResultsFile& ResultsFile::operator=(ResultsFile&&) noexcept = default;
ResultsFile::~ResultsFile() = default;

ResultsFile ResultsFile::open(const std::filesystem::path& path) {
  std::error_code ec;
  require(std::filesystem::is_regular_file(path, ec), "results file '{}' does not exist",
          path.string());
  auto impl = std::make_unique<Impl>(path);
  const h5::H5Io& io = impl->io;
  require(KF_H5(io, "/", H5Fis_hdf5, path.c_str()) > 0, "'{}' is not an HDF5 file", path.string());
  impl->file =
      h5::Handle(KF_H5(io, "/", H5Fopen, path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  h5::Handle root = h5::open_group(io, impl->file.get(), "/", "/");
  const bool ours = h5::has_attribute(io, root.get(), "/", "format") &&
                    h5::read_string_attribute(io, root.get(), "/", "format") == kFormatName;
  require(ours, "'{}' is an HDF5 file but not a kinetofem results file (no format = '{}')",
          path.string(), kFormatName);
  impl->version = h5::read_int_attribute(io, root.get(), "/", "format_version");
  require(impl->version <= kFormatVersion,
          "results file '{}' has format version {}; this build reads up to {}", path.string(),
          impl->version, kFormatVersion);
  return ResultsFile(std::move(impl));
}

const std::filesystem::path& ResultsFile::path() const { return impl_->path; }
std::int64_t ResultsFile::format_version() const { return impl_->version; }

Provenance ResultsFile::provenance() const {
  const Impl& f = *impl_;
  const std::string p = fmt::format("/{}", layout::kProvenance);
  h5::Handle group = h5::open_group(f.io, f.file.get(), p, p);
  auto text = [&](const char* name) { return h5::read_string_attribute(f.io, group.get(), p, name); };
  Provenance out;
  out.kinetofem_version = text("kinetofem_version");
  out.git_commit = text("git_commit");
  out.created_utc = text("created_utc");
  out.case_path = text("case_path");
  out.command_line = text("command_line");
  out.units_note = text("units_note");
  const std::string case_text = join(p, layout::kCaseText);
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), case_text, case_text);
  out.case_text = h5::read_string_dataset(f.io, d.get(), case_text);
  return out;
}

std::vector<std::string> ResultsFile::bodies() const {
  return impl_->children_of(fmt::format("/{}", layout::kBodies), h5::ChildKind::Group);
}

fem::Mesh ResultsFile::read_mesh(const std::string& body) const {
  const Impl& f = *impl_;
  const std::string mesh_path = join(f.body_path(body), layout::kMesh);
  fem::Mesh mesh;
  {
    const std::string p = join(mesh_path, layout::kNodes);
    h5::Handle d = h5::open_dataset(f.io, f.file.get(), p, p);
    const auto dims = h5::dataset_dims(f.io, d.get(), p);
    require(dims.size() == 2 && dims[1] == 3, "'{}' in '{}' is not an N x 3 array", p,
            f.path.string());
    const auto values = h5::read_doubles(f.io, d.get(), p);
    mesh.nodes.resize(Eigen::Index(dims[0]), 3);
    std::copy(values.begin(), values.end(), mesh.nodes.data());
  }
  const std::string blocks_path = join(mesh_path, layout::kBlocks);
  for (size_t b = 0; f.exists(join(blocks_path, layout::block_name(b))); ++b) {
    const std::string p = join(blocks_path, layout::block_name(b));
    h5::Handle group = h5::open_group(f.io, f.file.get(), p, p);
    fem::ElementBlock block;
    block.type =
        element_type_named(h5::read_string_attribute(f.io, group.get(), p, "element_type"), p);
    const std::string connectivity = join(p, layout::kConnectivity);
    block.connectivity = f.indices(connectivity, mesh.node_count(), "node");
    const size_t per_element = size_t(fem::nodes_per_element(block.type));
    require(block.connectivity.size() % per_element == 0,
            "'{}': dataset '{}' has {} entries, not a multiple of {} nodes per {}: the results file is damaged",
            f.path.string(), connectivity, block.connectivity.size(), per_element, fem::name_of(block.type));
    mesh.blocks.push_back(std::move(block));
  }
  const std::string node_sets = join(mesh_path, layout::kNodeSets);
  for (const auto& set : f.children_of(node_sets, h5::ChildKind::Dataset))
    mesh.node_sets[set] = f.indices(join(node_sets, set), mesh.node_count(), "node");
  const std::string element_sets = join(mesh_path, layout::kElementSets);
  for (const auto& set : f.children_of(element_sets, h5::ChildKind::Dataset))
    mesh.element_sets[set] = f.indices(join(element_sets, set), mesh.element_count(), "element");
  const std::string face_sets = join(mesh_path, layout::kFaceSets);
  for (const auto& set : f.children_of(face_sets, h5::ChildKind::Group)) {
    const std::string set_path = join(face_sets, set);
    auto& blocks = mesh.face_sets[set];
    for (size_t b = 0; f.exists(join(set_path, layout::block_name(b))); ++b) {
      const std::string p = join(set_path, layout::block_name(b));
      h5::Handle group = h5::open_group(f.io, f.file.get(), p, p);
      fem::FaceBlock faces;
      faces.type = face_type_named(h5::read_string_attribute(f.io, group.get(), p, "face_type"), p);
      const std::string connectivity = join(p, layout::kConnectivity);
      faces.connectivity = f.indices(connectivity, mesh.node_count(), "node");
      const size_t per_face = size_t(fem::nodes_per_face(faces.type));
      require(faces.connectivity.size() % per_face == 0,
              "'{}': dataset '{}' has {} entries, not a multiple of {} nodes per {}: the results file is damaged",
              f.path.string(), connectivity, faces.connectivity.size(), per_face, fem::name_of(faces.type));
      blocks.push_back(std::move(faces));
    }
  }
  return mesh;
}

std::vector<std::string> ResultsFile::static_fields(const std::string& body) const {
  return impl_->children_of(join(impl_->body_path(body), layout::kStatic), h5::ChildKind::Dataset);
}

FieldData ResultsFile::read_static(const std::string& body, const std::string& field) const {
  return impl_->field(join(impl_->body_path(body), layout::kStatic), field, "static field");
}

std::vector<std::string> ResultsFile::element_fields(const std::string& body) const {
  return impl_->children_of(join(impl_->body_path(body), layout::kElementFields),
                            h5::ChildKind::Dataset);
}

FieldData ResultsFile::read_element_field(const std::string& body, const std::string& field) const {
  return impl_->field(join(impl_->body_path(body), layout::kElementFields), field,
                      "element field");
}

std::vector<std::string> ResultsFile::series_fields(const std::string& body) const {
  auto names =
      impl_->children_of(join(impl_->body_path(body), layout::kSeries), h5::ChildKind::Dataset);
  std::erase(names, std::string(layout::kTime));
  return names;
}

std::vector<double> ResultsFile::series_times(const std::string& body) const {
  const Impl& f = *impl_;
  const std::string p = join(join(f.body_path(body), layout::kSeries), layout::kTime);
  if (!f.exists(p)) return {};
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), p, p);
  return h5::read_doubles(f.io, d.get(), p);
}

bool ResultsFile::has_load_patterns(const std::string& body) const {
  return impl_->exists(join(impl_->body_path(body), layout::kLoadPatterns));
}

LoadPatternData ResultsFile::read_load_patterns(const std::string& body) const {
  const Impl& f = *impl_;
  const std::string group_path = join(f.body_path(body), layout::kLoadPatterns);
  require(f.exists(group_path), "{}: body '{}' has no load patterns (a step-by-step run)", f.path.string(), body);
  h5::Handle group = h5::open_group(f.io, f.file.get(), group_path, group_path);
  LoadPatternData out;
  out.names = h5::read_strings_attribute(f.io, group.get(), group_path, layout::kPatternNames);
  const Eigen::Index m = Eigen::Index(out.names.size());
  auto read = [&](const char* name) {
    const std::string p = join(group_path, name);
    h5::Handle d = h5::open_dataset(f.io, f.file.get(), p, p);
    return std::pair{h5::read_doubles(f.io, d.get(), p), h5::dataset_dims(f.io, d.get(), p)};
  };
  out.time_s = read(layout::kTime).first;
  const Eigen::Index T = Eigen::Index(out.time_s.size());
  const auto [c, c_dims] = read(layout::kPatternCoefficients);
  require(c_dims.size() == 2 && Eigen::Index(c_dims[0]) == T && Eigen::Index(c_dims[1]) == m,
          "{}: {}/{} is not a (T, m) = ({}, {}) array", f.path.string(), group_path, layout::kPatternCoefficients, T, m);
  out.coefficients = Eigen::Map<const Eigen::MatrixXd>(c.data(), m, T);
  const auto [u, u_dims] = read(layout::kPatternDisplacement);
  const auto [s, s_dims] = read(layout::kPatternStress);
  require(u_dims.size() == 3 && Eigen::Index(u_dims[0]) == m && u_dims[2] == 3 && s_dims.size() == 3 &&
              Eigen::Index(s_dims[0]) == m && s_dims[1] == u_dims[1] && s_dims[2] == 6,
          "{}: {}: pattern fields are not (m, N, 3) and (m, N, 6) arrays", f.path.string(), group_path);
  const Eigen::Index nodes = Eigen::Index(u_dims[1]);
  out.elastic_displacement_m = Eigen::Map<const Eigen::MatrixXd>(u.data(), 3 * nodes, m);
  out.stress_pa = Eigen::Map<const Eigen::MatrixXd>(s.data(), 6 * nodes, m);
  return out;
}

FieldData ResultsFile::read_step(const std::string& body, const std::string& field,
                                 fem::Index step) const {
  const Impl& f = *impl_;
  const std::string group = join(f.body_path(body), layout::kSeries);
  const std::string p = join(group, field);
  h5::Handle d = f.dataset(group, field, "series field");
  const auto dims = h5::dataset_dims(f.io, d.get(), p);
  require(dims.size() == 3, "series field '{}' in '{}' is not a (T, N, c) array", p,
          f.path.string());
  require(step >= 0 && hsize_t(step) < dims[0],
          "body '{}' series field '{}': step {} out of range (file has {} steps)", body, field,
          step, dims[0]);
  const hsize_t start[3] = {hsize_t(step), 0, 0}, count[3] = {1, dims[1], dims[2]};
  FieldData out;
  out.values = f.matrix(d.get(), p, start, count);
  out.units = h5::read_string_attribute(f.io, d.get(), p, "units");
  if (h5::has_attribute(f.io, d.get(), p, "components"))
    out.component_names = h5::read_strings_attribute(f.io, d.get(), p, "components");
  return out;
}

std::string ResultsFile::geometry_field(const std::string& body) const {
  const Impl& f = *impl_;
  const std::string group = join(f.body_path(body), layout::kSeries);
  for (const auto& field : series_fields(body)) {
    const std::string p = join(group, field);
    h5::Handle d = h5::open_dataset(f.io, f.file.get(), p, p);
    if (h5::has_attribute(f.io, d.get(), p, layout::kXdmfGeometry) &&
        h5::read_int_attribute(f.io, d.get(), p, layout::kXdmfGeometry) != 0)
      return field;
  }
  return "";
}

std::vector<std::string> ResultsFile::envelopes(const std::string& body) const {
  return impl_->children_of(join(impl_->body_path(body), layout::kEnvelopes),
                            h5::ChildKind::Group);
}

EnvelopeData ResultsFile::read_envelope(const std::string& body, const std::string& field) const {
  const Impl& f = *impl_;
  const std::string group = join(join(f.body_path(body), layout::kEnvelopes), field);
  if (!f.exists(group))
    fail("body '{}' in '{}' has no envelope '{}' (envelopes: {})", body, f.path.string(), field,
         names_or_none(envelopes(body)));
  EnvelopeData out;
  const FieldData value = f.field(group, layout::kEnvelopeValue, "envelope value");
  out.values = value.values;
  out.units = value.units;
  h5::Handle g = h5::open_group(f.io, f.file.get(), group, group);
  out.operation = h5::read_string_attribute(f.io, g.get(), group, "operation");
  const std::string own_time = join(group, layout::kTime);
  if (f.exists(own_time)) {
    h5::Handle d = h5::open_dataset(f.io, f.file.get(), own_time, own_time);
    out.times_s = h5::read_doubles(f.io, d.get(), own_time);
  } else {
    out.times_s = series_times(body);
  }
  // Each step indexes the envelope's times.
  const auto steps = f.indices(join(group, layout::kEnvelopeStep), std::int64_t(out.times_s.size()), "step");
  require(steps.size() == size_t(out.values.size()), "envelope '{}' of body '{}': {} steps for {} values",
          field, body, steps.size(), out.values.size());
  out.step.resize(out.values.rows(), out.values.cols());
  std::copy(steps.begin(), steps.end(), out.step.data());
  return out;
}

std::vector<double> ResultsFile::mechanism_time() const {
  const Impl& f = *impl_;
  const std::string p = fmt::format("/{}/{}", layout::kMechanism, layout::kTime);
  if (!f.exists(p)) return {};
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), p, p);
  return h5::read_doubles(f.io, d.get(), p);
}

std::vector<std::string> ResultsFile::histories() const {
  auto names =
      impl_->children_of(fmt::format("/{}", layout::kMechanism), h5::ChildKind::Dataset);
  std::erase(names, std::string(layout::kTime));
  return names;
}

FieldData ResultsFile::read_history(const std::string& name) const {
  return impl_->field(fmt::format("/{}", layout::kMechanism), name, "mechanism history");
}

std::vector<std::string> ResultsFile::tables() const {
  return impl_->children_of(fmt::format("/{}", layout::kTables), h5::ChildKind::Dataset);
}

FieldData ResultsFile::read_table(const std::string& name) const {
  return impl_->field(fmt::format("/{}", layout::kTables), name, "table");
}

std::vector<std::string> ResultsFile::datasets() const {
  return h5::all_datasets(impl_->io, impl_->file.get());
}

IndexMatrix ResultsFile::read_indices(const std::string& dataset) const {
  const Impl& f = *impl_;
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), dataset, dataset);
  const auto dims = h5::dataset_dims(f.io, d.get(), dataset);
  require(dims.size() == 1 || dims.size() == 2, "'{}' in '{}' is not a 1-D or 2-D array", dataset,
          f.path.string());
  const auto values = h5::read_int64s(f.io, d.get(), dataset);
  IndexMatrix out(static_cast<Eigen::Index>(dims[0]),
                  static_cast<Eigen::Index>(dims.size() == 2 ? dims[1] : 1));
  std::copy(values.begin(), values.end(), out.data());
  return out;
}

bool ResultsFile::has_units(const std::string& dataset) const {
  const Impl& f = *impl_;
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), dataset, dataset);
  return h5::has_attribute(f.io, d.get(), dataset, "units");
}

std::string ResultsFile::units_of(const std::string& dataset) const {
  const Impl& f = *impl_;
  h5::Handle d = h5::open_dataset(f.io, f.file.get(), dataset, dataset);
  return h5::read_string_attribute(f.io, d.get(), dataset, "units");
}

}  // namespace kinetofem::post
