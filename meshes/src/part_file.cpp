#include "kinetofem/meshes/part_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gmsh.h>

#include "geometry_meshing.hpp"
#include "gmsh_model.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/text_file.hpp"
#include "kinetofem/meshes/geo_file_scan.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "kinetofem/solver/element_traits.hpp"
#include "welded_part.hpp"

namespace kinetofem::meshes {

const std::vector<std::string>& part_file_extensions() {
  static const std::vector<std::string> extensions = {".step", ".stp", ".iges", ".igs",
                                                      ".brep", ".geo",  ".msh"};
  return extensions;
}

namespace {

bool same_unit(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(a, b); }

// One value if all agree (relative 1e-9), else nullopt.
std::optional<double> the_one(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  for (double v : values)
    if (!same_unit(v, values.front())) return std::nullopt;
  return values.front();
}

// ---- STEP (ISO 10303-21) ----------------------------------------------------

// The entity instances "#id=BODY" of a STEP file, BODY without blanks and in
// upper case outside strings (comments dropped).
std::map<long, std::string> step_records(const std::string& text) {
  std::map<long, std::string> records;
  std::string record;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      record += c;
      if (c == '\'') {
        if (i + 1 < text.size() && text[i + 1] == '\'') record += text[++i];  // '' inside a string
        else in_string = false;
      }
      continue;
    }
    if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const auto end = text.find("*/", i + 2);
      if (end == std::string::npos) break;
      i = end + 1;
      continue;
    }
    if (c == '\'') {
      in_string = true;
      record += c;
    } else if (c == ';') {
      if (record.size() > 1 && record[0] == '#') {
        const auto equals = record.find('=');
        char* end = nullptr;
        const long id = std::strtol(record.c_str() + 1, &end, 10);
        if (equals != std::string::npos && end == record.c_str() + equals)
          records[id] = record.substr(equals + 1);
      }
      record.clear();
    } else if (!std::isspace(static_cast<unsigned char>(c))) {
      record += char(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return records;
}

std::optional<double> si_prefix(const std::string& prefix) {
  static const std::map<std::string, double> prefixes = {
      {"$", 1.0},        {".EXA.", 1e18},   {".PETA.", 1e15},  {".TERA.", 1e12},
      {".GIGA.", 1e9},   {".MEGA.", 1e6},   {".KILO.", 1e3},   {".HECTO.", 1e2},
      {".DECA.", 1e1},   {".DECI.", 1e-1},  {".CENTI.", 1e-2}, {".MILLI.", 1e-3},
      {".MICRO.", 1e-6}, {".NANO.", 1e-9},  {".PICO.", 1e-12}, {".FEMTO.", 1e-15},
      {".ATTO.", 1e-18}};
  const auto it = prefixes.find(prefix);
  if (it == prefixes.end()) return std::nullopt;
  return it->second;
}

long reference_after(const std::string& body, std::size_t from) {
  const auto hash = body.find('#', from);
  if (hash == std::string::npos) return -1;
  return std::strtol(body.c_str() + hash + 1, nullptr, 10);
}

// Metres per unit of the LENGTH_UNIT instance `id`.
std::optional<double> step_length_unit(const std::map<long, std::string>& records, long id,
                                       int depth = 0) {
  const auto it = records.find(id);
  if (depth > 8 || it == records.end()) return std::nullopt;
  const std::string& body = it->second;
  if (body.find("LENGTH_UNIT(") == std::string::npos) return std::nullopt;
  if (const auto at = body.find("CONVERSION_BASED_UNIT("); at != std::string::npos) {
    // CONVERSION_BASED_UNIT('INCH',#m), #m = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#u)
    const auto measure = records.find(reference_after(body, at));
    if (measure == records.end()) return std::nullopt;
    const std::string& m = measure->second;
    const auto with_unit = m.find("MEASURE_WITH_UNIT(");
    if (with_unit == std::string::npos) return std::nullopt;
    const auto open = m.find('(', with_unit + 18);
    if (open == std::string::npos) return std::nullopt;
    char* end = nullptr;
    const double factor = std::strtod(m.c_str() + open + 1, &end);
    if (end == m.c_str() + open + 1 || !std::isfinite(factor) || factor <= 0) return std::nullopt;
    const auto base = step_length_unit(records, reference_after(m, std::size_t(end - m.c_str())),
                                       depth + 1);
    if (!base) return std::nullopt;
    return factor * *base;
  }
  if (const auto at = body.find("SI_UNIT("); at != std::string::npos) {
    const auto comma = body.find(',', at);
    const auto close = body.find(')', at);
    if (comma == std::string::npos || close == std::string::npos || comma > close)
      return std::nullopt;
    const std::string prefix = body.substr(at + 8, comma - at - 8);
    const std::string name = body.substr(comma + 1, close - comma - 1);
    if (name != ".METRE.") return std::nullopt;
    return si_prefix(prefix);
  }
  return std::nullopt;
}

std::optional<double> step_file_unit(const std::string& text) {
  const auto records = step_records(text);
  std::vector<double> units;
  bool has_context = false;
  for (const auto& [id, body] : records) {
    const auto at = body.find("GLOBAL_UNIT_ASSIGNED_CONTEXT(");
    if (at == std::string::npos) continue;
    has_context = true;
    // GLOBAL_UNIT_ASSIGNED_CONTEXT((#a,#b,#c)): the units of the context.
    const auto open = body.find('(', at + 29);
    const auto close = open == std::string::npos ? open : body.find(')', open);
    if (close == std::string::npos) continue;
    for (std::size_t p = body.find('#', open); p != std::string::npos && p < close;
         p = body.find('#', p + 1))
      if (auto unit = step_length_unit(records, std::strtol(body.c_str() + p + 1, nullptr, 10)))
        units.push_back(*unit);
  }
  if (!has_context) {
    // No context: every length unit that is not the base of a conversion.
    std::set<long> bases;
    for (const auto& [id, body] : records)
      if (const auto at = body.find("MEASURE_WITH_UNIT("); at != std::string::npos) {
        const auto close = body.find(')', at);
        if (close != std::string::npos) bases.insert(reference_after(body, close));
      }
    for (const auto& [id, body] : records)
      if (!bases.count(id))
        if (auto unit = step_length_unit(records, id)) units.push_back(*unit);
  }
  return the_one(units);
}

// ---- IGES (global section) --------------------------------------------------

std::optional<double> iges_file_unit(const std::string& text) {
  // Columns 1-72 of the lines with 'G' in column 73.
  std::string global;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() >= 73 && line[72] == 'G') global += line.substr(0, 72);
  }
  if (global.empty()) return std::nullopt;
  char delimiter = ',', end_of_record = ';';
  std::size_t p = 0;
  // Field 1 (the parameter delimiter) and 2 (the record delimiter): "1Hx" or empty.
  auto special = [&](char& value) {
    while (p < global.size() && global[p] == ' ') ++p;
    if (p + 2 < global.size() && global[p] == '1' && global[p + 1] == 'H') {
      value = global[p + 2];
      p += 3;
    }
    while (p < global.size() && global[p] == ' ') ++p;
    if (p < global.size() && (global[p] == delimiter || global[p] == end_of_record)) ++p;
  };
  special(delimiter);
  special(end_of_record);
  std::vector<std::string> fields = {std::string(1, delimiter), std::string(1, end_of_record)};
  while (p < global.size() && fields.size() < 16) {
    while (p < global.size() && global[p] == ' ') ++p;
    std::size_t q = p;
    while (q < global.size() && std::isdigit(static_cast<unsigned char>(global[q]))) ++q;
    std::string field;
    if (q > p && q < global.size() && global[q] == 'H') {  // Hollerith string nHxxx
      const std::size_t n = std::strtoul(global.c_str() + p, nullptr, 10);
      field = global.substr(q + 1, n);
      p = q + 1 + n;
      while (p < global.size() && global[p] != delimiter && global[p] != end_of_record) ++p;
    } else {
      while (p < global.size() && global[p] != delimiter && global[p] != end_of_record)
        field += global[p++];
    }
    while (!field.empty() && field.back() == ' ') field.pop_back();
    fields.push_back(field);
    if (p < global.size() && global[p] == end_of_record) break;
    ++p;
  }
  if (fields.size() < 14) return std::nullopt;
  // Field 14: units flag; field 15: units name (used with flag 3).
  static const std::map<int, double> flags = {{1, 0.0254}, {2, 1e-3},    {4, 0.3048},
                                              {5, 1609.344}, {6, 1.0},   {7, 1e3},
                                              {8, 2.54e-5},  {9, 1e-6},  {10, 1e-2},
                                              {11, 2.54e-8}};
  static const std::map<std::string, double> names = {
      {"IN", 0.0254}, {"INCH", 0.0254}, {"MM", 1e-3}, {"FT", 0.3048}, {"MI", 1609.344},
      {"M", 1.0},     {"KM", 1e3},      {"MIL", 2.54e-5}, {"UM", 1e-6}, {"CM", 1e-2},
      {"UIN", 2.54e-8}};
  char* end = nullptr;
  const long flag = std::strtol(fields[13].c_str(), &end, 10);
  if (end == fields[13].c_str()) return std::nullopt;
  if (flag == 3) {
    if (fields.size() < 15) return std::nullopt;
    std::string name = fields[14];
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return char(std::toupper(c)); });
    const auto it = names.find(name);
    if (it == names.end()) return std::nullopt;
    return it->second;
  }
  const auto it = flags.find(int(flag));
  if (it == flags.end()) return std::nullopt;
  return it->second;
}

