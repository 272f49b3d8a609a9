#pragma once
// Case-file keys shared by several case types, declared once: the material
// of the FE parts, the linear solver of the FE solves and the [sweep] table
// read by `kinetofem batch`.
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/material.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::app {

// [material]: name, youngs_modulus_mpa, poisson_ratio, density_kg_m3 (defaults: steel).
std::vector<KeySpec> material_keys();
fem::IsotropicMaterial read_material(const CaseFile& case_file);

// [solver]: method (auto | direct | iterative), ordering, max_factor_gb,
// pcg_tolerance, pcg_max_iterations. `auto` takes the iterative path only when
// CHOLMOD's symbolic analysis predicts a factor above max_factor_gb.
std::vector<KeySpec> solver_keys();
fem::StaticSolverOptions read_solver_options(const CaseFile& case_file);

// [sweep]: parameters, values, linspace (kinetofem run ignores them).
std::vector<KeySpec> sweep_keys();

// mesh.time_limit_s: the time limit of reading and meshing one geometry
// file (MeshOptions::time_limit_s), for every case type that meshes.
KeySpec mesh_time_limit_key();
// The largest dimension of a parametric part (lever, arm, ...), mm, and the
// note its range message gives: beyond it OpenCASCADE can stay busy for
// minutes building the geometry, and no mechanism part is that large.
inline constexpr double kMaxPartDimensionMm = 1e5;
inline constexpr const char* kPartDimensionNote = "a plausible part dimension: up to 100 m";
// [mesh] of the parts of a motion case: element_size_mm, order, cache, time_limit_s.
std::vector<KeySpec> part_mesh_keys();
// Mesh options of the parts; the cache in <output_dir>/mesh_cache.
meshes::MeshOptions read_part_mesh_options(const CaseFile& case_file, const std::filesystem::path& output_dir);

// solver.block_size: right-hand sides per block solve over the motion.
std::vector<KeySpec> motion_solver_keys();
loads::LinkStressOptions read_stress_options(const CaseFile& case_file);
// The output times that get full fields (output.field_every /
// output.field_times_s) as a mask over `times` (empty: all). Times asked for
// that are not output times are merged into `times`. Throws Error naming the
// key for a time outside the motion.
std::vector<bool> read_field_output_steps(const CaseFile& case_file, std::vector<double>& times);

// The SPEC §1 dimensions under `prefix` ("mechanism." or "geometry."): a_mm,
// c_mm, h_mm, r_mm, defaults the published example (mech::LeverChainExample).
std::vector<KeySpec> lever_chain_dimension_keys(const std::string& prefix);
// The geometry (1)-(3) of those keys; Error naming the case file if they are impossible.
mech::LeverChainGeometry read_lever_chain_geometry(const CaseFile& case_file, const std::string& prefix);

// `keys` followed by the material, solver and sweep keys.
std::vector<KeySpec> with_common_keys(std::vector<KeySpec> keys);

}  // namespace kinetofem::app
