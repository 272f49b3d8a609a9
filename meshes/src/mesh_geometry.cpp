#include "kinetofem/meshes/mesh_geometry.hpp"

#include <array>
#include <algorithm>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>
#include <fstream>
#include <sstream>
#include <cctype>
#include <cmath>

#include <gmsh.h>

#include "geometry_meshing.hpp"
#include "gmsh_model.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geo_file_scan.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "meshing_process.hpp"

namespace kinetofem::meshes {

void MeshOptions::validate() const {
  require(std::isfinite(element_size_m) && element_size_m > 0,
          "mesh option element_size_m = {} must be a positive length in m", element_size_m);
  require(order == 1 || order == 2, "mesh option order = {} must be 1 or 2", order);
  require(elements_per_circle >= 0 && elements_per_circle <= 360,
          "mesh option elements_per_circle = {} must be in 0..360", elements_per_circle);
  require(std::isfinite(time_limit_s) && time_limit_s > 0,
          "mesh option time_limit_s = {} must be a positive time in s", time_limit_s);
}

double estimated_element_count(double volume_m3, const MeshOptions& options) {
  // Gmsh's Delaunay tetrahedra at MeshSizeMax = h: about 6 per h^3 (a regular
  // tetrahedron of edge h fills h^3 / 8.5; edges come out shorter than h);
  // each tetrahedron split into 4 hexahedra.
  const double h = options.element_size_m;
  const double tetrahedra = 6.0 * volume_m3 / (h * h * h);
  switch (options.family) {
    case ElementFamily::Tetrahedra: return tetrahedra;
    case ElementFamily::Hexahedra: return 4.0 * tetrahedra;
  }
  return tetrahedra;
}

namespace {

// Every Gmsh option kinetofem sets for meshing, by name: set by
// apply_options and written into the mesh cache key, so a change here is a
// new key.
std::vector<std::pair<std::string, double>> gmsh_mesh_options(const MeshOptions& options) {
  const bool hex = options.family == ElementFamily::Hexahedra;
  return {
      {"Mesh.MeshSizeMax", options.element_size_m},
      {"Mesh.MeshSizeMin", 0.0},
      {"Mesh.MeshSizeFromCurvature", double(options.elements_per_circle)},
      {"Mesh.Algorithm3D", 1},  // Delaunay: robust and deterministic
      {"Mesh.Optimize", options.optimize ? 1 : 0},
      {"Mesh.OptimizeNetgen", 0},
      // Gmsh raises the order inside generate(), after the hex subdivision and
      // before the high-order optimizer (setOrder() would skip the optimizer).
      {"Mesh.ElementOrder", double(options.order)},
      {"Mesh.RecombineAll", 0},
      {"Mesh.Recombine3DAll", 0},
      {"Mesh.SubdivisionAlgorithm", hex ? 2 : 0},
      // 20-node serendipity hexahedra and 8-node quadrangles, not Lagrange 27/9.
      {"Mesh.SecondOrderIncomplete", 1},
      // Curved mid-nodes may tangle thin elements near bores. 1 = optimize only
      // the elements whose Jacobian ratio is poor; 2 (elastic analogy first)
      // gives the same valid lever meshes 7x slower (23.7 s vs 3.1 s at 5 mm).
      // Not for the subdivided hexahedra: in Gmsh 4.8 the optimizer runs for
      // minutes there and has left NaN coordinates.
      {"Mesh.HighOrderOptimize", options.optimize && !hex ? 1 : 0},
      {"General.NumThreads", 1},
  };
}

void apply_options(const MeshOptions& options) {
  for (const auto& [name, value] : gmsh_mesh_options(options)) gmsh::option::setNumber(name, value);
}

}  // namespace

std::string detail::lower_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension;
}

