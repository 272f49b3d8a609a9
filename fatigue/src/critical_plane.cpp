#include "kinetofem/fatigue/critical_plane.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <utility>

#include <Eigen/Eigenvalues>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/miner.hpp"

namespace kinetofem::fatigue {

namespace {

// Voigt rows of the project (solver/stress_recovery.hpp).
enum : int { kXx = 0, kYy = 1, kZz = 2, kXy = 3, kYz = 4, kZx = 5 };

Eigen::Matrix3d tensor_at(const StressHistory& history, Eigen::Index t) {
  const auto s = history.col(t);
  Eigen::Matrix3d m;
  m << s(kXx), s(kXy), s(kZx),  //
      s(kXy), s(kYy), s(kYz),   //
      s(kZx), s(kYz), s(kZz);
  return m;
}

void check_history(const StressHistory& history) {
  require(history.cols() > 0, "fatigue: the stress history has no time steps");
  for (Eigen::Index t = 0; t < history.cols(); ++t) {
    for (int k = 0; k < 6; ++k) {
      require(std::isfinite(history(k, t)),
              "fatigue: stress component {} at time step {} is not finite ({})", k, t,
              history(k, t));
    }
  }
}

// n or -n: the one with z > 0, or on z = 0 with y > 0, or on y = z = 0 with x > 0.
Eigen::Vector3d canonical(const Eigen::Vector3d& n) {
  const double lead = n.z() != 0.0 ? n.z() : (n.y() != 0.0 ? n.y() : n.x());
  return lead < 0.0 ? Eigen::Vector3d(-n) : n;
}

double largest_range(const std::vector<Cycle>& cycles) {
  double r = 0.0;
  for (const Cycle& c : cycles) r = std::max(r, c.range_pa);
  return r;
}

// Damage and cycles of one scalar history.
struct Counted {
  double damage = 0.0;
  double max_range_pa = 0.0;
  std::vector<Cycle> cycles;
};

Counted count(std::span<const double> history, const SnCurve& curve, const FatigueOptions& o) {
  Counted c;
  c.cycles = rainflow_count(history, o.residue);
  c.damage = miner_damage(c.cycles, curve, o.mean_stress);
  c.max_range_pa = largest_range(c.cycles);
  return c;
}

// a better than b: larger damage, ties (relative 1e-12) to the larger range.
bool better(const Counted& a, const Counted& b) {
  const double scale = std::max(a.damage, b.damage);
  if (std::abs(a.damage - b.damage) > 1e-12 * scale) return a.damage > b.damage;
  return a.max_range_pa > b.max_range_pa;
}

}  // namespace

double covering_radius_bound_deg(double polar_spacing_deg) {
  const double h = 0.5 * polar_spacing_deg * units::kDeg;
  const double s = std::sin(0.5 * h);
  return 2.0 * std::asin(std::sqrt(s * s + 0.25 * h * h)) / units::kDeg;
}

CandidatePlanes hemisphere_planes(double max_spacing_deg) {
  require(std::isfinite(max_spacing_deg) && max_spacing_deg > 0.0 && max_spacing_deg <= 90.0,
          "fatigue: candidate plane spacing {} deg must be in (0, 90]", max_spacing_deg);
  const int rings = static_cast<int>(std::ceil(90.0 / max_spacing_deg - 1e-9));
  const double dtheta = 90.0 / rings;
  std::vector<Eigen::Vector3d> normals;
  normals.emplace_back(0.0, 0.0, 1.0);
  for (int i = 1; i <= rings; ++i) {
    const double theta_deg = i * dtheta;
    const double theta = theta_deg * units::kDeg;
    const double outer = std::min(theta_deg + 0.5 * dtheta, 90.0) * units::kDeg;
    const int m = static_cast<int>(std::ceil(360.0 * std::sin(outer) / dtheta - 1e-9));
    const bool equator = i == rings;
    const int count = equator ? (m + 1) / 2 : m;  // equator: [0, 180) of an even m
    const double dphi = equator ? 180.0 / count : 360.0 / m;
    const double st = equator ? 1.0 : std::sin(theta), ct = equator ? 0.0 : std::cos(theta);
    for (int j = 0; j < count; ++j) {
      const double phi = j * dphi * units::kDeg;
      normals.emplace_back(st * std::cos(phi), st * std::sin(phi), ct);
    }
  }
  CandidatePlanes planes;
  const auto n = static_cast<Eigen::Index>(normals.size());
  planes.normals.resize(n, 3);
  planes.projection.resize(n, 6);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d& v = normals[static_cast<std::size_t>(k)];
    planes.normals.row(k) = v.transpose();
    planes.projection(k, kXx) = v.x() * v.x();
    planes.projection(k, kYy) = v.y() * v.y();
    planes.projection(k, kZz) = v.z() * v.z();
    planes.projection(k, kXy) = 2.0 * v.x() * v.y();
    planes.projection(k, kYz) = 2.0 * v.y() * v.z();
    planes.projection(k, kZx) = 2.0 * v.z() * v.x();
  }
  planes.polar_spacing_deg = dtheta;
  planes.covering_radius_deg = covering_radius_bound_deg(dtheta);
  return planes;
}

