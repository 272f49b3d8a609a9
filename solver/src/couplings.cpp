#include "kinetofem/solver/couplings.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "face_integration.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/element_library.hpp"

namespace kinetofem::fem {

namespace {

using detail::for_each_face_point;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

}  // namespace

DistributingCoupling::DistributingCoupling(const Mesh& mesh, const std::string& face_set) {
  const auto& faces = mesh.face_set(face_set);
  nodes_ = nodes_of_faces(faces);
  require(!nodes_.empty(), "distributing coupling: face set '{}' is empty", face_set);
  std::vector<double> weight_of(size_t(mesh.node_count()), 0.0);
  for_each_face_point(mesh, faces, [&](std::span<const Index> nodes, const Eigen::VectorXd& N,
                                       const Eigen::Vector3d&, double dA) {
    for (Eigen::Index a = 0; a < N.size(); ++a) weight_of[size_t(nodes[size_t(a)])] += N[a] * dA;
  });
  const Index n = Index(nodes_.size());
  weight_.resize(n);
  centroid_.setZero();
  for (Index k = 0; k < n; ++k) {
    // Quadratic faces give corner nodes zero (or slightly negative) consistent
    // weight; a node set's load must not pull against the resultant.
    weight_[k] = std::max(0.0, weight_of[size_t(nodes_[size_t(k)])]);
    centroid_ += weight_[k] * mesh.nodes.row(nodes_[size_t(k)]).transpose();
  }
  total_weight_ = weight_.sum();
  require(total_weight_ > 0, "distributing coupling: face set '{}' has zero area", face_set);
  centroid_ /= total_weight_;
  arm_.resize(n, 3);
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (Index k = 0; k < n; ++k) {
    const Eigen::Vector3d r = mesh.nodes.row(nodes_[size_t(k)]).transpose() - centroid_;
    arm_.row(k) = r.transpose();
    J += weight_[k] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(J);
  require(eig.eigenvalues().minCoeff() > 1e-12 * eig.eigenvalues().maxCoeff(),
          "distributing coupling: the nodes of face set '{}' lie on a line; they cannot carry a "
          "moment",
          face_set);
  polar_inverse_ = J.inverse();
}

void DistributingCoupling::add(const Eigen::Vector3d& force_n, const Eigen::Vector3d& moment_nm,
                               const Eigen::Vector3d& reference_point_m,
                               Eigen::Ref<Eigen::VectorXd> forces) const {
  const Eigen::Vector3d moment_about_centroid =
      moment_nm + (reference_point_m - centroid_).cross(force_n);
  const Eigen::Vector3d theta = polar_inverse_ * moment_about_centroid;
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Vector3d r = arm_.row(Index(k)).transpose();
    forces.segment<3>(3 * nodes_[k]) +=
        weight_[Index(k)] * (force_n / total_weight_ + theta.cross(r));
  }
}

Eigen::Vector3d add_bearing_pressure(const Mesh& mesh, const BoreGeometry& bore,
                                     const Eigen::Vector3d& force_n,
                                     Eigen::Ref<Eigen::VectorXd> forces) {
  const Eigen::Vector3d axis = bore.axis_direction.normalized();
  const Eigen::Vector3d axial = force_n.dot(axis) * axis;
  const Eigen::Vector3d radial_force = force_n - axial;
  const double magnitude = radial_force.norm();
  if (magnitude == 0.0) return axial;
  const Eigen::Vector3d direction = radial_force / magnitude;
  const auto& faces = mesh.face_set(bore.face_set);
  // Unit radial direction (from the axis outwards, into the material) and
  // cos(phi) of a point of the bore.
  auto radial = [&](const Eigen::Vector3d& x) {
    Eigen::Vector3d r = x - bore.axis_point_m;
    r -= r.dot(axis) * axis;
    return Eigen::Vector3d(r.normalized());
  };
  // Pressure p = (a . n_r)+ : a cosine distribution about the direction of
  // the vector a. With a = p0 * direction the discrete resultant would miss
  // the force by the asymmetry of the mesh; instead a solves
  //   G(a) a = F_radial,  G(a) = int_{a . n_r > 0} n_r n_r^T dA,
  // iterated until the loaded half stops changing, so the resultant is exact.
  Eigen::Vector3d a = radial_force;
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
    for_each_face_point(mesh, faces, [&](std::span<const Index>, const Eigen::VectorXd&,
                                         const Eigen::Vector3d& x, double dA) {
      const Eigen::Vector3d n = radial(x);
      if (n.dot(a) > 0) G += dA * n * n.transpose();
    });
    require(G.trace() > 0, "bearing pressure: bore '{}' has no surface facing the force",
            bore.face_set);
    G += G.trace() * axis * axis.transpose();  // no stiffness along the axis: keep G invertible
    const Eigen::Vector3d next = G.ldlt().solve(radial_force);
    const bool settled = (next - a).norm() <= 1e-14 * next.norm() ||
                         (iteration > 0 && (next.normalized() - a.normalized()).norm() < 1e-15);
    a = next;
    if (settled) break;
  }
  (void)direction;
  for_each_face_point(mesh, faces, [&](std::span<const Index> nodes, const Eigen::VectorXd& N,
                                       const Eigen::Vector3d& x, double dA) {
    const Eigen::Vector3d n = radial(x);
    const double p = n.dot(a);
    if (p <= 0) return;
    for (Eigen::Index k = 0; k < N.size(); ++k)
      forces.segment<3>(3 * nodes[size_t(k)]) += N[k] * dA * p * n;
  });
  return axial;
}

