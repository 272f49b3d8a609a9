#include "kinetofem/vibration/craig_bampton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <numeric>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::vibration {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Rows of the free equations of a 3N x k matrix.
MatrixXd restrict_rows(const MatrixXd& full, const fem::DofMap& dofs) {
  MatrixXd out = MatrixXd::Zero(dofs.free_count(), full.cols());
  for (Index d = 0; d < full.rows(); ++d)
    if (const Index eq = dofs.equation(d); eq >= 0) out.row(eq) = full.row(d);
  return out;
}

// K with the equations `removed` deleted (upper triangle), and the map
// equation -> reduced equation (-1: removed).
fem::SymmetricUpperMatrix remove_equations(const fem::SymmetricUpperMatrix& K,
                                           const std::vector<Index>& removed,
                                           std::vector<Index>& map) {
  map.assign(size_t(K.rows()), 0);
  for (Index r : removed) map[size_t(r)] = -1;
  Index next = 0;
  for (auto& m : map) m = (m < 0) ? -1 : next++;
  std::vector<Eigen::Triplet<double, std::int64_t>> entries;
  entries.reserve(size_t(K.nonZeros()));
  for (Index c = 0; c < K.outerSize(); ++c)
    for (fem::SymmetricUpperMatrix::InnerIterator it(K, c); it; ++it) {
      const Index i = map[size_t(it.row())], j = map[size_t(c)];
      if (i >= 0 && j >= 0) entries.emplace_back(i, j, it.value());
    }
  fem::SymmetricUpperMatrix out(next, next);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// K_s^-1 B over the free equations of the part's DofMap (n x k -> n x k,
// zero at the 3-2-1 DoFs of a free part).
using StaticSolve = std::function<MatrixXd(const MatrixXd&)>;

// The part's own factorization of K_s (K less the 3-2-1 equations).
class OwnFactor {
 public:
  OwnFactor(const fem::SymmetricUpperMatrix& K, const std::vector<Index>& support_equations,
            const std::string& label)
      : n_(K.rows()) {
    if (support_equations.empty()) {
      Ks_ = K;
      map_.resize(size_t(n_));
      std::iota(map_.begin(), map_.end(), Index(0));
    } else {
      Ks_ = remove_equations(K, support_equations, map_);
    }
    try {
      factor_.analyze(Ks_);
      factor_.factorize(Ks_);
    } catch (const fem::NotPositiveDefinite& e) {
      fail("Craig-Bampton reduction of '{}': the part's stiffness is singular with its supports "
           "(a part held in some directions only is not supported; give all supports or none): {}",
           label, e.what());
    }
  }
  MatrixXd solve(const MatrixXd& B) {
    MatrixXd Bs(Ks_.rows(), B.cols());
    for (Index i = 0; i < n_; ++i)
      if (map_[size_t(i)] >= 0) Bs.row(map_[size_t(i)]) = B.row(i);
    const MatrixXd Xs = factor_.solve(Bs);
    MatrixXd X = MatrixXd::Zero(n_, B.cols());
    for (Index i = 0; i < n_; ++i)
      if (map_[size_t(i)] >= 0) X.row(i) = Xs.row(map_[size_t(i)]);
    return X;
  }
  double factor_nonzeros() const { return factor_.statistics().factor_nonzeros; }

 private:
  Index n_;
  fem::SymmetricUpperMatrix Ks_;
  std::vector<Index> map_;
  fem::CholmodSolver factor_;
};

// The small matrix S and the two operators built on K_s (header).
class PartSolver {
 public:
  PartSolver(StaticSolve static_solve, const MatrixXd& G, const MatrixXd& R,
             const std::string& label)
      : static_solve_(std::move(static_solve)), G_(G), R_(R), label_(label) {
    ZG_ = solve(G_);
    const Index nb = G_.cols(), r = R_.cols();
    MatrixXd S = MatrixXd::Zero(nb + r, nb + r);
    S.topLeftCorner(nb, nb) = G_.transpose() * ZG_;
    S.topLeftCorner(nb, nb) = 0.5 * (S.topLeftCorner(nb, nb) + S.topLeftCorner(nb, nb).transpose()).eval();
    if (r > 0) {
      const MatrixXd H = G_.transpose() * R_;
      S.topRightCorner(nb, r) = H;
      S.bottomLeftCorner(r, nb) = H.transpose();
    }
    // Diagonal scaling: boundary rows by 1/sqrt(F_ii), rigid rows by the
    // scaled H's column norms, so the rank test is unit-free.
    // A coordinate on a 3-2-1 support DoF has F_ii = 0 (its motion is
    // rigid-body only, carried by H): the mean flexibility scales it.
    scale_ = VectorXd::Ones(nb + r);
    const double mean_flexibility = nb > 0 ? S.diagonal().head(nb).mean() : 1.0;
    for (Index i = 0; i < nb; ++i) {
      require(G_.col(i).norm() > 0, "Craig-Bampton reduction of '{}': boundary coordinate {} "
              "is zero (an interface on prescribed DoFs only)", label, i);
      require(mean_flexibility > 0, "Craig-Bampton reduction of '{}': the interfaces have no "
              "flexibility", label);
      scale_[i] = 1.0 / std::sqrt(S(i, i) > 1e-12 * mean_flexibility ? S(i, i) : mean_flexibility);
    }
    for (Index j = 0; j < r; ++j) {
      const double norm = (scale_.head(nb).asDiagonal() * S.col(nb + j).head(nb)).norm();
      require(norm > 0, "Craig-Bampton reduction of '{}': the interfaces do not hold the free "
              "part's rigid-body motion {}", label, j);
      scale_[nb + j] = 1.0 / norm;
    }
    small_.setThreshold(1e-10);
    small_.compute(scale_.asDiagonal() * S * scale_.asDiagonal());
    require(small_.rank() == nb + r,
            "Craig-Bampton reduction of '{}': the interfaces' {} boundary coordinates do not hold "
            "the part's {} rigid-body modes, or depend on each other (rank {} of {})",
            label, nb, r, small_.rank(), nb + r);
  }

  // K_s^-1 B (zero at the 3-2-1 DoFs).
  MatrixXd solve(const MatrixXd& B) {
    solves_ += B.cols();
    return static_solve_(B);
  }
  // S^-1 rhs.
  MatrixXd solve_small(const MatrixXd& rhs) const {
    return scale_.asDiagonal() * small_.solve(scale_.asDiagonal() * rhs);
  }
  MatrixXd constraint_modes() const {
    const Index nb = G_.cols(), r = R_.cols();
    MatrixXd rhs = MatrixXd::Zero(nb + r, nb);
    rhs.topRows(nb).setIdentity();
    const MatrixXd LA = solve_small(rhs);
    MatrixXd Psi = ZG_ * LA.topRows(nb);
    if (r > 0) Psi += R_ * LA.bottomRows(r);
    return Psi;
  }
  // Y = K_0^+ B: K y = b + G mu, G^T y = 0 per column (header).
  MatrixXd fixed_interface_inverse(const MatrixXd& B) {
    const Index nb = G_.cols(), r = R_.cols();
    const MatrixXd ZB = solve(B);
    MatrixXd rhs(nb + r, B.cols());
    rhs.topRows(nb) = -G_.transpose() * ZB;
    if (r > 0) rhs.bottomRows(r) = -R_.transpose() * B;
    const MatrixXd mu_alpha = solve_small(rhs);
    MatrixXd Y = ZB + ZG_ * mu_alpha.topRows(nb);
    if (r > 0) Y += R_ * mu_alpha.bottomRows(r);
    return Y;
  }
  long long solves() const { return solves_; }

 private:
  StaticSolve static_solve_;
  const MatrixXd& G_;
  const MatrixXd& R_;
  std::string label_;
  MatrixXd ZG_;
  VectorXd scale_;
  Eigen::FullPivLU<MatrixXd> small_;
  long long solves_ = 0;
};

}  // namespace

