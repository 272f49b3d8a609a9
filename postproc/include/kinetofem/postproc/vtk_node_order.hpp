#pragma once
// Node order of an element for XDMF / VTK (ParaView), converted from Gmsh's.
//
// The mesh (kinetofem::fem::Mesh) numbers the nodes of an element as Gmsh
// does; XDMF's Tetrahedron_10 and Hexahedron_20 follow VTK, which differs in
// the mid-edge nodes. Corner nodes agree for all four types.
//
//   TET10: Gmsh 4..9 = edges 01, 12, 20, 30, 32, 31
//          VTK  4..9 = edges 01, 12, 20, 30, 31, 32   -> local nodes 8 and 9 swap.
//   HEX20: Gmsh 8..19 = edges 01, 03, 04, 12, 15, 23, 26, 37, 45, 47, 56, 67
//          VTK  8..19 = edges 01, 12, 23, 30, 45, 56, 67, 74, 04, 15, 26, 37
//
// vtk_from_gmsh(type)[k] is the Gmsh local node that becomes VTK local node k:
// vtk_connectivity[k] = gmsh_connectivity[vtk_from_gmsh(type)[k]]. The orders
// and XDMF codes are rows of fem::element_facts (solver/element_traits.hpp).
#include <span>
#include <vector>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

std::span<const int> vtk_from_gmsh(fem::ElementType type);

// The block's connectivity (row-major, Gmsh order) in VTK order.
std::vector<fem::Index> vtk_connectivity(const fem::ElementBlock& block);

// XDMF TopologyType name: "Tetrahedron", "Tetrahedron_10", "Hexahedron", "Hexahedron_20".
const char* xdmf_topology_name(fem::ElementType type);
// XDMF cell-type code of the type inside a Mixed topology (6, 38, 9, 48).
int xdmf_mixed_code(fem::ElementType type);

}  // namespace kinetofem::post