PlaneHistories normal_stress_histories(const CandidatePlanes& planes,
                                       const StressHistory& history) {
  PlaneHistories out = planes.projection * history;
  return out;
}

Eigen::VectorXd max_principal_history(const StressHistory& history) {
  Eigen::VectorXd out(history.cols());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  for (Eigen::Index t = 0; t < history.cols(); ++t) {
    solver.compute(tensor_at(history, t), Eigen::EigenvaluesOnly);
    out(t) = solver.eigenvalues()(2);
  }
  return out;
}

Eigen::VectorXd signed_von_mises_history(const StressHistory& history) {
  Eigen::VectorXd out(history.cols());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  for (Eigen::Index t = 0; t < history.cols(); ++t) {
    const auto s = history.col(t);
    const double d1 = s(kXx) - s(kYy), d2 = s(kYy) - s(kZz), d3 = s(kZz) - s(kXx);
    const double vm = std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) +
                                3.0 * (s(kXy) * s(kXy) + s(kYz) * s(kYz) + s(kZx) * s(kZx)));
    solver.compute(tensor_at(history, t), Eigen::EigenvaluesOnly);
    const double sum13 = solver.eigenvalues()(2) + solver.eigenvalues()(0);
    out(t) = sum13 < 0.0 ? -vm : vm;
  }
  return out;
}

NodeFatigue assess_node(const StressHistory& history, const SnCurve& curve,
                        const FatigueOptions& options) {
  if (options.measure != StressMeasure::CriticalPlane) {
    return assess_node(history, curve, options, CandidatePlanes{});
  }
  return assess_node(history, curve, options, hemisphere_planes(options.plane_spacing_deg));
}

NodeFatigue assess_node(const StressHistory& history, const SnCurve& curve,
                        const FatigueOptions& options, const CandidatePlanes& planes) {
  check_history(history);
  NodeFatigue result;
  if (options.measure == StressMeasure::CriticalPlane) {
    require(planes.projection.rows() > 0, "fatigue: no candidate planes for the critical plane");
    const PlaneHistories sigma_n = normal_stress_histories(planes, history);
    const auto steps = static_cast<std::size_t>(sigma_n.cols());
    Counted best;
    int best_plane = -1;
    // Shortcut, the same result: a plane's largest counted range is its
    // max - min, and mean stress treatment only lowers ranges; if the curve
    // gives the largest max - min of all planes no damage, every plane has
    // D = 0 and the tie rule picks the first plane of the largest range, so
    // only that plane needs counting.
    const Eigen::VectorXd spread = sigma_n.rowwise().maxCoeff() - sigma_n.rowwise().minCoeff();
    Eigen::Index widest = 0;
    const double widest_range = spread.maxCoeff(&widest);
    const bool undamaged = std::isinf(curve.endurance(widest_range));
    if (undamaged) {
      best = count(std::span<const double>(sigma_n.row(widest).data(), steps), curve, options);
      best_plane = static_cast<int>(widest);
    }
    for (Eigen::Index k = 0; !undamaged && k < sigma_n.rows(); ++k) {
      Counted c = count(std::span<const double>(sigma_n.row(k).data(), steps), curve, options);
      if (best_plane < 0 || better(c, best)) {
        best = std::move(c);
        best_plane = static_cast<int>(k);
      }
    }
    result.damage = best.damage;
    result.max_range_pa = best.max_range_pa;
    result.cycles = std::move(best.cycles);
    result.plane = best_plane;
    result.planes_searched = static_cast<int>(sigma_n.rows());
    result.normal = planes.normals.row(best_plane).transpose();
    return result;
  }
  const Eigen::VectorXd scalar = options.measure == StressMeasure::MaxPrincipal
                                     ? max_principal_history(history)
                                     : signed_von_mises_history(history);
  Counted c = count(std::span<const double>(scalar.data(), static_cast<std::size_t>(scalar.size())),
                    curve, options);
  result.damage = c.damage;
  result.max_range_pa = c.max_range_pa;
  result.cycles = std::move(c.cycles);
  if (options.measure == StressMeasure::MaxPrincipal) {
    Eigen::Index t_max = 0;
    scalar.maxCoeff(&t_max);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor_at(history, t_max));
    result.normal = canonical(solver.eigenvectors().col(2));
  }
  return result;
}

}  // namespace kinetofem::fatigue