PartInterface coupling_interface(const fem::Mesh& mesh, const std::string& face_set,
                                 const Eigen::Vector3d& reference_point_m, std::string name) {
  const fem::DistributingCoupling coupling(mesh, face_set);
  PartInterface out{std::move(name), MatrixXd::Zero(3 * mesh.node_count(), 6)};
  for (int k = 0; k < 6; ++k) {
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
    (k < 3 ? force : moment)[k % 3] = 1.0;
    coupling.add(force, moment, reference_point_m, out.columns.col(k));
  }
  return out;
}

PartInterface nodal_interface(const fem::Mesh& mesh, const std::vector<fem::Index>& nodes,
                              std::string name) {
  PartInterface out{std::move(name), MatrixXd::Zero(3 * mesh.node_count(), 3 * Index(nodes.size()))};
  for (size_t k = 0; k < nodes.size(); ++k) {
    require(nodes[k] >= 0 && nodes[k] < mesh.node_count(),
            "interface '{}': node {} is not in the mesh ({} nodes)", out.name, nodes[k],
            mesh.node_count());
    for (int c = 0; c < 3; ++c) out.columns(3 * nodes[k] + c, 3 * Index(k) + c) = 1.0;
  }
  return out;
}

namespace {

void check_options(const CraigBamptonOptions& options, const std::string& label) {
  require(!options.fixed_interface_modes || (options.highest_frequency_of_interest_hz > 0 &&
                                             std::isfinite(options.highest_frequency_of_interest_hz)),
          "Craig-Bampton reduction of '{}': highest frequency of interest {} Hz must be positive",
          label, options.highest_frequency_of_interest_hz);
  require(options.cutoff_factor >= 1 && std::isfinite(options.cutoff_factor),
          "Craig-Bampton reduction of '{}': cutoff factor {} must be at least 1", label,
          options.cutoff_factor);
  require(options.first_batch >= 1 && options.max_modes >= options.first_batch,
          "Craig-Bampton reduction of '{}': first batch {} and max modes {} must satisfy 1 <= "
          "first batch <= max modes",
          label, options.first_batch, options.max_modes);
  require(options.residual_tolerance > 0 && options.residual_tolerance < 1,
          "Craig-Bampton reduction of '{}': residual tolerance {} must lie in (0, 1)", label,
          options.residual_tolerance);
}

// Random fields of the start block (header): the modes X_0 does not excite.
constexpr Index kRandomStartColumns = 4;
// Ritz vectors expanded beyond the wanted ones (header): measured on the
// lever-chain manipulator's links, 2 gave the fewest solves' worth of time
// (6: 1.3-1.9 x as long; the whole latest block, block Davidson: 3 x).
constexpr Index kExtraRitzVectors = 2;
// The basis restarts from its lowest Ritz vectors beyond this many columns.
constexpr Index kBasisBeforeRestart = 60;
// Block steps before the block Davidson gives up (each one solve of a block).
constexpr int kMaxBlockSteps = 200;

// A block of fields with its mass products, tracked through every linear
// combination so that M is applied once per block (a sparse product with a
// block costs about as much as a tenth of a block solve here).
struct MassBlock {
  MatrixXd x, mx;  // n x k: the fields and M times them
};

// W made M-orthonormal to V (M-orthonormal) and within itself; columns that
// depend on V or on each other (Gram eigenvalue below 1e-12 of the largest
// column's) are dropped. Twice, against round-off. Each pass first takes W
// back onto G^T u = 0 (QG: orthonormal basis of G's columns, MQG = M QG):
// the normalization of a nearly dependent column magnifies its round-off off
// the constraint, where the energy is lower, and the Ritz values would sink
// below the constrained problem's.
MassBlock m_orthonormalize(MassBlock W, const MassBlock& V, const MatrixXd& QG, const MatrixXd& MQG) {
  if (W.x.cols() == 0) return W;
  double reference = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    const MatrixXd off = QG.transpose() * W.x;
    W.x -= QG * off;
    W.mx -= MQG * off;
    for (int twice = 0; twice < 2 && V.x.cols() > 0; ++twice) {
      const MatrixXd c = V.mx.transpose() * W.x;
      W.x -= V.x * c;
      W.mx -= V.mx * c;
    }
    const Eigen::SelfAdjointEigenSolver<MatrixXd> gram(0.5 * (W.x.transpose() * W.mx + W.mx.transpose() * W.x));
    if (pass == 0) reference = std::max(gram.eigenvalues().maxCoeff(), 0.0);
    std::vector<Index> keep;
    for (Index j = 0; j < W.x.cols(); ++j)
      if (gram.eigenvalues()[j] > 1e-12 * reference) keep.push_back(j);
    MatrixXd T(W.x.cols(), Index(keep.size()));
    for (size_t j = 0; j < keep.size(); ++j)
      T.col(Index(j)) = gram.eigenvectors().col(keep[j]) / std::sqrt(gram.eigenvalues()[keep[j]]);
    W.x = (W.x * T).eval();
    W.mx = (W.mx * T).eval();
    if (W.x.cols() == 0) break;
    reference = 1.0;
  }
  return W;
}

}  // namespace

