#include "kinetofem/solver/bore_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <limits>
#include <set>

#include <fmt/ranges.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "face_integration.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/element_traits.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::fem {

namespace {

using Index = Eigen::Index;

// The scales the tolerances are relative to: a force (N) and a gap (m).
struct ContactScales {
  double force = 0.0, gap = 0.0;
};

ContactScales scales_of(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E,
                        const Eigen::VectorXd& r) {
  // A force of the resultant's size (a moment over the pin's lever arm, the
  // largest |E| entry of a tilt column), or what closes the largest gap the
  // other loads close (an open gap asks for no force); a gap of the
  // clearances' size, or what that force opens.
  double force = 0.0;
  for (Index k = 0; k < r.size(); ++k) {
    const double arm = std::max(E.col(k).cwiseAbs().maxCoeff(), 1e-300);
    force = std::max(force, std::abs(r[k]) / arm);
  }
  for (Index i = 0; i < b.size(); ++i)
    if (b[i] < 0) force = std::max(force, -b[i] / std::max(A(i, i), 1e-300));
  force = std::max(force, 1e-300);
  const double gap = std::max({b.cwiseAbs().maxCoeff(), force * A.diagonal().maxCoeff(), 1e-300});
  return {force, gap};
}

// The equality-constrained solve on a contact set I: lambda_I, q from
//   A_II lambda_I - E_I q = -b_I,  E_I^T lambda_I + C q = r.
// When E_I cannot carry every component of r (too few nodes in contact,
// e.g. one line of nodes along the pin), q is the least-squares choice (the
// pseudo-inverse of the Schur complement): the resultant is then not met
// and the gaps of that pin motion show which nodes to add. false when A_II
// is not positive definite.
bool solve_on_set(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E,
                  const Eigen::MatrixXd& C, const Eigen::VectorXd& r, const std::vector<char>& in_set,
                  Eigen::VectorXd& lambda, Eigen::VectorXd& q) {
  std::vector<Index> idx;
  for (Index i = 0; i < Index(in_set.size()); ++i)
    if (in_set[size_t(i)]) idx.push_back(i);
  const Index n = Index(idx.size()), k = E.cols();
  lambda = Eigen::VectorXd::Zero(A.rows());
  q = Eigen::VectorXd::Zero(k);
  if (n == 0 && C.isZero(0.0)) return true;
  Eigen::MatrixXd A_II(n, n), E_I(n, k);
  Eigen::VectorXd b_I(n);
  for (Index a = 0; a < n; ++a) {
    for (Index c = 0; c < n; ++c) A_II(a, c) = A(idx[size_t(a)], idx[size_t(c)]);
    E_I.row(a) = E.row(idx[size_t(a)]);
    b_I[a] = b[idx[size_t(a)]];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(A_II);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::MatrixXd Y = llt.solve(E_I);        // A_II^-1 E_I
  const Eigen::VectorXd y = llt.solve(b_I);        // A_II^-1 b_I
  // k x k, SPD when E_I has full column rank (or C is positive definite).
  const Eigen::MatrixXd S = E_I.transpose() * Y + C;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const double cut = 1e-12 * std::max(eig.eigenvalues().maxCoeff(), 1e-300);
  const Eigen::VectorXd inverse =
      eig.eigenvalues().unaryExpr([cut](double v) { return v > cut ? 1.0 / v : 0.0; });
  q = eig.eigenvectors() *
      (inverse.asDiagonal() * (eig.eigenvectors().transpose() * (r + E_I.transpose() * y)));
  const Eigen::VectorXd lambda_I = Y * q - y;
  for (Index a = 0; a < n; ++a) lambda[idx[size_t(a)]] = lambda_I[a];
  return true;
}

// The contact set a pin moving with its load starts from: the nodes it
// approaches (E_i q0 > 0 for the rigid motion q0 that the resultant would
// give on all nodes alike) and those the other loads already close.
std::vector<char> facing_set(const Eigen::MatrixXd& E, const Eigen::VectorXd& b, const Eigen::VectorXd& r) {
  const Eigen::MatrixXd EtE = E.transpose() * E;
  const Eigen::VectorXd q0 = EtE.ldlt().solve(r);
  const Eigen::VectorXd approach = E * q0;
  std::vector<char> set(size_t(E.rows()));
  for (Index i = 0; i < E.rows(); ++i) set[size_t(i)] = approach[i] > 0 || b[i] < 0;
  return set;
}

// Primal-dual active-set steps from the contact set `set` (updated): on the
// set lambda from the equality-constrained solve, off it the gaps; a node
// stays in contact while its lambda > 0 and joins when its gap < 0. Returns
// the steps taken when the KKT conditions hold (to the tolerances), 0 when
// it has not settled in `max_steps`, cycles, or meets a singular block.
int active_set(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E, const Eigen::MatrixXd& C,
               const Eigen::VectorXd& r, const ContactScales& s, const ContactSolverOptions& options, int max_steps, std::vector<char>& set,
               Eigen::VectorXd& lambda, Eigen::VectorXd& q) {
  const double gap_tolerance = options.tolerance * s.gap, force_tolerance = options.tolerance * s.force;
  std::set<std::vector<char>> seen;
  for (int step = 1; step <= max_steps; ++step) {
    if (!solve_on_set(A, b, E, C, r, set, lambda, q)) return 0;
    const Eigen::VectorXd g = A * lambda + b - E * q;
    std::vector<char> next(set.size());
    bool optimal = (E.transpose() * lambda + C * q - r).norm() <= options.tolerance * std::max(r.norm(), s.force);
    for (Index i = 0; i < A.rows(); ++i) {
      if (set[size_t(i)]) {
        next[size_t(i)] = lambda[i] > 0;
        optimal = optimal && lambda[i] >= -force_tolerance;
      } else {
        next[size_t(i)] = g[i] < 0;
        optimal = optimal && g[i] >= -gap_tolerance;
      }
    }
    if (optimal) return step;
    if (!seen.insert(set).second) return 0;  // cycling
    set = std::move(next);
  }
  return 0;
}

// Primal-dual interior point method for the QP (the fallback): Mehrotra's
// predictor-corrector on A lambda + b - E q - g = 0, E^T lambda + C q = r,
// lambda_i g_i = sigma mu, with the fraction-to-the-boundary rule.
bool interior_point(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E,
                    const Eigen::MatrixXd& C, const Eigen::VectorXd& r, const ContactScales& s, const ContactSolverOptions& options,
                    Eigen::VectorXd& lambda, Eigen::VectorXd& q, Eigen::VectorXd& g, int& steps) {
  const Index m = A.rows();
  lambda = Eigen::VectorXd::Constant(m, s.force / double(m));
  g = Eigen::VectorXd::Constant(m, s.gap);
  q = Eigen::VectorXd::Zero(E.cols());
  const double arm = std::max(E.cwiseAbs().maxCoeff(), 1e-300);
  // The step to the boundary along (dl, dg), times 0.995 (at most 1).
  auto step_length = [&](const Eigen::VectorXd& dl, const Eigen::VectorXd& dg, double fraction) {
    double alpha = 1.0;
    for (Index i = 0; i < m; ++i) {
      if (dl[i] < 0) alpha = std::min(alpha, -fraction * lambda[i] / dl[i]);
      if (dg[i] < 0) alpha = std::min(alpha, -fraction * g[i] / dg[i]);
    }
    return alpha;
  };
  for (steps = 1; steps <= options.max_interior_point_steps; ++steps) {
    const Eigen::VectorXd rd = A * lambda + b - E * q - g;
    const Eigen::VectorXd rp = E.transpose() * lambda + C * q - r;
    const double mu = lambda.dot(g) / double(m);
    if (rd.cwiseAbs().maxCoeff() <= options.tolerance * s.gap &&
        rp.cwiseAbs().maxCoeff() <= options.tolerance * s.force * arm &&
        lambda.cwiseProduct(g).maxCoeff() <= options.tolerance * s.force * s.gap)
      return true;
    Eigen::MatrixXd H = A;
    H.diagonal() += g.cwiseQuotient(lambda);
    const Eigen::LLT<Eigen::MatrixXd> llt(H);
    if (llt.info() != Eigen::Success) return false;
    const Eigen::MatrixXd Y = llt.solve(E);
    const Eigen::LDLT<Eigen::MatrixXd> schur(E.transpose() * Y + C);
    // Newton direction for the complementarity target lambda_i g_i = t_i:
    //   (A + G/L) dl - E dq = -rd + (t - lambda g) / lambda,  E^T dl + C dq = -rp,
    //   dg = (t - lambda g - g dl) / lambda.
    auto direction = [&](const Eigen::VectorXd& target, Eigen::VectorXd& dl, Eigen::VectorXd& dq,
                         Eigen::VectorXd& dg) {
      const Eigen::VectorXd c = target - lambda.cwiseProduct(g);
      const Eigen::VectorXd y = llt.solve(-rd + c.cwiseQuotient(lambda));
      dq = schur.solve(-rp - E.transpose() * y);
      dl = y + Y * dq;
      dg = (c - g.cwiseProduct(dl)).cwiseQuotient(lambda);
    };
    Eigen::VectorXd dl, dq, dg;
    direction(Eigen::VectorXd::Zero(m), dl, dq, dg);  // predictor
    const double alpha_affine = step_length(dl, dg, 1.0);
    const double mu_affine = (lambda + alpha_affine * dl).dot(g + alpha_affine * dg) / double(m);
    const double sigma = std::pow(std::clamp(mu_affine / mu, 0.0, 1.0), 3);
    direction(Eigen::VectorXd::Constant(m, sigma * mu) - dl.cwiseProduct(dg), dl, dq, dg);  // corrector
    const double alpha = step_length(dl, dg, 0.995);
    lambda += alpha * dl;
    g += alpha * dg;
    q += alpha * dq;
  }
  return false;
}

}  // namespace

ContactSolution solve_contact(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E,
                              const Eigen::VectorXd& r, const std::vector<char>& start,
                              const ContactSolverOptions& options) {
  return solve_contact(A, b, E, Eigen::MatrixXd::Zero(E.cols(), E.cols()), r, start, options);
}

ContactSolution solve_contact(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::MatrixXd& E,
                              const Eigen::MatrixXd& C, const Eigen::VectorXd& r, const std::vector<char>& start,
                              const ContactSolverOptions& options) {
  const Index m = A.rows();
  require(A.cols() == m && b.size() == m && E.rows() == m && r.size() == E.cols() && m > 0 &&
              C.rows() == E.cols() && C.cols() == E.cols(),
          "contact: inconsistent problem sizes (A {} x {}, b {}, E {} x {}, C {} x {}, r {})", A.rows(), A.cols(),
          b.size(), E.rows(), E.cols(), C.rows(), C.cols(), r.size());
  require(start.empty() || Index(start.size()) == m, "contact: the starting contact set has {} entries for {} nodes",
          start.size(), m);
  const ContactScales s = scales_of(A, b, E, r);

  ContactSolution out;
  std::vector<char> set = start.empty() ? facing_set(E, b, r) : start;
  Eigen::VectorXd lambda, q;
  out.active_set_steps = active_set(A, b, E, C, r, s, options, options.max_active_set_steps, set, lambda, q);
  const bool converged = out.active_set_steps > 0;
  if (!converged) {
    out.active_set_steps = options.max_active_set_steps;
    Eigen::VectorXd g;
    const bool ok = interior_point(A, b, E, C, r, s, options, lambda, q, g, out.interior_point_steps);
    require(ok,
            "the contact problem did not converge ({} active-set steps, {} interior-point steps): the resultant "
            "({}) may not be carried by pressure on the bore alone",
            out.active_set_steps, out.interior_point_steps, fmt::join(r, ", "));
    // Polish: the active set from the interior point's contact set (close
    // to the solution, so it settles in a step or two), solved exactly.
    std::vector<char> polished(static_cast<size_t>(m), 0);
    for (Index i = 0; i < m; ++i) polished[size_t(i)] = lambda[i] * s.gap > g[i] * s.force;
    Eigen::VectorXd lambda_exact, q_exact;
    if (active_set(A, b, E, C, r, s, options, options.max_polish_steps, polished, lambda_exact, q_exact) > 0) {
      lambda = lambda_exact;
      q = q_exact;
      out.polished = true;
    }
  }
  // Round-off may leave a node of the contact set at -1e-17 N: no tension.
  out.pressure = lambda.cwiseMax(0.0);
  out.pin_motion = q;
  out.gap = A * out.pressure + b - E * q;
  out.in_contact.resize(size_t(m));
  for (Index i = 0; i < m; ++i) out.in_contact[size_t(i)] = out.pressure[i] > 0;
  out.worst_penetration = std::max(0.0, -out.gap.minCoeff());
  out.resultant_error = (E.transpose() * out.pressure + C * q - r).norm() / std::max(r.norm(), s.force);
  return out;
}

BoreContactSurface::BoreContactSurface(const Mesh& mesh, const std::string& face_set,
                                       const Eigen::Vector3d& axis_point_m, const Eigen::Vector3d& axis_direction)
    : face_set_(face_set), centre_(axis_point_m) {
  require(axis_direction.norm() > 0, "contact on bore '{}': the axis direction is zero", face_set);
  axis_ = axis_direction.normalized();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - axis_ * axis_.transpose();
  e1_ = across * Eigen::Vector3d::UnitX();
  if (e1_.norm() < 0.5) e1_ = across * Eigen::Vector3d::UnitY();
  e1_.normalize();
  e2_ = axis_.cross(e1_);

  const auto& faces = mesh.face_set(face_set);
  nodes_ = nodes_of_faces(faces);
  require(!nodes_.empty(), "contact on bore '{}': the face set is empty", face_set);
  std::vector<Index> node_row(size_t(mesh.node_count()), -1), corner_column(size_t(mesh.node_count()), -1);
  for (size_t k = 0; k < nodes_.size(); ++k) node_row[size_t(nodes_[k])] = Index(k);
  for (const auto& block : faces) {
    const int corners = face_facts(block.type).corners;
    for (Index f = 0; f < block.size(); ++f) {
      const auto nodes = block.face(f);
      for (int c = 0; c < corners; ++c)
        if (corner_column[size_t(nodes[size_t(c)])] < 0) {
          corner_column[size_t(nodes[size_t(c)])] = Index(corners_.size());
          corners_.push_back(nodes[size_t(c)]);
        }
    }
  }
  // Each node's corners: itself, or the two ends of its edge (Gmsh order:
  // mid-edge node k of a face lies on edge (k - corners, k - corners + 1)).
  node_corners_.assign(nodes_.size(), {-1, -1});
  for (const auto& block : faces) {
    const int n = face_facts(block.type).nodes, corners = face_facts(block.type).corners;
    for (Index f = 0; f < block.size(); ++f) {
      const auto nodes = block.face(f);
      for (int a = 0; a < n; ++a) {
        const Index row = node_row[size_t(nodes[size_t(a)])];
        if (a < corners) {
          const Index c = corner_column[size_t(nodes[size_t(a)])];
          node_corners_[size_t(row)] = {c, c};
        } else if (node_corners_[size_t(row)][0] < 0) {
          const int edge = a - corners;
          node_corners_[size_t(row)] = {corner_column[size_t(nodes[size_t(edge)])],
                                        corner_column[size_t(nodes[size_t((edge + 1) % corners)])]};
        }
      }
    }
  }
  // M_ac = integral of N_a L_c over the faces (Gauss rule of the face type).
  force_map_ = Eigen::MatrixXd::Zero(Index(nodes_.size()), Index(corners_.size()));
  Eigen::VectorXd L;
  Eigen::MatrixXd dL;
  detail::for_each_face_quadrature_point(
      mesh, faces,
      [&](std::span<const Index> nodes, const Eigen::Vector3d& xi, const Eigen::VectorXd& N, const Eigen::Vector3d&,
          double dA) {
        // Triangles (3 or 6 nodes) have 3 corners, quadrilaterals (4 or 8) 4.
        const FaceType linear = nodes.size() % 3 == 0 ? FaceType::Tri3 : FaceType::Quad4;
        shape_functions(linear, xi, L, dL);
        for (Index a = 0; a < N.size(); ++a)
          for (Index c = 0; c < L.size(); ++c)
            force_map_(node_row[size_t(nodes[size_t(a)])], corner_column[size_t(nodes[size_t(c)])]) += N[a] * L[c] * dA;
      });
  const Index count = Index(nodes_.size()), m = Index(corners_.size());
  normals_.resize(count, 3);
  Eigen::Matrix<double, Eigen::Dynamic, 4> node_pin(count, 4);
  double axial_min = std::numeric_limits<double>::infinity(), axial_max = -axial_min;
  for (Index a = 0; a < count; ++a) {
    const Eigen::Vector3d r = mesh.nodes.row(nodes_[size_t(a)]).transpose() - centre_;
    const Eigen::Vector3d radial = across * r;
    require(radial.norm() > 1e-9 * std::max(1.0, r.norm()),
            "contact on bore '{}': node {} lies on the pin's axis (no radial direction)", face_set, nodes_[size_t(a)]);
    const Eigen::Vector3d normal = radial.normalized();
    normals_.row(a) = normal.transpose();
    const Eigen::Vector3d arm = r.cross(normal);
    node_pin.row(a) << normal.dot(e1_), normal.dot(e2_), arm.dot(e1_), arm.dot(e2_);
    radius_ += radial.norm() / double(count);
    axial_min = std::min(axial_min, r.dot(axis_));
    axial_max = std::max(axial_max, r.dot(axis_));
  }
  length_ = axial_max - axial_min;
  rigid_pin_ = force_map_.transpose() * node_pin;
  pressure_force_ = force_map_.transpose() * normals_;
  area_ = force_map_.colwise().sum().transpose();
  angle_.resize(m);
  for (Index c = 0; c < m; ++c) {
    const Eigen::Vector3d normal = normals_.row(node_row[size_t(corners_[size_t(c)])]).transpose();
    angle_[c] = std::atan2(normal.dot(e2_), normal.dot(e1_));
  }
  require(area_.minCoeff() > 0, "contact on bore '{}': a corner node has no share of the bore's area", face_set);
}

Eigen::Vector4d BoreContactSurface::carried(const Eigen::Vector3d& force_n, const Eigen::Vector3d& moment_nm) const {
  return {force_n.dot(e1_), force_n.dot(e2_), moment_nm.dot(e1_), moment_nm.dot(e2_)};
}

void BoreContactSurface::add_forces(const Eigen::Ref<const Eigen::MatrixXd>& pressure_pa,
                                    Eigen::Ref<Eigen::MatrixXd> forces) const {
  const Eigen::MatrixXd lambda = force_map_ * pressure_pa;  // nodal normal forces, N
  for (Index c = 0; c < lambda.cols(); ++c)
    for (Index a = 0; a < Index(nodes_.size()); ++a)
      forces.col(c).segment<3>(3 * nodes_[size_t(a)]) += lambda(a, c) * normals_.row(a).transpose();
}

Eigen::VectorXd BoreContactSurface::nodal_pressure(const Eigen::Ref<const Eigen::VectorXd>& pressure_pa) const {
  Eigen::VectorXd out(Index(nodes_.size()));
  for (size_t a = 0; a < nodes_.size(); ++a)
    out[Index(a)] = 0.5 * (pressure_pa[node_corners_[a][0]] + pressure_pa[node_corners_[a][1]]);
  return out;
}

Eigen::MatrixXd BoreContactSurface::weighted_normal_components(
    const Eigen::Ref<const Eigen::MatrixXd>& displacements) const {
  Eigen::MatrixXd normal(Index(nodes_.size()), displacements.cols());
  for (Index c = 0; c < displacements.cols(); ++c)
    for (Index a = 0; a < Index(nodes_.size()); ++a)
      normal(a, c) = normals_.row(a).dot(displacements.col(c).segment<3>(3 * nodes_[size_t(a)]));
  return force_map_.transpose() * normal;
}

CondensedContact condense_contact(LinearStaticAnalysis& analysis, const std::vector<const BoreContactSurface*>& surfaces,
                                  const Eigen::MatrixXd& P) {
  const Index dofs = 3 * analysis.model().mesh.node_count();
  require(P.rows() == dofs, "contact: {} pattern force rows for {} DoFs", P.rows(), dofs);
  Index m = 0;
  std::vector<Index> offset;
  for (const BoreContactSurface* s : surfaces) {
    offset.push_back(m);
    m += s->size();
  }
  Eigen::MatrixXd A(m, m), D(m, P.cols());
  const Index block = 64;
  for (Index first = 0; first < m; first += block) {
    const Index count = std::min(block, m - first);
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(dofs, count);
    for (size_t b = 0; b < surfaces.size(); ++b) {
      const auto& s = *surfaces[b];
      Eigen::MatrixXd unit_pressure = Eigen::MatrixXd::Zero(s.size(), count);
      for (Index i = 0; i < s.size(); ++i)
        if (offset[b] + i >= first && offset[b] + i < first + count) unit_pressure(i, offset[b] + i - first) = 1.0;
      if (!unit_pressure.isZero(0.0)) s.add_forces(unit_pressure, unit);
    }
    const std::vector<DisplacementField> u = analysis.solve_forces(unit);
    Eigen::MatrixXd W(dofs, count);
    for (Index k = 0; k < count; ++k) W.col(k) = Eigen::Map<const Eigen::VectorXd>(u[size_t(k)].data(), dofs);
    for (size_t b = 0; b < surfaces.size(); ++b)
      A.block(offset[b], first, surfaces[b]->size(), count) = surfaces[b]->weighted_normal_components(W);
    D.middleRows(first, count).noalias() = W.transpose() * P;
  }
  A = 0.5 * (A + A.transpose()).eval();  // exactly symmetric (evaluated first: A is aliased)
  return {std::move(A), std::move(D)};
}

BoreContactState contact_state(const BoreContactSurface& bore, const Eigen::Ref<const Eigen::VectorXd>& pressure_pa) {
  BoreContactState s;
  std::vector<double> angles;
  for (Index c = 0; c < bore.size(); ++c) {
    if (!(pressure_pa[c] > 0)) continue;
    if (pressure_pa[c] > s.peak_pressure_pa) {
      s.peak_pressure_pa = pressure_pa[c];
      s.peak_angle_rad = bore.angle_rad()[c];
    }
    angles.push_back(bore.angle_rad()[c]);
    ++s.corners_in_contact;
  }
  s.force_n = bore.pressure_resultants().transpose() * pressure_pa;
  if (angles.size() > 1) {
    // The arc: the full turn less the widest angular gap between contact corners.
    std::sort(angles.begin(), angles.end());
    double widest = angles.front() + 2 * std::numbers::pi - angles.back();
    for (size_t k = 1; k < angles.size(); ++k) widest = std::max(widest, angles[k] - angles[k - 1]);
    s.arc_rad = 2 * std::numbers::pi - widest;
  }
  return s;
}

}  // namespace kinetofem::fem
