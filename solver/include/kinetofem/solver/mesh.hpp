#pragma once
// Mesh — the finite-element mesh of one solid body, in SI units (m).
//
// Nodes are a row-major N x 3 array of coordinates. Elements come in blocks of
// one type each; an element's global index is its position in the
// concatenation of the blocks. Named sets come from Gmsh physical groups (or
// from the code that builds the mesh): node sets (for supports and couplings),
// face sets (boundary faces, for tractions and pressure) and element sets.
//
// Node numbering inside an element follows Gmsh (the .msh convention), so a
// mesh read from a .msh file needs no reordering. Reference coordinates
// (xi, eta, zeta):
//
//   TET4 / TET10: 0 (0,0,0), 1 (1,0,0), 2 (0,1,0), 3 (0,0,1)
//         mid-edge nodes of TET10: 4 (0-1), 5 (1-2), 6 (2-0), 7 (3-0), 8 (3-2), 9 (3-1)
//
//                  3
//                 /|\ .          (note: VTK/XDMF swaps nodes 8 and 9;
//                7 | 9            the XDMF writer converts)
//               /  8  \ .
//              0---|-4-1
//               \  |  /
//                6 | 5
//                 \|/
//                  2
//
//   HEX8 / HEX20: corners 0 (-1,-1,-1), 1 (1,-1,-1), 2 (1,1,-1), 3 (-1,1,-1),
//                         4 (-1,-1, 1), 5 (1,-1, 1), 6 (1,1, 1), 7 (-1,1, 1)
//         mid-edge nodes of HEX20: 8 (0-1), 9 (0-3), 10 (0-4), 11 (1-2), 12 (1-5),
//                                  13 (2-3), 14 (2-6), 15 (3-7), 16 (4-5), 17 (4-7),
//                                  18 (5-6), 19 (6-7)
//
//              7----19----6
//             /|         /|
//           17 |       18 |
//           / 15       /  14
//          4----16----5   |
//          |   3----13|---2
//          10 /       12 /
//          | 9        | 11
//          |/         |/
//          0-----8----1
//
//   Faces: TRI3 0,1,2; TRI6 adds 3 (0-1), 4 (1-2), 5 (2-0);
//          QUAD4 0,1,2,3; QUAD8 adds 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0).
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/element_traits.hpp"

namespace kinetofem::fem {

using Index = std::int64_t;
using NodeCoordinates = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Shorthands for the facts of element_traits.hpp.
int nodes_per_element(ElementType type);
int nodes_per_face(FaceType type);
const char* name_of(ElementType type);  // "TET4", ...
const char* name_of(FaceType type);     // "TRI3", ...
// Corner-node count: 4 for tetrahedra, 8 for hexahedra.
int corner_nodes(ElementType type);
// The boundary face type of an element type (TET10 -> TRI6, HEX8 -> QUAD4, ...).
FaceType face_type_of(ElementType type);
// Local node numbers of face `face` (0-based) of an element, in the order of
// the face type, numbered so that the face normal points out of the element.
std::vector<int> element_face_nodes(ElementType type, int face);
int faces_per_element(ElementType type);

// Elements of one type; connectivity is row-major, nodes_per_element entries
// per element, 0-based node indices.
struct ElementBlock {
  ElementType type = ElementType::Tet4;
  std::vector<Index> connectivity;

  Index size() const { return Index(connectivity.size()) / nodes_per_element(type); }
  std::span<const Index> element(Index e) const {
    const int n = nodes_per_element(type);
    return {connectivity.data() + e * n, size_t(n)};
  }
};

// Boundary faces of one type (for tractions and pressure), row-major.
struct FaceBlock {
  FaceType type = FaceType::Tri3;
  std::vector<Index> connectivity;

  Index size() const { return Index(connectivity.size()) / nodes_per_face(type); }
  std::span<const Index> face(Index f) const {
    const int n = nodes_per_face(type);
    return {connectivity.data() + f * n, size_t(n)};
  }
};

struct Mesh {
  NodeCoordinates nodes;                     // m
  std::vector<ElementBlock> blocks;
  std::map<std::string, std::vector<Index>> node_sets;           // sorted, unique
  std::map<std::string, std::vector<FaceBlock>> face_sets;
  std::map<std::string, std::vector<Index>> element_sets;        // global element indices

  Index node_count() const { return nodes.rows(); }
  Index element_count() const;

  // Throws kinetofem::Error if a connectivity or set entry is out of range,
  // or a coordinate is not finite.
  void validate() const;

  // The node set `name`; throws Error naming the set and the sets present.
  const std::vector<Index>& node_set(const std::string& name) const;
  const std::vector<FaceBlock>& face_set(const std::string& name) const;
};

// All nodes touched by the faces of a face set, sorted and unique.
std::vector<Index> nodes_of_faces(const std::vector<FaceBlock>& faces);

}  // namespace kinetofem::fem
