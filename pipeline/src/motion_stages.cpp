#include "kinetofem/pipeline/motion_stages.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::pipeline {

namespace {

// s(t) = from + (to - from) * (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t in
// [0, 1], held outside: the static pose's continuation path.
class RampLaw final : public mech::MotionLaw {
 public:
  RampLaw(double from, double to) : from_(from), rise_(std::make_shared<mech::Polynomial345Law>(to - from, 1.0)) {}
  mech::MotionState at(double t) const override {
    mech::MotionState m = rise_->at(t);
    m.s += from_;
    return m;
  }
  double stroke() const override { return rise_->stroke(); }
  double duration() const override { return 1.0; }
  std::string describe() const override { return fmt::format("3-4-5 ramp from {:g}", from_); }

 private:
  double from_;
  std::shared_ptr<const mech::MotionLaw> rise_;
};

// The motion by the chosen method, unchecked.
mech::Results run_motion(const mech::MultibodySystem& system, const std::vector<double>& times,
                         const DynamicsSettings& settings) {
  const int dof = degrees_of_freedom(system);
  switch (settings.method) {
    case DynamicsMethod::Kinematic: {
      require(dof == 0,
              "the kinematic method needs a fully driven linkage (0 DoF); this one has {} DoF: add motion drives or "
              "use IDAS",
              dof);
      mech::KinematicOptions ko;
      ko.slack_is_error = settings.options.slack_is_error;
      return mech::run_kinematics(system, times, ko);
    }
    case DynamicsMethod::Cvodes: {
      require(dof == 1, "the CVODES method needs a linkage with 1 DoF; this one has {} DoF", dof);
      mech::RelativeCoordinate rc;
      if (settings.cvodes_coordinate) {
        rc = *settings.cvodes_coordinate;
      } else {
        require(!system.model().force_drives.empty(),
                "the CVODES method needs an independent coordinate (none given and no force drive to take it from)");
        rc = system.model().force_drives.front().coordinate;
      }
      return mech::simulate_minimal(system, rc, times, settings.options);
    }
    case DynamicsMethod::Idas: break;
  }
  return mech::simulate_ggl(system, times, settings.options);
}

}  // namespace

int degrees_of_freedom(const mech::MultibodySystem& system) {
  const Eigen::VectorXd q0 = system.initial_coordinates();
  return mech::degrees_of_freedom(system, mech::assemble(system, q0, 0.0), 0.0);
}

void check_motion_before_meshing(const mech::MultibodyModel& model, const std::vector<double>& times,
                                 const std::vector<std::string>& bodies_from_meshes) {
  mech::MultibodyModel nominal = model;
  const double length = std::max(model.characteristic_length_m, 1e-3);
  for (auto& body : nominal.bodies) {
    if (body.fixed) continue;
    const bool from_mesh =
        std::find(bodies_from_meshes.begin(), bodies_from_meshes.end(), body.name) != bodies_from_meshes.end();
    if (from_mesh || body.mass_kg <= 0 || body.inertia_kgm2 <= 0) {
      body.mass_kg = 1.0;
      body.inertia_kgm2 = length * length / 12.0;
    }
  }
  const mech::MultibodySystem system(nominal);
  if (degrees_of_freedom(system) != 0) return;  // assembled at t = 0; the rest needs the masses
  mech::KinematicOptions check;
  check.slack_is_error = false;  // the chain tension is checked with the real masses
  mech::run_kinematics(system, times, check);
}

void require_accurate_motion(const mech::Results& results, const mech::DynamicsOptions& options) {
  const mech::RunSummary& s = results.summary;
  const std::string tolerances = fmt::format(
      "at relative tolerance {:g} and absolute tolerance {:g}: tighten them (simulation.relative_tolerance, "
      "simulation.absolute_tolerance)",
      options.relative_tolerance, options.absolute_tolerance);
  if (!(s.max_drift_relative <= kMaxRelativeConstraintDrift))
    fail("the motion ({}) is not accurate enough to use: its joints drift apart by {:.3g} of the characteristic "
         "length ({:.3g} m), more than the {:g} accepted, {}",
         s.method, s.max_drift_relative, s.max_drift_position_m, kMaxRelativeConstraintDrift, tolerances);
  if (!(s.energy_balance_error <= kMaxEnergyBalanceError))
    fail("the motion ({}) is not accurate enough to use: its energy balance |dT + dV - W| is off by {:.3g} of the "
         "energy scale, more than the {:g} accepted, {}",
         s.method, s.energy_balance_error, kMaxEnergyBalanceError, tolerances);
}

mech::Results run_dynamics(const mech::MultibodySystem& system, const std::vector<double>& times,
                           const DynamicsSettings& settings) {
  mech::Results results = run_motion(system, times, settings);
  require_accurate_motion(results, settings.options);
  return results;
}

mech::Frame solve_static_pose(const mech::MultibodyModel& model, const std::vector<double>& law_values) {
  require(law_values.size() == model.motion_drives.size(), "static pose: {} target values for {} motion drives",
          law_values.size(), model.motion_drives.size());
  mech::MultibodyModel at_rest = model;
  for (std::size_t d = 0; d < at_rest.motion_drives.size(); ++d) {
    auto& drive = at_rest.motion_drives[d];
    const double from = drive.law ? drive.law->at(0.0).s : 0.0;
    drive.law = std::make_shared<RampLaw>(from, law_values[d]);
  }
  const mech::MultibodySystem system(at_rest);
  require(degrees_of_freedom(system) == 0,
          "the static pose study needs a fully driven linkage (its motion drives fix every DoF at rest)");
  std::vector<double> ramp;
  for (int k = 0; k <= 40; ++k) ramp.push_back(k / 40.0);
  mech::KinematicOptions options;
  options.slack_is_error = false;  // only the final, static state counts
  mech::Frame frame = mech::run_kinematics(system, ramp, options).frames.back();
  for (const auto& chain : frame.chains)
    require(chain.tension_N > 0, "chain '{}' is slack at rest in this pose (tension {:.4g} N)", chain.name,
            chain.tension_N);
  return frame;
}

}  // namespace kinetofem::pipeline
