#include "kinetofem/solver/element_materials.hpp"

#include <utility>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

ElementMaterials::ElementMaterials(IsotropicMaterial material)
    : materials_{std::move(material)}, element_sets_{std::string()} {}

void ElementMaterials::validate() const {
  for (size_t k = 0; k < materials_.size(); ++k) {
    if (k == 0) {
      materials_[k].validate();
      continue;
    }
    try {
      materials_[k].validate();
    } catch (const Error& e) {
      fail("element set '{}': {}", element_sets_[k], e.what());
    }
  }
}

ElementMaterials element_materials(const FeModel& model) {
  ElementMaterials out(model.material);
  if (model.set_materials.empty()) {
    out.validate();
    return out;
  }
  const Mesh& mesh = model.mesh;
  const Index elements = mesh.element_count();
  out.index_.assign(size_t(elements), 0);
  for (const ElementSetMaterial& entry : model.set_materials) {
    const auto it = mesh.element_sets.find(entry.element_set);
    if (it == mesh.element_sets.end()) {
      std::string present;
      for (const auto& [name, members] : mesh.element_sets)
        present += (present.empty() ? "" : ", ") + name;
      fail("material '{}' is for element set '{}', which the mesh does not have (element sets "
           "present: {})",
           entry.material.name, entry.element_set, present.empty() ? "none" : present);
    }
    for (size_t j = 1; j < out.element_sets_.size(); ++j)
      require(out.element_sets_[j] != entry.element_set,
              "element set '{}' is given a material twice: give each set one material",
              entry.element_set);
    const int k = int(out.materials_.size());
    out.materials_.push_back(entry.material);
    out.element_sets_.push_back(entry.element_set);
    for (const Index e : it->second) {
      require(e >= 0 && e < elements, "element set '{}' refers to element {} (mesh has {})",
              entry.element_set, e, elements);
      const int before = out.index_[size_t(e)];
      require(before == 0 || before == k,
              "element {} is in two element sets with a material, '{}' and '{}': each element "
              "takes one material",
              e, out.element_sets_[size_t(before)], entry.element_set);
      out.index_[size_t(e)] = k;
    }
  }
  out.validate();
  return out;
}

}  // namespace kinetofem::fem
