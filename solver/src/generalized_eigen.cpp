#include "kinetofem/solver/generalized_eigen.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/LU>
#include <Spectra/SymGEigsShiftSolver.h>

#include "kinetofem/core/log.hpp"

namespace kinetofem::fem {

namespace {

using Vec = Eigen::VectorXd;

// Spectra's operator concepts (the members SymGEigsShiftSolver calls) over
// type-erased operators.
class ShiftInverseOp {
 public:
  using Scalar = double;
  explicit ShiftInverseOp(const EigenOperators& ops) : ops_(ops) {}
  Eigen::Index rows() const { return ops_.size; }
  Eigen::Index cols() const { return ops_.size; }
  // The shift is built into the operator; Spectra passes the same sigma on.
  void set_shift(double sigma) {
    require(sigma == ops_.shift_rad2_s2, "eigen solve: shift {} does not match the operator's {}",
            sigma, ops_.shift_rad2_s2);
  }
  void perform_op(const double* x, double* y) const {
    ops_.shift_inverse(Eigen::Map<const Vec>(x, ops_.size), Eigen::Map<Vec>(y, ops_.size));
    ++applications_;
  }
  long long applications() const { return applications_; }

 private:
  const EigenOperators& ops_;
  mutable long long applications_ = 0;
};

class MassOp {
 public:
  using Scalar = double;
  explicit MassOp(const EigenOperators& ops) : ops_(ops) {}
  Eigen::Index rows() const { return ops_.size; }
  Eigen::Index cols() const { return ops_.size; }
  void perform_op(const double* x, double* y) const {
    ops_.mass(Eigen::Map<const Vec>(x, ops_.size), Eigen::Map<Vec>(y, ops_.size));
  }

