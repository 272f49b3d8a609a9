#include "welded_part.hpp"

#include <algorithm>
#include <cctype>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <unordered_map>

#include <fmt/format.h>
#include <gmsh.h>

#include "geometry_meshing.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes {

std::string solid_set_name(const std::string& solid) { return kSolidSetPrefix + solid; }

std::string weld_set_name(const std::string& solid_a, const std::string& solid_b) {
  const auto& [a, b] = std::minmax(solid_a, solid_b);
  return fmt::format("{}{}.{}", kWeldSetPrefix, a, b);
}

ElementSolids element_solids(const fem::Mesh& mesh) {
  ElementSolids solids;
  solids.of_element.assign(std::size_t(mesh.element_count()), -1);
  const std::string prefix = kSolidSetPrefix;
  for (const auto& [set, elements] : mesh.element_sets) {  // a std::map: alphabetical
    if (set.rfind(prefix, 0) != 0) continue;
    solids.names.push_back(set.substr(prefix.size()));
    for (fem::Index e : elements) solids.of_element[std::size_t(e)] = int(solids.names.size() - 1);
  }
  return solids;
}

std::string place_in_welded_part(const fem::Mesh& mesh, fem::Index node) {
  const auto [names, solid_of] = element_solids(mesh);
  if (names.empty()) return {};
  int solid = -1;
  fem::Index global = 0;
  for (const auto& block : mesh.blocks)
    for (fem::Index e = 0; e < block.size(); ++e, ++global) {
      const int s = solid_of[std::size_t(global)];
      if (s < 0 || (solid >= 0 && s >= solid)) continue;
      const auto nodes = block.element(e);
      if (std::find(nodes.begin(), nodes.end(), node) != nodes.end()) solid = s;
    }
  if (solid < 0) return {};
  std::string place = "solid " + names[std::size_t(solid)];
  const std::string seam_prefix = kWeldSetPrefix;
  for (const auto& [name, nodes] : mesh.node_sets)
    if (name.rfind(seam_prefix, 0) == 0 && std::binary_search(nodes.begin(), nodes.end(), node))
      return place + ", seam " + name;
  return place;
}

