#pragma once
// Rigid-body properties of a meshed part: its mass properties, the removal of
// a rigid-body motion from a displacement field, and the statically
// determinate support that holds a free body without constraining its
// deformation. SI units (m, kg), in the mesh's frame.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

// Rigid-body mass properties of a meshed part: mass (kg), centre of mass
// (m, mesh frame) and inertia tensor about the centre of mass (kg m^2), by
// the elements' load Gauss rules (exact for straight-sided elements), each
// element of its own density (ElementMaterials).
struct MassProperties {
  double mass_kg = 0.0;
  Eigen::Vector3d centre_of_mass_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_about_com_kgm2 = Eigen::Matrix3d::Zero();
};
MassProperties mass_properties(const Mesh& mesh, const ElementMaterials& materials);

// The displacement field minus its best-fitting (least-squares, all nodes
// weighted equally) small rigid-body motion t + theta x x: the deformation
// of a free body, independent of which nodes hold it (e.g. the 3-2-1
// support). Returns N x 3, m.
Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> remove_rigid_body_motion(
    const Mesh& mesh, const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& displacement);

// A statically determinate (3-2-1) support that removes the six rigid-body
// modes of a free body without constraining its deformation: node a fixed in
// x, y, z; node b (far from a) fixed in the two directions normal to ab;
// node c (far from the line ab) fixed normal to the plane abc. Nodes are
// chosen among `candidates` (e.g. all nodes). Under a self-equilibrated load
// its reactions are zero up to round-off: check them.
std::vector<DisplacementSupport> three_two_one_support(const Mesh& mesh,
                                                       const std::vector<Index>& candidates);

}  // namespace kinetofem::fem
