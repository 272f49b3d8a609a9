#include "hdf5_io.hpp"

#include <utility>

#include "kinetofem/core/error.hpp"

namespace kinetofem::post::h5 {

namespace {

// Collects the most specific entry of the HDF5 error stack (the first one
// visited when walking upward from where the error was detected).
herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* client) {
  auto* message = static_cast<std::string*>(client);
  if (n == 0 && error != nullptr) {
    *message = error->desc != nullptr ? error->desc : "";
    if (error->func_name != nullptr) *message += fmt::format(" (in {})", error->func_name);
  }
  return 0;
}

// HDF5's file driver describes a failed system call as "file write failed:
// time = ..., filename = ..., file descriptor = 3, errno = 27, error message =
// 'File too large', buf = ..., offset = 0 (in H5FD__sec2_write)": a user needs
// what failed and the system's reason, not the call's arguments.
std::string condensed(const std::string& message) {
  constexpr std::string_view reason_key = "error message = '";
  const auto reason_at = message.find(reason_key);
  const auto colon = message.find(": ");
  if (reason_at == std::string::npos || colon == std::string::npos || colon > reason_at) return message;
  const auto start = reason_at + reason_key.size();
  const auto end = message.find('\'', start);
  if (end == std::string::npos) return message;
  return message.substr(0, colon) + ": " + message.substr(start, end - start);
}

}  // namespace

void throw_failure(const char* function, std::string_view object, const std::string& file) {
  std::string message;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &message);
  H5Eclear2(H5E_DEFAULT);
  if (message.empty()) message = "no message on the HDF5 error stack";
  // One-line errors: HDF5's messages may carry newlines (e.g. a failed write).
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  fail("HDF5 {} failed on '{}' in '{}': {}", function, object, file, condensed(message));
}

H5Io::H5Io(std::string file_path) : file_(std::move(file_path)) {
  // HDF5 1.10 can crash in its atexit clean-up after a failed write (full
  // disk); the library's objects are all closed by their owners anyway.
  H5dont_atexit();
  // Failures are reported by the Error thrown from check(); HDF5's own
  // printing of its error stack to stderr would only repeat it, noisily.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = std::exchange(other.id_, -1);
    closer_ = other.closer_;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = -1;
}

Handle make_group(const H5Io& io, hid_t parent, const std::string& name, std::string_view path) {
  return {KF_H5(io, path, H5Gcreate2, parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
          H5Gclose};
}

Handle open_group(const H5Io& io, hid_t parent, const std::string& name, std::string_view path) {
  return {KF_H5(io, path, H5Gopen2, parent, name.c_str(), H5P_DEFAULT), H5Gclose};
}

Handle open_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path) {
  return {KF_H5(io, path, H5Dopen2, parent, name.c_str(), H5P_DEFAULT), H5Dclose};
}

bool has_child(const H5Io& io, hid_t parent, const std::string& name, std::string_view path) {
  return KF_H5(io, path, H5Lexists, parent, name.c_str(), H5P_DEFAULT) > 0;
}

namespace {
struct ChildList {
  ChildKind kind;
  std::vector<std::string> names;
};

herr_t collect_child(hid_t group, const char* name, const H5L_info_t*, void* client) {
  auto* list = static_cast<ChildList*>(client);
  if (list->kind != ChildKind::Any) {
    const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
    if (object < 0) return -1;
    const H5I_type_t type = H5Iget_type(object);
    H5Oclose(object);
    const bool wanted = list->kind == ChildKind::Group ? type == H5I_GROUP : type == H5I_DATASET;
    if (!wanted) return 0;
  }
  list->names.emplace_back(name);
  return 0;
}

struct DatasetList {
  std::vector<std::string> paths;
};

herr_t collect_dataset(hid_t group, const char* name, const H5L_info_t*, void* client) {
  const hid_t object = H5Oopen(group, name, H5P_DEFAULT);
  if (object < 0) return -1;
  const H5I_type_t type = H5Iget_type(object);
  H5Oclose(object);
  if (type == H5I_DATASET) static_cast<DatasetList*>(client)->paths.push_back(std::string("/") + name);
  return 0;
}
}  // namespace

std::vector<std::string> children(const H5Io& io, hid_t group, std::string_view path,
                                  ChildKind kind) {
  ChildList list{kind, {}};
  hsize_t index = 0;
  KF_H5(io, path, H5Literate, group, H5_INDEX_NAME, H5_ITER_INC, &index, collect_child, &list);
  return list.names;
}