// What one part's reduction reuses between its calls (header).
struct CraigBamptonReducer::Impl {
  std::string label;
  fem::Mesh mesh;
  fem::DofMap dofs;
  Index n = 0, nb = 0;
  bool free_body = false;
  std::vector<std::string> interface_names;
  std::vector<Index> interface_offset;
  fem::SymmetricUpperMatrix K, M;
  MatrixXd G, R;
  fem::LinearStaticAnalysis* supported = nullptr;  // lent, or null: `own`
  std::unique_ptr<OwnFactor> own;
  StaticSolve static_solve;  // K_s^-1 with the analysis lent or `own`
  std::unique_ptr<PartSolver> solver;  // made by the first reduce()
  MatrixXd constraint_modes, mass_psi, static_response;  // Psi, M Psi, X_0 = K_0^+ M Psi
  double factor_nonzeros = 0.0;
  std::array<double, 5> setup_phase{};
  double setup_seconds = 0.0;
  long long setup_solves = 0;
  bool setup_reported = false;

  // `analysis`: a free part's 3-2-1-supported analysis, or a held part's own
  // (its supports in `part`); null: own factorization of `part`.
  Impl(const fem::FeModel& part, const std::vector<PartInterface>& interfaces, std::string name,
       fem::LinearStaticAnalysis* analysis);

  fem::EigenSolution block_lanczos(double cutoff_hz, const CraigBamptonOptions& options) const;
  fem::EigenSolution spectra_lanczos(double cutoff_hz, const CraigBamptonOptions& options) const;
  // The solves of the set-up (Z_G, Psi, X_0), on the first reduce().
  void solve_set_up();
  CraigBamptonModel reduce(const CraigBamptonOptions& options, const Log* log);
};