// ---- face selections --------------------------------------------------------

// A length in m shown in mm: at most three decimals, trailing zeros dropped.
std::string mm(double metres) {
  std::string text = fmt::format("{:.3f}", metres * 1e3);
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

std::string box_mm(const std::array<double, 6>& box_m) {
  return fmt::format("[{}, {}, {}, {}, {}, {}]", mm(box_m[0]), mm(box_m[1]), mm(box_m[2]),
                     mm(box_m[3]), mm(box_m[4]), mm(box_m[5]));
}

std::array<double, 6> box_of(const FaceSelection& selection) {
  return {selection.box_min_m.x(), selection.box_min_m.y(), selection.box_min_m.z(),
          selection.box_max_m.x(), selection.box_max_m.y(), selection.box_max_m.z()};
}

// Before any Gmsh call: names and boxes.
void check_selections(const std::string& context, const std::vector<FaceSelection>& selections) {
  std::set<std::string> names;
  for (const auto& selection : selections) {
    require(!selection.name.empty(), "{}: a face set selection has an empty name", context);
    require(names.insert(selection.name).second,
            "face set '{}' of {}: the name is given to two selections", selection.name, context);
    const auto box = box_of(selection);
    require(std::all_of(box.begin(), box.end(), [](double v) { return std::isfinite(v); }),
            "face set '{}' of {}: the box [{}, {}, {}, {}, {}, {}] m has a corner that is not "
            "finite",
            selection.name, context, box[0], box[1], box[2], box[3], box[4], box[5]);
    for (int c = 0; c < 3; ++c)
      require(box[c] <= box[c + 3],
              "face set '{}' of {}: the box {} mm has min > max in {} ({} > {} mm); give "
              "[xmin, ymin, zmin, xmax, ymax, zmax]",
              selection.name, context, box_mm(box), "xyz"[c], mm(box[c]), mm(box[c + 3]));
  }
}

// The names of the physical groups of Gmsh's current model, as mesh_from_model
// names them ("physical_<dim>d_<tag>" when unnamed), with their dimension.
std::map<std::string, int> physical_group_names(GmshSession& session, const std::string& context) {
  std::map<std::string, int> names;
  session.call(context, "reading the physical groups", [&] {
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, -1);
    for (const auto& [dim, tag] : groups) {
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      if (name.empty()) name = fmt::format("physical_{}d_{}", dim, tag);
      names.emplace(name, dim);
    }
  });
  return names;
}

