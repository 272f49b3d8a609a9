#include "msh_structure.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes::detail {

namespace {

// Nodes of the Gmsh element types kinetofem meets (points, lines, faces and
// the volume types of fem::Mesh and their lower-order relatives); 0: unknown.
int nodes_of_element_type(std::int64_t type) {
  switch (type) {
    case 1: return 2;    // 2-node line
    case 2: return 3;    // 3-node triangle
    case 3: return 4;    // 4-node quadrangle
    case 4: return 4;    // 4-node tetrahedron
    case 5: return 8;    // 8-node hexahedron
    case 6: return 6;    // 6-node prism
    case 7: return 5;    // 5-node pyramid
    case 8: return 3;    // 3-node line
    case 9: return 6;    // 6-node triangle
    case 10: return 9;   // 9-node quadrangle
    case 11: return 10;  // 10-node tetrahedron
    case 12: return 27;  // 27-node hexahedron
    case 13: return 18;  // 18-node prism
    case 14: return 14;  // 14-node pyramid
    case 15: return 1;   // point
    case 16: return 8;   // 8-node quadrangle
    case 17: return 20;  // 20-node hexahedron
    case 18: return 15;  // 15-node prism
    case 19: return 13;  // 13-node pyramid
    default: return 0;
  }
}

// Reads the values of one section, ASCII or binary (size_t = 8 bytes,
// int = 4, double = 8, native byte order), with every read bounded by the data.
class SectionReader {
 public:
  SectionReader(const std::string& data, std::size_t& position, bool binary, const std::string& where)
      : data_(data), pos_(position), binary_(binary), where_(where) {}

  std::uint64_t count(const char* what) {
    const std::int64_t value = integer(8, what);
    // Each counted item takes at least one byte: a larger count cannot be
    // what the file holds (and would make Gmsh allocate for it).
    require(value >= 0 && std::uint64_t(value) <= data_.size() - pos_,
            "{}: {} = {} is more than the rest of the file can hold", where_, what, value);
    return std::uint64_t(value);
  }
  std::int64_t size_value(const char* what) { return integer(8, what); }
  std::int64_t int_value(const char* what) { return integer(4, what); }
  void skip_doubles(std::uint64_t n, const char* what) {
    if (binary_) {
      require(n <= (data_.size() - pos_) / 8, "{}: the file ends inside {}", where_, what);
      pos_ += std::size_t(n) * 8;
      return;
    }
    for (std::uint64_t k = 0; k < n; ++k) {
      const std::string_view t = token(what);
      double value = 0;
      const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
      require(error == std::errc() && end == t.data() + t.size(), "{}: {}: '{}' is not a number", where_, what,
              std::string(t));
    }
  }
  void skip_ints(std::uint64_t n, const char* what) {
    if (binary_) {
      require(n <= (data_.size() - pos_) / 4, "{}: the file ends inside {}", where_, what);
      pos_ += std::size_t(n) * 4;
      return;
    }
    for (std::uint64_t k = 0; k < n; ++k) int_value(what);
  }

 private:
  const std::string& data_;
  std::size_t& pos_;
  bool binary_;
  const std::string& where_;

  std::string_view token(const char* what) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    require(pos_ > start, "{}: the file ends before {}", where_, what);
    return std::string_view(data_).substr(start, pos_ - start);
  }

  std::int64_t integer(int bytes, const char* what) {
    if (binary_) {
      require(data_.size() - pos_ >= std::size_t(bytes), "{}: the file ends before {}", where_, what);
      std::int64_t value = 0;
      if (bytes == 8) {
        std::uint64_t raw = 0;
        std::memcpy(&raw, data_.data() + pos_, 8);
        require(raw <= std::uint64_t(INT64_MAX), "{}: {} = {} is out of range", where_, what, raw);
        value = std::int64_t(raw);
      } else {
        std::int32_t raw = 0;
        std::memcpy(&raw, data_.data() + pos_, 4);
        value = raw;
      }
      pos_ += std::size_t(bytes);
      return value;
    }
    const std::string_view t = token(what);
    std::int64_t value = 0;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
    require(error == std::errc() && end == t.data() + t.size(), "{}: {}: '{}' is not an integer", where_, what,
            std::string(t));
    require(bytes == 8 || (value >= INT32_MIN && value <= INT32_MAX), "{}: {} = {} is out of range", where_, what,
            value);
    return value;
  }
};

