#pragma once
// CalculiX (ccx) input decks from an FeModel, and readers for ccx's results —
// for running the identical problem in CalculiX and comparing (bench/
// calculix_compare.cpp, tests/unit/solver/test_calculix_export.cpp).
//
// The deck (Abaqus-style keywords, SI units as in the model: m, N, Pa):
//   *NODE                 node k of the mesh is ccx node k + 1
//   *ELEMENT              TET10 -> C3D10, HEX8 -> C3D8, HEX20 -> C3D20, TET4 -> C3D4;
//                         element e (global index) is ccx element e + 1, one ELSET
//                         per block ("E1", "E2", ... in block order)
//   *MATERIAL, *ELASTIC   E, nu of the model's material
//   *SOLID SECTION        one per element block
//   With per-set materials (FeModel::set_materials) instead: per material k
//   that holds elements (element_materials.hpp: 0 the model's own, then the
//   listed sets) an *ELSET "M<k+1>" of its elements, *MATERIAL "MAT<k+1>" and
//   one *SOLID SECTION; the deck of a one-material model is unchanged.
//   *BOUNDARY             every prescribed DoF: the zero ones in the model data,
//                         the nonzero ones with their values in the first step
//                         (ccx takes only homogeneous ones in the model data);
//                         both hold in every step
//   one *STEP per load case: *STATIC (ccx's default linear solver: the Debian
//                         build links SPOOLES only, so SPOOLES), *CLOAD, OP=NEW with
//                         the nonzero entries of the case's external force vector,
//                         and the requested output.
// Loads go in as nodal forces: the consistent nodal force vector that
// kinetofem assembles (assemble_external_forces), so both programs solve with
// the identical right-hand side; the decks do not use ccx's own *DLOAD.
//
// Node order inside an element: CalculiX uses the Abaqus order, kinetofem the
// Gmsh order (mesh.hpp). 0-based Abaqus positions:
//   C3D10: corners 0-3 as Gmsh; mid-edge 4:(0-1) 5:(1-2) 6:(2-0) 7:(0-3) 8:(1-3) 9:(2-3)
//   C3D20: corners 0-7 as Gmsh; mid-edge 8:(0-1) 9:(1-2) 10:(2-3) 11:(3-0)
//          12:(4-5) 13:(5-6) 14:(6-7) 15:(7-4) 16:(0-4) 17:(1-5) 18:(2-6) 19:(3-7)
// calculix_node_order() gives, for each Abaqus position, the Gmsh local node
// (found from the corner pairs of element_library's edge_corners()).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::fem {

struct CalculixDeckOptions {
  std::string heading = "kinetofem model";
  // *NODE PRINT U (displacements to the .dat file, 7 significant digits) of
  // these nodes (0-based), every step; empty with print_all_displacements:
  // all nodes.
  bool print_displacements = true;
  bool print_all_displacements = true;
  std::vector<Index> printed_nodes;
  // *NODE FILE U and *EL FILE S (the .frd file, nodal values, 6 significant
  // digits; ccx extrapolates stresses from the Gauss points to the nodes and
  // averages them over the elements at a node).
  bool file_displacements = false;
  bool file_stresses = false;
  // SOLVER= of *STATIC; empty: ccx's default (SPOOLES in the Debian build).
  std::string solver;
};

// The ccx element name: "C3D4", "C3D10", "C3D8", "C3D20".
const char* calculix_element_name(ElementType type);

// For each CalculiX (Abaqus) node position p of the element, the kinetofem
// (Gmsh) local node that goes there.
std::vector<int> calculix_node_order(ElementType type);

// Writes the deck with one step per column of `external_forces` (the
// external force vector over all DoFs, 3 N, N; as assemble_external_forces
// returns). Throws Error if the file cannot be written or the column size is
// not the model's DoF count.
void write_calculix_deck(const FeModel& model, const Eigen::MatrixXd& external_forces,
                         const std::filesystem::path& path,
                         const CalculixDeckOptions& options = {});

// The same, assembling the load cases' consistent nodal forces first.
void write_calculix_deck(const FeModel& model, const std::vector<LoadCase>& load_cases,
                         const std::filesystem::path& path,
                         const CalculixDeckOptions& options = {});

// Displacements printed by *NODE PRINT U in a ccx .dat file, one field per
// step (N x 3, m, for `node_count` nodes); nodes not printed are NaN.
// Throws Error if the file cannot be read or names a node out of range.
std::vector<DisplacementField> read_calculix_dat_displacements(const std::filesystem::path& path,
                                                               Index node_count);

// Nodal stresses of the "STRESS" blocks of an ASCII ccx .frd file, one field
// per step (N x 6, Pa, Voigt order xx, yy, zz, xy, yz, zx as in
// stress_recovery.hpp); nodes not written are NaN.
std::vector<StressField> read_calculix_frd_stresses(const std::filesystem::path& path,
                                                    Index node_count);

}  // namespace kinetofem::fem