// Adds a physical surface per selection to Gmsh's current model, whose unit
// is model_unit_m metres.
void add_face_selections(GmshSession& session, const std::string& context,
                         const std::vector<FaceSelection>& selections, double model_unit_m) {
  if (selections.empty()) return;
  const auto existing = physical_group_names(session, context);
  for (const auto& selection : selections)
    if (const auto it = existing.find(selection.name); it != existing.end())
      fail("face set '{}' of {}: the file already has a physical group of that name (dimension "
           "{}); rename the selection or use the file's group",
           selection.name, context, it->second);
  const double s = model_unit_m;
  std::array<double, 6> part{};  // m
  session.call(context, "gmsh::model::getBoundingBox", [&] {
    gmsh::model::getBoundingBox(-1, -1, part[0], part[1], part[2], part[3], part[4], part[5]);
  });
  for (double& v : part) v *= s;
  for (const auto& selection : selections) {
    const auto box = box_of(selection);
    gmsh::vectorpair inside;
    session.call(context, fmt::format("selecting the surfaces of face set '{}'", selection.name),
                 [&] {
                   gmsh::model::getEntitiesInBoundingBox(box[0] / s, box[1] / s, box[2] / s,
                                                         box[3] / s, box[4] / s, box[5] / s,
                                                         inside, 2);
                 });
    if (inside.empty()) {
      // How many surfaces the box cuts through (partly inside): a hint that it
      // is too small rather than misplaced.
      int crossing = 0;
      session.call(context, "gmsh::model::getBoundingBox", [&] {
        gmsh::vectorpair surfaces;
        gmsh::model::getEntities(surfaces, 2);
        for (const auto& [dim, tag] : surfaces) {
          std::array<double, 6> b{};
          gmsh::model::getBoundingBox(dim, tag, b[0], b[1], b[2], b[3], b[4], b[5]);
          bool overlaps = true;
          for (int c = 0; c < 3; ++c)
            overlaps = overlaps && b[c] * s <= box[c + 3] && b[c + 3] * s >= box[c];
          crossing += overlaps;
        }
      });
      fail("face set '{}' of {}: no surface lies inside box {} mm; the part spans {} mm{}",
           selection.name, context, box_mm(box), box_mm(part),
           crossing ? fmt::format(" ({} surface{} partly inside: the box must hold a whole face)",
                                  crossing, crossing == 1 ? "" : "s")
                    : std::string());
    }
    std::vector<int> tags;
    session.call(context, "gmsh::model::getAdjacencies", [&] {
      for (const auto& [dim, tag] : inside) {
        // A seam between two welded solids lies inside the part: no load
        // acts there.
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(dim, tag, up, down);
        if (up.size() <= 1) tags.push_back(tag);
      }
    });
    require(!tags.empty(),
            "face set '{}' of {}: the box {} mm holds only seams between welded solids, no "
            "surface on the part's outside",
            selection.name, context, box_mm(box));
    std::sort(tags.begin(), tags.end());
    session.call(context, fmt::format("adding face set '{}'", selection.name), [&] {
      const int group = gmsh::model::addPhysicalGroup(2, tags);
      gmsh::model::setPhysicalName(2, group, selection.name);
    });
  }
}

