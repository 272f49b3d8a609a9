#pragma once
// The elastic assembly of one pose as a CalculiX (ccx) input deck, and a
// reader for what ccx gives back: the identical linear problem that
// ElasticAssembly::solve (planar) or SpatialElasticAssembly::solve (spatial)
// condenses, written out in full so that an independent program solves it
// (tests/verification/structure/test_assembly_calculix.cpp,
// test_spatial_assembly_calculix.cpp; docs/elastic_assembly.md).
//
// Both assemblies describe their pose as a PoseDeckStructure (below: the
// parts placed in world with their meshes, nodal loads and interface columns
// G; the interfaces; the constraints C and springs S over the interfaces'
// motions; the moving rigid bodies' loads) and write_calculix_pose_deck
// writes any such description; the two write_calculix_assembly_deck are the
// assemblies' descriptions of a pose.
//
// The deck (Abaqus-style keywords, SI units: m, N, Pa; world axes; the
// rigid configuration of the pose is the undeformed one):
//   *NODE      every part's mesh placed by its body's frame (x_world = origin
//              + R x_body), part after part; then per interface
//              (the assembly's interfaces() order) a translation node and a
//              rotation node at its reference point (ccx has no rotations on
//              solid nodes: the rotation node's DoFs 1-3 carry the rotation
//              about world x, y, z); per moving rigid body (no part) the same
//              pair at its frame origin; one node per spring.
//   *ELEMENT   the parts' elements in ccx's node order (fem::calculix_node_order,
//              fem::calculix_element_name), one ELSET per part, block and
//              material (P<p>B<b>M<k>); ESOLID all of them.
//   *MATERIAL, *SOLID SECTION   per part and material: the part's own
//              material, or the material of its element set
//              (FeModel::set_materials).
//   *EQUATION  every linear relation of the assembly, with u the interfaces'
//              motions (world axes):
//                tie of an interface on a part (the distributing coupling's
//                motion definition, so its reaction enters the face as G [F; M]):
//                  u_ref = Q6 G_k^T Q^T u_face       (Q = blockdiag(R), Q6 = blockdiag(R, R))
//                an interface on a moving rigid body: u_ref = transfer(arm) u_body;
//                the joints, slides and rigid drives: C u = 0 (the assembly's
//                interface_structure: a planar revolute 5 rows with the rigid
//                pin's offset term, fixed 6, the rigid drive the z rotations;
//                a spatial joint the components its reaction carries, a
//                slide's lands on the slider's bracketing stations; to the
//                ground the moving side's components alone).
//              ccx wants each equation's first DoF (the dependent one) in no
//              other equation and in no *BOUNDARY. The relations are therefore
//              written after a Gauss-Jordan elimination (reduced row echelon
//              form): each row solved for one DoF of its own (a tie for its
//              reference DoF, a joint row for the largest coefficient after
//              the ties are substituted), that DoF removed from every other
//              row. The rows span the same constraints; coefficients below
//              AssemblyDeckOptions::drop_tolerance of a row's largest (round-off
//              of the elimination) are dropped, and the largest dropped one is
//              reported (AssemblyDeck::largest_dropped).
//   *SPRING    the chains, the compliant drives and the elastic pins: the
//              springs' matrix S (interface_structure) written as
//              sum lambda v v^T (its eigenvectors; a chain or a drive is rank
//              one, k g g^T); each term a SPRING1 of stiffness lambda on DoF 1
//              of its own node w, with the equation w = v^T u. The energy is
//              u^T S u / 2 as in kinetofem (a linear, pre-tension-free chain).
//   *BOUNDARY  the foundation of a frame part (every node of Part::held_face).
//   *CLOAD     the loads kinetofem applies in that pose: every part's nodal
//              load vector (body axes, rotated to world axes: the planar
//              loads::LinkLoads::loads_at through ElasticAssembly::part_loads,
//              the spatial SpatialElasticAssembly::part_loads), a moving rigid
//              body's applied minus inertia loads at its node pair (the
//              assemblies' body_loads). A load on a DoF that an equation makes
//              dependent is moved onto that equation's independent DoFs here
//              (F d = F sum(-a_j u_j): the same work), so the deck does not
//              rely on ccx doing so.
//   output     *NODE PRINT U of the interfaces' nodes (and of every part node
//              with print_part_displacements) to the .dat file; *EL PRINT S of
//              ESOLID (integration-point stresses, .dat) and *EL FILE S (nodal
//              stresses extrapolated and averaged by ccx, .frd).
// Needs distributing couplings (planar BoreCoupling::RigidBore: Error, as
// interface_columns) and, planar, every part set up
// (ElasticAssembly::set_up_part).
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/part.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"