CraigBamptonReducer::Impl::Impl(const fem::FeModel& part, const std::vector<PartInterface>& interfaces,
                                std::string name, fem::LinearStaticAnalysis* analysis)
    : label(std::move(name)), mesh(part.mesh), dofs(part.mesh.node_count(), part.supports),
      supported(analysis) {
  const Stopwatch clock;
  require(!interfaces.empty(), "Craig-Bampton reduction of '{}': no interface given", label);
  n = dofs.free_count();
  // The 3-2-1 support of a free part: its own, or the analysis's.
  const std::vector<fem::DisplacementSupport> determinate =
      supported ? supported->model().supports
                : (part.supports.empty() ? fem::three_two_one_support(mesh, [&] {
                    std::vector<fem::Index> all(size_t(mesh.node_count()));
                    std::iota(all.begin(), all.end(), fem::Index(0));
                    return all;
                  }())
                                         : std::vector<fem::DisplacementSupport>{});
  Stopwatch phase;
  const fem::ElementMaterials materials = fem::element_materials(part);
  K = fem::assemble_stiffness(mesh, materials, dofs).free_free;
  M = fem::assemble_mass(mesh, materials, dofs);
  fem::check_mass_positive(M, label);

  // Boundary coordinates.
  for (const auto& itf : interfaces) {
    require(itf.columns.rows() == 3 * mesh.node_count(),
            "Craig-Bampton reduction of '{}': interface '{}' has {} rows, the mesh {} DoFs", label,
            itf.name, itf.columns.rows(), 3 * mesh.node_count());
    interface_names.push_back(itf.name);
    interface_offset.push_back(nb);
    nb += itf.columns.cols();
  }
  interface_offset.push_back(nb);
  G.resize(n, nb);
  for (size_t k = 0; k < interfaces.size(); ++k)
    G.middleCols(interface_offset[k], interfaces[k].columns.cols()) = restrict_rows(interfaces[k].columns, dofs);

  // A free body: 3-2-1 support and its rigid-body modes about the centroid.
  R.resize(n, 0);
  std::vector<Index> support_equations;
  free_body = part.supports.empty();
  if (free_body) {
    for (const auto& s : determinate)
      for (fem::Index node : s.nodes)
        for (int c = 0; c < 3; ++c)
          if (s.fixed[size_t(c)]) support_equations.push_back(dofs.equation(3 * node + c));
    const Eigen::Vector3d centre = mesh.nodes.colwise().mean().transpose();
    R.resize(n, 6);
    for (int k = 0; k < 6; ++k) {
      Eigen::Vector3d t = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();
      (k < 3 ? t : w)[k % 3] = 1.0;
      const VectorXd field = fem::rigid_body_field(mesh, t - w.cross(centre), w);
      R.col(k) = restrict_rows(field, dofs);
    }
  }
  if (supported) {
    const fem::DofMap& sd = supported->dofs();
    if (free_body) {
      // The free part's static solve over all 3N DoFs, with its 3-2-1 support:
      // check that it is one (6 prescribed DoFs holding the six rigid modes).
      std::sort(support_equations.begin(), support_equations.end());
      support_equations.erase(std::unique(support_equations.begin(), support_equations.end()),
                              support_equations.end());
      MatrixXd Rs(Index(support_equations.size()), 6);
      for (size_t i = 0; i < support_equations.size(); ++i) Rs.row(Index(i)) = R.row(support_equations[i]);
      require(sd.prescribed_count() == 6 && Eigen::FullPivLU<MatrixXd>(Rs).rank() == 6,
              "Craig-Bampton reduction of '{}': the given static analysis has {} prescribed DoFs; a "
              "statically determinate (3-2-1) support of the free part is needed",
              label, sd.prescribed_count());
    } else {
      // A part held by the analysis's own supports: the same free equations.
      require(sd.free_count() == n && sd.prescribed_count() == dofs.prescribed_count(),
              "Craig-Bampton reduction of '{}': the given static analysis has {} free DoFs, the held part {}",
              label, sd.free_count(), n);
    }
    // B and the result over the free equations of `dofs` (all 3N for a free
    // part); the analysis takes and gives all 3N DoFs.
    static_solve = [this](const MatrixXd& B) {
      const Index nodes = mesh.node_count();
      MatrixXd full = MatrixXd::Zero(3 * nodes, B.cols());
      for (Index d = 0; d < 3 * nodes; ++d)
        if (const Index eq = dofs.equation(d); eq >= 0) full.row(d) = B.row(eq);
      const std::vector<fem::DisplacementField> u = supported->solve_forces(full);
      for (Index k = 0; k < B.cols(); ++k)
        full.col(k) = Eigen::Map<const Eigen::VectorXd>(u[size_t(k)].data(), 3 * nodes);
      return restrict_rows(full, dofs);
    };
  } else {
    own = std::make_unique<OwnFactor>(K, support_equations, label);
    static_solve = [o = own.get()](const MatrixXd& B) { return o->solve(B); };
    factor_nonzeros = own->factor_nonzeros();
  }
  setup_phase[0] = phase.seconds();
  setup_seconds = clock.seconds();
}

void CraigBamptonReducer::Impl::solve_set_up() {
  const Stopwatch clock;
  Stopwatch phase;
  if (supported) factor_nonzeros = supported->solver_statistics().factor_nonzeros;
  solver = std::make_unique<PartSolver>(static_solve, G, R, label);
  constraint_modes = solver->constraint_modes();
  setup_phase[1] = phase.seconds();
  phase.restart();
  // The static response to the constraint modes' inertia (sparse times dense
  // blocks, all columns at once: several times faster than column by column).
  mass_psi = M.selfadjointView<Eigen::Upper>() * constraint_modes;
  static_response = solver->fixed_interface_inverse(mass_psi);
  setup_phase[3] = phase.seconds();
  setup_solves = solver->solves();
  setup_seconds += clock.seconds();
}