std::string cache_key_extra(const PartFileOptions& part, double model_unit_m) {
  std::string key = fmt::format("\npart-file v1 length_unit={} model_unit={:.17g}",
                                part.length_unit_m ? fmt::format("{:.17g}", *part.length_unit_m)
                                                   : std::string("file"),
                                model_unit_m);
  for (const auto& selection : part.face_sets) {
    const auto box = box_of(selection);
    key += fmt::format("\nface_set {}:{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}",
                       selection.name.size(), selection.name, box[0], box[1], box[2], box[3],
                       box[4], box[5]);
  }
  return key;
}

// The welded part's share of the cache key: the tolerance and every solid
// (name, point, and its file's text: it is not the key's main file).
std::string weld_cache_key(const PartFileOptions& part) {
  std::string key = fmt::format("\nweld v1 tolerance={:.17g}", part.weld_tolerance_m);
  for (const auto& solid : part.solids) {
    key += fmt::format("\nsolid {}:{}", solid.name.size(), solid.name);
    if (solid.inside_m)
      key += fmt::format(" inside {:.17g} {:.17g} {:.17g}", solid.inside_m->x(), solid.inside_m->y(),
                         solid.inside_m->z());
    if (!solid.file.empty()) {
      std::ifstream in(solid.file, std::ios::binary);
      std::stringstream content;
      content << in.rdbuf();
      key += fmt::format(" file {} bytes\n", content.str().size()) + content.str();
    }
  }
  return key;
}