namespace detail {

namespace {

// A length in m shown in mm: at most four significant decimals, trailing
// zeros dropped.
std::string mm(double metres) {
  std::string text = fmt::format("{:.4f}", metres * 1e3);
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

bool is_step_or_iges(const std::filesystem::path& file) {
  const auto extension = lower_extension(file);
  return extension == ".step" || extension == ".stp" || extension == ".iges" || extension == ".igs";
}

// Imports `file` into the current model, scaled into the model's unit; its
// volumes in the order OpenCASCADE gives them (the file's order).
std::vector<int> import_volumes(GmshSession& session, const std::filesystem::path& file,
                                const WeldedPartJob& job) {
  std::vector<int> volumes;
  std::size_t shape_count = 0;
  session.call(file.string(), "importing the shape", [&] {
    const bool step = is_step_or_iges(file);
    // STEP/IGES come in metres (OpenCASCADE converts); a .brep is in the
    // part's length unit.
    if (step) gmsh::option::setString("Geometry.OCCTargetUnit", "M");
    gmsh::vectorpair shapes;
    gmsh::model::occ::importShapes(file.string(), shapes);
    shape_count = shapes.size();
    for (const auto& [dim, tag] : shapes)
      if (dim == 3) volumes.push_back(tag);
    const double unit_m = step ? 1.0 : job.brep_unit_m;
    const double scale = unit_m / job.model_unit_m;
    if (!volumes.empty() && std::abs(scale - 1.0) > 1e-15) {
      gmsh::vectorpair dim_tags;
      for (int v : volumes) dim_tags.emplace_back(3, v);
      gmsh::model::occ::dilate(dim_tags, 0, 0, 0, scale, scale, scale);
    }
  });
  require(shape_count > 0, "{}: OpenCASCADE read no shape from the file (not a valid {} file?)",
          file.string(), lower_extension(file));
  return volumes;
}

// Which volume of the part file holds each PartSolid's point: the part file is
// imported, and a box of 1 um about the point is
// intersected with each volume (Gmsh 4.8 has no point-in-volume query for
// OpenCASCADE volumes), and the model is cleared afterwards. -1: in none.
std::vector<int> volumes_holding_points(GmshSession& session, const std::string& context,
                                        const WeldedPartJob& job,
                                        const std::vector<Eigen::Vector3d>& points_m) {
  std::vector<int> holder(points_m.size(), -1);
  if (points_m.empty()) return holder;
  const auto volumes = import_volumes(session, job.part_file, job);
  session.call(context, "locating the points of the [[solid]] entries", [&] {
    const double half = 0.5e-6 / job.model_unit_m;
    for (std::size_t p = 0; p < points_m.size(); ++p) {
      const Eigen::Vector3d x = points_m[p] / job.model_unit_m;
      for (std::size_t v = 0; v < volumes.size() && holder[p] < 0; ++v) {
        const int probe = gmsh::model::occ::addBox(x.x() - half, x.y() - half, x.z() - half,
                                                   2 * half, 2 * half, 2 * half);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        gmsh::model::occ::intersect({{3, volumes[v]}}, {{3, probe}}, out, map, -1, false, true);
        double volume = 0.0;
        for (const auto& [dim, tag] : out) {
          double mass = 0.0;
          if (dim == 3) gmsh::model::occ::getMass(dim, tag, mass);
          volume += mass;
        }
        if (volume > 0.0) holder[p] = int(v);
        if (!out.empty()) gmsh::model::occ::remove(out, false);
      }
    }
    gmsh::clear();  // the part is imported again, untouched by the probes
  });
  return holder;
}

struct Solid {
  std::string name;
  int input_tag = 0;        // its volume before the fragment
  std::vector<int> pieces;  // its volumes after the fragment
};

// The least distance between two solids, m, from their surface meshes: the
// least distance between their nodes, and from each node of one to the
// closest point on each surface of the other (kept when that point lies in
// the surface's box: Gmsh projects onto the untrimmed surface).
double gap_between(const std::map<int, std::vector<double>>& nodes_of_surface,
                   const std::set<int>& surfaces_a, const std::set<int>& surfaces_b) {
  double least = std::numeric_limits<double>::infinity();
  auto points_of = [&](const std::set<int>& surfaces) {
    std::vector<double> points;
    for (int s : surfaces) {
      const auto it = nodes_of_surface.find(s);
      if (it != nodes_of_surface.end()) points.insert(points.end(), it->second.begin(), it->second.end());
    }
    return points;
  };
  const auto a = points_of(surfaces_a), b = points_of(surfaces_b);
  for (std::size_t i = 0; i < a.size(); i += 3)
    for (std::size_t j = 0; j < b.size(); j += 3)
      least = std::min(least, std::hypot(a[i] - b[j], a[i + 1] - b[j + 1], a[i + 2] - b[j + 2]));
  auto project = [&](const std::vector<double>& points, const std::set<int>& onto) {
    if (points.empty()) return;
    for (int s : onto) {
      std::array<double, 6> box{};
      gmsh::model::getBoundingBox(2, s, box[0], box[1], box[2], box[3], box[4], box[5]);
      const double slack = 1e-9 * (1.0 + std::abs(box[3] - box[0]) + std::abs(box[4] - box[1]) +
                                   std::abs(box[5] - box[2]));
      std::vector<double> closest, parametric;
      gmsh::model::getClosestPoint(2, s, points, closest, parametric);
      for (std::size_t i = 0; i + 2 < closest.size() && i + 2 < points.size(); i += 3) {
        bool inside = true;
        for (int c = 0; c < 3; ++c)
          inside = inside && closest[i + c] >= box[c] - slack && closest[i + c] <= box[c + 3] + slack;
        if (inside)
          least = std::min(least, std::hypot(points[i] - closest[i], points[i + 1] - closest[i + 1],
                                             points[i + 2] - closest[i + 2]));
      }
    }
  };
  project(a, surfaces_b);
  project(b, surfaces_a);
  return least;
}

// The surfaces bounding a volume.
std::set<int> surfaces_of(const std::vector<int>& volumes) {
  std::set<int> surfaces;
  for (int v : volumes) {
    std::vector<int> up, down;
    gmsh::model::getAdjacencies(3, v, up, down);
    surfaces.insert(down.begin(), down.end());
  }
  return surfaces;
}

// Every solid must reach every other through shared faces; else the error
// names the nearest two solids of different groups and their gap.
void check_connected(GmshSession& session, const std::string& context, const WeldedPartJob& job,
                     const std::vector<Solid>& solids) {
  std::vector<std::set<int>> surfaces(solids.size());
  session.call(context, "gmsh::model::getAdjacencies", [&] {
    for (std::size_t i = 0; i < solids.size(); ++i) surfaces[i] = surfaces_of(solids[i].pieces);
  });
  std::vector<std::size_t> group(solids.size());
  std::iota(group.begin(), group.end(), std::size_t(0));
  auto root = [&](std::size_t i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  for (std::size_t i = 0; i < solids.size(); ++i)
    for (std::size_t j = i + 1; j < solids.size(); ++j) {
      const bool shared = std::any_of(surfaces[i].begin(), surfaces[i].end(),
                                      [&](int s) { return surfaces[j].count(s) > 0; });
      if (shared) group[root(j)] = root(i);
    }
  std::set<std::size_t> roots;
  for (std::size_t i = 0; i < solids.size(); ++i) roots.insert(root(i));
  if (roots.size() <= 1) return;

  // Surface meshes at the part's element size measure the gap (error path).
  std::map<int, std::vector<double>> nodes_of_surface;
  session.call(context, "meshing the surfaces to measure the gap between solids", [&] {
    gmsh::option::setNumber("Mesh.MeshSizeMax", job.element_size_m / job.model_unit_m);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::model::mesh::generate(2);
    gmsh::vectorpair all;
    gmsh::model::getEntities(all, 2);
    for (const auto& [dim, tag] : all) {
      std::vector<std::size_t> tags;
      std::vector<double> coords, parametric;
      gmsh::model::mesh::getNodes(tags, coords, parametric, 2, tag, true, false);
      nodes_of_surface[tag] = std::move(coords);
    }
  });
  double least = std::numeric_limits<double>::infinity();
  std::size_t a = 0, b = 1;
  session.call(context, "measuring the gap between solids", [&] {
    for (std::size_t i = 0; i < solids.size(); ++i)
      for (std::size_t j = i + 1; j < solids.size(); ++j) {
        if (root(i) == root(j)) continue;
        const double gap = gap_between(nodes_of_surface, surfaces[i], surfaces[j]);
        if (gap < least) least = gap, a = i, b = j;
      }
  });
  const auto& [first, second] = std::minmax(solids[a].name, solids[b].name);
  fail("{}: solids '{}' and '{}' are not welded: their gap is {} mm, more than the weld tolerance "
       "{} mm ({} groups of solids that do not touch); close the gap or raise weld_tolerance_mm",
       context, first, second, mm(least * job.model_unit_m), mm(job.tolerance_m), roots.size());
}

}  // namespace

void load_welded_part(GmshSession& session, const std::string& context, const WeldedPartJob& job) {
  // ---- the solids of the part file, then one per PartSolid file ----
  std::vector<Solid> solids;
  std::vector<std::string> file_names;  // per solid of the part file, "" until named
  if (!job.part_file.empty()) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& solid : job.solids)
      if (solid.file.empty() && solid.inside_m) points.push_back(*solid.inside_m);
    const auto holders = volumes_holding_points(session, context, job, points);
    const auto volumes = import_volumes(session, job.part_file, job);
    file_names.assign(volumes.size(), std::string());
    std::size_t point = 0;
    for (const auto& solid : job.solids) {
      if (!solid.file.empty()) continue;
      std::size_t index = 0;
      if (solid.inside_m) {
        const int holder = holders[point++];
        const Eigen::Vector3d x = *solid.inside_m;
        require(holder >= 0,
                "{}: [[solid]] '{}': the point inside_mm = [{}, {}, {}] lies in none of the "
                "file's {} solid{}",
                context, solid.name, mm(x.x()), mm(x.y()), mm(x.z()), volumes.size(),
                volumes.size() == 1 ? "" : "s");
        index = std::size_t(holder);
      } else if (volumes.size() > 1) {
        // "solid<k>" names the k-th solid of the file (its name by position).
        std::size_t k = 0;
        const bool by_position =
            solid.name.rfind("solid", 0) == 0 && solid.name.size() > 5 &&
            std::all_of(solid.name.begin() + 5, solid.name.end(),
                        [](unsigned char c) { return std::isdigit(c); }) &&
            (k = std::size_t(std::stoul(solid.name.substr(5)))) >= 1 && k <= volumes.size();
        require(by_position,
                "{}: the part has no solid '{}' (the file's {} solids are solid1 to solid{} by "
                "position): give inside_mm, a point inside the solid it names",
                context, solid.name, volumes.size(), volumes.size());
        index = k - 1;
      }
      require(file_names[index].empty(),
              "{}: [[solid]] '{}' and '{}' name the same solid (solid {} of the file)", context,
              file_names[index], solid.name, index + 1);
      file_names[index] = solid.name;
    }
    for (std::size_t v = 0; v < volumes.size(); ++v)
      solids.push_back({file_names[v].empty() ? fmt::format("solid{}", v + 1) : file_names[v],
                        volumes[v], {}});
  }
  for (const auto& solid : job.solids) {
    if (solid.file.empty()) continue;
    const auto volumes = import_volumes(session, solid.file, job);
    require(volumes.size() == 1,
            "{}: [[solid]] '{}': the file holds {} solids; a [[solid]] file holds one (list each "
            "solid of a multi-solid file by inside_mm under a [[part]] file instead)",
            solid.file.string(), solid.name, volumes.size());
    solids.push_back({solid.name, volumes.front(), {}});
  }
  {
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < solids.size(); ++i) {
      const auto [it, added] = seen.emplace(solids[i].name, i);
      require(added,
              "{}: the solid name '{}' is given twice (the file's unnamed solids are solid1, "
              "solid2, ... by position); give each solid its own name",
              context, solids[i].name);
    }
  }
  require(!solids.empty(), "{}: the geometry has no volumes to mesh", context);

