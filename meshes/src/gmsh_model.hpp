#pragma once
// Internal: conversion between Gmsh's current model and fem::Mesh. Both need
// an open GmshSession (Gmsh's global model); `context` (a file name, usually)
// goes into every error message.
#include <string>

#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes::detail {

// The mesh of Gmsh's current model: volume elements of types TET4/TET10/
// HEX8/HEX20 only, nodes renumbered 0..N-1 in increasing Gmsh tag order
// (nodes of no volume element dropped), physical groups turned into sets
// (conventions in msh_io.hpp). Throws Error naming `context` on anything
// it cannot represent.
fem::Mesh mesh_from_model(GmshSession& session, const std::string& context);

// Replaces Gmsh's current model by discrete entities holding `mesh`, with
// physical groups for its sets (so that mesh_from_model gives it back).
void model_from_mesh(GmshSession& session, const fem::Mesh& mesh, const std::string& context);

}  // namespace kinetofem::meshes::detail