bool is_cad(const std::string& extension) {
  return extension == ".step" || extension == ".stp" || extension == ".iges" ||
         extension == ".igs" || extension == ".brep";
}

// Before any Gmsh call: the solids' names, files and points, and the tolerance.
void check_solids(const std::string& context, const std::filesystem::path& file,
                  const PartFileOptions& part) {
  require(std::isfinite(part.weld_tolerance_m) && part.weld_tolerance_m >= 0,
          "{}: weld_tolerance = {} m must be a length >= 0", context, part.weld_tolerance_m);
  std::set<std::string> names;
  for (const auto& solid : part.solids) {
    require(!solid.name.empty() &&
                std::all_of(solid.name.begin(), solid.name.end(),
                            [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '-'; }),
            "{}: [[solid]] name '{}' must be non-empty letters, digits, '_' or '-' (it names the "
            "sets solid.<name> and weld.<a>.<b>)",
            context, solid.name);
    require(names.insert(solid.name).second, "{}: [[solid]] name '{}' is given twice", context,
            solid.name);
    require(solid.file.empty() || !solid.inside_m,
            "{}: [[solid]] '{}' gives both file and inside_mm; a solid is its own file or a solid "
            "of the part file",
            context, solid.name);
    if (solid.inside_m)
      require(solid.inside_m->allFinite(), "{}: [[solid]] '{}': inside_mm is not finite", context,
              solid.name);
    if (!solid.file.empty()) {
      std::error_code error;
      require(std::filesystem::is_regular_file(solid.file, error), "{}: [[solid]] '{}': no such file",
              solid.file.string(), solid.name);
      require(is_cad(detail::lower_extension(solid.file)),
              "{}: [[solid]] '{}': a solid's file must be STEP, IGES or BREP (.step, .stp, .iges, "
              ".igs, .brep)",
              solid.file.string(), solid.name);
    } else {
      require(!file.empty(),
              "{}: [[solid]] '{}' has no file, and the part has no file it could be a solid of",
              context, solid.name);
    }
  }
  if (file.empty())
    require(!part.solids.empty(), "the part has no file and no [[solid]] files");
  else if (!part.solids.empty())
    require(is_cad(detail::lower_extension(file)),
            "{}: [[solid]] entries need a STEP, IGES or BREP part file ({} files name their "
            "volumes as physical groups)",
            context, detail::lower_extension(file));
}

