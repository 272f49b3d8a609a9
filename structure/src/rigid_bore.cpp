#include "kinetofem/structure/rigid_bore.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/structure/rigid_motion.hpp"

namespace kinetofem::structure {

namespace {

using detail::Matrix6d;
using detail::skew;
using detail::solve_columns;
using detail::transfer;
using Eigen::Vector3d;

// The inverse of a small symmetric positive definite matrix through its
// Jacobi-scaled eigen decomposition (mixed units: translations and
// rotations). Returns the smallest over the largest scaled eigenvalue;
// `inverse` is set only when that exceeds `threshold`.
double spd_inverse(const Eigen::MatrixXd& A, double threshold, Eigen::MatrixXd& inverse) {
  const Eigen::Index n = A.rows();
  if (n == 0) {
    inverse.resize(0, 0);
    return 1.0;
  }
  if (!(A.diagonal().minCoeff() > 0)) return 0.0;
  const Eigen::VectorXd s = A.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd As = s.asDiagonal() * (0.5 * (A + A.transpose())) * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(As);
  if (eig.info() != Eigen::Success) return 0.0;
  const double ratio = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  if (!(ratio > threshold)) return ratio;
  const Eigen::MatrixXd& V = eig.eigenvectors();
  const Eigen::MatrixXd inv_s = V * eig.eigenvalues().cwiseInverse().asDiagonal() * V.transpose();
  inverse = s.asDiagonal() * inv_s * s.asDiagonal();
  inverse = 0.5 * (inverse + inverse.transpose()).eval();
  return ratio;
}

// Below this, a bore's (or the held rows') scaled matrix counts as singular.
constexpr double kSingular = 1e-10;

}  // namespace

// ---------------------------------------------------------------------------

RigidBoreCondensation::RigidBoreCondensation(fem::LinearStaticAnalysis& analysis, const fem::Mesh& mesh,
                                             std::vector<RigidBoreInterface> interfaces, const Log& log,
                                             RigidBoreOptions options)
    : analysis_(analysis), mesh_(mesh), interfaces_(std::move(interfaces)) {
  Stopwatch clock;
  require(!interfaces_.empty(), "rigid bores: no interfaces given");
  require(options.chunk_columns >= 1, "rigid bores: chunk_columns = {} must be >= 1", options.chunk_columns);
  require(3 * mesh_.node_count() == analysis_.dofs().dof_count(),
          "rigid bores: the mesh has {} nodes ({} DoFs), the analysis {} DoFs: not the analysis's mesh",
          mesh_.node_count(), 3 * mesh_.node_count(), analysis_.dofs().dof_count());
  const Eigen::VectorXd& prescribed = analysis_.dofs().prescribed_values();
  require(prescribed.size() == 0 || prescribed.cwiseAbs().maxCoeff() == 0.0,
          "rigid bores: the part's supports prescribe a nonzero displacement ({:.6g} m); the condensation needs "
          "K_s^-1 to be linear (a support that holds at zero, e.g. fem::three_two_one_support)",
          prescribed.cwiseAbs().maxCoeff());

  collect_bores();
  number_face_dofs();
  condense(face_flexibility(options.chunk_columns));
  interface_columns();
  stats_.setup_seconds = clock.seconds();
  log.info("{}", summary());
}

void RigidBoreCondensation::collect_bores() {
  std::map<std::string, int> bore_of_set;
  for (size_t l = 0; l < interfaces_.size(); ++l) {
    const RigidBoreInterface& in = interfaces_[l];
    require(in.reference_m.allFinite(), "rigid bores: interface {} (face set '{}') has a reference point that is not finite",
            l, in.face_set);
    const auto it = bore_of_set.find(in.face_set);
    if (it != bore_of_set.end()) {
      bore_of_interface_.push_back(it->second);
      continue;
    }
    Bore bore;
    bore.face_set = in.face_set;
    bore.reference_m = in.reference_m;
    try {
      bore.nodes = fem::nodes_of_faces(mesh_.face_set(in.face_set));
    } catch (const Error& e) {
      fail("rigid bores: interface {}: {}", l, e.what());
    }
    require(!bore.nodes.empty(), "rigid bores: face set '{}' has no nodes", in.face_set);
    bore_of_set.emplace(in.face_set, int(bores_.size()));
    bore_of_interface_.push_back(int(bores_.size()));
    bores_.push_back(std::move(bore));
  }
  // A node can follow one rigid bore only.
  std::vector<int> owner(size_t(mesh_.node_count()), -1);
  for (size_t b = 0; b < bores_.size(); ++b)
    for (fem::Index n : bores_[b].nodes) {
      const int o = owner[size_t(n)];
      if (o >= 0) {
        const Vector3d x = mesh_.nodes.row(n).transpose();
        fail(
            "rigid bores: face sets '{}' and '{}' share node {} at ({:.6g}, {:.6g}, {:.6g}) m; a node can follow one "
            "rigid bore only (put the two interfaces on one face set, or make the face sets disjoint)",
            bores_[size_t(o)].face_set, bores_[b].face_set, n, x.x(), x.y(), x.z());
      }
      owner[size_t(n)] = int(b);
    }
  // q_l = X_l q_b: interface l's motion from its bore's.
  const Eigen::Index m = Eigen::Index(interfaces_.size()), nb = Eigen::Index(bores_.size());
  transfer_ = Eigen::MatrixXd::Zero(6 * m, 6 * nb);
  for (Eigen::Index l = 0; l < m; ++l) {
    const int b = bore_of_interface_[size_t(l)];
    transfer_.block<6, 6>(6 * l, 6 * b) = transfer(interfaces_[size_t(l)].reference_m - bores_[size_t(b)].reference_m);
  }
  stats_.interfaces = int(m);
  stats_.bores = int(nb);
  for (const Bore& b : bores_) stats_.face_nodes += long(b.nodes.size());
}

void RigidBoreCondensation::number_face_dofs() {
  // T rows of each face DoF: u_n = t + theta x (x_n - x_ref) = [I, -skew(x_n - x_ref)] q_b.
  std::vector<Eigen::Matrix<double, 1, 6>> free_rows, held_rows;
  std::vector<int> free_bore, held_bore;
  for (size_t b = 0; b < bores_.size(); ++b)
    for (fem::Index n : bores_[b].nodes) {
      const Vector3d arm = mesh_.nodes.row(n).transpose() - bores_[b].reference_m;
      Eigen::Matrix<double, 3, 6> T;
      T << Eigen::Matrix3d::Identity(), -skew(arm);
      for (int c = 0; c < 3; ++c) {
        const fem::Index dof = 3 * n + c;
        const bool held = analysis_.dofs().equation(dof) < 0;
        (held ? held_dofs_ : free_dofs_).push_back(dof);
        (held ? held_rows : free_rows).push_back(T.row(c));
        (held ? held_bore : free_bore).push_back(int(b));
      }
    }
  const Eigen::Index nb = Eigen::Index(bores_.size());
  auto fill = [&](const std::vector<Eigen::Matrix<double, 1, 6>>& rows, const std::vector<int>& bore) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(Eigen::Index(rows.size()), 6 * nb);
    for (size_t r = 0; r < rows.size(); ++r) M.block<1, 6>(Eigen::Index(r), 6 * bore[r]) = rows[r];
    return M;
  };
  t_free_ = fill(free_rows, free_bore);
  t_held_ = fill(held_rows, held_bore);
  stats_.free_face_dofs = long(free_dofs_.size());
  stats_.held_face_dofs = long(held_dofs_.size());
}