namespace {

// FNV-1a, 64 bit: a stable content hash (std::hash is not stable across builds).
std::uint64_t fnv1a(const std::string& text, std::uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

// nullopt when the inputs cannot all be known (a trusted .geo that names a
// file it reads by an expression): such a file is not cached.
std::optional<std::string> cache_key(const std::filesystem::path& file, const MeshOptions& options,
                                     const detail::GeometryJob& job) {
  const GeometryParameters& parameters = job.parameters;
  const auto inputs = geometry_inputs_key(file);
  if (!inputs) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  // Everything that changes the mesh: the file's text, every file it reads,
  // the parameters, the options and every Gmsh option set for meshing, the
  // Gmsh version, and the mesh format of this cache.
  std::string key = "kinetofem-mesh-cache-v2\n" + content.str() + *inputs;
  for (const auto& [name, value] : parameters) key += fmt::format("\n{}={:.17g}", name, value);
  key += fmt::format("\nsize={:.17g} order={} family={} per_circle={} optimize={}",
                     options.element_size_m, options.order, int(options.family),
                     options.elements_per_circle, options.optimize);
  for (const auto& [name, value] : gmsh_mesh_options(options)) key += fmt::format("\n{}={:.17g}", name, value);
  key += fmt::format("\ngmsh {}", GMSH_API_VERSION);
  key += job.cache_key_extra;
  return fmt::format("{}_{:016x}", file.stem().string(), fnv1a(key));
}

fem::Mesh mesh_geometry_uncached(const std::filesystem::path& file, const MeshOptions& options,
                                 const detail::GeometryJob& job);

}  // namespace

fem::Mesh mesh_geometry(const std::filesystem::path& file, const MeshOptions& options,
                        const GeometryParameters& parameters) {
  detail::GeometryJob job;
  job.parameters = parameters;
  return detail::mesh_geometry_file(file, options, job);
}

fem::Mesh detail::mesh_geometry_file(const std::filesystem::path& file, const MeshOptions& options,
                                     const GeometryJob& job) {
  options.validate();
  require(std::isfinite(job.model_unit_m) && job.model_unit_m > 0,
          "{}: the model unit {} m is not a positive length", file.string(), job.model_unit_m);
  if (options.cache_dir.empty() || !std::filesystem::is_regular_file(file))
    return mesh_geometry_uncached(file, options, job);
  const auto key = cache_key(file, options, job);
  if (!key) return mesh_geometry_uncached(file, options, job);
  const std::filesystem::path cached = options.cache_dir / (*key + ".msh");
  std::error_code error;
  if (std::filesystem::is_regular_file(cached, error)) {
    try {
      return read_msh(cached);
    } catch (const Error&) {
      // A damaged cache entry is not the user's problem: mesh again below.
    }
  }
  fem::Mesh mesh = mesh_geometry_uncached(file, options, job);
  std::filesystem::create_directories(options.cache_dir, error);
  if (!error) {
    // Atomic: a half-written cache entry is never found under its name.
    const std::filesystem::path temporary =
        options.cache_dir / (cached.stem().string() + ".partial.msh");
    try {
      write_msh(mesh, temporary, MshEncoding::Binary);
      std::filesystem::rename(temporary, cached, error);
    } catch (const Error&) {
      std::filesystem::remove(temporary, error);  // the cache is an optimisation only
    }
  }
  return mesh;
}

namespace {

// In this process: mesh_geometry_uncached runs it in a child process.
fem::Mesh mesh_geometry_in_this_process(const std::filesystem::path& file, const MeshOptions& options,
                                        const detail::GeometryJob& job) {
  const GeometryParameters& parameters = job.parameters;
  const std::string context = file.string();
  std::error_code error;
  require(std::filesystem::is_regular_file(file, error), "{}: no such geometry file", context);
  const std::string extension = detail::lower_extension(file);
  const bool is_geo = extension == ".geo";
  const bool is_cad = extension == ".step" || extension == ".stp" || extension == ".iges" ||
                      extension == ".igs" || extension == ".brep";
  require(is_geo || is_cad,
          "{}: unknown geometry file type '{}' (expected .geo, .step, .stp, .iges, .igs or .brep)",
          context, extension);
  require(is_geo || parameters.empty(),
          "{}: geometry parameters can only be passed to .geo files", context);

  GmshSession session(options.verbose);
  for (const auto& parameter : parameters)
    session.call(context, fmt::format("setting parameter '{}'", parameter.first),
                 [&] { gmsh::onelab::setNumber(parameter.first, {parameter.second}); });
  if (is_geo) {
    session.call(context, "gmsh::open", [&] {
      // OpenCASCADE keeps its STEP/IGES target unit ("xstep.cascade.unit") in
      // process-wide state that gmsh::finalize does not reset, and Gmsh sets
      // it only when this option is not empty: after a STEP import in metres
      // (below), a script's Merge/ShapeFromFile of a STEP would then also come
      // in metres. Set OpenCASCADE's own default (mm) explicitly, so a script
      // reads what it reads in a fresh gmsh; it may set the option itself.
      gmsh::option::setString("Geometry.OCCTargetUnit", "MM");
      gmsh::open(context);
    });
  } else if (job.load_model) {
    job.load_model(session, context);
  } else {
    const auto shape_count = session.call(context, "importing the shape", [&] {
      if (extension != ".brep") gmsh::option::setString("Geometry.OCCTargetUnit", "M");
      gmsh::vectorpair shapes;
      gmsh::model::occ::importShapes(context, shapes);
      gmsh::model::occ::synchronize();
      gmsh::vectorpair volumes;
      gmsh::model::getEntities(volumes, 3);
      std::vector<int> tags;
      for (const auto& [dim, tag] : volumes) tags.push_back(tag);
      if (!tags.empty()) gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, tags), "body");
      return shapes.size();
    });
    // OpenCASCADE's BREP reader fails silently (it only prints to stdout).
    require(shape_count > 0, "{}: OpenCASCADE read no shape from the file (not a valid {} file?)",
            context, extension);
  }
  const auto volume_count = session.call(context, "gmsh::model::getEntities", [&] {
    gmsh::vectorpair volumes;
    gmsh::model::getEntities(volumes, 3);
    return volumes.size();
  });
  require(volume_count > 0, "{}: the geometry has no volumes to mesh", context);
  {
    // A part thousands of elements across would not fit in memory and would
    // keep Gmsh busy for hours: most often a wrong length unit (a part drawn
    // in mm read as m is 1000 times too large). Stop before meshing.
    std::array<double, 6> box{};
    session.call(context, "gmsh::model::getBoundingBox", [&] {
      gmsh::model::getBoundingBox(-1, -1, box[0], box[1], box[2], box[3], box[4], box[5]);
    });
    const double span = std::sqrt((box[3] - box[0]) * (box[3] - box[0]) + (box[4] - box[1]) * (box[4] - box[1]) +
                                  (box[5] - box[2]) * (box[5] - box[2])) * job.model_unit_m;
    constexpr double kMaxElementsAcross = 2000.0;
    require(span <= kMaxElementsAcross * options.element_size_m,
            "{}: the part spans {:.4g} m, {:.0f} elements of {:.4g} m across (at most {:.0f}): is its length unit "
            "right, or the element size?",
            context, span, span / options.element_size_m, options.element_size_m, kMaxElementsAcross);
    // A part within that span can still need far too many elements (a long
    // plate at a fine size): estimate the count from the volume before
    // meshing. OpenCASCADE knows each volume's size; the built-in kernel's
    // volumes are bounded by the box instead (an overestimate).
    double volume_m3 = 0.0;
    try {
      gmsh::vectorpair volumes;
      gmsh::model::getEntities(volumes, 3);
      for (const auto& [dim, tag] : volumes) {
        double mass = 0.0;
        gmsh::model::occ::getMass(dim, tag, mass);
        volume_m3 += mass;
      }
      volume_m3 *= std::pow(job.model_unit_m, 3);
    } catch (...) {
      volume_m3 = 0.0;
    }
    if (!(volume_m3 > 0))
      volume_m3 = (box[3] - box[0]) * (box[4] - box[1]) * (box[5] - box[2]) * std::pow(job.model_unit_m, 3);
    const double estimate = estimated_element_count(volume_m3, options);
    require(estimate <= kMaxEstimatedElements,
            "{}: the part's volume {:.4g} m^3 at an element size of {:.4g} m needs about {:.3g} elements, more "
            "than the {:.0e} allowed: make the element size larger (or the part smaller)",
            context, volume_m3, options.element_size_m, estimate, kMaxEstimatedElements);
  }

