#include "kinetofem/solver/rigid_body.hpp"

#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/element_library.hpp"

namespace kinetofem::fem {

MassProperties mass_properties(const Mesh& mesh, const ElementMaterials& materials) {
  // Moments of order 0, 1, 2 of the volume of each material k: V_k,
  // int x dV, int x x^T dV over its elements.
  const size_t kinds = materials.materials().size();
  std::vector<double> volume(kinds, 0.0);
  std::vector<Eigen::Vector3d> first(kinds, Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> second(kinds, Eigen::Matrix3d::Zero());
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  Index first_element = 0;
  for (const auto& block : mesh.blocks) {
    const int n = nodes_per_element(block.type);
    for (Index e = 0; e < block.size(); ++e) {
      const size_t k = size_t(materials.index_of(first_element + e));
      const auto nodes = block.element(e);
      Eigen::MatrixXd X(n, 3);
      for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(nodes[size_t(a)]);
      for (const auto& qp : load_quadrature(block.type)) {
        shape_functions(block.type, qp.xi, N, dN);
        const double dV = qp.weight * (X.transpose() * dN).determinant();
        const Eigen::Vector3d x = X.transpose() * N;
        volume[k] += dV;
        first[k] += dV * x;
        second[k] += dV * x * x.transpose();
      }
    }
    first_element += block.size();
  }
  MassProperties out;
  bool one_density = true;
  for (const IsotropicMaterial& m : materials.materials())
    one_density = one_density && m.density_kg_m3 == materials.materials()[0].density_kg_m3;
  if (one_density) {
    // The centre of mass is the centroid of the volume (for a zero density too).
    double total_volume = volume[0];
    Eigen::Vector3d total_first = first[0];
    Eigen::Matrix3d total_second = second[0];
    for (size_t k = 1; k < kinds; ++k) {
      total_volume += volume[k];
      total_first += first[k];
      total_second += second[k];
    }
    const double rho = materials.materials()[0].density_kg_m3;
    out.mass_kg = rho * total_volume;
    if (total_volume <= 0) return out;
    out.centre_of_mass_m = total_first / total_volume;
    // Second moment about the centre of mass, then I = tr(S) 1 - S.
    const Eigen::Matrix3d S = rho * (total_second - total_volume * out.centre_of_mass_m *
                                                        out.centre_of_mass_m.transpose());
    out.inertia_about_com_kgm2 = S.trace() * Eigen::Matrix3d::Identity() - S;
    return out;
  }
  // Densities differ: the moments of mass are the density-weighted sums.
  Eigen::Vector3d mass_first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d mass_second = Eigen::Matrix3d::Zero();
  for (size_t k = 0; k < kinds; ++k) {
    const double rho = materials.materials()[k].density_kg_m3;
    out.mass_kg += rho * volume[k];
    mass_first += rho * first[k];
    mass_second += rho * second[k];
  }
  if (out.mass_kg <= 0) return out;
  out.centre_of_mass_m = mass_first / out.mass_kg;
  const Eigen::Matrix3d S =
      mass_second - out.mass_kg * out.centre_of_mass_m * out.centre_of_mass_m.transpose();
  out.inertia_about_com_kgm2 = S.trace() * Eigen::Matrix3d::Identity() - S;
  return out;
}

Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> remove_rigid_body_motion(
    const Mesh& mesh, const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& u) {
  // Minimise sum |u_i - t - theta x r_i|^2 with r_i = x_i - centroid: the
  // normal equations decouple into t = mean(u) and J theta = sum r_i x u_i,
  // J = sum (|r_i|^2 I - r_i r_i^T).
  const Index n = mesh.node_count();
  const Eigen::Vector3d centroid = mesh.nodes.colwise().mean().transpose();
  const Eigen::Vector3d t = u.colwise().mean().transpose();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (Index i = 0; i < n; ++i) {
    const Eigen::Vector3d r = mesh.nodes.row(i).transpose() - centroid;
    J += r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
    b += r.cross(u.row(i).transpose());
  }
  const Eigen::Vector3d theta = J.ldlt().solve(b);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> out(n, 3);
  for (Index i = 0; i < n; ++i) {
    const Eigen::Vector3d r = mesh.nodes.row(i).transpose() - centroid;
    out.row(i) = (u.row(i).transpose() - t - theta.cross(r)).transpose();
  }
  return out;
}

std::vector<DisplacementSupport> three_two_one_support(const Mesh& mesh,
                                                       const std::vector<Index>& candidates) {
  require(candidates.size() >= 3, "3-2-1 support needs at least 3 candidate nodes");
  auto x = [&](Index node) { return Eigen::Vector3d(mesh.nodes.row(node).transpose()); };
  // a and b: the extremes along the longest extent of the candidates.
  Eigen::Vector3d lo = x(candidates[0]), hi = lo;
  for (Index node : candidates) {
    lo = lo.cwiseMin(x(node));
    hi = hi.cwiseMax(x(node));
  }
  int k;
  (hi - lo).maxCoeff(&k);
  Index a = candidates[0], b = candidates[0];
  for (Index node : candidates) {
    if (x(node)[k] < x(a)[k]) a = node;
    if (x(node)[k] > x(b)[k]) b = node;
  }
  // c: farthest from the line ab.
  const Eigen::Vector3d ab = (x(b) - x(a)).normalized();
  Index c = candidates[0];
  double best = -1;
  for (Index node : candidates) {
    Eigen::Vector3d d = x(node) - x(a);
    d -= d.dot(ab) * ab;
    if (d.norm() > best) {
      best = d.norm();
      c = node;
    }
  }
  require(best > 0, "3-2-1 support: the candidate nodes are collinear");
  // b is held in the two components other than k; c in the component in
  // which a rotation about ab through a moves it most.
  std::array<bool, 3> b_fixed = {true, true, true};
  b_fixed[size_t(k)] = false;
  const Eigen::Vector3d swing = ab.cross(x(c) - x(a));
  int m;
  swing.cwiseAbs().maxCoeff(&m);
  std::array<bool, 3> c_fixed = {false, false, false};
  c_fixed[size_t(m)] = true;
  std::vector<DisplacementSupport> supports = {
      {"3-2-1 support a", {a}, {true, true, true}, Eigen::Vector3d::Zero()},
      {"3-2-1 support b", {b}, b_fixed, Eigen::Vector3d::Zero()},
      {"3-2-1 support c", {c}, c_fixed, Eigen::Vector3d::Zero()}};
  // The six constraints must remove the six rigid-body modes: the 6 x 6
  // matrix of the modes at the constrained DoFs must be non-singular.
  Eigen::Matrix<double, 6, 6> modes;
  int row = 0;
  for (const auto& s : supports)
    for (int comp = 0; comp < 3; ++comp) {
      if (!s.fixed[size_t(comp)]) continue;
      const Eigen::Vector3d p = x(s.nodes[0]) - x(a);
      for (int t = 0; t < 3; ++t) modes(row, t) = comp == t ? 1.0 : 0.0;
      for (int r = 0; r < 3; ++r) modes(row, 3 + r) = Eigen::Vector3d::Unit(r).cross(p)[comp];
      ++row;
    }
  const double scale = (hi - lo).norm();
  Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(modes);
  require(svd.singularValues().minCoeff() > 1e-6 * std::max(1.0, scale),
          "3-2-1 support: the chosen nodes do not remove all rigid-body modes");
  return supports;
}

}  // namespace kinetofem::fem