// The node tags a file holds: a bitmap over [min, max] when the tags are
// dense (as Gmsh writes them), else a sorted list (a file may number its nodes
// sparsely, and a bitmap over a range of 2^40 would not fit in memory).
class NodeTags {
 public:
  void reset(std::int64_t min_tag, std::int64_t max_tag, std::uint64_t count) {
    min_ = min_tag;
    const std::uint64_t range = std::uint64_t(max_tag - min_tag) + 1;
    dense_ = range <= 4 * count + 1024;
    present_.assign(dense_ ? std::size_t(range) : 0, false);
    sorted_.clear();
    if (!dense_) sorted_.reserve(std::size_t(count));
  }
  // False when the tag was added before.
  bool add(std::int64_t tag) {
    if (!dense_) {
      sorted_.push_back(tag);
      return true;  // duplicates: see finish()
    }
    if (present_[std::size_t(tag - min_)]) return false;
    present_[std::size_t(tag - min_)] = true;
    return true;
  }
  // Sorts the sparse list; returns a tag given twice, or 0 (tags are >= 1).
  std::int64_t finish() {
    if (dense_) return 0;
    std::sort(sorted_.begin(), sorted_.end());
    const auto twice = std::adjacent_find(sorted_.begin(), sorted_.end());
    return twice == sorted_.end() ? 0 : *twice;
  }
  bool contains(std::int64_t tag) const {
    if (!dense_) return std::binary_search(sorted_.begin(), sorted_.end(), tag);
    return tag >= min_ && std::uint64_t(tag - min_) < present_.size() && present_[std::size_t(tag - min_)];
  }

 private:
  std::int64_t min_ = 0;
  bool dense_ = true;
  std::vector<bool> present_;
  std::vector<std::int64_t> sorted_;
};

struct Structure {
  std::set<std::int64_t> entities[4];  // tags declared in $Entities, per dimension
  bool have_entities = false;
  NodeTags nodes;
};

void read_entities(SectionReader& in, Structure& s, const std::string& where) {
  std::uint64_t counts[4];
  const char* names[4] = {"the number of points", "the number of curves", "the number of surfaces",
                          "the number of volumes"};
  for (int d = 0; d < 4; ++d) counts[d] = in.count(names[d]);
  for (int d = 0; d < 4; ++d) {
    for (std::uint64_t k = 0; k < counts[d]; ++k) {
      const std::int64_t tag = in.int_value("an entity tag");
      in.skip_doubles(d == 0 ? 3 : 6, "an entity's coordinates");
      in.skip_ints(in.count("the number of physical tags"), "the physical tags");
      if (d > 0) {
        const std::uint64_t bounding = in.count("the number of bounding entities");
        for (std::uint64_t b = 0; b < bounding; ++b) {
          const std::int64_t bound = in.int_value("a bounding entity tag");
          const std::int64_t magnitude = bound < 0 ? -bound : bound;
          require(s.entities[d - 1].count(magnitude) == 1,
                  "{}: entity {} of dimension {} is bounded by entity {} of dimension {}, which the file "
                  "does not declare",
                  where, tag, d, magnitude, d - 1);
        }
      }
      s.entities[d].insert(tag);
    }
  }
  s.have_entities = true;
}

void read_nodes(SectionReader& in, Structure& s, const std::string& where) {
  const std::uint64_t blocks = in.count("the number of node blocks");
  const std::uint64_t nodes = in.count("the number of nodes");
  const std::int64_t min_tag = in.size_value("the smallest node tag");
  const std::int64_t max_tag = in.size_value("the largest node tag");
  if (nodes == 0) {
    require(blocks == 0, "{}: {} node blocks announced for no nodes", where, blocks);
    return;
  }
  require(min_tag >= 1 && max_tag >= min_tag && std::uint64_t(max_tag - min_tag) < std::uint64_t(1) << 40,
          "{}: node tags {}..{} are not a valid range", where, min_tag, max_tag);
  require(std::uint64_t(max_tag - min_tag) + 1 >= nodes, "{}: {} nodes cannot have tags in {}..{}", where, nodes,
          min_tag, max_tag);
  s.nodes.reset(min_tag, max_tag, nodes);
  std::uint64_t seen = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::int64_t dim = in.int_value("a node block's entity dimension");
    require(dim >= 0 && dim <= 3, "{}: node block {} has entity dimension {} (must be 0 to 3)", where, b + 1, dim);
    const std::int64_t entity = in.int_value("a node block's entity tag");
    require(!s.have_entities || s.entities[dim].count(entity) == 1,
            "{}: node block {} belongs to entity {} of dimension {}, which $Entities does not declare", where,
            b + 1, entity, dim);
    const std::int64_t parametric = in.int_value("a node block's parametric flag");
    require(parametric == 0 || parametric == 1, "{}: node block {} has parametric flag {} (must be 0 or 1)", where,
            b + 1, parametric);
    const std::uint64_t count = in.count("the number of nodes in a block");
    require(seen + count <= nodes, "{}: the node blocks hold more than the {} nodes announced", where, nodes);
    seen += count;
    for (std::uint64_t k = 0; k < count; ++k) {
      const std::int64_t tag = in.size_value("a node tag");
      require(tag >= min_tag && tag <= max_tag, "{}: node tag {} is outside the announced range {}..{}", where,
              tag, min_tag, max_tag);
      require(s.nodes.add(tag), "{}: node tag {} is given twice", where, tag);
    }
    in.skip_doubles(count * std::uint64_t(3 + (parametric ? dim : 0)), "the node coordinates");
  }
  require(seen == nodes, "{}: {} nodes announced, the blocks hold {}", where, nodes, seen);
  const std::int64_t twice = s.nodes.finish();
  require(twice == 0, "{}: node tag {} is given twice", where, twice);
}

