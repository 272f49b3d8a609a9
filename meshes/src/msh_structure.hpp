#pragma once
// Structural check of a Gmsh MSH 4.1 file (ASCII or binary) before Gmsh reads
// it. Gmsh 4.8 trusts the counts and tags of a file: a corrupt one makes it
// read out of bounds (a SEGV in GModel::getMeshVertexByTag for an element
// that names a node the file does not hold, found by fuzz/fuzz_read_msh) or
// ask for ~1e18 bytes. This walks $Entities, $Nodes and $Elements with the
// same grammar and rejects, naming the file, the section and what is wrong:
//   - a count larger than the rest of the file could hold,
//   - a node tag outside [minNodeTag, maxNodeTag] or given twice,
//   - an element that names a node the file does not hold,
//   - an element type kinetofem does not know, an entity dimension outside 0..3,
//   - a bounding entity that $Entities does not declare,
//   - a section that ends before its data or without its $End marker.
// Other sections are skipped to their $End marker. A file of another version
// (e.g. MSH 2.2) is an error saying how to convert it.
#include <filesystem>

namespace kinetofem::meshes::detail {

void check_msh41_structure(const std::filesystem::path& file);

}  // namespace kinetofem::meshes::detail