  if (job.before_meshing) job.before_meshing(session, context);

  // The model is in its own unit (job.model_unit_m metres): mesh with the
  // element size in that unit and scale the nodes to metres afterwards.
  MeshOptions in_model_unit = options;
  in_model_unit.element_size_m = options.element_size_m / job.model_unit_m;
  session.call(context, "meshing", [&] {
    apply_options(in_model_unit);
    gmsh::model::mesh::generate(3);
  });
  auto mesh = detail::mesh_from_model(session, context);
  if (job.model_unit_m != 1.0) mesh.nodes *= job.model_unit_m;
  mesh.validate();
  return mesh;
}

// Gmsh reads and meshes the file in a child process: a crash, an exit or a
// hang inside Gmsh becomes an Error naming the file (meshing_process.hpp).
fem::Mesh mesh_geometry_uncached(const std::filesystem::path& file, const MeshOptions& options,
                                 const detail::GeometryJob& job) {
  fem::Mesh mesh = detail::mesh_in_child_process(file.string(), detail::lower_extension(file), options,
                                                 [&] { return mesh_geometry_in_this_process(file, options, job); });
  if (job.after_meshing) job.after_meshing(mesh);  // here: the child's mesh comes back through a .msh
  return mesh;
}

}  // namespace

}  // namespace kinetofem::meshes