void read_elements(SectionReader& in, const Structure& s, const std::string& where) {
  const std::uint64_t blocks = in.count("the number of element blocks");
  const std::uint64_t elements = in.count("the number of elements");
  in.size_value("the smallest element tag");
  in.size_value("the largest element tag");
  std::uint64_t seen = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::int64_t dim = in.int_value("an element block's entity dimension");
    require(dim >= 0 && dim <= 3, "{}: element block {} has entity dimension {} (must be 0 to 3)", where, b + 1,
            dim);
    const std::int64_t entity = in.int_value("an element block's entity tag");
    require(!s.have_entities || s.entities[dim].count(entity) == 1,
            "{}: element block {} belongs to entity {} of dimension {}, which $Entities does not declare", where,
            b + 1, entity, dim);
    const std::int64_t type = in.int_value("an element type");
    const int per_element = nodes_of_element_type(type);
    require(per_element > 0, "{}: element block {} has element type {}, which kinetofem does not read", where,
            b + 1, type);
    const std::uint64_t count = in.count("the number of elements in a block");
    require(seen + count <= elements, "{}: the element blocks hold more than the {} elements announced", where,
            elements);
    seen += count;
    for (std::uint64_t k = 0; k < count; ++k) {
      const std::int64_t tag = in.size_value("an element tag");
      for (int n = 0; n < per_element; ++n) {
        const std::int64_t node = in.size_value("an element's node tag");
        require(s.nodes.contains(node), "{}: element {} refers to node {}, which the file does not hold", where, tag, node);
      }
    }
  }
  require(seen == elements, "{}: {} elements announced, the blocks hold {}", where, elements, seen);
}

std::string next_line(const std::string& data, std::size_t& pos) {
  const std::size_t end = data.find('\n', pos);
  std::string line = data.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
  pos = end == std::string::npos ? data.size() : end + 1;
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

}  // namespace

void check_msh41_structure(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  require(bool(in), "{}: cannot open the mesh file", file.string());
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string name = file.string();
  std::size_t pos = 0;
  require(next_line(data, pos) == "$MeshFormat", "{}: not a Gmsh .msh file (it does not start with $MeshFormat)",
          name);
  const std::string format = next_line(data, pos);
  char version[16] = {};
  int file_type = -1, data_size = -1;
  require(std::sscanf(format.c_str(), "%15s %d %d", version, &file_type, &data_size) == 3,
          "{}: $MeshFormat: expected 'version file-type data-size', got '{}'", name, format);
  // Gmsh's readers of older versions crash on corrupt files too (MSH 2.2: a
  // SEGV in GModel::_associateEntityWithMeshVertices, found by fuzzing), and
  // the format is what Gmsh writes by default: read 4.1 only.
  require(std::string(version) == "4.1",
          "{}: MSH format version {}: kinetofem reads MSH 4.1 only (convert the file with "
          "`gmsh {} -format msh41 -save -o NEW.msh`)",
          name, version, name);
  require(file_type == 0 || file_type == 1, "{}: $MeshFormat: file type {} (must be 0, ASCII, or 1, binary)", name,
          file_type);
  const bool binary = file_type == 1;
  require(!binary || data_size == 8, "{}: $MeshFormat: binary data size {} (kinetofem reads 8-byte size_t only)",
          name, data_size);
  if (binary) {
    require(data.size() - pos >= 4, "{}: $MeshFormat: the file ends before the byte-order mark", name);
    std::int32_t one = 0;
    std::memcpy(&one, data.data() + pos, 4);
    require(one == 1, "{}: $MeshFormat: the byte-order mark is {}, not 1 (a file of the other byte order?)", name,
            one);
    pos += 4;
  }

  Structure s;
  while (pos < data.size()) {
    const std::string line = next_line(data, pos);
    if (line.empty() || line[0] != '$') continue;
    const std::string section = line.substr(1);
    if (section == "EndMeshFormat") continue;
    const std::string where = fmt::format("{}: ${}", name, section);
    if (section == "Entities" || section == "Nodes" || section == "Elements") {
      SectionReader reader(data, pos, binary, where);
      if (section == "Entities") read_entities(reader, s, where);
      if (section == "Nodes") read_nodes(reader, s, where);
      if (section == "Elements") read_elements(reader, s, where);
      std::string end;
      while (pos < data.size() && (end = next_line(data, pos)).empty()) {
      }
      require(end == "$End" + section, "{}: the section's data ends with '{}', not ${}", where,
              end.substr(0, 40), "End" + section);
      continue;
    }
    // Any other section ($PhysicalNames, $NodeData, ...): skip to its end.
    const std::size_t end = data.find("$End" + section, pos);
    require(end != std::string::npos, "{}: no $End{} marker", where, section);
    pos = end;
    next_line(data, pos);
  }
}

}  // namespace kinetofem::meshes::detail