fem::EigenSolution CraigBamptonReducer::Impl::block_lanczos(double cutoff_hz,
                                                            const CraigBamptonOptions& options) const {
  const Stopwatch clock;
  const auto Ku = K.selfadjointView<Eigen::Upper>();
  const auto Mu = M.selfadjointView<Eigen::Upper>();
  const double cutoff_w2 = std::pow(2.0 * std::numbers::pi * cutoff_hz, 2);
  const Index interior = n - nb - R.cols();  // dimension of the fixed-interface space (<=)
  const long long solves_before = solver->solves();
  // Random fields inside G^T u = 0 (the seed of the single-vector Lanczos).
  std::mt19937_64 random(12345);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto random_fields = [&](Index count) {
    MatrixXd v(n, count);
    for (Index j = 0; j < count; ++j)
      for (Index i = 0; i < n; ++i) v(i, j) = uniform(random);
    return solver->fixed_interface_inverse(MatrixXd(Mu * v));
  };
  MassBlock start;
  start.x.resize(n, static_response.cols() + kRandomStartColumns);
  start.x << static_response, random_fields(kRandomStartColumns);
  start.mx = Mu * start.x;
  const Index p = start.x.cols();
  // Orthonormal basis of the interface columns: the constraint G^T u = 0 is
  // QG^T u = 0, and the residuals are taken off them (their reactions G mu
  // are admitted).
  const Eigen::HouseholderQR<MatrixXd> qr(G);
  MatrixXd QG = MatrixXd::Identity(n, nb);
  QG.applyOnTheLeft(qr.householderQ());  // the thin Q, without forming the n x n one
  const MatrixXd MQG = Mu * QG;
  MassBlock V = m_orthonormalize(std::move(start), MassBlock{MatrixXd(n, 0), MatrixXd(n, 0)}, QG, MQG);
  // H = V^T K V, grown block by block (V^T M V = I).
  MatrixXd H = V.x.transpose() * (Ku * V.x);
  MassBlock block = V;

  fem::EigenSolution out;
  out.statistics.size = n;
  for (int step = 0;; ++step) {
    const Eigen::SelfAdjointEigenSolver<MatrixXd> ritz(0.5 * (H + H.transpose()));
    const VectorXd& theta = ritz.eigenvalues();
    Index below = 0;
    while (below < theta.size() && theta[below] <= cutoff_w2) ++below;
    require(below < options.max_modes,
            "Craig-Bampton reduction of '{}': {} fixed-interface modes lie below the cutoff "
            "{:.4g} Hz (max modes {}): raise max_modes or lower the cutoff",
            label, below, cutoff_hz, options.max_modes);
    const Index need = below + 1;  // every mode kept and the first dropped
    Index converged = 0;
    std::vector<bool> done;  // per wanted Ritz pair: converged
    double worst = 0.0;
    if (need <= theta.size()) {
      const MatrixXd phi = V.x * ritz.eigenvectors().leftCols(need);
      const MatrixXd Kphi = Ku * phi, Mphi = V.mx * ritz.eigenvectors().leftCols(need);
      for (Index j = 0; j < need; ++j) {
        VectorXd r = Kphi.col(j) - theta[j] * Mphi.col(j);
        r -= QG * (QG.transpose() * r);
        const double relative = r.norm() / (Kphi.col(j).norm() + std::abs(theta[j]) * Mphi.col(j).norm());
        worst = std::max(worst, relative);
        // The first dropped only has to lie above the cutoff: its frequency
        // (error ~ residual^2) is printed, not used.
        if (relative <= (j < below ? options.residual_tolerance : std::sqrt(options.residual_tolerance)))
          ++converged, done.push_back(true);
        else
          done.push_back(false);
      }
      if (converged == need) {
        out.omega2_rad2_s2 = theta.head(need);
        out.frequency_hz.resize(need);
        for (Index j = 0; j < need; ++j) out.frequency_hz[j] = fem::frequency_hz(theta[j]);
        out.modes = phi;
        out.statistics.converged = need;
        out.statistics.max_relative_residual = worst;
        break;
      }
    }
    require(need <= theta.size() || V.x.cols() < interior,
            "Craig-Bampton reduction of '{}': all {} fixed-interface modes lie below the cutoff {:.4g} Hz: lower "
            "the cutoff or refine the part",
            label, theta.size(), cutoff_hz);
    if (step >= kMaxBlockSteps || V.x.cols() >= interior) {
      out.statistics.converged = converged;
      out.statistics.operator_applications = solver->solves() - solves_before;
      out.statistics.seconds = clock.seconds();
      throw fem::EigenNotConverged(
          fmt::format("Craig-Bampton reduction of '{}': block Davidson: {} of the {} fixed-interface modes up to "
                      "the first above the cutoff {:.4g} Hz converged after {} block solves (largest relative "
                      "residual {:.2e}, tolerance {:.1e})",
                      label, converged, need, cutoff_hz, step, worst, options.residual_tolerance),
          out.statistics);
    }
    // The block to expand: the wanted Ritz vectors not converged yet and the
    // next kExtraRitzVectors (header).
    std::vector<Index> expand;
    for (Index j = 0; j < std::min<Index>(theta.size(), need + kExtraRitzVectors); ++j)
      if (j >= Index(done.size()) || !done[size_t(j)]) expand.push_back(j);
    MatrixXd Y(theta.size(), Index(expand.size()));
    for (size_t j = 0; j < expand.size(); ++j) Y.col(Index(j)) = ritz.eigenvectors().col(expand[j]);
    block = {V.x * Y, V.mx * Y};
    if (V.x.cols() + Y.cols() > std::max(kBasisBeforeRestart, 2 * (need + kExtraRitzVectors))) {
      // Restart from the lowest Ritz vectors.
      const Index keep = std::min<Index>(V.x.cols(), need + kExtraRitzVectors);
      const MatrixXd Z = ritz.eigenvectors().leftCols(keep);
      V.x = (V.x * Z).eval();
      V.mx = (V.mx * Z).eval();
      H = theta.head(keep).asDiagonal();
    }
    MassBlock W;
    W.x = solver->fixed_interface_inverse(block.mx);
    W.mx = Mu * W.x;
    W = m_orthonormalize(std::move(W), V, QG, MQG);
    if (W.x.cols() == 0) {  // an invariant subspace: widen it
      W.x = random_fields(p);
      W.mx = Mu * W.x;
      W = m_orthonormalize(std::move(W), V, QG, MQG);
    }
    const MatrixXd KW = Ku * W.x;
    const MatrixXd C = V.x.transpose() * KW;
    MatrixXd grown(H.rows() + W.x.cols(), H.cols() + W.x.cols());
    grown << H, C, C.transpose(), W.x.transpose() * KW;
    H = std::move(grown);
    MatrixXd widened(n, V.x.cols() + W.x.cols()), widened_m(n, V.x.cols() + W.x.cols());
    widened << V.x, W.x;
    widened_m << V.mx, W.mx;
    V = {std::move(widened), std::move(widened_m)};
    block = std::move(W);
  }
  out.statistics.operator_applications = solver->solves() - solves_before;
  out.statistics.seconds = clock.seconds();
  return out;
}