std::vector<std::string> all_datasets(const H5Io& io, hid_t group) {
  DatasetList list;
  KF_H5(io, "/", H5Lvisit, group, H5_INDEX_NAME, H5_ITER_INC, collect_dataset, &list);
  return list.paths;
}

namespace {
Handle utf8_string_type(const H5Io& io, std::string_view path) {
  Handle type(KF_H5(io, path, H5Tcopy, H5T_C_S1), H5Tclose);
  KF_H5(io, path, H5Tset_size, type.get(), H5T_VARIABLE);
  KF_H5(io, path, H5Tset_cset, type.get(), H5T_CSET_UTF8);
  return type;
}

std::string attribute_path(std::string_view path, const char* name) {
  return fmt::format("{}@{}", path, name);
}
}  // namespace

void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     const std::string& value) {
  const std::string where = attribute_path(path, name);
  Handle type = utf8_string_type(io, where);
  Handle space(KF_H5(io, where, H5Screate, H5S_SCALAR), H5Sclose);
  Handle attribute(
      KF_H5(io, where, H5Acreate2, object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  const char* text = value.c_str();
  KF_H5(io, where, H5Awrite, attribute.get(), type.get(), &text);
}

void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     const std::vector<std::string>& values) {
  const std::string where = attribute_path(path, name);
  Handle type = utf8_string_type(io, where);
  const hsize_t size = values.size();
  Handle space(KF_H5(io, where, H5Screate_simple, 1, &size, nullptr), H5Sclose);
  Handle attribute(
      KF_H5(io, where, H5Acreate2, object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  std::vector<const char*> texts;
  for (const auto& value : values) texts.push_back(value.c_str());
  KF_H5(io, where, H5Awrite, attribute.get(), type.get(), texts.data());
}

void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     std::int64_t value) {
  const std::string where = attribute_path(path, name);
  Handle space(KF_H5(io, where, H5Screate, H5S_SCALAR), H5Sclose);
  Handle attribute(KF_H5(io, where, H5Acreate2, object, name, H5T_STD_I64LE, space.get(),
                         H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  KF_H5(io, where, H5Awrite, attribute.get(), H5T_NATIVE_INT64, &value);
}

bool has_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name) {
  return KF_H5(io, attribute_path(path, name), H5Aexists, object, name) > 0;
}

namespace {
// Reads a string attribute of any storage (variable or fixed length) as variable-length strings.
std::vector<std::string> read_strings(const H5Io& io, hid_t object, std::string_view path,
                                      const char* name) {
  const std::string where = attribute_path(path, name);
  Handle attribute(KF_H5(io, where, H5Aopen, object, name, H5P_DEFAULT), H5Aclose);
  Handle file_type(KF_H5(io, where, H5Aget_type, attribute.get()), H5Tclose);
  if (KF_H5(io, where, H5Tget_class, file_type.get()) != H5T_STRING)
    fail("attribute '{}' in '{}' is not a string", where, io.file());
  Handle space(KF_H5(io, where, H5Aget_space, attribute.get()), H5Sclose);
  const hssize_t count = KF_H5(io, where, H5Sget_simple_extent_npoints, space.get());
  Handle type = utf8_string_type(io, where);
  std::vector<char*> texts(size_t(count), nullptr);
  KF_H5(io, where, H5Aread, attribute.get(), type.get(), texts.data());
  std::vector<std::string> values;
  for (char* text : texts) values.emplace_back(text != nullptr ? text : "");
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, texts.data());
  return values;
}
}  // namespace

std::string read_string_attribute(const H5Io& io, hid_t object, std::string_view path,
                                  const char* name) {
  auto values = read_strings(io, object, path, name);
  if (values.size() != 1)
    fail("attribute '{}' in '{}' holds {} strings, expected 1", attribute_path(path, name),
         io.file(), values.size());
  return values.front();
}

std::vector<std::string> read_strings_attribute(const H5Io& io, hid_t object,
                                                std::string_view path, const char* name) {
  return read_strings(io, object, path, name);
}

std::int64_t read_int_attribute(const H5Io& io, hid_t object, std::string_view path,
                                const char* name) {
  const std::string where = attribute_path(path, name);
  Handle attribute(KF_H5(io, where, H5Aopen, object, name, H5P_DEFAULT), H5Aclose);
  std::int64_t value = 0;
  KF_H5(io, where, H5Aread, attribute.get(), H5T_NATIVE_INT64, &value);
  return value;
}

namespace {
void write_numeric(const H5Io& io, hid_t parent, const std::string& name, std::string_view path,
                   std::span<const hsize_t> dims, hid_t file_type, hid_t memory_type,
                   const void* data, const std::string& units) {
  Handle space(KF_H5(io, path, H5Screate_simple, int(dims.size()), dims.data(), nullptr),
               H5Sclose);
  Handle dataset(KF_H5(io, path, H5Dcreate2, parent, name.c_str(), file_type, space.get(),
                       H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > 0)
    KF_H5(io, path, H5Dwrite, dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  write_attribute(io, dataset.get(), path, "units", units);
}
}  // namespace

void write_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path,
                   std::span<const hsize_t> dims, const double* data, const std::string& units) {
  write_numeric(io, parent, name, path, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, units);
}

void write_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path,
                   std::span<const hsize_t> dims, const std::int64_t* data,
                   const std::string& units) {
  write_numeric(io, parent, name, path, dims, H5T_STD_I64LE, H5T_NATIVE_INT64, data, units);
}

void write_string_dataset(const H5Io& io, hid_t parent, const std::string& name,
                          std::string_view path, const std::string& value,
                          const std::string& units) {
  Handle type = utf8_string_type(io, path);
  Handle space(KF_H5(io, path, H5Screate, H5S_SCALAR), H5Sclose);
  Handle dataset(KF_H5(io, path, H5Dcreate2, parent, name.c_str(), type.get(), space.get(),
                       H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  const char* text = value.c_str();
  KF_H5(io, path, H5Dwrite, dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
  write_attribute(io, dataset.get(), path, "units", units);
}

std::string read_string_dataset(const H5Io& io, hid_t dataset, std::string_view path) {
  Handle type = utf8_string_type(io, path);
  Handle space(KF_H5(io, path, H5Dget_space, dataset), H5Sclose);
  require(KF_H5(io, path, H5Sget_simple_extent_npoints, space.get()) == 1,
          "dataset '{}' in '{}' is not a single string", path, io.file());
  char* text = nullptr;
  KF_H5(io, path, H5Dread, dataset, type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
  std::string value = text != nullptr ? text : "";
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &text);
  return value;
}

std::vector<hsize_t> dataset_dims(const H5Io& io, hid_t dataset, std::string_view path) {
  Handle space(KF_H5(io, path, H5Dget_space, dataset), H5Sclose);
  const int rank = KF_H5(io, path, H5Sget_simple_extent_ndims, space.get());
  std::vector<hsize_t> dims(size_t(rank), 0);
  if (rank > 0) KF_H5(io, path, H5Sget_simple_extent_dims, space.get(), dims.data(), nullptr);
  return dims;
}

namespace {
template <typename T>
std::vector<T> read_numeric(const H5Io& io, hid_t dataset, std::string_view path,
                            hid_t memory_type, std::span<const hsize_t> start,
                            std::span<const hsize_t> count) {
  const auto dims = dataset_dims(io, dataset, path);
  Handle file_space(KF_H5(io, path, H5Dget_space, dataset), H5Sclose);
  hsize_t total = 1;
  if (start.empty()) {
    for (hsize_t d : dims) total *= d;
  } else {
    require(start.size() == dims.size() && count.size() == dims.size(),
            "hyperslab of rank {} on dataset '{}' of rank {}", start.size(), path, dims.size());
    for (size_t k = 0; k < dims.size(); ++k) {
      require(start[k] + count[k] <= dims[k],
              "hyperslab beyond the end of dataset '{}' in '{}' (dimension {}: {} + {} > {})",
              path, io.file(), k, start[k], count[k], dims[k]);
      total *= count[k];
    }
    KF_H5(io, path, H5Sselect_hyperslab, file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
          count.data(), nullptr);
  }
  std::vector<T> values(total);
  if (total == 0) return values;
  const hsize_t memory_size = total;
  Handle memory_space(KF_H5(io, path, H5Screate_simple, 1, &memory_size, nullptr), H5Sclose);
  KF_H5(io, path, H5Dread, dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT,
        values.data());
  return values;
}
}  // namespace

std::vector<double> read_doubles(const H5Io& io, hid_t dataset, std::string_view path,
                                 std::span<const hsize_t> start, std::span<const hsize_t> count) {
  return read_numeric<double>(io, dataset, path, H5T_NATIVE_DOUBLE, start, count);
}

std::vector<std::int64_t> read_int64s(const H5Io& io, hid_t dataset, std::string_view path) {
  return read_numeric<std::int64_t>(io, dataset, path, H5T_NATIVE_INT64, {}, {});
}

}  // namespace kinetofem::post::h5
