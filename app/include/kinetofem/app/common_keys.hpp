#pragma once
// Case-file keys shared by several case types, declared once: the material
// of the FE parts and the [sweep] table read by `kinetofem batch`.
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/solver/material.hpp"

namespace kinetofem::app {

// [material]: name, youngs_modulus_mpa, poisson_ratio, density_kg_m3 (defaults: steel).
std::vector<KeySpec> material_keys();
fem::IsotropicMaterial read_material(const CaseFile& case_file);

// [sweep]: parameters, values, linspace (kinetofem run ignores them).
std::vector<KeySpec> sweep_keys();

// `keys` followed by the material and sweep keys.
std::vector<KeySpec> with_material_and_sweep(std::vector<KeySpec> keys);

}  // namespace kinetofem::app
