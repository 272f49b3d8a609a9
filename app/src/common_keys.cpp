#include "kinetofem/app/common_keys.hpp"

#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

std::vector<KeySpec> material_keys() {
  using Type = KeySpec::Type;
  const fem::IsotropicMaterial steel;
  return {
      {.path = "material.name", .type = Type::String, .default_text = "steel", .doc = "material name (for the record)"},
      {.path = "material.youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = 1e6,
       .default_number = steel.youngs_modulus_pa / 1e6, .min = 0, .min_exclusive = true, .doc = "Young's modulus E"},
      {.path = "material.poisson_ratio", .type = Type::Number, .default_number = steel.poisson_ratio, .min = -1,
       .max = 0.4999, .doc = "Poisson's ratio nu (must be below 0.5)"},
      {.path = "material.density_kg_m3", .type = Type::Number, .unit = "kg/m^3", .default_number = steel.density_kg_m3,
       .min = 0, .doc = "density (for gravity and inertia loads)"},
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

std::vector<KeySpec> with_material_and_sweep(std::vector<KeySpec> keys) {
  for (auto&& k : material_keys()) keys.push_back(std::move(k));
  for (auto&& k : sweep_keys()) keys.push_back(std::move(k));
  return keys;
}

}  // namespace kinetofem::app