 private:
  const EigenOperators& ops_;
};

}  // namespace

double frequency_hz(double omega2) {
  const double w = std::sqrt(std::abs(omega2));
  return (omega2 < 0 ? -w : w) / (2.0 * std::numbers::pi);
}

void check_mass_positive(const SymmetricUpperMatrix& mass, const std::string& label) {
  for (Eigen::Index c = 0; c < mass.outerSize(); ++c) {
    double diagonal = 0.0;
    for (SymmetricUpperMatrix::InnerIterator it(mass, c); it; ++it)
      if (it.row() == c) diagonal = it.value();
    if (!(diagonal > 0.0) || !std::isfinite(diagonal))
      fail("mass matrix of '{}' is not positive: equation {} has diagonal {:.3e} kg (zero "
           "density, or a node no element gives mass)",
           label, c, diagonal);
  }
}

EigenSolution solve_eigen(const EigenOperators& ops, const EigenOptions& options, const Log* log) {
  const Stopwatch clock;
  const Eigen::Index n = ops.size;
  const Eigen::Index nev = options.modes;
  require(options.modes >= 1, "eigen solve of '{}': number of modes {} must be at least 1",
          options.label, options.modes);
  require(nev < n, "eigen solve of '{}': {} modes wanted, the problem has only {} equations",
          options.label, nev, n);
  require(options.max_restarts >= 1 && options.tolerance > 0,
          "eigen solve of '{}': max_restarts {} must be >= 1 and tolerance {} > 0", options.label,
          options.max_restarts, options.tolerance);
  Eigen::Index ncv = options.lanczos_vectors > 0 ? options.lanczos_vectors
                                                 : std::max(2 * nev + 1, nev + 20);
  ncv = std::min(ncv, n);
  require(ncv > nev, "eigen solve of '{}': {} Lanczos vectors must exceed the {} modes",
          options.label, ncv, nev);

  ShiftInverseOp op(ops);
  MassOp bop(ops);
  Spectra::SymGEigsShiftSolver<ShiftInverseOp, MassOp, Spectra::GEigsMode::ShiftInvert> solver(
      op, bop, nev, ncv, ops.shift_rad2_s2);
  if (ops.start.size() == n)
    solver.init(ops.start.data());
  else
    solver.init();
  const Eigen::Index converged = solver.compute(Spectra::SortRule::LargestMagn,
                                                options.max_restarts, options.tolerance,
                                                Spectra::SortRule::SmallestAlge);
  EigenSolution out;
  EigenStatistics& stats = out.statistics;
  stats.size = n;
  stats.converged = converged;
  stats.restarts = solver.num_iterations();
  stats.operator_applications = op.applications();
  if (solver.info() != Spectra::CompInfo::Successful) {
    stats.seconds = clock.seconds();
    throw EigenNotConverged(
        fmt::format("eigen solve of '{}' did not converge: {} of {} modes converged after {} "
                    "restarts ({} solves, {} Lanczos vectors, tolerance {:.1e}); raise the "
                    "Lanczos vectors or the restarts, or move the shift",
                    options.label, converged, nev, stats.restarts, stats.operator_applications,
                    ncv, options.tolerance),
        stats);
  }
  out.omega2_rad2_s2 = solver.eigenvalues();
  out.modes = solver.eigenvectors();
  // Spectra sorts SmallestAlge descending-first in some versions: sort ascending.
  std::vector<Eigen::Index> order(static_cast<size_t>(nev));
  for (Eigen::Index i = 0; i < nev; ++i) order[size_t(i)] = i;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return out.omega2_rad2_s2[a] < out.omega2_rad2_s2[b];
  });
  const Vec values = out.omega2_rad2_s2;
  const Eigen::MatrixXd vectors = out.modes;
  for (Eigen::Index i = 0; i < nev; ++i) {
    out.omega2_rad2_s2[i] = values[order[size_t(i)]];
    out.modes.col(i) = vectors.col(order[size_t(i)]);
  }

  // Mass-normalize (Lanczos in the M-inner product already is, to its
  // tolerance) and check residuals and M-orthogonality.
  out.frequency_hz.resize(nev);
  Eigen::MatrixXd Mphi(n, nev);
  Vec Kphi(n);
  for (Eigen::Index i = 0; i < nev; ++i) {
    auto phi = out.modes.col(i);
    ops.mass(phi, Mphi.col(i));
    const double norm2 = phi.dot(Mphi.col(i));
    require(norm2 > 0 && std::isfinite(norm2),
            "eigen solve of '{}': mode {} has mass norm {:.3e} (mass matrix not positive)",
            options.label, i + 1, norm2);
    phi /= std::sqrt(norm2);
    Mphi.col(i) /= std::sqrt(norm2);
    ops.stiffness(phi, Kphi);
    const double w2 = out.omega2_rad2_s2[i];
    // Relative to the shifted operator's scale: shift-invert resolves omega^2
    // to about |omega^2 - sigma| x tolerance, so a rigid mode's omega^2 ~ 0 is
    // measured against |sigma|.
    const double scale =
        Kphi.norm() + std::max(std::abs(w2), std::abs(ops.shift_rad2_s2)) * Mphi.col(i).norm();
    const double residual = scale > 0 ? (Kphi - w2 * Mphi.col(i)).norm() / scale : 0.0;
    stats.max_relative_residual = std::max(stats.max_relative_residual, residual);
    out.frequency_hz[i] = frequency_hz(w2);
  }
  const Eigen::MatrixXd gram = out.modes.transpose() * Mphi;
  stats.max_orthogonality_error =
      (gram - Eigen::MatrixXd::Identity(nev, nev)).cwiseAbs().maxCoeff();
  stats.seconds = clock.seconds();
  if (log)
    log->info("eigen '{}': {} modes of {} equations, {:.4g} .. {:.4g} Hz; shift {:.4g} (rad/s)^2, "
              "{} restarts, {} solves, residual {:.1e}, M-orthogonality {:.1e}, {:.2f} s",
              options.label, nev, n, out.frequency_hz[0], out.frequency_hz[nev - 1],
              ops.shift_rad2_s2, stats.restarts, stats.operator_applications,
              stats.max_relative_residual, stats.max_orthogonality_error, stats.seconds);
  return out;
}

