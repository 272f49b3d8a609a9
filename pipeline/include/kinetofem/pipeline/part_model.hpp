#pragma once
// Stage "build the part models": the FE part of each elastic body of a
// linkage, meshed and placed in its BODY frame, with its mass properties.
//
// A part is either one of the parametric links of SPEC §1/§2 (lever, arm with
// roller, coupler, rocker: meshes/lever.hpp, meshes/arm.hpp, in their own
// frames documented there) or a geometry file (.step/.stp, .brep, .geo or a
// .msh 4.1 mesh; meshes/part_file.hpp) with its length unit. Its placement
// maps the part's own coordinates into the body frame of the multibody model:
//     x_body = R_z(angle) x_part + (offset_x, offset_y, offset_z)    [m]
// where offset_z places the part in its own plane along the pin axes (a
// revolute joint between bores at different z is an elastic pin in the
// elastic assembly, structure/elastic_assembly.hpp).
// so the stiffness (assembled in the body frame) is the same at every pose.
//
// Each part names how the mechanism acts on it (loads::LinkDefinition: the
// face set of every joint, chain, drive, point mass, spring and point force
// on its body). check_part_against_model() verifies, before any solve, that
// the part fits the model: every named face set exists and is a surface, the
// part's size agrees with the distance between its joint points (a wrong
// length unit shows here), and every revolute or chain joint point lies in
// its bore's axis (the in-plane distance from the face set's centroid: a
// wrong placement shows here; the bore may sit at any z).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/meshes/arm.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/structure/part.hpp"

namespace kinetofem::pipeline {

enum class PartSource { File, Lever, ArmWithRoller, Coupler, Rocker };
// "file", "lever", "arm_with_roller", "coupler", "rocker".
const char* name_of(PartSource source);

struct PartPlacement {
  Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();  // part origin in the body frame (z: along the pin axes), m
  double angle_rad = 0.0;                              // part axes turned about z, rad
};

// A solid of a welded part with a material of its own (meshes::PartSolid;
// element set "solid.<solid>"): each value given replaces the case's.
struct SolidMaterial {
  std::string solid;
  std::optional<double> youngs_modulus_pa;
  std::optional<double> poisson_ratio;
  std::optional<double> density_kg_m3;
};

struct PartSpec {
  PartSource source = PartSource::File;
  std::filesystem::path file;             // PartSource::File
  meshes::PartFileOptions file_options;   // length unit, named faces by bounding box, welded solids
  // The solids with their own material (FeModel::set_materials); the others,
  // and a part without solids, take the case's material.
  std::vector<SolidMaterial> solid_materials;
  meshes::LeverDimensions lever;          // Lever, Rocker
  meshes::ArmDimensions arm;              // ArmWithRoller, Coupler
  PartPlacement placement;
  // true: the body's mass, centre of mass and inertia come from the mesh and
  // the material; false: the case's own values are kept (both are printed).
  bool mass_from_mesh = true;
  // The body this part belongs to and where each load on it acts
  // (LinkDefinition::model is set by build_part_models).
  loads::LinkDefinition attachments;
  std::string label;  // for messages: "part 'crank' (parts/crank.step)"
  // A part of the ground (the frame): the face set of its foundation
  // (structure::Part::held_face); empty for a moving body's part.
  std::string held_face;
};

// A built part (structure/part.hpp): the libraries beneath the pipeline
// (structure/, vibration/) take it; its spec stays here.
using Part = structure::Part;

// Meshes every part (Gmsh, through the mesh cache when options.cache_dir is
// set), places it and computes its mass properties; prints one line per part
// (nodes, elements, DoFs, mass). Throws Error naming the part on a bad file,
// bad dimensions or a failed mesh, and for two parts of the same body.
std::vector<Part> build_part_models(const std::vector<PartSpec>& specs, const fem::IsotropicMaterial& material,
                                    const meshes::MeshOptions& options, const Log& log);

// x_body = R(angle) x + offset for every node (face and node sets unchanged).
void place_mesh(fem::Mesh& mesh, const PartPlacement& placement);

// Writes each part's mass properties into its body of `model` (unless its
// spec keeps the case's values: PartSpec::mass_from_mesh; `specs` empty:
// every part's from its mesh, else one spec per part, in order) and prints
// both, mesh and case, per body. A part on the ground (the frame) only has
// its mass printed: the ground does not move. Throws Error for a part on a
// body the model lacks.
void apply_mass_properties(mech::MultibodyModel& model, const std::vector<Part>& parts, const Log& log,
                           const std::vector<PartSpec>& specs = {});

// The fit checks of the header comment; throws Error naming the part, the
// joint, the face set and the distance.
void check_part_against_model(const Part& part, const mech::MultibodyModel& model);

// Whether the parts sit in more than one plane (their placements' z differ):
// then the per-part stage, which is planar, lacks the moments of the offsets
// between the planes, which only the elastic assembly carries.
bool parts_in_several_planes(const std::vector<PartSpec>& specs);

// A welded part (a mesh of several named solids): each element's solid index
// as the cell field `solid` of its body, so a viewer can colour the part by
// solid (the names: meshes::element_solids). Nothing for a one-solid part.
void write_solid_field(post::BodyWriter& body, const fem::Mesh& mesh);

}  // namespace kinetofem::pipeline
