#include "assembly_modes_shared.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"

namespace kinetofem::vibration::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using structure::detail::rotate6;
using structure::detail::skew;
using structure::detail::transfer;

Matrix6d point_mass_6x6(double m, const Vector3d& c) {
  Eigen::Matrix<double, 3, 6> L;
  L << Eigen::Matrix3d::Identity(), -skew(c);
  return m * L.transpose() * L;
}

int find_face_interface(const std::vector<CbInterface>& interfaces, const std::string& face_set) {
  for (size_t i = 0; i < interfaces.size(); ++i)
    if (interfaces[i].face_set == face_set) return int(i);
  return -1;
}

void add_face_interface(std::vector<CbInterface>& interfaces, const std::string& label, const std::string& name,
                        const std::string& face_set, const Vector3d& reference, const MatrixXd& columns) {
  const int i = find_face_interface(interfaces, face_set);
  if (i < 0) {
    interfaces.push_back({name, face_set, reference, columns, Matrix6d::Zero()});
    return;
  }
  // The coupling's motion at another reference point is the rigid transfer
  // of its motion at the first: G_k = G_first transfer(arm)^T.
  const CbInterface& first = interfaces[size_t(i)];
  const MatrixXd moved = first.columns * transfer(reference - first.reference).transpose();
  const double error = (moved - columns).cwiseAbs().maxCoeff();
  require(error <= 1e-9 * columns.cwiseAbs().maxCoeff(),
          "vibration: {}: the {} on face set '{}' does not move rigidly with '{}' on the same face (columns differ by "
          "{:.2e})",
          label, name, face_set, first.name, error);
}

void carry_point_mass(std::vector<CbInterface>& interfaces, const fem::Mesh& mesh, const std::string& face_set,
                      const Vector3d& reference, const std::string& name, double mass_kg,
                      const Eigen::Matrix3d& inertia_kgm2) {
  int i = find_face_interface(interfaces, face_set);
  if (i < 0) {
    interfaces.push_back({"mass." + name, face_set, reference,
                          vibration::coupling_interface(mesh, face_set, reference, name).columns, Matrix6d::Zero()});
    i = int(interfaces.size()) - 1;
  }
  CbInterface& carrier = interfaces[size_t(i)];
  carrier.mass += point_mass_6x6(mass_kg, reference - carrier.reference);
  carrier.mass.bottomRightCorner<3, 3>() += inertia_kgm2;
}

MatrixXd interface_map(const std::vector<InterfaceMap>& map, const std::vector<Eigen::Matrix3d>& body_rotation,
                       Index n) {
  MatrixXd U = MatrixXd::Zero(6 * Index(map.size()), n);
  for (size_t k = 0; k < map.size(); ++k) {
    const InterfaceMap& im = map[k];
    const Matrix6d Q = rotate6(body_rotation[size_t(im.body_index)]);
    U.block<6, 6>(6 * Index(k), im.column) = Q * transfer(im.arm);
  }
  return U;
}

MatrixXd null_space_basis(const MatrixXd& constraints, const VectorXd& scale) {
  const Index n = scale.size();
  MatrixXd A = constraints * scale.asDiagonal();
  if (A.rows() == 0) return scale.asDiagonal();
  Eigen::ColPivHouseholderQR<MatrixXd> qr(A.transpose());
  qr.setThreshold(1e-10);
  const Index rank = qr.rank();
  const MatrixXd Q = qr.householderQ();
  return scale.asDiagonal() * Q.rightCols(n - rank);
}

PoseModes modes_on_basis(MatrixXd Kc, MatrixXd Mc, const MatrixXd& N, int count, double t) {
  // Diagonal scaling to unit modal mass (kg, kg m^2 and modal coordinates mixed).
  const VectorXd d = Mc.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  Kc = d.asDiagonal() * Kc * d.asDiagonal();
  Mc = d.asDiagonal() * Mc * d.asDiagonal();
  Kc = (0.5 * (Kc + Kc.transpose())).eval();
  Mc = (0.5 * (Mc + Mc.transpose())).eval();
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(Kc, Mc);
  require(eig.info() == Eigen::Success,
          "vibration at t = {:.6g} s: the reduced mass matrix is not positive definite (a body without mass?)", t);
  PoseModes out;
  out.t = t;
  out.constrained_size = N.cols();
  out.omega_rad_s.resize(count);
  out.frequency_hz.resize(count);
  for (int i = 0; i < count; ++i) {
    const double w2 = eig.eigenvalues()(i);
    out.omega_rad_s(i) = w2 > 0 ? std::sqrt(w2) : 0.0;
    out.frequency_hz(i) = fem::frequency_hz(w2);
  }
  out.shapes = N * d.asDiagonal() * eig.eigenvectors().leftCols(count);
  return out;
}