RigidBodyMotionLoads::RigidBodyMotionLoads(const Mesh& mesh, const ElementMaterials& materials) {
  // Fields of force per unit mass: each element's density multiplies them.
  std::vector<LoadCase> basis(12);
  for (int k = 0; k < 3; ++k) {
    basis[size_t(k)].name = fmt::format("rho e_{}", k);
    basis[size_t(k)].acceleration = [k](const Eigen::Vector3d&) {
      return Eigen::Vector3d(Eigen::Vector3d::Unit(k));
    };
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      basis[size_t(3 + 3 * i + j)].name = fmt::format("rho x_{} e_{}", j, i);
      basis[size_t(3 + 3 * i + j)].acceleration = [i, j](const Eigen::Vector3d& x) {
        return Eigen::Vector3d(x[j] * Eigen::Vector3d::Unit(i));
      };
    }
  basis_ = assemble_external_forces(mesh, materials, basis);
  // Mass and first moments from the basis: sum over nodes of column e_k's k
  // components is rho V; of column x_j e_i's i components, rho int x_j dV.
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  for (Index node = 0; node < mesh.node_count(); ++node) {
    mass_ += basis_(3 * node, 0);
    for (int j = 0; j < 3; ++j) first_moment[j] += basis_(3 * node, 3 + j);
  }
  if (mass_ > 0) centre_of_mass_ = first_moment / mass_;
}

Eigen::Matrix<double, 12, 1> RigidBodyMotionLoads::coefficients(const Eigen::Vector3d& gravity,
                                                                const Eigen::Vector3d& origin_acceleration,
                                                                const Eigen::Vector3d& omega,
                                                                const Eigen::Vector3d& alpha) {
  // b(x) / rho = c + A x with c = g - a_O, A = -(skew(alpha) + skew(omega)^2).
  const Eigen::Vector3d c = gravity - origin_acceleration;
  const Eigen::Matrix3d A = -(skew(alpha) + skew(omega) * skew(omega));
  Eigen::Matrix<double, 12, 1> out;
  out.head<3>() = c;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[3 + 3 * i + j] = A(i, j);
  return out;
}

Eigen::VectorXd RigidBodyMotionLoads::forces(const Eigen::Vector3d& gravity,
                                             const Eigen::Vector3d& origin_acceleration,
                                             const Eigen::Vector3d& omega,
                                             const Eigen::Vector3d& alpha) const {
  return basis_ * coefficients(gravity, origin_acceleration, omega, alpha);
}

void resultant(const Mesh& mesh, const Eigen::VectorXd& forces, const Eigen::Vector3d& point,
               Eigen::Vector3d& force_n, Eigen::Vector3d& moment_nm) {
  force_n.setZero();
  moment_nm.setZero();
  for (Index node = 0; node < mesh.node_count(); ++node) {
    const Eigen::Vector3d f = forces.segment<3>(3 * node);
    force_n += f;
    moment_nm += (mesh.nodes.row(node).transpose() - point).cross(f);
  }
}

}  // namespace kinetofem::fem