// A part is one body: its elements connected through shared nodes. Two
// separate solids (a STEP holding a second body, a .geo's loose volume) would
// give the dynamics the mass of both and leave one of them unsupported.
void check_one_body(const std::string& context, const fem::Mesh& mesh) {
  std::vector<fem::Index> parent(std::size_t(mesh.node_count()));
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = fem::Index(i);
  auto root = [&](fem::Index i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
  };
  std::vector<char> used(parent.size(), 0);
  for (const auto& block : mesh.blocks)
    for (fem::Index e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      used[std::size_t(nodes[0])] = 1;
      for (const fem::Index n : nodes) {
        used[std::size_t(n)] = 1;
        parent[std::size_t(root(n))] = root(nodes[0]);
      }
    }
  std::vector<std::array<double, 6>> boxes;  // per body, m
  std::map<fem::Index, std::size_t> body_of_root;
  for (std::size_t i = 0; i < parent.size(); ++i) {
    if (!used[i]) continue;
    const auto [it, added] = body_of_root.emplace(root(fem::Index(i)), boxes.size());
    if (added) boxes.push_back({1e300, 1e300, 1e300, -1e300, -1e300, -1e300});
    auto& box = boxes[it->second];
    for (int c = 0; c < 3; ++c) {
      box[c] = std::min(box[c], mesh.nodes(fem::Index(i), c));
      box[c + 3] = std::max(box[c + 3], mesh.nodes(fem::Index(i), c));
    }
  }
  if (boxes.size() <= 1) return;
  std::vector<std::string> listed;
  for (std::size_t b = 0; b < boxes.size() && b < 3; ++b) listed.push_back(box_mm(boxes[b]));
  fail("{}: the part is {} separate solids (not connected to each other; boxes in mm: {}{}); a part is one "
       "body: keep one solid in the file, or join them (e.g. BooleanUnion/BooleanFragments in a .geo)",
       context, boxes.size(), fmt::join(listed, ", "), boxes.size() > 3 ? ", ..." : "");
}

fem::Mesh mesh_msh_part(const std::filesystem::path& file, const PartFileOptions& part,
                        const MeshOptions& options, double unit_m) {
  const std::string context = file.string();
  fem::Mesh mesh = read_msh(file);  // every structural check before Gmsh parses the file
  if (!part.face_sets.empty()) {
    GmshSession session(options.verbose);
    session.call(context, "gmsh::open", [&] { gmsh::open(context); });
    add_face_selections(session, context, part.face_sets, unit_m);
    mesh = detail::mesh_from_model(session, context);
  }
  if (unit_m != 1.0) mesh.nodes *= unit_m;
  mesh.validate();
  check_one_body(context, mesh);
  return mesh;
}

}  // namespace

std::optional<double> cad_file_length_unit_m(const std::filesystem::path& file) {
  const std::string extension = detail::lower_extension(file);
  const bool step = extension == ".step" || extension == ".stp";
  const bool iges = extension == ".iges" || extension == ".igs";
  require(step || iges, "{}: not a STEP or IGES file (expected .step, .stp, .iges or .igs)",
          file.string());
  std::error_code error;
  require(std::filesystem::is_regular_file(file, error), "{}: no such file", file.string());
  const std::string text = read_text_file(file);
  return step ? step_file_unit(text) : iges_file_unit(text);
}