fem::EigenSolution CraigBamptonReducer::Impl::spectra_lanczos(double cutoff_hz,
                                                              const CraigBamptonOptions& options) const {
  // Growing batches until one lies above the cutoff.
  const auto Ku = K.selfadjointView<Eigen::Upper>();
  const auto Mu = M.selfadjointView<Eigen::Upper>();
  fem::EigenOperators ops;
  ops.size = n;
  ops.shift_rad2_s2 = 0.0;
  ops.shift_inverse = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) {
    y = solver->fixed_interface_inverse(MatrixXd(x)).col(0);
  };
  ops.mass = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) { y = Mu * x; };
  ops.stiffness = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) { y = Ku * x; };
  {
    std::mt19937_64 random(12345);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    VectorXd v(n);
    for (Index i = 0; i < n; ++i) v[i] = uniform(random);
    ops.start = solver->fixed_interface_inverse(MatrixXd(Mu * v)).col(0);  // inside G^T u = 0
  }
  const Index interior = n - nb - R.cols();  // dimension of the fixed-interface space (<=)
  fem::EigenOptions eigen = options.eigen;
  eigen.label = label;
  eigen.modes = int(std::min<Index>(options.first_batch, interior - 1));
  fem::EigenSolution modes;
  for (;;) {
    modes = fem::solve_eigen(ops, eigen, nullptr);
    const double highest = modes.frequency_hz[modes.frequency_hz.size() - 1];
    if (highest > cutoff_hz) break;
    require(eigen.modes < options.max_modes && eigen.modes < interior - 1,
            "Craig-Bampton reduction of '{}': {} fixed-interface modes lie below the cutoff "
            "{:.4g} Hz (max modes {}): raise max_modes or lower the cutoff",
            label, eigen.modes, cutoff_hz, options.max_modes);
    eigen.modes = int(std::min<Index>({2 * Index(eigen.modes), Index(options.max_modes), interior - 1}));
  }
  return modes;
}

