#pragma once
// ElementMaterials — the material of every element of a part's mesh: the
// model's own material (FeModel::material), or the material of the element
// set the element is in (FeModel::set_materials: the solids of a welded part,
// each of its own material). SI units as IsotropicMaterial (Pa, kg/m^3).
//
// The one place that maps an element (its global index: the position in the
// concatenation of the mesh's blocks) to its material. Every consumer asks it
// element by element: the stiffness and internal forces (D of the element),
// the mass matrix and every body load (the element's density: gravity, the
// rigid-body motion's d'Alembert loads), stress recovery, mass properties and
// the CalculiX deck.
//
// A single IsotropicMaterial converts to it implicitly (every element of that
// material), so code that builds its own one-material model reads as before.
// A caller holding an FeModel passes element_materials(model), never
// model.material, or the per-set materials would be ignored.
//
//   const fem::ElementMaterials materials = fem::element_materials(model);
//   fem::assemble_stiffness(model.mesh, materials, dofs);
//   fem::recover_nodal_stress(model.mesh, materials, u);
#include <string>
#include <vector>

#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::fem {

class ElementMaterials {
 public:
  // Every element of `material` (implicit on purpose: a one-material model).
  ElementMaterials(IsotropicMaterial material);  // NOLINT(google-explicit-constructor)

  // Material k: 0 the model's own, then those of FeModel::set_materials in
  // their order (also when a set's material equals another).
  const std::vector<IsotropicMaterial>& materials() const { return materials_; }
  // The element set of material k ("" for material 0, the model's own).
  const std::string& element_set(size_t k) const { return element_sets_[k]; }
  // The material index of an element (global index).
  int index_of(Index element) const { return index_.empty() ? 0 : index_[size_t(element)]; }
  const IsotropicMaterial& of(Index element) const { return materials_[size_t(index_of(element))]; }
  // One material for every element: no per-set material was given.
  bool uniform() const { return index_.empty(); }

  // Throws Error unless every material is valid (IsotropicMaterial::validate).
  void validate() const;

 private:
  friend ElementMaterials element_materials(const FeModel& model);
  std::vector<IsotropicMaterial> materials_;
  std::vector<std::string> element_sets_;
  std::vector<int> index_;  // per element; empty when uniform
};

// The materials of a model's elements. Throws Error (one line) if a set of
// set_materials is not an element set of the mesh, if an element is in two of
// the listed sets, or if a material is not valid. Cheap when set_materials is
// empty (no per-element table); else one pass over the listed sets.
ElementMaterials element_materials(const FeModel& model);

}  // namespace kinetofem::fem
