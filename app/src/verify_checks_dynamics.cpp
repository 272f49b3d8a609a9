// `kinetofem verify`: multibody dynamics (SUNDIALS IDAS and CVODES) against
// the exact pendulum period, against the closed-form SPEC §1 mechanism and
// against SPEC §4's Q-manipulator with a belt (a transmission). Models,
// references and computations are those of tests/verification/mechanisms/,
// from the verification library (pendulum.hpp, lever_chain_multibody.hpp,
// spec4_belt_arm.hpp).
#include <vector>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/verification/lever_chain_multibody.hpp"
#include "kinetofem/verification/pendulum.hpp"
#include "kinetofem/verification/spec4_belt_arm.hpp"

namespace kinetofem::app {

namespace {

namespace kv = kinetofem::verification;

std::vector<CheckRow> pendulum_period(const CheckContext&) {
  const kv::PendulumRun run = kv::run_compound_pendulum({}, 60.0 * units::kDeg);
  const auto& summary = run.results.summary;
  return {compare_relative("compound pendulum, 60 deg: period (IDAS)", "T = 4 sqrt(I_O/(m g d)) K(sin(a/2))", "s",
                           run.exact_period_s, run.computed_period_s, 1e-7, "IDAS rtol 1e-10 -> ~1e-9; 1e-7 allowed"),
          compare_absolute("compound pendulum: constraint drift / length", "Phi(q) = 0", "1", 0.0,
                           summary.max_drift_relative, 1e-8, "required: 1e-8 of the characteristic length"),
          compare_absolute("compound pendulum: energy balance error", "dT + dV = 0 (conservative)", "1", 0.0,
                           summary.energy_balance_error, 1e-8, "relative to the energy scale at rtol 1e-10")};
}

std::vector<CheckRow> idas_vs_cvodes(const CheckContext&) {
  const kv::PendulumAgreement agreement = kv::idas_vs_cvodes({}, 1.2);
  // Two independent formulations: agreement to 1e-6 relative.
  return {compare_absolute("pendulum 1.2 rad: IDAS vs CVODES angle / amplitude", "agreement of two formulations", "1",
                           0.0, agreement.angle, 1e-6, "required: 1e-6 relative"),
          compare_absolute("pendulum 1.2 rad: IDAS vs CVODES pivot force / weight", "agreement of two formulations",
                           "1", 0.0, agreement.force, 1e-6, "required: 1e-6 relative")};
}

std::vector<CheckRow> lever_chain_multibody(const CheckContext&) {
  const kv::ClosedFormAgreement agreement = kv::lever_chain_multibody_vs_closed_form();
  return {compare_absolute("lever-chain multibody vs closed form: dpsi", "SPEC §1 (4)-(7)", "rad", 0.0,
                           agreement.worst_angle_rad, kv::kClosedFormTolerance, "required: 1e-9"),
          compare_absolute("lever-chain multibody vs closed form: C and H", "SPEC §1 (12), (15)", "m", 0.0,
                           agreement.worst_point_m, kv::kClosedFormTolerance, "required: 1e-9")};
}

std::vector<CheckRow> belt_q_manipulator(const CheckContext&) {
  namespace s4 = kv::spec4;
  std::vector<double> times;
  for (int k = 0; k <= 200; ++k) times.push_back(s4::kBeltArmDuration * k / 200);
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(s4::belt_arm_model()), times);
  const s4::BeltArmAgreement agreement = s4::belt_arm_against_references(results);
  return {compare_absolute("belt Q-manipulator (ratio -4), full turn: |H - H(P)|",
                           "SPEC §4 H = l1 e(P) + l2 e((1 - i) P), i = 4", "m", 0.0, agreement.path_m,
                           s4::kBeltArmTolerance * s4::kBeltArmL1, "required: 1e-9 of l1"),
          compare_absolute("belt Q-manipulator: belt moment on link 2 - hand kinetostatics",
                           "link 2 about A, docs/transmissions.md", "N*m", 0.0, agreement.moment_Nm,
                           s4::kBeltArmTolerance * agreement.moment_scale_Nm, "required: 1e-9 of the peak moment")};
}

}  // namespace

std::vector<Check> dynamics_checks() {
  return {
      {"dynamics.pendulum_period", "dynamics", true, pendulum_period},
      {"dynamics.idas_vs_cvodes", "dynamics", true, idas_vs_cvodes},
      {"dynamics.lever_chain_multibody", "dynamics", true, lever_chain_multibody},
      {"dynamics.belt_q_manipulator", "dynamics", true, belt_q_manipulator},
  };
}

}  // namespace kinetofem::app
