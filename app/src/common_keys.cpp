#include "kinetofem/app/common_keys.hpp"

#include "kinetofem/core/error.hpp"

#include <algorithm>
#include <cmath>

#include <toml++/toml.h>

namespace kinetofem::app {

std::vector<KeySpec> material_keys() {
  using Type = KeySpec::Type;
  const fem::IsotropicMaterial steel;
  return {
      {.path = "material.name", .type = Type::String, .default_text = "steel", .doc = "material name (for the record)"},
      // From soft gels (1 kPa) to above diamond (1.2e6 MPa): a modulus outside
      // this overflows or underflows the displacements of any load in range.
      {.path = "material.youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = 1e6,
       .default_number = steel.youngs_modulus_pa / 1e6, .min = 1e-3, .max = 1e7, .doc = "Young's modulus E",
       .range_note = "plausible for a solid: from a soft gel to above diamond"},
      // The range the solver accepts (IsotropicMaterial::validate: -1 < nu < 0.5),
      // kept off 0.5 where the elasticity matrix becomes singular.
      {.path = "material.poisson_ratio", .type = Type::Number, .default_number = steel.poisson_ratio, .min = -1,
       .max = 0.4999, .min_exclusive = true, .doc = "Poisson's ratio nu (must be below 0.5)"},
      {.path = "material.density_kg_m3", .type = Type::Number, .unit = "kg/m^3", .default_number = steel.density_kg_m3,
       .min = 1, .max = 1e5, .doc = "density (for gravity and inertia loads)", .zero_allowed = true,
       .range_note = "0 for a massless part, else plausible for a solid: osmium is 22 590 kg/m^3"},
  };
}

fem::IsotropicMaterial read_material(const CaseFile& c) {
  fem::IsotropicMaterial material;
  material.name = c.text_value("material.name");
  material.youngs_modulus_pa = c.number("material.youngs_modulus_mpa");
  material.poisson_ratio = c.number("material.poisson_ratio");
  material.density_kg_m3 = c.number("material.density_kg_m3");
  try {
    material.validate();
  } catch (const Error& e) {
    fail("{}: [material]: {}", c.path().string(), e.what());
  }
  return material;
}

std::vector<KeySpec> solver_keys() {
  using Type = KeySpec::Type;
  const fem::AmgOptions amg;
  return {
      {.path = "solver.method", .type = Type::String, .default_text = "auto", .allowed = {"auto", "direct", "iterative"},
       .doc = "linear solver of the FE solves: 'direct' (CHOLMOD Cholesky), 'iterative' (CG with algebraic multigrid, "
              "hypre BoomerAMG), 'auto' (direct unless the symbolic analysis predicts a factor above max_factor_gb)"},
      {.path = "solver.ordering", .type = Type::String, .default_text = "metis", .allowed = {"metis", "metis_dof", "amd", "best"},
       .doc = "fill-reducing ordering of the Cholesky factorization: metis (nested dissection of the mesh's node "
              "graph, expanded to the DoFs; about 1.7-2x faster analysis than on the DoF graph), metis_dof "
              "(CHOLMOD's METIS on the DoF graph), amd, best (CHOLMOD's default: AMD, METIS if better)"},
      {.path = "solver.max_factor_gb", .type = Type::Number, .unit = "GB", .default_number = 0.0, .min = 0,
       .doc = "memory allowed for a Cholesky factor; 0 = 80 % of the memory left to the process (the least of the "
              "physical memory, RLIMIT_AS and the cgroup limit) after the BLAS threads' buffers, which also caps a "
              "larger value. Above it: 'direct' stops with an error before the numeric factorization, 'auto' "
              "switches to 'iterative'"},
      {.path = "solver.concurrent_parts", .type = Type::Integer,
       .default_number = double(fem::StaticSolverOptions{}.concurrent_parts), .min = 0, .max = 1024,
       .doc = "parts whose Cholesky factorizations run side by side, one BLAS thread each, when their predicted "
              "factors fit max_factor_gb together (0 = one per hardware thread, 1 = one after the other)"},
      {.path = "solver.pcg_tolerance", .type = Type::Number, .default_number = amg.relative_tolerance, .min = 1e-14,
       .max = 1e-2, .doc = "iterative solver: relative tolerance of CG in the preconditioner's norm"},
      {.path = "solver.pcg_max_iterations", .type = Type::Integer, .default_number = double(amg.max_iterations),
       .min = 1, .max = 1000000, .doc = "iterative solver: CG iterations allowed per right-hand side"},
  };
}

fem::StaticSolverOptions read_solver_options(const CaseFile& c) {
  fem::StaticSolverOptions options;
  const std::string method = c.text_value("solver.method");
  options.method = method == "direct"      ? fem::LinearSolverMethod::Direct
                   : method == "iterative" ? fem::LinearSolverMethod::Iterative
                                           : fem::LinearSolverMethod::Auto;
  const std::string ordering = c.text_value("solver.ordering");
  options.direct.ordering = ordering == "amd"         ? fem::CholmodOptions::Ordering::Amd
                            : ordering == "best"      ? fem::CholmodOptions::Ordering::Best
                            : ordering == "metis_dof" ? fem::CholmodOptions::Ordering::Metis
                                                      : fem::CholmodOptions::Ordering::NodeGraphMetis;
  options.direct.max_factor_bytes = c.number("solver.max_factor_gb") * 1e9;
  options.concurrent_parts = int(c.integer("solver.concurrent_parts"));
  options.iterative.relative_tolerance = c.number("solver.pcg_tolerance");
  options.iterative.max_iterations = int(c.integer("solver.pcg_max_iterations"));
  return options;
}

std::vector<KeySpec> sweep_keys() {
  using Type = KeySpec::Type;
  return {
      {.path = "sweep.parameters", .type = Type::StringList,
       .doc = "kinetofem batch: keys to sweep, e.g. [\"payload.casting_mass_kg\"] (kinetofem run ignores [sweep])"},
      {.path = "sweep.values", .type = Type::Array,
       .doc = "kinetofem batch: the values of each swept key, e.g. [[5, 10, 15]] ([] where linspace gives them)"},
      {.path = "sweep.linspace", .type = Type::Array,
       .doc = "kinetofem batch: [start, stop, count] of each swept key, e.g. [[5.0, 40.0, 20]] ([] where values gives them)"},
  };
}

KeySpec mesh_time_limit_key() {
  const meshes::MeshOptions defaults;
  return {.path = "mesh.time_limit_s", .type = KeySpec::Type::Number, .unit = "s", .default_number = defaults.time_limit_s,
          .min = 0, .max = 1e6, .min_exclusive = true,
          .doc = "wall-clock limit for reading and meshing one geometry file (Gmsh runs in a child process, stopped there)"};
}

std::vector<KeySpec> part_mesh_keys() {
  using Type = KeySpec::Type;
  const meshes::MeshOptions defaults;
  return {
      {.path = "mesh.element_size_mm", .type = Type::Number, .unit = "mm", .to_si = 1e-3, .default_number = 8.0, .min = 0,
       .min_exclusive = true, .doc = "target element edge length of the parts"},
      {.path = "mesh.order", .type = Type::Integer, .default_number = double(defaults.order), .min = 1, .max = 2,
       .doc = "element order: 1 (TET4) or 2 (TET10)"},
      {.path = "mesh.cache", .type = Type::Boolean, .default_number = 1,
       .doc = "keep meshes in <output dir>/mesh_cache, keyed by a hash of the geometry, dimensions and mesh options, and reuse them"},
      mesh_time_limit_key(),
  };
}

meshes::MeshOptions read_part_mesh_options(const CaseFile& c, const std::filesystem::path& output_dir) {
  meshes::MeshOptions options;
  options.element_size_m = c.number("mesh.element_size_mm");
  options.order = int(c.integer("mesh.order"));
  if (c.boolean("mesh.cache")) options.cache_dir = output_dir / "mesh_cache";
  options.time_limit_s = c.number("mesh.time_limit_s");
  return options;
}

std::vector<KeySpec> motion_solver_keys() {
  const loads::LinkStressOptions defaults;
  return {{.path = "solver.block_size", .type = KeySpec::Type::Integer, .default_number = double(defaults.block_size),
           .min = 1, .max = 100000, .doc = "right-hand sides per block solve over the motion"},
          {.path = "solver.load_path", .type = KeySpec::Type::String, .default_text = "auto",
           .allowed = {"auto", "superposition", "step_by_step"},
           .doc = "how the parts' stress over the motion is computed: unit-load superposition (the load patterns "
                  "solved once, every output time a combination; exact), step by step (one solve per output "
                  "time), or auto (superposition unless a part has a bearing-pressure pin)"},
          {.path = "output.field_every", .type = KeySpec::Type::Integer, .default_number = 1, .min = 0, .max = 1e9,
           .doc = "full fields (displacement, von Mises) in the results file at every k-th output time (the first "
                  "and the last included; 0: none). Envelopes, hot spots and histories cover every output time"},
          {.path = "output.field_times_s", .type = KeySpec::Type::Array, .unit = "s",
           .doc = "full fields at these times instead (s, within the motion; each becomes an output time)"}};
}

loads::LinkStressOptions read_stress_options(const CaseFile& c) {
  loads::LinkStressOptions options;
  options.block_size = int(c.integer("solver.block_size"));
  const std::string path = c.text_value("solver.load_path");
  options.load_path = path == "superposition" ? loads::LoadPath::Superposition
                      : path == "step_by_step" ? loads::LoadPath::StepByStep
                                               : loads::LoadPath::Auto;
  options.solver = read_solver_options(c);
  return options;
}

std::vector<bool> read_field_output_steps(const CaseFile& c, std::vector<double>& times) {
  require(!times.empty(), "{}: no output times", c.path().string());
  const double start = times.front(), end = times.back();
  if (c.has("output.field_times_s")) {
    const toml::array* list = c.node("output.field_times_s")->as_array();
    require(list != nullptr && !list->empty(), "{}: give a list of times in s, e.g. [0.5, 1.0]",
            c.where("output.field_times_s"));
    std::vector<double> asked;
    for (const auto& element : *list) {
      const std::optional<double> t = element.value<double>();
      require(t.has_value() && std::isfinite(*t), "{}: every element must be a time in s",
              c.where("output.field_times_s"));
      require(*t >= start && *t <= end, "{}: {} s is outside the motion [{}, {}] s", c.where("output.field_times_s"),
              *t, start, end);
      asked.push_back(*t);
    }
    // Each asked time is an output time: the nearest one if it is that within
    // round-off, else a new one.
    const double tolerance = 1e-9 * std::max(end - start, 1e-300);
    std::vector<double> merged = times;
    for (const double t : asked) {
      const bool present = std::any_of(merged.begin(), merged.end(), [&](double u) { return std::abs(u - t) <= tolerance; });
      if (!present) merged.push_back(t);
    }
    std::sort(merged.begin(), merged.end());
    times = merged;
    std::vector<bool> mask(times.size(), false);
    for (size_t k = 0; k < times.size(); ++k)
      mask[k] = std::any_of(asked.begin(), asked.end(), [&](double t) { return std::abs(times[k] - t) <= tolerance; });
    return mask;
  }
  const long every = c.integer("output.field_every");
  if (every == 1) return {};  // all
  std::vector<bool> mask(times.size(), false);
  for (size_t k = 0; every > 0 && k < times.size(); k += size_t(every)) mask[k] = true;
  if (every > 0) mask.back() = true;  // the end of the motion too
  return mask;
}

std::vector<KeySpec> lever_chain_dimension_keys(const std::string& prefix) {
  using Type = KeySpec::Type;
  using E = mech::LeverChainExample;
  return {
      {.path = prefix + "a_mm", .type = Type::Number, .unit = "mm", .to_si = 1e-3, .default_number = E::a_m / 1e-3, .min = 0,
       .min_exclusive = true, .doc = "lever length a = |A0 A| (SPEC §1; the four-bar's crank)"},
      {.path = prefix + "c_mm", .type = Type::Number, .unit = "mm", .to_si = 1e-3, .default_number = E::c_m / 1e-3, .min = 0,
       .min_exclusive = true, .doc = "c = |A C| along link 2"},
      {.path = prefix + "h_mm", .type = Type::Number, .unit = "mm", .to_si = 1e-3, .default_number = E::h_m / 1e-3, .min = 0,
       .doc = "h: offset of the gripper point H from C"},
      {.path = prefix + "r_mm", .type = Type::Number, .unit = "mm", .to_si = 1e-3, .default_number = E::r_m / 1e-3, .min = 0,
       .min_exclusive = true, .doc = "roller radius r (lever-chain) = coupler length AB (four-bar)"},
  };
}

mech::LeverChainGeometry read_lever_chain_geometry(const CaseFile& c, const std::string& prefix) {
  try {
    return mech::make_lever_chain_geometry(c.number(prefix + "a_mm"), c.number(prefix + "c_mm"), c.number(prefix + "h_mm"),
                                           c.number(prefix + "r_mm"));
  } catch (const Error& e) {
    fail("{}: [{}]: {}", c.path().string(), prefix.substr(0, prefix.size() - 1), e.what());
  }
}

std::vector<KeySpec> with_common_keys(std::vector<KeySpec> keys) {
  for (auto&& k : material_keys()) keys.push_back(std::move(k));
  for (auto&& k : solver_keys()) keys.push_back(std::move(k));
  for (auto&& k : sweep_keys()) keys.push_back(std::move(k));
  return keys;
}

}  // namespace kinetofem::app
