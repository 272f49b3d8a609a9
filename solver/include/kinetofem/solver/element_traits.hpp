#pragma once
// Element and face types of the finite-element mesh, and every fact about a
// type that is not numerics (shape functions and quadrature rules live in
// element_library.hpp): node counts, faces, edges, and the type's code and
// node order in each file format the project reads or writes.
//
// One table per enum: adding a type means one row here (plus its shape
// functions and quadrature in element_library.cpp); a `switch` over either
// enum has no `default:`, so a new value is a -Wswitch warning wherever it
// needs a decision.
//
// Local node numbering follows Gmsh (the .msh convention; drawings in
// mesh.hpp). Mid-edge node `corners + k` sits on edge `edges[k]`. Faces list
// their corners counter-clockwise seen from outside (outward normal by the
// right-hand rule), then their mid-edge nodes in the order of the face's
// edges (c0-c1, c1-c2, ...), so a face's local numbering is that of its face
// type.
//
// Usage:
//   const fem::ElementFacts& facts = fem::element_facts(block.type);
//   for (int f = 0; f < facts.face_count; ++f) { auto local = facts.face(f); ... }
//   gmsh code: facts.gmsh_code; VTK connectivity[k] = gmsh[facts.vtk_from_gmsh[k]]
#include <array>
#include <span>

namespace kinetofem::fem {

enum class ElementType { Tet4, Tet10, Hex8, Hex20 };
enum class FaceType { Tri3, Tri6, Quad4, Quad8 };

// The reference cell: tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1);
// hexahedron [-1, 1]^3.
enum class ElementShape { Tetrahedron, Hexahedron };

inline constexpr std::array all_element_types = {ElementType::Tet4, ElementType::Tet10,
                                                 ElementType::Hex8, ElementType::Hex20};
inline constexpr std::array all_face_types = {FaceType::Tri3, FaceType::Tri6, FaceType::Quad4,
                                              FaceType::Quad8};

struct FaceFacts {
  const char* name;  // "TRI3", ...
  int corners;       // 3 (triangle) or 4 (quadrilateral)
  int nodes;         // corners + mid-edge nodes
  int gmsh_code;     // Gmsh element type number (Gmsh manual, "MSH file format")
};

struct ElementFacts {
  const char* name;  // "TET4", ...
  ElementShape shape;
  int dimension;     // of the reference cell
  int corners;
  int nodes;         // corners + mid-edge nodes
  // Corner pairs of the mid-edge nodes corners, corners + 1, ... (Gmsh order);
  // empty for linear types.
  std::span<const std::array<int, 2>> edges;
  FaceType face_type;
  int face_count;
  // face_count rows of face_facts(face_type).nodes local node numbers.
  std::span<const int> face_nodes;
  int gmsh_code;                      // Gmsh element type number
  std::span<const int> vtk_from_gmsh;  // VTK/XDMF local node k is Gmsh local node [k]
  const char* xdmf_topology;          // XDMF TopologyType name
  int xdmf_mixed_code;                // XdmfTopologyType id inside a Mixed topology
  const char* calculix_name;          // CalculiX / Abaqus element name
  std::span<const int> calculix_from_gmsh;  // CalculiX local node k is Gmsh local node [k]