Eigen::MatrixXd RigidBoreCondensation::face_flexibility(int chunk_columns) {
  // F_SS = B K_s^-1 B^T, chunk by chunk: of each block of solves only B x is kept.
  Stopwatch clock;
  const Eigen::Index kf = Eigen::Index(free_dofs_.size()), ndof = 3 * mesh_.node_count();
  Eigen::MatrixXd F(kf, kf);
  for (Eigen::Index first = 0; first < kf; first += chunk_columns) {
    const Eigen::Index count = std::min<Eigen::Index>(chunk_columns, kf - first);
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(ndof, count);
    for (Eigen::Index j = 0; j < count; ++j) unit(free_dofs_[size_t(first + j)], j) = 1.0;
    const std::vector<fem::DisplacementField> fields = analysis_.solve_forces(unit);
    for (Eigen::Index j = 0; j < count; ++j) {
      const double* x = fields[size_t(j)].data();
      for (Eigen::Index i = 0; i < kf; ++i) F(i, first + j) = x[free_dofs_[size_t(i)]];
    }
  }
  stats_.setup_solves += long(kf);
  stats_.face_solve_seconds = clock.seconds();
  const double chunk_bytes = 2.0 * double(ndof) * double(std::min<Eigen::Index>(chunk_columns, kf)) * 8.0;
  stats_.working_bytes = chunk_bytes + 2.0 * double(kf) * double(kf) * 8.0;
  return F;
}