EigenSolution solve_generalized_eigen(const SymmetricUpperMatrix& K, const SymmetricUpperMatrix& M,
                                      const EigenOptions& options, const LowRankMass* point_masses,
                                      const Log* log, const CholmodOptions& cholmod) {
  const Stopwatch clock;
  require(K.rows() == K.cols() && M.rows() == K.rows() && M.cols() == K.cols(),
          "eigen solve of '{}': stiffness is {} x {}, mass {} x {}", options.label, K.rows(),
          K.cols(), M.rows(), M.cols());
  check_mass_positive(M, options.label);
  const double sigma = options.shift_rad2_s2;
  require(std::isfinite(sigma), "eigen solve of '{}': shift {} is not finite", options.label,
          sigma);
  const Eigen::Index n = K.rows();
  const bool has_point_masses = point_masses && point_masses->basis.cols() > 0;
  if (has_point_masses) {
    require(point_masses->basis.rows() == n &&
                point_masses->mass.rows() == point_masses->basis.cols() &&
                point_masses->mass.cols() == point_masses->basis.cols(),
            "eigen solve of '{}': point-mass basis is {} x {}, its mass {} x {}, the model has {} "
            "equations",
            options.label, point_masses->basis.rows(), point_masses->basis.cols(),
            point_masses->mass.rows(), point_masses->mass.cols(), n);
    require(point_masses->mass.allFinite() && point_masses->basis.allFinite(),
            "eigen solve of '{}': point masses are not finite", options.label);
  }

  // K - sigma M on the common pattern: the same structure, so the value
  // arrays combine (checked).
  SymmetricUpperMatrix shifted = K;
  if (sigma != 0.0) {
    const bool same_pattern =
        K.nonZeros() == M.nonZeros() &&
        std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1, M.outerIndexPtr()) &&
        std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), M.innerIndexPtr());
    if (same_pattern)
      Eigen::Map<Vec>(shifted.valuePtr(), shifted.nonZeros()) -=
          sigma * Eigen::Map<const Vec>(M.valuePtr(), M.nonZeros());
    else
      shifted = SymmetricUpperMatrix(K - sigma * M);
  }
  CholmodSolver factor(cholmod, nullptr);
  try {
    factor.analyze(shifted);
    factor.factorize(shifted);
  } catch (const NotPositiveDefinite& e) {
    fail("eigen solve of '{}': K - sigma M is not positive definite with the shift sigma = "
         "{:.4g} (rad/s)^2 ({:.4g} Hz): the shift must lie below the lowest eigenvalue (negative "
         "for a part with rigid-body modes); {}",
         options.label, sigma, frequency_hz(sigma), e.what());
  }

  // Woodbury for the point masses: (A - sigma U C U^T)^-1 with A = K - sigma M:
  //   A^-1 x - Z (I - sigma C U^T Z)^-1 (-sigma C) U^T A^-1 x,   Z = A^-1 U.
  Eigen::MatrixXd Z;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance;
  Eigen::MatrixXd sigma_C;
  const bool woodbury = has_point_masses && sigma != 0.0;
  if (woodbury) {
    const Eigen::MatrixXd& U = point_masses->basis;
    Z = factor.solve(U);
    sigma_C = -sigma * point_masses->mass;
    const Eigen::Index p = U.cols();
    capacitance.compute(Eigen::MatrixXd::Identity(p, p) + sigma_C * (U.transpose() * Z));
  }

  EigenOperators ops;
  ops.size = n;
  ops.shift_rad2_s2 = sigma;
  ops.shift_inverse = [&](const Eigen::Ref<const Vec>& x, Eigen::Ref<Vec> y) {
    const Eigen::MatrixXd ax = factor.solve(Eigen::MatrixXd(x));
    if (woodbury)
      y = ax.col(0) -
          Z * capacitance.solve(sigma_C * (point_masses->basis.transpose() * ax.col(0)));
    else
      y = ax.col(0);
  };
  const auto Ku = K.selfadjointView<Eigen::Upper>();
  const auto Mu = M.selfadjointView<Eigen::Upper>();
  ops.mass = [&](const Eigen::Ref<const Vec>& x, Eigen::Ref<Vec> y) {
    y = Mu * x;
    if (has_point_masses)
      y += point_masses->basis * (point_masses->mass * (point_masses->basis.transpose() * x));
  };
  ops.stiffness = [&](const Eigen::Ref<const Vec>& x, Eigen::Ref<Vec> y) { y = Ku * x; };
  EigenSolution out = solve_eigen(ops, options, nullptr);
  out.statistics.factor_nonzeros = factor.statistics().factor_nonzeros;
  out.statistics.seconds = clock.seconds();  // factorization included
  if (log)
    log->info("eigen '{}': {} modes of {} equations, {:.5g} .. {:.5g} Hz; shift {:.4g} (rad/s)^2, "
              "factor nnz {:.3g}, {} restarts, {} solves, residual {:.1e}, M-orthogonality {:.1e}, "
              "{:.2f} s",
              options.label, options.modes, n, out.frequency_hz[0],
              out.frequency_hz[out.frequency_hz.size() - 1], sigma,
              out.statistics.factor_nonzeros, out.statistics.restarts,
              out.statistics.operator_applications, out.statistics.max_relative_residual,
              out.statistics.max_orthogonality_error, out.statistics.seconds);
  return out;
}

}  // namespace kinetofem::fem
