#pragma once
// FeModel — one linear-elastic solid body ready to solve: mesh, material,
// supports and load cases. SI units throughout (m, N, Pa, kg/m^3).
//
// The material is one per part, or one per element set (the solids of a
// welded part, FeModel::set_materials).
//
// Supports prescribe displacement components on node sets; they are
// eliminated from the system (the reduced stiffness stays symmetric and the
// prescribed values move to the right-hand side). Loads of one load case are
// summed: nodal forces, surface tractions (force per area, any direction) and
// pressures on face sets, gravity, a body-force field f(x) in N/m^3, and a
// field of force per unit mass a(x) in m/s^2 (d'Alembert loads of a motion;
// like gravity, times the density of each element).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/material.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

struct DisplacementSupport {
  std::string label;                         // for messages
  std::vector<Index> nodes;
  std::array<bool, 3> fixed = {true, true, true};  // which of x, y, z are prescribed
  Eigen::Vector3d value_m = Eigen::Vector3d::Zero();
};

struct NodalForce {
  Index node = 0;
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
};

struct SurfaceTraction {
  std::string face_set;
  Eigen::Vector3d traction_pa = Eigen::Vector3d::Zero();  // force per unit area
};

struct SurfacePressure {
  std::string face_set;
  double pressure_pa = 0.0;  // positive pushes into the body (along -outward normal)
};

// Body force per unit volume (N/m^3) at a point x (m).
using BodyForceField = std::function<Eigen::Vector3d(const Eigen::Vector3d& x)>;
// Force per unit mass (m/s^2) at a point x (m): times each element's density.
using AccelerationField = std::function<Eigen::Vector3d(const Eigen::Vector3d& x)>;

struct LoadCase {
  std::string name = "load";
  std::vector<NodalForce> nodal_forces;
  std::vector<SurfaceTraction> tractions;
  std::vector<SurfacePressure> pressures;
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();  // body force rho * g
  BodyForceField body_force;                               // optional, N/m^3
  AccelerationField acceleration;  // optional, m/s^2: body force rho a(x), rho of each element
};

// A material for the elements of one element set (a solid of a welded part); elements in no
// listed set take FeModel::material.
struct ElementSetMaterial {
  std::string element_set;  // a key of Mesh::element_sets
  IsotropicMaterial material;
};

struct FeModel {
  Mesh mesh;
  IsotropicMaterial material;  // of every element in no set of set_materials
  // Per-solid materials; an element set named here must exist in the mesh and an element may
  // be in at most one of them (element_materials.hpp checks both and is where every consumer
  // looks an element's material up). Empty: one material for the whole part.
  std::vector<ElementSetMaterial> set_materials;
  std::vector<DisplacementSupport> supports;
};

}  // namespace kinetofem::fem