  // ---- one solid: as a one-solid part always was ----
  if (solids.size() == 1) {
    session.call(context, "naming the part's volume", [&] {
      gmsh::model::occ::synchronize();
      gmsh::vectorpair volumes;
      gmsh::model::getEntities(volumes, 3);
      std::vector<int> tags;
      for (const auto& [dim, tag] : volumes) tags.push_back(tag);
      gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, tags), "body");
      if (!job.solids.empty())
        gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, tags),
                                     solid_set_name(solids.front().name));
    });
    return;
  }

  // ---- the fragment: touching (and nearly touching) solids share faces ----
  std::vector<gmsh::vectorpair> pieces_of;
  session.call(context, "gmsh::model::occ::fragment (welding the solids)", [&] {
    gmsh::option::setNumber("Geometry.ToleranceBoolean", job.tolerance_m / job.model_unit_m);
    gmsh::vectorpair objects = {{3, solids.front().input_tag}}, tools, out;
    for (std::size_t i = 1; i < solids.size(); ++i) tools.emplace_back(3, solids[i].input_tag);
    gmsh::model::occ::fragment(objects, tools, out, pieces_of);
    gmsh::model::occ::synchronize();
  });
  require(pieces_of.size() == solids.size(),
          "{}: OpenCASCADE's fragment gave {} piece lists for {} solids", context, pieces_of.size(),
          solids.size());

  // ---- overlaps: a piece inside two solids ----
  std::map<int, std::vector<std::size_t>> owners;  // piece -> solids holding it
  for (std::size_t i = 0; i < solids.size(); ++i)
    for (const auto& [dim, tag] : pieces_of[i])
      if (dim == 3) owners[tag].push_back(i);
  for (const auto& [piece, holders] : owners) {
    if (holders.size() > 1) {
      std::array<double, 6> box{};
      double volume = 0.0;
      session.call(context, "measuring an overlap of two solids", [&, piece = piece] {
        gmsh::model::occ::getBoundingBox(3, piece, box[0], box[1], box[2], box[3], box[4], box[5]);
        gmsh::model::occ::getMass(3, piece, volume);
      });
      const double thickness_m =
          std::min({box[3] - box[0], box[4] - box[1], box[5] - box[2]}) * job.model_unit_m;
      const auto& [first, second] =
          std::minmax(solids[holders[0]].name, solids[holders[1]].name);
      require(thickness_m <= job.tolerance_m,
              "{}: solids '{}' and '{}' overlap (interference): {} mm^3, {} mm thick, more than "
              "the weld tolerance {} mm; solids of a welded part may touch but not overlap",
              context, first, second, fmt::format("{:.4g}", volume * std::pow(job.model_unit_m, 3) * 1e9),
              mm(thickness_m), mm(job.tolerance_m));
    }
    // A sliver within the tolerance goes to the first solid that holds it.
    solids[holders.front()].pieces.push_back(piece);
  }
  for (const auto& solid : solids)
    require(!solid.pieces.empty(), "{}: solid '{}' has no volume left after the fragment", context,
            solid.name);

  check_connected(session, context, job, solids);

  session.call(context, "naming the welded part's volumes", [&] {
    std::vector<int> all;
    for (const auto& solid : solids) all.insert(all.end(), solid.pieces.begin(), solid.pieces.end());
    std::sort(all.begin(), all.end());
    gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, all), "body");
    for (const auto& solid : solids)
      gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, solid.pieces),
                                   solid_set_name(solid.name));
  });
}

