#include "kinetofem/pipeline/rotary_module_stage.hpp"

#include <algorithm>
#include <cmath>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/rotary_module.hpp"
#include "kinetofem/pipeline/spatial_histories.hpp"
#include "kinetofem/pipeline/spatial_part_factors.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::pipeline {

namespace names = mech::manipulator;

namespace {

// A planar part's attachments as the spatial loads take them, the gripper
// and the casting moved from the arm to the module.
SpatialPart spatial_part(const Part& part, const mech::spatial::RotaryModule& module) {
  SpatialPart out = structure::spatial_part_of(part);
  loads::SpatialLinkDefinition& a = out.attachments;
  if (part.body() != module.carrier) return out;
  std::erase_if(a.point_masses, [](const loads::SpatialAttachment& m) {
    return m.name == names::kGripperMass || m.name == names::kCastingMass;
  });
  // The module's bearing sits where the planar case hung the gripper.
  std::string mount = names::kGripperMount;
  for (const loads::PointMassAttachment& m : part.attachments.point_masses)
    if (m.point_mass == names::kGripperMass) mount = m.face_set;
  a.joints.push_back({mech::spatial::rotary_joint_name(module), mount});
  a.joints.push_back({mech::spatial::rotary_drive_name(module), mount});
  return out;
}

}  // namespace

RotaryModuleSummary analyse_rotary_module(const mech::MultibodyModel& model, const std::vector<Part>& parts,
                                          const std::vector<double>& times, const RotaryModuleSettings& settings,
                                          const std::filesystem::path& results_file, const post::Provenance& provenance,
                                          const loads::LinkStressOptions& options, const Log& log,
                                          const structure::AssemblyOptions* assembly,
                                          const vibration::AssemblyModesOptions* modes,
                                          const FatigueSettings* fatigue) {
  require(times.size() >= 2, "rotary module: fewer than two output times");
  require(settings.duration_s > 0 && std::isfinite(settings.duration_s) && settings.start_s >= 0,
          "rotary module: its turn must take a positive time from a start >= 0 (start {} s, duration {} s)",
          settings.start_s, settings.duration_s);
  // The gripper and the casting, lumped at H on the planar arm, become the module.
  mech::spatial::Model spatial = mech::spatial::from_planar(model);
  const auto arm = std::find_if(spatial.bodies.begin(), spatial.bodies.end(),
                                [](const mech::spatial::Body& b) { return b.name == names::kArm; });
  require(arm != spatial.bodies.end(), "rotary module: the mechanism has no arm");
  double gripper_kg = 0.0, casting_kg = 0.0;
  for (const mech::spatial::PointMass& m : arm->point_masses) {
    if (m.name == names::kGripperMass) gripper_kg += m.mass_kg;
    if (m.name == names::kCastingMass) casting_kg += m.mass_kg;
  }
  std::erase_if(arm->point_masses, [](const mech::spatial::PointMass& m) {
    return m.name == names::kGripperMass || m.name == names::kCastingMass;
  });
  mech::spatial::RotaryModule module;
  // (std::string temporaries: assigning the short literals in place trips
  // GCC 12's -Wrestrict false positive.)
  module.carrier = std::string(names::kArm);
  module.mount_point = std::string(names::kPointH);
  const Eigen::Vector3d c = arm->points.at(names::kPointC);  // the arm's axis: from A (its origin) towards C
  module.axis_carrier = c;
  module.mass_kg = gripper_kg;
  module.inertia_kgm2 = settings.gripper_inertia_kgm2;
  module.payload = {names::kCastingMass, casting_kg, settings.casting_offset_m, settings.casting_inertia_kgm2};
  module.angle = std::make_shared<mech::DelayedLaw>(
      std::make_shared<mech::CycloidalLaw>(settings.angle_rad, settings.duration_s), settings.start_s);
  spatial = mech::spatial::with_rotary_module(std::move(spatial), module);

  RotaryModuleSummary out;
  out.times = times;
  const double step = (times.back() - times.front()) / double(times.size() - 1);
  const double end = settings.start_s + settings.duration_s;
  while (out.times.back() < end - 1e-9 * step) out.times.push_back(std::min(end, out.times.back() + step));
  log.info(
      "rotary module: the casting turned {:.1f} deg about the arm from t = {:.4g} s in {:.4g} s; {} output times "
      "through the spatial multibody core",
      settings.angle_rad / units::kDeg, settings.start_s, settings.duration_s, out.times.size());
  const mech::spatial::Results run = mech::spatial::run_kinematics(mech::spatial::System(spatial), out.times);
  const std::string drive = mech::spatial::rotary_drive_name(module);
  for (const mech::spatial::Frame& f : run.frames)
    for (const mech::spatial::DriveState& d : f.drives)
      if (d.name == drive && std::abs(d.effort) > std::abs(out.peak_torque_nm)) {
        out.peak_torque_nm = d.effort;
        out.peak_torque_time_s = f.t;
      }

  std::vector<SpatialPart> spatial_parts;
  for (const Part& p : parts) spatial_parts.push_back(spatial_part(p, module));
  const SpatialPartFactors factors(spatial_parts, options.solver, log);
  post::ResultsWriter writer(results_file, provenance);
  write_spatial_mechanism_histories(writer, spatial, run);
  if (assembly) {
    require(assembly->drives.empty() && assembly->pins.empty() && assembly->transmissions.empty() &&
                assembly->coupling == structure::BoreCoupling::Distributing,
            "rotary module: the spatial elastic assembly takes the chains and the tracked points of the planar one; "
            "compliant drives, elastic pins, transmissions and rigid-bore couplings are not taken yet");
    structure::SpatialAssemblyOptions o;
    o.chains = assembly->chains;
    o.solver = options.solver;
    for (const structure::AssemblyPoint& p : assembly->points)
      o.points.push_back({p.name, p.body, p.point, p.face_set});
    o.points.push_back({std::string(names::kCastingMass), module.name, std::string(names::kCastingMass), ""});
    out.assembly = analyse_spatial_assembly_over_motion(spatial_parts, spatial, run.frames, writer, o, {}, log,
                                                        factors.lent(), modes);
  }
  for (size_t k = 0; k < spatial_parts.size(); ++k) {
    PartStressHistory history;
    out.parts.push_back(analyse_spatial_part_over_motion(spatial_parts[k], spatial, run.frames, writer, options, log,
                                                         fatigue ? &history : nullptr, &factors.of(k)));
    if (fatigue) {
      out.fatigue.push_back(assess_part_fatigue(parts[k], history, *fatigue, log));
      write_part_fatigue(writer.body(parts[k].body()), out.fatigue.back());
    }
  }
  writer.commit();
  out.results_file = results_file;
  return out;
}

}  // namespace kinetofem::pipeline