void check_options(const AssemblyModesOptions& options, size_t poses) {
  require(options.modes >= 1, "vibration: modes = {}: at least one natural frequency must be wanted", options.modes);
  require(options.part_mode_cutoff_hz >= 0 && std::isfinite(options.part_mode_cutoff_hz),
          "vibration: part_mode_cutoff_hz = {} must be positive (or 0: automatic)", options.part_mode_cutoff_hz);
  require(options.cutoff_factor >= 1 && std::isfinite(options.cutoff_factor),
          "vibration: cutoff_factor = {} must be at least 1", options.cutoff_factor);
  require(poses > 0, "vibration: no poses to estimate the frequencies of");
}

PartRuleResult reduce_parts_by_rule(const AssemblyModesOptions& options, size_t poses, const PartRuleSteps& steps,
                                    const Log& log) {
  const size_t parts = steps.parts;
  PartRuleResult result;
  vibration::CraigBamptonOptions cbo;
  if (options.part_mode_cutoff_hz > 0) {
    cbo.highest_frequency_of_interest_hz = options.part_mode_cutoff_hz;
    cbo.cutoff_factor = 1.0;
    for (size_t p = 0; p < parts; ++p) {
      vibration::CraigBamptonReducer reducer = steps.make_reducer(p);
      steps.borrow(p);
      steps.take(p, reducer.reduce(steps.part_options(p, cbo), &log));
      steps.give_back(p);
    }
  } else {
    // K and M of every part in order (no factor: a massless part is named
    // in order); the set-up's solves from the last part to the first (the
    // set-up's order backwards: a lender one at a time may still hold the
    // last part's factor), then the fixed-interface modes from the first,
    // whose factor serves both without being lent twice.
    std::vector<vibration::CraigBamptonReducer> reducers;
    for (size_t p = 0; p < parts; ++p) reducers.push_back(steps.make_reducer(p));
    cbo.fixed_interface_modes = false;  // the bound: the set-up's solves only
    for (size_t p = parts; p-- > 0;) {
      steps.borrow(p);
      steps.take(p, reducers[p].reduce(steps.part_options(p, cbo), &log));
      if (p > 0) steps.give_back(p);
    }
    result.fmax_estimate_hz = steps.static_fmax_hz();
    require(result.fmax_estimate_hz > 0, "vibration: the static reduction gives no positive frequency (a mechanism?)");
    log.info(
        "vibration: part-mode rule: f_max <= {:.5g} Hz (static reduction over {} poses, an upper bound); "
        "cutoff = {:.3g} x f_max",
        result.fmax_estimate_hz, poses, options.cutoff_factor);
    cbo = {};
    cbo.highest_frequency_of_interest_hz = result.fmax_estimate_hz;
    cbo.cutoff_factor = options.cutoff_factor;
    for (size_t p = 0; p < parts; ++p) {
      if (p > 0) steps.borrow(p);
      steps.take(p, reducers[p].reduce(steps.part_options(p, cbo), &log));
      steps.give_back(p);
      const vibration::CraigBamptonReducer done = std::move(reducers[p]);  // its K, M, Z_G, X_0 go
    }
  }
  result.cutoff_hz = cbo.cutoff_factor * cbo.highest_frequency_of_interest_hz;
  return result;
}

std::string format_rule(const AssemblyModesOptions& options, double cutoff_hz, double highest_frequency_seen_hz) {
  const bool given = options.part_mode_cutoff_hz > 0;
  const double required = given ? 1.0 : options.cutoff_factor;
  return fmt::format(
      "part-mode rule: every fixed-interface mode up to {:.5g} Hz kept ({}), plus the residual vectors; the highest "
      "assembly frequency wanted over the poses solved is {:.5g} Hz, so the cutoff is {:.2f} x it (required {:.2f}): "
      "{}",
      cutoff_hz, given ? "given" : "automatic", highest_frequency_seen_hz, cutoff_hz / highest_frequency_seen_hz,
      required,
      cutoff_hz >= required * highest_frequency_seen_hz * (1 - 1e-12) ? "holds" : "FAILS (raise part_mode_cutoff_hz)");
}

}  // namespace kinetofem::vibration::detail
