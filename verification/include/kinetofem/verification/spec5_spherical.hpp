#pragma once
// SPEC §5: the spherical 3-DoF manipulator. Reference: the work-energy
// theorem for a rest-to-rest straight-line motion — the drives' work equals
// the potential energy gained by the arm (centre of mass S3, at q3 - l/2
// along the arm) and the payload (at M); column and sleeve do not rise.
#include <Eigen/Core>

#include "kinetofem/mechanisms/spherical_manipulator.hpp"

namespace kinetofem::verification::spec5 {

// Work of the drives: composite Simpson (200 intervals) of the total drive
// power over each segment of the trapezoidal law (the power jumps at the
// breakpoints and is smooth inside; its error ~1e-10 of peak power x
// duration).
double drive_work_J(const mech::SphericalDesign& design, const mech::StraightLineMotion& motion);

// m3 g dz(S3) + m_payload g dz(M) from a to b (J).
double potential_energy_gain_J(const mech::SphericalDesign& design, double payload_kg, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b);

// The check: variant `variant` sized for a 20 kg payload, the straight line
// (1.4, -0.7, 0.5) -> (1.2, 0.8, 0.9) m (inside the zones of A, C and E) at
// the variant's speed, analysed at 61 times (which checks the service zone).
inline constexpr double kWorkEnergyPayload_kg = 20.0;
struct WorkEnergyBalance {
  double duration_s = 0.0;
  double work_J = 0.0;            // drive_work_J
  double potential_gain_J = 0.0;  // potential_energy_gain_J
  double scale_J = 0.0;           // the largest |total drive power| x duration
  mech::SphericalRun run;
};
WorkEnergyBalance work_energy_balance(char variant);
// Tolerance on |work - gain|, relative to scale_J (Simpson's error ~1e-10).
inline constexpr double kWorkEnergyTolerance = 1e-8;

}  // namespace kinetofem::verification::spec5
