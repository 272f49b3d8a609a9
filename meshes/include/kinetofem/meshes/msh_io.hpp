#pragma once
// Reading and writing Gmsh .msh files (format 4.1, ASCII or binary) as
// fem::Mesh, through the Gmsh API (one GmshSession per call: not
// thread-safe, see gmsh_session.hpp).
//
// What read_msh keeps:
//   - volume elements of types TET4, TET10, HEX8, HEX20 (Gmsh types 4, 11, 5,
//     17), one block per type in that order, each block in increasing Gmsh
//     element tag order; any other volume type (prism, pyramid, 27-node hex,
//     ...) is an Error naming the file and the type. Lower-dimensional
//     elements only feed the named sets below.
//   - nodes referenced by a volume element, renumbered 0..N-1 in increasing
//     Gmsh node tag order. Other nodes (geometry points, nodes of a 2D/1D
//     mesh not attached to the volume) are dropped.
//   - coordinates as stored: the file is taken to be in metres.
//   - node ordering inside elements as in Gmsh, which is fem::Mesh's.
// Physical groups -> sets (a group without a name is called
// "physical_<dim>d_<tag>"; a name used by two groups is an Error):
//   - every group (0D..3D) -> node set: all volume-mesh nodes of the group's
//     entities, their boundaries included;
//   - 3D group -> element set: global indices of its volume elements;
//   - 2D group -> face set: its TRI3/TRI6/QUAD4/QUAD8 elements, renumbered as
//     the face of the volume element they lie on, so each face's normal (right
//     hand rule on its corners) points out of that element — outward on the
//     boundary; on an interface between two volumes, out of the element with
//     the lower global index. A face that is no face of a volume element is an
//     Error.
// Errors (kinetofem::Error, the message naming the file): missing, empty,
// truncated (no closing "$End..." line) or unreadable files, unsupported
// element types, a file without volume elements, a non-finite node
// coordinate, an inverted or degenerate element (Jacobian determinant not
// positive: fem::check_element_jacobians).
#include <filesystem>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

fem::Mesh read_msh(const std::filesystem::path& file);

enum class MshEncoding { Ascii, Binary };

// Writes `mesh` as .msh 4.1: node tags = index + 1, element tags = global
// index + 1 (read_msh gives the same mesh back). Element sets become 3D
// physical groups, face sets 2D groups, node sets that are not the nodes of a
// face/element set of the same name 0D groups of point elements. Throws Error
// if the mesh is invalid, a name is both a face and an element set, or the
// file cannot be written.
void write_msh(const fem::Mesh& mesh, const std::filesystem::path& file,
               MshEncoding encoding = MshEncoding::Ascii);

}  // namespace kinetofem::meshes
