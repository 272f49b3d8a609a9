#pragma once
// Private to kinetofem_postproc: the one checked path into the HDF5 C library.
//
// Every HDF5 call of the module goes through KF_H5(io, object, H5Xyz, args...),
// which calls H5Xyz(args...) and, when the result is negative (the library's
// failure value for herr_t, hid_t and htri_t alike), throws kinetofem::Error
// naming the function, the object inside the file, the file path and the
// innermost message of HDF5's error stack. Automatic printing of that stack is
// switched off when an H5Io is made, so a failure is reported once, by the
// Error, and not also as a screen of library text.
//
// Identifiers are owned by Handle (move-only), which closes them with the
// matching H5?close, so no identifier leaks on an error path. Those closes,
// and the error-stack calls made while reporting a failure, are the only
// unchecked calls: they run on cleanup paths that must not throw. Closing a
// file on success is checked (release() the Handle into KF_H5(..., H5Fclose)).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <hdf5.h>

namespace kinetofem::post::h5 {

// Throws kinetofem::Error: "HDF5 <function> failed on '<object>' in '<file>': <message>".
[[noreturn]] void throw_failure(const char* function, std::string_view object,
                                const std::string& file);

// Context of the calls on one file: its path, for messages.
class H5Io {
 public:
  explicit H5Io(std::string file_path);
  const std::string& file() const { return file_; }

  template <typename Result>
  Result check(Result result, const char* function, std::string_view object) const {
    if (result < 0) throw_failure(function, object, file_);
    return result;
  }

 private:
  std::string file_;
};

#define KF_H5(io, object, function, ...) (io).check(function(__VA_ARGS__), #function, (object))

// Owns one HDF5 identifier.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Closes without checking (destructors, error paths).
  void reset();
  // Gives up ownership, for a checked close by the caller.
  hid_t release() { return std::exchange(id_, -1); }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

Handle make_group(const H5Io& io, hid_t parent, const std::string& name, std::string_view path);
Handle open_group(const H5Io& io, hid_t parent, const std::string& name, std::string_view path);
Handle open_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path);
// Whether `parent` has a direct child link `name`.
bool has_child(const H5Io& io, hid_t parent, const std::string& name, std::string_view path);
// Names of the direct children of a group, in name order, optionally only the
// groups or only the datasets.
enum class ChildKind { Any, Group, Dataset };
std::vector<std::string> children(const H5Io& io, hid_t group, std::string_view path,
                                  ChildKind kind = ChildKind::Any);
// Paths of every dataset in the file below `group` (recursively).
std::vector<std::string> all_datasets(const H5Io& io, hid_t group);

// Attributes: UTF-8 variable-length strings (read back as str by h5py) and int64.
void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     const std::string& value);
void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     const std::vector<std::string>& values);
void write_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name,
                     std::int64_t value);
bool has_attribute(const H5Io& io, hid_t object, std::string_view path, const char* name);
std::string read_string_attribute(const H5Io& io, hid_t object, std::string_view path,
                                  const char* name);
std::vector<std::string> read_strings_attribute(const H5Io& io, hid_t object,
                                                std::string_view path, const char* name);
std::int64_t read_int_attribute(const H5Io& io, hid_t object, std::string_view path,
                                const char* name);

// Contiguous datasets written whole, with their `units` attribute.
void write_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path,
                   std::span<const hsize_t> dims, const double* data, const std::string& units);
void write_dataset(const H5Io& io, hid_t parent, const std::string& name, std::string_view path,
                   std::span<const hsize_t> dims, const std::int64_t* data,
                   const std::string& units);
// A scalar UTF-8 string dataset (the case file text).
void write_string_dataset(const H5Io& io, hid_t parent, const std::string& name,
                          std::string_view path, const std::string& value,
                          const std::string& units);
std::string read_string_dataset(const H5Io& io, hid_t dataset, std::string_view path);

std::vector<hsize_t> dataset_dims(const H5Io& io, hid_t dataset, std::string_view path);
// Reads a whole dataset (or, with start/count, a hyperslab of it) as double / int64.
std::vector<double> read_doubles(const H5Io& io, hid_t dataset, std::string_view path,
                                 std::span<const hsize_t> start = {},
                                 std::span<const hsize_t> count = {});
std::vector<std::int64_t> read_int64s(const H5Io& io, hid_t dataset, std::string_view path);

}  // namespace kinetofem::post::h5