void RigidBoreCondensation::condense(const Eigen::MatrixXd& face_flexibility) {
  Stopwatch clock;
  const Eigen::Index kf = face_flexibility.rows();
  // Cholesky of the Jacobi-scaled F_SS (SPD: the support holds the part, the face DoFs are free ones).
  require(kf == 0 || face_flexibility.diagonal().minCoeff() > 0,
          "rigid bores: a face DoF has zero flexibility under the part's support");
  face_scale_ = face_flexibility.diagonal().cwiseSqrt().cwiseInverse();
  face_factor_.compute(face_scale_.asDiagonal() * (0.5 * (face_flexibility + face_flexibility.transpose())) *
                       face_scale_.asDiagonal());
  require(face_factor_.info() == Eigen::Success,
          "rigid bores: the face flexibility B K_s^-1 B^T ({} x {}) is not positive definite", kf, kf);

  // A = T_f^T F_SS^-1 T_f (6b x 6b), its inverse, and the projection that keeps T_p q = 0.
  const Eigen::MatrixXd Y = solve_face(t_free_);  // F_SS^-1 T_f
  const Eigen::MatrixXd A = t_free_.transpose() * Y;
  Eigen::MatrixXd A_inv;
  for (size_t b = 0; b < bores_.size(); ++b) {
    Eigen::MatrixXd unused;
    const double ratio = spd_inverse(A.block<6, 6>(6 * Eigen::Index(b), 6 * Eigen::Index(b)), kSingular, unused);
    require(ratio > kSingular,
            "rigid bores: face set '{}' cannot hold a rigid motion of its reference point (its {} nodes' "
            "stiffness against the six motions is singular, ratio {:.1e}: nodes on one line?)",
            bores_[b].face_set, bores_[b].nodes.size(), ratio);
  }
  const double ratio = spd_inverse(A, kSingular, A_inv);
  require(ratio > kSingular, "rigid bores: the bores' stiffness T^T F_SS^-1 T is singular (ratio {:.1e})", ratio);

  Eigen::MatrixXd F_bore = A_inv;
  const Eigen::Index kp = t_held_.rows();
  reaction_held_ = Eigen::MatrixXd::Zero(kp, A.cols());
  if (kp > 0) {
    const Eigen::MatrixXd AiTp = A_inv * t_held_.transpose();  // 6b x k_p
    Eigen::MatrixXd S_inv;
    const double held_ratio = spd_inverse(t_held_ * AiTp, kSingular, S_inv);
    require(held_ratio > kSingular,
            "rigid bores: the part's supports hold {} DoFs of the bores' nodes, more than a rigid motion of the bores "
            "allows (ratio {:.1e}); a statically determinate support (fem::three_two_one_support) is needed",
            kp, held_ratio);
    reaction_held_ = S_inv * AiTp.transpose();  // E_b = S^-1 T_p A^-1
    F_bore = A_inv - AiTp * reaction_held_;
    F_bore = 0.5 * (F_bore + F_bore.transpose()).eval();
  }
  reaction_free_ = Y * F_bore;  // H_b = F_SS^-1 T_f F_b
  flexibility_ = transfer_ * F_bore * transfer_.transpose();
  flexibility_ = 0.5 * (flexibility_ + flexibility_.transpose()).eval();
  stats_.factor_seconds = clock.seconds();
}

void RigidBoreCondensation::interface_columns() {
  // D_b: the bores' nodal loads of unit bore loads (free face DoFs: H_b;
  // held ones: E_b), Z_Db = K_s^-1 D_b (6b solves); D = D_b X^T, Z_D = Z_Db X^T.
  Stopwatch clock;
  const Eigen::Index ndof = 3 * mesh_.node_count(), nb6 = transfer_.cols();
  Eigen::MatrixXd D_bore = Eigen::MatrixXd::Zero(ndof, nb6);
  for (size_t i = 0; i < free_dofs_.size(); ++i) D_bore.row(free_dofs_[i]) = reaction_free_.row(Eigen::Index(i));
  for (size_t i = 0; i < held_dofs_.size(); ++i) D_bore.row(held_dofs_[i]) = reaction_held_.row(Eigen::Index(i));
  const Eigen::MatrixXd Z_bore = solve_columns(analysis_, D_bore);
  stats_.setup_solves += long(nb6);
  loads_ = D_bore * transfer_.transpose();
  load_displacement_ = Z_bore * transfer_.transpose();
  const Eigen::MatrixXd check = loads_.transpose() * load_displacement_;
  const double size = flexibility_.cwiseAbs().maxCoeff();
  stats_.consistency = size > 0 ? (check - flexibility_).cwiseAbs().maxCoeff() / size : 0.0;
  stats_.interface_solve_seconds = clock.seconds();
  stats_.working_bytes += 2.0 * double(ndof) * double(nb6 + loads_.cols()) * 8.0;
}

Eigen::MatrixXd RigidBoreCondensation::solve_face(const Eigen::MatrixXd& rhs) const {
  return face_scale_.asDiagonal() * face_factor_.solve(face_scale_.asDiagonal() * rhs);
}