namespace kinetofem::structure {

struct AssemblyDeckOptions {
  std::string heading = "kinetofem elastic assembly";
  bool print_part_displacements = false;  // *NODE PRINT U of every part node too
  bool print_gauss_stresses = true;       // *EL PRINT S (integration points, .dat)
  bool file_stresses = true;              // *EL FILE S (nodal, .frd)
  // Coefficients of an eliminated equation below this fraction of its largest
  // are round-off of the elimination and are dropped.
  double drop_tolerance = 1e-13;
  std::string solver;  // SOLVER= of *STATIC; empty: ccx's default (SPOOLES in the Debian build)
};

// Where each thing of the assembly went in the deck (ccx numbers, 1-based).
struct AssemblyDeckPart {
  std::string body;
  long long first_node = 0, first_element = 0;  // node k of the mesh is first_node + k
  fem::Index nodes = 0, elements = 0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // body axes -> world, the pose's
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();      // world
};

struct AssemblyDeck {
  std::vector<AssemblyDeckPart> parts;  // the order of the parts given
  // Per interface (the assembly's interfaces() order).
  std::vector<long long> translation_node, rotation_node;
  long long node_count = 0;   // nodes written (the largest number)
  long long solid_elements = 0;
  int equations = 0, boundaries = 0, springs = 0, loads = 0;
  long long equation_terms = 0;
  double largest_dropped = 0.0;  // relative to its row's largest coefficient
};

// One pose of an assembly as the deck writer takes it. World axes, SI units;
// the pose's rigid configuration. The description borrows the parts' models
// and interface columns from the assembly and its parts: they must outlive
// the writing.
struct PoseDeckPart {
  std::string name;  // in messages, "part 'lever'"
  std::string body;
  const fem::FeModel* model = nullptr;                     // borrowed: mesh (body frame), material, element sets
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // body axes -> world
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();      // the body frame's origin, world
  Eigen::VectorXd nodal_loads_n;                           // 3N, N, body axes
  // Borrowed: G (3N x 6m, body axes), a column block of 6 per interface on
  // the part; null when no interface is on it.
  const Eigen::MatrixXd* interface_columns = nullptr;
  std::vector<fem::Index> held_nodes;  // the foundation (a frame part), held in every component
};

struct PoseDeckRigidBody {  // a moving body without a part
  std::string name;
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  // world
  Vector6d load = Vector6d::Zero();  // applied minus inertia: force N, moment N m about the origin, world axes
};

struct PoseDeckInterface {
  std::string tie_owner;                                 // in messages, "the tie of joint 'A' on 'lever'"
  int part = -1;                                         // index into PoseDeckStructure::parts, or -1: on a rigid body
  int column = -1;                                       // on a part: its block of 6 columns in the part's G
  int rigid_body = -1;                                   // on a rigid body: index into PoseDeckStructure::rigid_bodies
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // reference point, world
  Eigen::Vector3d arm_m = Eigen::Vector3d::Zero();       // reference point - its body's origin, world axes
};

struct PoseDeckStructure {
  std::vector<PoseDeckPart> parts;
  std::vector<PoseDeckRigidBody> rigid_bodies;
  std::vector<PoseDeckInterface> interfaces;
  // Over the interfaces' motions u (6M, world axes; InterfaceStructure):
  // C u = 0 (rows x 6M, an owner per row) and the energy u^T S u / 2.
  Eigen::MatrixXd constraints;
  std::vector<std::string> constraint_owner;
  Eigen::MatrixXd springs;  // 6M x 6M or empty
};

// Writes `pose` to `path`. Throws Error if a part's loads or columns do not
// match its mesh (not the part the assembly was built with), an index is out
// of range, the equations are dependent (a constraint row that the others
// already imply, naming it), the springs' matrix has a negative eigenvalue,
// or the file cannot be written.
AssemblyDeck write_calculix_pose_deck(const PoseDeckStructure& pose, const std::filesystem::path& path,
                                      const AssemblyDeckOptions& options = {});

// Writes the pose `frame` of `assembly` (built from `parts` and `model`) to
// `path`. Throws Error if a part is not the assembly's, a coupling is not
// distributing, the equations are dependent (a constraint row that the others
// already imply, naming it), or the file cannot be written.
AssemblyDeck write_calculix_assembly_deck(const ElasticAssembly& assembly, const std::vector<Part>& parts,
                                          const mech::MultibodyModel& model, const mech::Frame& frame,
                                          const std::filesystem::path& path, const AssemblyDeckOptions& options = {});

// Writes the pose `frame` of the spatial `assembly` (built from `model`; its
// parts are assembly.parts(), written with their 3-2-1-supported models'
// meshes and materials; the chains are springs) to `path`. Throws Error like
// write_calculix_pose_deck, and for a frame of another mechanism.
AssemblyDeck write_calculix_assembly_deck(const SpatialElasticAssembly& assembly, const mech::spatial::Model& model,
                                          const mech::spatial::Frame& frame, const std::filesystem::path& path,
                                          const AssemblyDeckOptions& options = {});

// What ccx computed for such a deck (its one step).
struct AssemblyDeckResults {
  // Per interface: translation (m) and rotation (rad) of its reference point,
  // world axes.
  std::vector<Vector6d> interface_motion;
  // Per part: nodal displacements (world axes, m; NaN unless printed), ccx's
  // nodal von Mises stress (.frd; empty without it) and the largest von Mises
  // stress over its integration points (.dat; 0 without it).
  std::vector<fem::DisplacementField> displacement_m;
  std::vector<Eigen::VectorXd> nodal_von_mises_pa;
  std::vector<double> peak_gauss_von_mises_pa;
};

// Reads `job`.dat (and `job`.frd when present) of a deck written as `deck`.
// Throws Error if the .dat is missing or has no displacement block of the
// interfaces.
AssemblyDeckResults read_calculix_assembly_results(const AssemblyDeck& deck, const std::filesystem::path& job);

}  // namespace kinetofem::structure