fem::Mesh mesh_part_file(const std::filesystem::path& part_file, const PartFileOptions& part,
                         const MeshOptions& mesh) {
  mesh.validate();
  check_solids(part_file.empty() ? std::string("the part") : part_file.string(), part_file, part);
  // A part of [[solid]] files only: the first stands for the part (messages,
  // the cache key's main file; the others are in weld_cache_key).
  const std::filesystem::path file = part_file.empty() ? part.solids.front().file : part_file;
  const std::string context = file.string();
  std::error_code error;
  require(std::filesystem::is_regular_file(file, error), "{}: no such part file", context);
  const std::string extension = detail::lower_extension(file);
  const auto& accepted = part_file_extensions();
  require(std::find(accepted.begin(), accepted.end(), extension) != accepted.end(),
          "{}: unknown part file type '{}' (expected one of {})", context, extension,
          fmt::join(accepted, ", "));
  check_selections(context, part.face_sets);
  {
    // Before Gmsh reads anything: Gmsh opens a .geo (and merges "<file>.opt"
    // after a .msh it opens) as a script that can run programs.
    GeoScanPolicy policy;
    if (!part.case_folder.empty()) policy.read_roots.push_back(part.case_folder);
    policy.trusted = part.trusted;
    std::filesystem::path options_file = file;
    options_file += ".opt";
    if (extension == ".geo") scan_geo_file(file, policy);
    else if (extension == ".msh" && std::filesystem::exists(options_file, error)) scan_geo_file(options_file, policy);
  }

  const bool carries_unit = extension == ".step" || extension == ".stp" ||
                            extension == ".iges" || extension == ".igs";
  if (part.length_unit_m)
    require(std::isfinite(*part.length_unit_m) && *part.length_unit_m > 0,
            "{}: length_unit = {} m per file unit must be positive (1e-3 for mm, 1 for m)",
            context, *part.length_unit_m);
  double model_unit_m = 1.0;
  if (carries_unit) {
    if (part.length_unit_m) {
      const auto declared = cad_file_length_unit_m(file);
      require(declared.has_value(),
              "{}: cannot read the file's length unit to check length_unit = {} m against it "
              "(no single LENGTH_UNIT / units flag found); leave length_unit out to use the "
              "unit OpenCASCADE reads",
              context, *part.length_unit_m);
      require(same_unit(*declared, *part.length_unit_m),
              "{}: length_unit = {} m per file unit disagrees with the file's own unit, {} m; "
              "the file's unit is used for STEP/IGES: drop length_unit or fix it",
              context, *part.length_unit_m, *declared);
    }
  } else {
    require(part.length_unit_m.has_value(),
            "{}: {} files carry no length unit: give length_unit (metres per file unit: 1e-3 "
            "for mm, 1 for m)",
            context, extension);
    model_unit_m = *part.length_unit_m;
  }
  // Solid files: a .brep in the part's length unit; with a STEP/IGES among
  // them the model is in metres.
  for (const auto& solid : part.solids) {
    if (solid.file.empty()) continue;
    const std::string solid_extension = detail::lower_extension(solid.file);
    if (solid_extension == ".brep")
      require(part.length_unit_m.has_value(),
              "{}: [[solid]] '{}': .brep files carry no length unit: give the part's length_unit",
              solid.file.string(), solid.name);
    else if (!carries_unit)
      model_unit_m = 1.0;
  }

  if (extension == ".msh") return mesh_msh_part(file, part, mesh, model_unit_m);

  detail::GeometryJob job;
  job.model_unit_m = model_unit_m;
  job.before_meshing = [&](GmshSession& session, const std::string& name) {
    add_face_selections(session, name, part.face_sets, model_unit_m);
  };
  job.cache_key_extra = cache_key_extra(part, model_unit_m);
  if (is_cad(extension)) {
    // Every CAD part goes through the welding import: a file of one solid
    // without [[solid]] entries is imported there as it always was.
    detail::WeldedPartJob weld;
    weld.part_file = part_file;
    weld.solids = part.solids;
    weld.model_unit_m = model_unit_m;
    weld.brep_unit_m = part.length_unit_m.value_or(0.0);
    weld.tolerance_m = part.weld_tolerance_m;
    weld.element_size_m = mesh.element_size_m;
    job.load_model = [weld](GmshSession& session, const std::string& name) {
      detail::load_welded_part(session, name, weld);
    };
    job.after_meshing = detail::fix_solid_node_sets;
    job.cache_key_extra += weld_cache_key(part);
  }
  fem::Mesh meshed = detail::mesh_geometry_file(file, mesh, job);
  detail::add_weld_sets(meshed);
  check_one_body(context, meshed);
  return meshed;
}

}  // namespace kinetofem::meshes