CraigBamptonModel CraigBamptonReducer::Impl::reduce(const CraigBamptonOptions& options, const Log* log) {
  check_options(options, label);
  if (!solver) solve_set_up();
  const Stopwatch clock;
  const long long solves_before = solver->solves();
  CraigBamptonModel out;
  out.label = label;
  out.interface_names = interface_names;
  out.interface_offset = interface_offset;
  out.boundary_count = nb;
  out.free_body = free_body;
  out.free_dofs = n;
  out.factor_nonzeros = factor_nonzeros;
  out.constraint_modes = constraint_modes;
  const auto Ku = K.selfadjointView<Eigen::Upper>();
  const auto Mu = M.selfadjointView<Eigen::Upper>();
  Stopwatch phase;
  // Fixed-interface modes: every one up to the cutoff and the first above it.
  out.cutoff_hz = options.cutoff_factor * options.highest_frequency_of_interest_hz;
  Index kept = 0;
  if (options.fixed_interface_modes) {
    const fem::EigenSolution modes = options.solver == FixedInterfaceSolver::BlockDavidson
                                         ? block_lanczos(out.cutoff_hz, options)
                                         : spectra_lanczos(out.cutoff_hz, options);
    while (kept < modes.frequency_hz.size() && modes.frequency_hz[kept] <= out.cutoff_hz) ++kept;
    out.first_dropped_hz = modes.frequency_hz[kept];
    out.normal_modes = modes.modes.leftCols(kept);
    out.normal_frequency_hz = modes.frequency_hz.head(kept);
  } else {
    out.cutoff_hz = 0.0;
    out.first_dropped_hz = std::numeric_limits<double>::quiet_NaN();
    out.normal_modes.resize(n, 0);
    out.normal_frequency_hz.resize(0);
  }
  out.mode_count = kept;
  out.phase_seconds[2] = phase.seconds();
  phase.restart();

  // Residual vectors: the fixed-interface static response to the constraint
  // modes' inertia (solved once, X_0), less its part in the kept modes
  // (header), M-orthonormal and K-diagonal among themselves.
  MatrixXd X(n, 0);
  if (options.residual_vectors) {
    X = static_response;
    if (kept > 0) {
      const Eigen::VectorXd w2 = (2.0 * std::numbers::pi * out.normal_frequency_hz).array().square();
      X -= out.normal_modes * (w2.cwiseInverse().asDiagonal() * (out.normal_modes.transpose() * mass_psi));
      // Twice, against round-off: X stays M-orthogonal to the kept modes.
      const MatrixXd MX = Mu * X;
      X -= out.normal_modes * (out.normal_modes.transpose() * MX);
    }
    const MatrixXd MX = Mu * X;
    const Eigen::SelfAdjointEigenSolver<MatrixXd> gram(X.transpose() * MX);
    const double largest = gram.eigenvalues().maxCoeff();
    std::vector<Index> keep;
    for (Index j = 0; j < X.cols(); ++j)
      if (gram.eigenvalues()[j] > 1e-12 * largest) keep.push_back(j);
    MatrixXd X1(n, Index(keep.size()));
    for (size_t j = 0; j < keep.size(); ++j)
      X1.col(Index(j)) = X * gram.eigenvectors().col(keep[j]) / std::sqrt(gram.eigenvalues()[keep[j]]);
    const MatrixXd KX1 = Ku * X1, MX1 = Mu * X1;
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> diag(X1.transpose() * KX1, X1.transpose() * MX1);
    X = X1 * diag.eigenvectors();
    out.residual_frequency_hz.resize(X.cols());
    for (Index j = 0; j < X.cols(); ++j) out.residual_frequency_hz[j] = fem::frequency_hz(diag.eigenvalues()[j]);
  }
  out.residual_vectors = X;
  out.residual_count = X.cols();
  out.phase_seconds[3] = phase.seconds();
  phase.restart();

  // Reduced matrices by projection.
  MatrixXd T(n, nb + kept + X.cols());
  T << constraint_modes, out.normal_modes, X;
  const MatrixXd KT = Ku * T, MT = Mu * T;
  out.stiffness = T.transpose() * KT;
  out.mass = T.transpose() * MT;
  out.stiffness = (0.5 * (out.stiffness + out.stiffness.transpose())).eval();
  out.mass = (0.5 * (out.mass + out.mass.transpose())).eval();
  const double kmax = out.stiffness.cwiseAbs().maxCoeff();
  const Index interior_count = kept + X.cols();
  out.coupling_stiffness_check =
      interior_count > 0 ? out.stiffness.bottomLeftCorner(interior_count, nb).cwiseAbs().maxCoeff() / kmax : 0.0;
  double constraint = (G.transpose() * constraint_modes - MatrixXd::Identity(nb, nb)).cwiseAbs().maxCoeff();
  if (kept > 0)
    constraint = std::max(constraint, (G.transpose() * out.normal_modes).cwiseAbs().maxCoeff() /
                                          out.normal_modes.cwiseAbs().maxCoeff());
  out.constraint_check = constraint;
  out.phase_seconds[4] = phase.seconds();
  out.lanczos_solves = solver->solves() - solves_before;
  out.seconds = clock.seconds();
  if (!setup_reported) {
    // The set-up (K and M, Psi, X_0) belongs to the first model made.
    setup_reported = true;
    out.phase_seconds[0] += setup_phase[0];
    out.phase_seconds[1] += setup_phase[1];
    out.phase_seconds[3] += setup_phase[3];
    out.lanczos_solves += setup_solves;
    out.seconds += setup_seconds;
  }
  // A static reduction (no fixed-interface modes) is the part-mode rule's bound, which only
  // bounds the frequencies wanted; the reduction used follows with its own lines.
  if (log && std::isnan(out.first_dropped_hz))
    log->detail("{}", format_check(out));
  else if (log)
    log->info("{}", format_check(out));
  if (log)
    log->detail("  time: K and M {:.2f} s, constraint modes {:.2f} s, fixed-interface modes {:.2f} s, residual "
                "vectors {:.2f} s, projection {:.2f} s",
                out.phase_seconds[0], out.phase_seconds[1], out.phase_seconds[2], out.phase_seconds[3],
                out.phase_seconds[4]);
  return out;
}

CraigBamptonReducer::CraigBamptonReducer(const fem::FeModel& part, const std::vector<PartInterface>& interfaces,
                                         const std::string& label)
    : impl_(std::make_unique<Impl>(part, interfaces, label, nullptr)) {}