Eigen::MatrixXd RigidBoreCondensation::free_face_reactions(const Eigen::MatrixXd& load_displacement_block) const {
  // W d_S = F_SS^-1 d_S - H_b T_f^T F_SS^-1 d_S.
  const Eigen::Index kf = Eigen::Index(free_dofs_.size()), P = load_displacement_block.cols();
  Eigen::MatrixXd d(kf, P);
  for (Eigen::Index i = 0; i < kf; ++i) d.row(i) = load_displacement_block.row(free_dofs_[size_t(i)]);
  const Eigen::MatrixXd y = solve_face(d);
  return y - reaction_free_ * (t_free_.transpose() * y);
}

Eigen::MatrixXd RigidBoreCondensation::correction(const Eigen::MatrixXd& load_displacement_block) {
  Stopwatch clock;
  const Eigen::Index ndof = 3 * mesh_.node_count(), P = load_displacement_block.cols();
  require(load_displacement_block.rows() == ndof, "rigid bores: correction of a block with {} rows, the part has {} DoFs",
          load_displacement_block.rows(), ndof);
  Eigen::MatrixXd loads = Eigen::MatrixXd::Zero(ndof, P);
  if (P == 0) return loads;
  const Eigen::MatrixXd w = free_face_reactions(load_displacement_block);
  for (size_t i = 0; i < free_dofs_.size(); ++i) loads.row(free_dofs_[i]) = -w.row(Eigen::Index(i));
  Eigen::MatrixXd c = solve_columns(analysis_, loads);
  stats_.correction_solves += long(P);
  stats_.correction_seconds += clock.seconds();
  return c;
}

Eigen::MatrixXd RigidBoreCondensation::face_loads(const Eigen::MatrixXd& interface_loads,
                                                  const Eigen::MatrixXd& load_displacement_block) const {
  const Eigen::Index ndof = 3 * mesh_.node_count(), P = interface_loads.cols();
  require(interface_loads.rows() == transfer_.rows() && load_displacement_block.rows() == ndof &&
              load_displacement_block.cols() == P,
          "rigid bores: face_loads of {} x {} interface loads and {} x {} load displacements; expected {} and {} rows, "
          "as many columns",
          interface_loads.rows(), interface_loads.cols(), load_displacement_block.rows(),
          load_displacement_block.cols(), transfer_.rows(), ndof);
  const Eigen::Index kf = Eigen::Index(free_dofs_.size());
  Eigen::MatrixXd d(kf, P);
  for (Eigen::Index i = 0; i < kf; ++i) d.row(i) = load_displacement_block.row(free_dofs_[size_t(i)]);
  const Eigen::MatrixXd y = solve_face(d);
  const Eigen::MatrixXd bore_loads = transfer_.transpose() * interface_loads;  // sum X_l^T lambda_l
  const Eigen::MatrixXd free = reaction_free_ * bore_loads - (y - reaction_free_ * (t_free_.transpose() * y));
  const Eigen::MatrixXd held = reaction_held_ * (bore_loads + t_free_.transpose() * y);
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(ndof, P);
  for (Eigen::Index i = 0; i < kf; ++i) out.row(free_dofs_[size_t(i)]) = free.row(i);
  for (size_t i = 0; i < held_dofs_.size(); ++i) out.row(held_dofs_[i]) = held.row(Eigen::Index(i));
  return out;
}

const std::vector<fem::Index>& RigidBoreCondensation::face_nodes(int interface) const {
  require(interface >= 0 && size_t(interface) < interfaces_.size(), "rigid bores: no interface {} (of {})", interface,
          interfaces_.size());
  return bores_[size_t(bore_of_interface_[size_t(interface)])].nodes;
}

std::string RigidBoreCondensation::summary() const {
  const RigidBoreStatistics& s = stats_;
  return fmt::format(
      "rigid bores: {} interface(s) on {} bore(s), {} face nodes, {} free face DoFs ({} held by the support); {} solves "
      "at setup; F_SS {:.3f} s, factor {:.3f} s, Z_D {:.3f} s, setup {:.3f} s, ~{:.1f} MB dense; |D^T Z_D - F_r| "
      "{:.1e}",
      s.interfaces, s.bores, s.face_nodes, s.free_face_dofs, s.held_face_dofs, s.setup_solves, s.face_solve_seconds,
      s.factor_seconds, s.interface_solve_seconds, s.setup_seconds, s.working_bytes * 1e-6, s.consistency);
}

std::vector<fem::Index> rigid_bore_support_candidates(const fem::Mesh& mesh, const std::vector<std::string>& face_sets) {
  std::vector<char> on_bore(size_t(mesh.node_count()), 0);
  for (const std::string& name : face_sets)
    for (fem::Index n : fem::nodes_of_faces(mesh.face_set(name))) on_bore[size_t(n)] = 1;
  std::vector<fem::Index> out;
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    if (!on_bore[size_t(n)]) out.push_back(n);
  require(out.size() >= 3, "rigid bores: only {} nodes lie off the face sets, too few for a 3-2-1 support", out.size());
  return out;
}

}  // namespace kinetofem::structure