void fix_solid_node_sets(fem::Mesh& mesh) {
  const auto [names, solid_of] = element_solids(mesh);
  std::vector<std::vector<fem::Index>> nodes(names.size());
  fem::Index global = 0;
  for (const auto& block : mesh.blocks)
    for (fem::Index e = 0; e < block.size(); ++e, ++global)
      if (const int s = solid_of[std::size_t(global)]; s >= 0)
        for (fem::Index n : block.element(e)) nodes[std::size_t(s)].push_back(n);
  for (std::size_t s = 0; s < names.size(); ++s) {
    auto& list = nodes[s];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    mesh.node_sets[solid_set_name(names[s])] = std::move(list);
  }
}

void add_weld_sets(fem::Mesh& mesh) {
  using fem::Index;
  const auto [names, solid_of] = element_solids(mesh);
  if (names.size() < 2) return;

  // Every element face by its sorted corners; a face met twice, from
  // elements of two solids, is on a seam.
  struct Side {
    Index block, element;
    int face, solid;
  };
  std::map<std::array<Index, 4>, std::vector<Side>> faces;
  Index global = 0;
  for (Index b = 0; b < Index(mesh.blocks.size()); ++b) {
    const auto& block = mesh.blocks[std::size_t(b)];
    const int corners = fem::face_facts(fem::face_type_of(block.type)).corners;
    for (Index e = 0; e < block.size(); ++e, ++global) {
      const int solid = solid_of[std::size_t(global)];
      if (solid < 0) continue;
      const auto element = block.element(e);
      for (int f = 0; f < fem::faces_per_element(block.type); ++f) {
        const auto local = fem::element_face_nodes(block.type, f);
        std::array<Index, 4> key{-1, -1, -1, -1};
        for (int k = 0; k < corners; ++k) key[std::size_t(k)] = element[local[std::size_t(k)]];
        std::sort(key.begin(), key.end());  // a triangle's -1 pad sorts first, alike for all
        faces[key].push_back({b, e, f, solid});
      }
    }
  }
  std::map<std::string, std::map<fem::FaceType, fem::FaceBlock>> seams;
  for (const auto& [key, sides] : faces) {
    if (sides.size() != 2 || sides[0].solid == sides[1].solid) continue;
    // Oriented out of the solid whose name comes first.
    const Side& out = names[std::size_t(sides[0].solid)] < names[std::size_t(sides[1].solid)] ? sides[0] : sides[1];
    const auto& block = mesh.blocks[std::size_t(out.block)];
    const auto element = block.element(out.element);
    const auto type = fem::face_type_of(block.type);
    auto& face_block = seams[weld_set_name(names[std::size_t(sides[0].solid)],
                                           names[std::size_t(sides[1].solid)])][type];
    face_block.type = type;
    for (int local : fem::element_face_nodes(block.type, out.face))
      face_block.connectivity.push_back(element[local]);
  }
  for (auto& [name, blocks] : seams) {
    auto& set = mesh.face_sets[name];
    set.clear();
    for (auto& [type, block] : blocks) set.push_back(std::move(block));
    mesh.node_sets[name] = fem::nodes_of_faces(set);
  }
}

}  // namespace detail
}  // namespace kinetofem::meshes