namespace {

// The model a lent analysis reduces: a free part's without its 3-2-1
// support (mesh, materials and all), a held part's as it is.
fem::FeModel reduced_model(const fem::LinearStaticAnalysis& analysis, bool held, const std::string& label) {
  fem::FeModel part = analysis.model();
  if (held)
    require(!part.supports.empty(),
            "Craig-Bampton reduction of '{}': the held part's static analysis has no supports (a free part: use "
            "reduce_craig_bampton)", label);
  else
    part.supports.clear();
  return part;
}

}  // namespace

CraigBamptonReducer::CraigBamptonReducer(fem::LinearStaticAnalysis& analysis,
                                         const std::vector<PartInterface>& interfaces, const std::string& label,
                                         bool held)
    : impl_(std::make_unique<Impl>(reduced_model(analysis, held, label), interfaces, label, &analysis)) {}

CraigBamptonReducer::~CraigBamptonReducer() = default;
CraigBamptonReducer::CraigBamptonReducer(CraigBamptonReducer&&) noexcept = default;
CraigBamptonReducer& CraigBamptonReducer::operator=(CraigBamptonReducer&&) noexcept = default;

CraigBamptonModel CraigBamptonReducer::reduce(const CraigBamptonOptions& options, const Log* log) {
  return impl_->reduce(options, log);
}

CraigBamptonModel reduce_craig_bampton(const fem::FeModel& part, const std::vector<PartInterface>& interfaces,
                                       const CraigBamptonOptions& options, const Log* log) {
  check_options(options, options.eigen.label);
  return CraigBamptonReducer(part, interfaces, options.eigen.label).reduce(options, log);
}

CraigBamptonModel reduce_craig_bampton(fem::LinearStaticAnalysis& supported,
                                       const std::vector<PartInterface>& interfaces,
                                       const CraigBamptonOptions& options, const Log* log) {
  check_options(options, options.eigen.label);
  return CraigBamptonReducer(supported, interfaces, options.eigen.label, false).reduce(options, log);
}

CraigBamptonModel reduce_held_craig_bampton(fem::LinearStaticAnalysis& held,
                                            const std::vector<PartInterface>& interfaces,
                                            const CraigBamptonOptions& options, const Log* log) {
  check_options(options, options.eigen.label);
  return CraigBamptonReducer(held, interfaces, options.eigen.label, true).reduce(options, log);
}

Eigen::MatrixXd expand_to_mesh_dofs(const Eigen::MatrixXd& free_rows, const fem::DofMap& dofs) {
  require(free_rows.rows() == dofs.free_count(), "expand_to_mesh_dofs: {} rows for {} free equations",
          free_rows.rows(), dofs.free_count());
  MatrixXd out = MatrixXd::Zero(dofs.dof_count(), free_rows.cols());
  for (Index d = 0; d < out.rows(); ++d)
    if (const Index eq = dofs.equation(d); eq >= 0) out.row(d) = free_rows.row(eq);
  return out;
}

std::string format_check(const CraigBamptonModel& m) {
  std::string text = fmt::format(
      "Craig-Bampton '{}': {} free DoFs{} -> {} coordinates ({} boundary over {} interface(s), "
      "{} fixed-interface modes, {} residual vectors); factor nnz {:.3g}, {} solves, {:.2f} s\n",
      m.label, m.free_dofs, m.free_body ? " (free body: 3-2-1 support + 6 rigid modes)" : "",
      m.boundary_count + m.mode_count + m.residual_count, m.boundary_count,
      m.interface_names.size(), m.mode_count, m.residual_count, m.factor_nonzeros,
      m.lanczos_solves, m.seconds);
  if (std::isnan(m.first_dropped_hz))
    text += "  static reduction: constraint modes and residual vectors, no fixed-interface modes\n";
  else
    text += fmt::format(
      "  part-mode rule: keep fixed-interface modes up to the cutoff {:.5g} Hz; kept {} "
      "({:.5g} .. {:.5g} Hz), first dropped {:.5g} Hz ({:.2f} x cutoff: the rule {})\n",
      m.cutoff_hz, m.mode_count, m.mode_count ? m.normal_frequency_hz[0] : 0.0,
      m.mode_count ? m.normal_frequency_hz[m.mode_count - 1] : 0.0, m.first_dropped_hz,
      m.first_dropped_hz / m.cutoff_hz, m.first_dropped_hz > m.cutoff_hz ? "holds" : "FAILS");
  text += fmt::format("  checks: |Phi^T K Psi| / max|K_r| = {:.1e}, interface constraint {:.1e}",
                      m.coupling_stiffness_check, m.constraint_check);
  return text;
}

Eigen::VectorXd dense_frequencies_hz(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M,
                                     Eigen::Index count) {
  require(K.rows() == K.cols() && M.rows() == K.rows() && M.cols() == K.cols(),
          "dense eigen solve: stiffness {} x {}, mass {} x {}", K.rows(), K.cols(), M.rows(),
          M.cols());
  require(count >= 1 && count <= K.rows(), "dense eigen solve: {} frequencies of a {}-DoF model",
          count, K.rows());
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(K, M, Eigen::EigenvaluesOnly);
  require(eig.info() == Eigen::Success,
          "dense eigen solve: the mass matrix is not positive definite ({} DoFs)", K.rows());
  VectorXd f(count);
  for (Index i = 0; i < count; ++i) f[i] = fem::frequency_hz(eig.eigenvalues()[i]);
  return f;
}

}  // namespace kinetofem::vibration