  // Local node numbers of face f (0 <= f < face_count).
  constexpr std::span<const int> face(int f) const;
};

namespace element_tables {
inline constexpr std::array<std::array<int, 2>, 6> tet_edges = {
    {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
inline constexpr std::array<std::array<int, 2>, 12> hex_edges = {
    {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6},
     {6, 7}}};
inline constexpr int tet4_faces[] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
inline constexpr int tet10_faces[] = {0, 2, 1, 6, 5, 4, 0, 1, 3, 4, 9, 7,
                                      0, 3, 2, 7, 8, 6, 1, 2, 3, 5, 8, 9};
inline constexpr int hex8_faces[] = {0, 3, 2, 1, 0, 1, 5, 4, 1, 2, 6, 5,
                                     2, 3, 7, 6, 3, 0, 4, 7, 4, 5, 6, 7};
inline constexpr int hex20_faces[] = {0, 3, 2, 1, 9,  13, 11, 8,  0, 1, 5, 4, 8,  12, 16, 10,
                                      1, 2, 6, 5, 11, 14, 18, 12, 2, 3, 7, 6, 13, 15, 19, 14,
                                      3, 0, 4, 7, 9,  10, 17, 15, 4, 5, 6, 7, 16, 18, 19, 17};
inline constexpr int tet4_identity[] = {0, 1, 2, 3};
inline constexpr int hex8_identity[] = {0, 1, 2, 3, 4, 5, 6, 7};
// VTK, XDMF and CalculiX (Abaqus) order the mid-edge nodes of TET10 as edges
// 01, 12, 20, 30, 31, 32 (Gmsh: ..., 32, 31): local nodes 8 and 9 swap.
inline constexpr int tet10_abaqus_from_gmsh[] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
// HEX20 in VTK, XDMF and CalculiX: edges 01, 12, 23, 30, 45, 56, 67, 74, 04,
// 15, 26, 37, each looked up in Gmsh's edge list above.
inline constexpr int hex20_abaqus_from_gmsh[] = {0,  1,  2,  3,  4,  5,  6,  7,  8,  11,
                                                 13, 9,  16, 18, 19, 17, 10, 12, 14, 15};

inline constexpr ElementFacts tet4{"TET4", ElementShape::Tetrahedron, 3, 4, 4, {},
                                   FaceType::Tri3, 4, tet4_faces, 4, tet4_identity,
                                   "Tetrahedron", 0x6, "C3D4", tet4_identity};
inline constexpr ElementFacts tet10{"TET10", ElementShape::Tetrahedron, 3, 4, 10, tet_edges,
                                    FaceType::Tri6, 4, tet10_faces, 11, tet10_abaqus_from_gmsh,
                                    "Tetrahedron_10", 0x26, "C3D10", tet10_abaqus_from_gmsh};
inline constexpr ElementFacts hex8{"HEX8", ElementShape::Hexahedron, 3, 8, 8, {},
                                   FaceType::Quad4, 6, hex8_faces, 5, hex8_identity,
                                   "Hexahedron", 0x9, "C3D8", hex8_identity};
inline constexpr ElementFacts hex20{"HEX20", ElementShape::Hexahedron, 3, 8, 20, hex_edges,
                                    FaceType::Quad8, 6, hex20_faces, 17, hex20_abaqus_from_gmsh,
                                    "Hexahedron_20", 0x30, "C3D20", hex20_abaqus_from_gmsh};

inline constexpr FaceFacts tri3{"TRI3", 3, 3, 2};
inline constexpr FaceFacts tri6{"TRI6", 3, 6, 9};
inline constexpr FaceFacts quad4{"QUAD4", 4, 4, 3};
inline constexpr FaceFacts quad8{"QUAD8", 4, 8, 16};
}  // namespace element_tables

constexpr const ElementFacts& element_facts(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return element_tables::tet4;
    case ElementType::Tet10: return element_tables::tet10;
    case ElementType::Hex8: return element_tables::hex8;
    case ElementType::Hex20: return element_tables::hex20;
  }
  return element_tables::tet4;  // unreachable for a valid enum value
}

constexpr const FaceFacts& face_facts(FaceType type) {
  switch (type) {
    case FaceType::Tri3: return element_tables::tri3;
    case FaceType::Tri6: return element_tables::tri6;
    case FaceType::Quad4: return element_tables::quad4;
    case FaceType::Quad8: return element_tables::quad8;
  }
  return element_tables::tri3;  // unreachable for a valid enum value
}

constexpr std::span<const int> ElementFacts::face(int f) const {
  const auto n = std::size_t(face_facts(face_type).nodes);
  return face_nodes.subspan(std::size_t(f) * n, n);
}

}  // namespace kinetofem::fem
