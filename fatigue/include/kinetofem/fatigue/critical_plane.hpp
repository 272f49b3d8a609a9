#pragma once
// Fatigue damage of one node's stress-tensor history: the critical-plane
// search over candidate planes, or the damage of a scalar equivalent stress.
//
// Units: stresses in Pa, angles in degrees where named _deg, damage per
// repetition of the history (the history is one load cycle, e.g. one motion
// cycle of the robot).
//
// Stress history: a 6 x T matrix, one column per time step, in the Voigt
// order of the solver's stress recovery (solver/stress_recovery.hpp):
//   (xx, yy, zz, xy, yz, zx), tensor (not engineering) shear components.
//
// StressMeasure::CriticalPlane. The normal stress on the plane of unit
// normal n is sigma_n = n^T sigma n
//   = nx^2 sxx + ny^2 syy + nz^2 szz + 2 nx ny sxy + 2 ny nz syz + 2 nz nx szx,
// so the histories of all candidate planes are one matrix product
// P (n_planes x 6, rows [nx^2, ny^2, nz^2, 2nxny, 2nynz, 2nznx]) times the
// 6 x T history. Each plane's history is rainflow counted (rainflow.hpp) and
// its Miner damage taken (miner.hpp); the critical plane is the one of the
// largest damage, ties (relative 1e-12, e.g. all below the cut-off: D = 0)
// going to the larger largest range, then to the first plane.
//
// Candidate planes (hemisphere_planes): n and -n are one plane, so the
// normals cover the hemisphere z >= 0. Polar angle theta from +z in rings
// theta_i = i * dtheta, i = 0..K, K = ceil(90 deg / spacing), dtheta = 90 / K
// (<= spacing): the pole, then on ring i >= 1 M_i equally spaced azimuths
// phi_j = j * 360 / M_i (j = 0..M_i-1) with
//   M_i = ceil(360 * sin(min(theta_i + dtheta/2, 90 deg)) / dtheta),
// so neighbours on a ring are at most dtheta apart along the band's outer
// edge; the equator ring (theta = 90 deg) keeps the azimuths in [0, 180)
// (the others are their opposites). Spacing 10 deg (the default): 226 planes.
// Bound guaranteed: every unit normal is within
//   delta = 2 asin( sqrt( sin^2(h/2) + h^2/4 ) ),   h = dtheta / 2 (rad),
// of a candidate normal (covering_radius_bound_deg; 7.07 deg for 10 deg):
// for p in the band of ring r (|theta_p - theta_r| <= h) and the nearest
// azimuth c on the ring (|dphi| <= 180 / M_r deg),
//   1 - cos d(p, c) = 2 sin^2((theta_p - theta_r)/2) + 2 sin theta_p sin theta_r sin^2(dphi/2)
//                  <= 2 sin^2(h/2) + 2 (sin(min(theta_r + h, 90)) dphi/2)^2
//                  <= 2 sin^2(h/2) + h^2/2.
//
// StressMeasure::MaxPrincipal: the history of the largest principal stress
// sigma_1(t) (signed); the reported normal is sigma_1's principal direction
// at the time step of the largest sigma_1 (sign: z > 0, or y > 0 on z = 0, or
// x > 0 on y = z = 0, as the candidate normals).
// StressMeasure::SignedVonMises: sigma_vM(t) times the sign of the principal
// stress of largest magnitude, which is the sign of sigma_1 + sigma_3
// (|sigma_1| >= |sigma_3| <=> sigma_1 + sigma_3 >= 0); + where
// sigma_1 + sigma_3 = 0 (pure shear: round-off may give either sign there).
// No plane: the reported normal is zero.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/fatigue/mean_stress.hpp"
#include "kinetofem/fatigue/rainflow.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"

namespace kinetofem::fatigue {

// 6 x T, Voigt (xx, yy, zz, xy, yz, zx), Pa.
using StressHistory = Eigen::Matrix<double, 6, Eigen::Dynamic>;
// n_planes x T, one plane's normal stress history per (contiguous) row, Pa.
using PlaneHistories = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct CandidatePlanes {
  Eigen::Matrix<double, Eigen::Dynamic, 3> normals;     // unit normals, z >= 0
  // rows [nx^2, ny^2, nz^2, 2nxny, 2nynz, 2nznx], the Voigt order of the history
  Eigen::Matrix<double, Eigen::Dynamic, 6> projection;
  double polar_spacing_deg = 0.0;                       // dtheta
  double covering_radius_deg = 0.0;                     // the guaranteed bound delta
};

// The candidate planes for a spacing in (0, 90] deg. Error otherwise.
CandidatePlanes hemisphere_planes(double max_spacing_deg = 10.0);
// delta of the ring grid with polar spacing dtheta (see above), deg.
double covering_radius_bound_deg(double polar_spacing_deg);

// The normal stress histories of all candidate planes: projection * history.
PlaneHistories normal_stress_histories(const CandidatePlanes& planes, const StressHistory& history);

enum class StressMeasure { CriticalPlane, MaxPrincipal, SignedVonMises };

struct FatigueOptions {
  StressMeasure measure = StressMeasure::CriticalPlane;
  MeanStressTreatment mean_stress = MeanStressTreatment::None;
  Residue residue = Residue::HalfCycles;
  double plane_spacing_deg = 10.0;  // CriticalPlane only
};

struct NodeFatigue {
  double damage = 0.0;                                // per repetition of the history
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   // critical plane's unit normal (see above)
  double max_range_pa = 0.0;                          // largest counted range (before mean stress)
  std::vector<Cycle> cycles;                          // counted cycles of the plane / measure
  int plane = -1;                                     // index of the critical plane, else -1
  int planes_searched = 0;
};

// Damage of the node's history. Error on an empty or non-finite history.
NodeFatigue assess_node(const StressHistory& history, const SnCurve& curve,
                        const FatigueOptions& options = {});
// The same with the candidate planes made once for many nodes (CriticalPlane;
// options.plane_spacing_deg is not used).
NodeFatigue assess_node(const StressHistory& history, const SnCurve& curve,
                        const FatigueOptions& options, const CandidatePlanes& planes);

// Scalar histories of the other measures, Pa (length T).
Eigen::VectorXd max_principal_history(const StressHistory& history);
Eigen::VectorXd signed_von_mises_history(const StressHistory& history);

}  // namespace kinetofem::fatigue
