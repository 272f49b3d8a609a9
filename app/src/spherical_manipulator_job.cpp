// The "spherical_manipulator" case type (SPEC §5): a variant A-E of the
// spherical-coordinate 3-DoF manipulator with a payload, sized by the
// source's rules, moving its gripper point M along a straight segment with
// the trapezoidal speed law; inverse kinematics, kinetostatic inverse dynamics
// (drive efforts, pair reactions, power) as histories, the CVODES
// forward-dynamics cross-check, and the same kinetostatics through the spatial
// multibody core compared with the closed form (an error beyond
// kClosedFormAgreement). With [parts] enabled: the column, sleeve and arm as
// FE parts sized by the SPEC §5 rules (pipeline/spherical_manipulator_parts.hpp),
// the spatial model with their mass properties, each part's stress over the
// motion from the spatial loads (unit-load superposition), and with
// [fatigue] enabled their fatigue over the work cycle. Model:
// mechanisms/spherical_manipulator.hpp and
// mechanisms/spatial/spherical_manipulator_model.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/fatigue_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/spherical_manipulator_model.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/spherical_manipulator_parts.hpp"
#include "kinetofem/pipeline/spatial_assembly_over_motion.hpp"
#include "kinetofem/pipeline/spatial_part_factors.hpp"
#include "kinetofem/pipeline/spatial_histories.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
}  // namespace

const std::vector<KeySpec>& spherical_manipulator_schema() {
  static const std::vector<KeySpec> schema = [] {
    const mech::SphericalSizingOptions sizing;
    const meshes::SphericalPartRules rules;
    std::vector<KeySpec> s = mechanism_case_keys("spherical_manipulator");
    s.insert(s.end(), {
      {.path = "manipulator.variant", .type = Type::String, .default_text = "A", .allowed = {"A", "B", "C", "D", "E"}, .doc = "row of the SPEC §5 data table"},
      {.path = "manipulator.payload_kg", .type = Type::Number, .unit = "kg", .min = 0, .doc = "payload at M (not in the SPEC table: a case input)", .required = true},
      {.path = "manipulator.sleeve_ratio", .type = Type::Number, .default_number = sizing.sleeve_ratio, .min = 0.2, .max = 0.5, .doc = "sleeve length l2 / arm length l1"},
      {.path = "manipulator.sleeve_diameter_ratio", .type = Type::Number, .default_number = sizing.sleeve_diameter_ratio, .min = 0.2, .max = 0.4, .doc = "sleeve diameter d2 / l2"},
      {.path = "manipulator.base_diameter_ratio", .type = Type::Number, .default_number = sizing.base_diameter_ratio, .min = 1.5, .max = 2.0, .doc = "base diameter d0 / height of A"},
      {.path = "manipulator.margin_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = sizing.margin_m / kMm, .min = 0, .doc = "l1 = r_Mmax + 0.5 l2 + margin"},
      {.path = "motion.start_mm", .type = Type::Vector3, .unit = "mm", .to_si = kMm, .doc = "start a of M's straight segment [x, y, z] (world: origin on the floor on the column axis, z up)", .required = true},
      {.path = "motion.end_mm", .type = Type::Vector3, .unit = "mm", .to_si = kMm, .doc = "end b of the segment", .required = true},
      {.path = "motion.speed_m_s", .type = Type::Number, .unit = "m/s", .default_number = 0, .min = 0, .doc = "steady speed V of M; 0: the variant's"},
      {.path = "motion.accel_fraction", .type = Type::Number, .default_number = 0, .min = 0, .max = 1, .doc = "kP; 0: the variant's"},
      {.path = "motion.decel_fraction", .type = Type::Number, .default_number = 0, .min = 0, .max = 1, .doc = "kT; 0: the variant's"},
      {.path = "motion.intervals", .type = Type::Integer, .default_number = 100, .min = 2, .max = 1000000, .doc = "output intervals over the motion (the law's breakpoints are added)"},
      {.path = "check.forward_dynamics", .type = Type::Boolean, .default_number = 1, .doc = "integrate the efforts forward with CVODES and compare M's path with the plan"},
      {.path = "parts.enabled", .type = Type::Boolean, .default_number = 0, .doc = "mesh the column, sleeve and arm (SPEC §5 sizing, docs/spherical_manipulator_parts.md) and compute their stress over the motion from the spatial multibody loads"},
      {.path = "parts.arm_diameter_ratio", .type = Type::Number, .default_number = rules.arm_diameter_ratio, .min = 0.3, .max = 0.85, .doc = "the arm's outer diameter D3 over the sleeve's d2 (a design choice the SPEC leaves open)"},
      {.path = "parts.guide_length_ratio", .type = Type::Number, .default_number = rules.guide_length_ratio, .min = 0.25, .max = 2.0, .doc = "each guide land's length l_g over the arm's diameter D3"},
      {.path = "parts.assembly", .type = Type::Boolean, .default_number = 1, .doc = "with the parts: the column, sleeve and arm as one elastic structure held by the ground at every output time (the spatial elastic assembly): M's positioning error over the motion, its compliance and each part's share"},
      {.path = "parts.vibration", .type = Type::Boolean, .default_number = 0, .doc = "with the assembly: the natural frequencies of the three parts as one structure frozen in each pose (one Craig-Bampton reduction per part, docs/vibration.md; minutes: the arm's slide stations are all boundary coordinates)"},
      {.path = "parts.vibration_modes", .type = Type::Integer, .default_number = 6, .min = 1, .max = 100, .doc = "natural frequencies per pose"},
      {.path = "parts.pin_diameter_ratio", .type = Type::Number, .default_number = rules.pin_diameter_ratio, .min = 0.1, .max = 0.5, .doc = "the tilt pin's (and trunnion journals') diameter over the sleeve's d2"},
    });
    const std::vector<KeySpec> material = material_keys(), mesh = part_mesh_keys(), stress = motion_solver_keys(),
                               solver = solver_keys(), sweep = sweep_keys();
    s.insert(s.end(), material.begin(), material.end());
    s.insert(s.end(), sweep.begin(), sweep.end());
    s.insert(s.end(), solver.begin(), solver.end());
    s.insert(s.end(), mesh.begin(), mesh.end());
    s.insert(s.end(), stress.begin(), stress.end());
    add_fatigue_keys(s);
    return s;
  }();
  return schema;
}

MechanismCaseSummary run_spherical_manipulator(const CaseFile& c, const RunOptions& options) {
  const std::string name = mechanism_case_name(c);
  const mech::SphericalVariant& v = mech::spherical_variant(c.text_value("manipulator.variant")[0]);
  const Log log = start_case_log(c, options, name, fmt::format("spherical manipulator variant {} (SPEC §5)", v.name));
  mech::SphericalSizingOptions sizing;
  sizing.sleeve_ratio = c.number("manipulator.sleeve_ratio");
  sizing.sleeve_diameter_ratio = c.number("manipulator.sleeve_diameter_ratio");
  sizing.base_diameter_ratio = c.number("manipulator.base_diameter_ratio");
  sizing.margin_m = c.number("manipulator.margin_mm");
  const mech::SphericalDesign design = mech::size_spherical_manipulator(v, c.number("manipulator.payload_kg"), sizing);
  const double speed = c.number("motion.speed_m_s") > 0 ? c.number("motion.speed_m_s") : v.speed_mps;
  const double kp = c.number("motion.accel_fraction") > 0 ? c.number("motion.accel_fraction") : v.k_accel;
  const double kt = c.number("motion.decel_fraction") > 0 ? c.number("motion.decel_fraction") : v.k_decel;
  require(kp + kt <= 1.0, "{}: kP + kT = {:g} must not exceed 1", c.where("motion.decel_fraction"), kp + kt);
  const Eigen::Vector3d a = c.vector3("motion.start_mm"), b = c.vector3("motion.end_mm");
  std::unique_ptr<mech::StraightLineMotion> motion;
  mech::SphericalRun run;
  try {
    motion = std::make_unique<mech::StraightLineMotion>(a, b, speed, kp, kt);
    run = mech::analyse_straight_line(design, *motion, int(c.integer("motion.intervals")));
  } catch (const Error& e) {
    fail("{}: [motion]: {}", c.path().string(), e.what());
  }
  // analyse_straight_line adds the law's breakpoints: keep strictly increasing times only.
  std::vector<const mech::SphericalDynamics*> kept;
  for (const auto& s : run.samples)
    if (kept.empty() || s.t > kept.back()->t + 1e-12) kept.push_back(&s);
  const std::size_t T = kept.size();
  std::vector<double> times(T);
  post::FieldMatrix m_pos(T, 3), m_vel(T, 3), m_acc(T, 3), q(T, 3), qd(T, 3), qdd(T, 3), efforts(T, 3), power(T, 4);
  post::FieldMatrix f32(T, 3), m32(T, 3), f21(T, 3), m21(T, 3), f10(T, 3), m10(T, 3);
  for (std::size_t k = 0; k < T; ++k) {
    const mech::SphericalDynamics& d = *kept[k];
    times[k] = d.t;
    const auto p = motion->at(d.t);
    m_pos.row(k) = p.m.transpose();
    m_vel.row(k) = p.m_dot.transpose();
    m_acc.row(k) = p.m_ddot.transpose();
    q.row(k) = d.joints.q.transpose();
    qd.row(k) = d.joints.qd.transpose();
    qdd.row(k) = d.joints.qdd.transpose();
    efforts.row(k) << d.pair10.drive, d.pair21.drive, d.pair32.drive;
    power.row(k) << d.drive_power_W.transpose(), d.total_power_W;
    f32.row(k) = d.pair32.reaction_force.transpose();
    m32.row(k) = d.pair32.reaction_moment.transpose();
    f21.row(k) = d.pair21.reaction_force.transpose();
    m21.row(k) = d.pair21.reaction_moment.transpose();
    f10.row(k) = d.pair10.reaction_force.transpose();
    m10.row(k) = d.pair10.reaction_moment.transpose();
  }
  double forward_deviation = -1.0;
  long forward_steps = 0;
  if (c.boolean("check.forward_dynamics")) {
    try {
      const mech::SphericalForwardResult fwd = mech::spherical_forward_dynamics(design, *motion, times);
      forward_deviation = fwd.max_path_deviation_m;
      forward_steps = fwd.steps;
    } catch (const Error& e) {
      fail("{}: forward-dynamics cross-check: {}", c.path().string(), e.what());
    }
  }
  // The same motion through the spatial multibody core (absolute coordinates,
  // multipliers): an independent formulation of the same kinetostatics.
  mech::spatial::ClosedFormComparison spatial_check;
  mech::spatial::RunSummary spatial_run;
  mech::spatial::Model spatial_model;
  mech::spatial::Results spatial;
  try {
    spatial_model = mech::spatial::spherical_manipulator_model(design, *motion);
    const mech::spatial::System system(spatial_model);
    spatial = mech::spatial::run_kinematics(system, times);
    spatial_check = mech::spatial::compare_with_closed_form(design, *motion, spatial);
    spatial_run = spatial.summary;
  } catch (const Error& e) {
    fail("{}: spatial multibody core cross-check: {}", c.path().string(), e.what());
  }
  require(spatial_check.largest() <= mech::spatial::kClosedFormAgreement,
          "{}: spatial multibody core vs closed form: max relative difference {:.2e} exceeds {:.0e} (M10d {:.2e}, "
          "M21d {:.2e}, F32d {:.2e}, reaction forces {:.2e}, moments {:.2e})",
          c.path().string(), spatial_check.largest(), mech::spatial::kClosedFormAgreement, spatial_check.drive(0),
          spatial_check.drive(1), spatial_check.drive(2), spatial_check.reaction_force, spatial_check.reaction_moment);

  // The parts: meshed, their mass properties on the spatial model's bodies,
  // the motion run again with them (the loads then balance on each part).
  const bool with_parts = c.boolean("parts.enabled");
  const std::vector<std::string> part_bodies =
      with_parts ? std::vector<std::string>{"column", "sleeve", "arm"} : std::vector<std::string>{};
  const std::optional<pipeline::FatigueSettings> fatigue = read_fatigue(c, part_bodies);
  std::optional<pipeline::SphericalManipulatorParts> parts;
  auto as_part = [](const pipeline::SpatialPart& p) {
    pipeline::Part view;
    view.label = p.label;
    view.attachments.body = p.attachments.body;
    view.model = p.model;
    return view;
  };
  if (with_parts) {
    try {
      meshes::SphericalPartRules rules;
      rules.arm_diameter_ratio = c.number("parts.arm_diameter_ratio");
      rules.guide_length_ratio = c.number("parts.guide_length_ratio");
      rules.pin_diameter_ratio = c.number("parts.pin_diameter_ratio");
      parts = pipeline::spherical_manipulator_parts(design, rules, read_part_mesh_options(c, options.output_dir),
                                                    read_material(c), log);
      std::vector<pipeline::Part> as_parts;
      for (const pipeline::SpatialPart& p : parts->parts) as_parts.push_back(as_part(p));
      if (fatigue) pipeline::check_fatigue_details(*fatigue, as_parts);
      pipeline::apply_spatial_mass_properties(spatial_model, parts->parts);
      spatial = mech::spatial::run_kinematics(mech::spatial::System(spatial_model), times);
    } catch (const Error& e) {
      fail("{}: parts: {}", c.path().string(), e.what());
    }
  }

  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  // The spatial run's histories and moving skeleton; it sets the time grid
  // (its frames are at `times`). With parts: the run with their masses.
  pipeline::write_spatial_mechanism_histories(w, spatial_model, spatial);
  const std::vector<std::string> xyz = {"x", "y", "z"}, joints = {"phi10", "phi21", "l_BM"};
  w.write_history("M.position", "m", m_pos, xyz);
  w.write_history("M.velocity", "m/s", m_vel, xyz);
  w.write_history("M.acceleration", "m/s^2", m_acc, xyz);
  w.write_history("joints.q", "rad, rad, m", q, joints);
  w.write_history("joints.q_dot", "rad/s, rad/s, m/s", qd, joints);
  w.write_history("joints.q_ddot", "rad/s^2, rad/s^2, m/s^2", qdd, joints);
  w.write_history("drive.efforts", "N*m, N*m, N", efforts, {"M10d", "M21d", "F32d"});
  w.write_history("drive.power", "W", power, {"M10d", "M21d", "F32d", "total"});
  w.write_history("pair32.reaction_force", "N", f32, xyz);
  w.write_history("pair32.reaction_moment", "N*m", m32, xyz);
  w.write_history("pair21.reaction_force", "N", f21, xyz);
  w.write_history("pair21.reaction_moment", "N*m", m21, xyz);
  w.write_history("pair10.reaction_force", "N", f10, xyz);
  w.write_history("pair10.reaction_moment", "N*m", m10, xyz);
  std::vector<pipeline::PartSummary> part_summaries;
  std::vector<pipeline::PartFatigue> part_fatigue;
  std::optional<pipeline::SpatialAssemblySummary> assembly;
  std::optional<pipeline::SpatialPartFactors> factors;
  if (parts) {
    try {
      factors.emplace(parts->parts, read_solver_options(c), log);
    } catch (const Error& e) {
      fail("{}: {}", c.path().string(), e.what());
    }
  }
  if (parts && c.boolean("parts.assembly")) {
    structure::SpatialAssemblyOptions assembly_options;
    assembly_options.points = {{std::string(mech::spatial::spherical_names::point_m),
                                std::string(mech::spatial::spherical_names::arm),
                                std::string(mech::spatial::spherical_names::point_m), "gripper_mount"}};
    assembly_options.solver = read_solver_options(c);
    std::optional<vibration::AssemblyModesOptions> modes;
    if (c.boolean("parts.vibration")) {
      modes.emplace();
      modes->modes = int(c.integer("parts.vibration_modes"));
    }
    try {
      assembly = pipeline::analyse_spatial_assembly_over_motion(parts->parts, spatial_model, spatial.frames, w,
                                                                assembly_options, {}, log, factors->lent(),
                                                                modes ? &*modes : nullptr);
    } catch (const Error& e) {
      fail("{}: {}", c.path().string(), e.what());
    }
  }
  if (parts) {
    const loads::LinkStressOptions stress = read_stress_options(c);
    for (std::size_t k = 0; k < parts->parts.size(); ++k) {
      const pipeline::SpatialPart& p = parts->parts[k];
      pipeline::PartStressHistory history;
      try {
        part_summaries.push_back(pipeline::analyse_spatial_part_over_motion(
            p, spatial_model, spatial.frames, w, stress, log, fatigue ? &history : nullptr, &factors->of(k)));
        if (fatigue) {
          part_fatigue.push_back(pipeline::assess_part_fatigue(as_part(p), history, *fatigue, log));
          pipeline::write_part_fatigue(w.body(p.attachments.body), part_fatigue.back());
        }
      } catch (const Error& e) {
        fail("{}: {}", c.path().string(), e.what());
      }
    }
  }
  w.commit();

  const double tc = motion->length() / (speed * (1 - 0.5 * kp - 0.5 * kt));
  summary.values = {{"duration_s", motion->duration()}, {"peak_M10d_nm", run.peak_drive(0)}, {"peak_M21d_nm", run.peak_drive(1)},
                    {"peak_F32d_n", run.peak_drive(2)}, {"peak_power_w", run.peak_power_W.sum()},
                    {"forward_deviation_m", forward_deviation}, {"arm_length_m", design.arm_length_m}};
  std::printf("\nSummary of '%s' (spherical manipulator, SPEC §5, variant %c, payload %.3g kg)\n", name.c_str(), v.name,
              design.payload_kg);
  std::printf("  SPEC §5 table: r_M %.2f/%.2f m, tilt +-%.0f deg, B/A %.2f/%.2f m, base +-%.0f deg, m1/m2/m3 %.0f/%.0f/%.0f kg, "
              "V %.2f m/s, kP/kT %.2f/%.2f\n",
              v.r_max_m, v.r_min_m, v.tilt_max_rad / kDeg, v.height_b_m, v.height_a_m, v.base_rotation_max_rad / kDeg, v.m1_kg,
              v.m2_kg, v.m3_kg, v.speed_mps, v.k_accel, v.k_decel);
  std::printf("  sizing: arm l1 = %.4f m (= r_Mmax + 0.5 l2 + %.3f), sleeve l2 = %.4f m, d2 = %.4f m, base d0 = %.4f m\n",
              design.arm_length_m, sizing.margin_m, design.sleeve_length_m, design.sleeve_diameter_m, design.base_diameter_m);
  std::printf("  segment a = (%.3f, %.3f, %.3f) -> b = (%.3f, %.3f, %.3f) m, l_ab = %.4f m; V = %.3g m/s, kP/kT = %.2f/%.2f\n",
              a.x(), a.y(), a.z(), b.x(), b.y(), b.z(), motion->length(), speed, kp, kt);
  std::printf("  T_c = l_ab / (V (1 - kP/2 - kT/2)) = %.5f s (SPEC §5); law duration %.5f s; %zu output times\n", tc,
              motion->duration(), T);
  std::printf("  peak drive efforts: M10d %.3f N m, M21d %.3f N m, F32d %.3f N; peak power %.2f / %.2f / %.2f W\n",
              run.peak_drive(0), run.peak_drive(1), run.peak_drive(2), run.peak_power_W(0), run.peak_power_W(1),
              run.peak_power_W(2));
  if (forward_deviation >= 0)
    std::printf("  forward dynamics (CVODES, efforts fed back, %ld steps): max |M_simulated - M_planned| = %.3g m\n",
                forward_steps, forward_deviation);
  std::printf("  spatial multibody core vs closed form: max relative difference %.2e (drive efforts %.2e, reactions "
              "%.2e; limit %.0e), drift %.2e of the arm length\n",
              spatial_check.largest(), spatial_check.drive.maxCoeff(),
              std::max(spatial_check.reaction_force, spatial_check.reaction_moment), mech::spatial::kClosedFormAgreement,
              spatial_run.max_drift_relative);
  if (parts) {
    const meshes::SphericalPartDimensions& d = parts->dimensions;
    std::printf("  parts (SPEC §5 sizing, walls from the masses; docs/spherical_manipulator_parts.md): column wall "
                "%.1f mm (%s), sleeve wall %.1f mm (%s), arm D3 %.1f mm wall %.1f mm (%s)\n",
                d.column.wall_m / kMm, std::string(meshes::wall_rule_name(d.column.wall_rule)).c_str(),
                d.sleeve.wall_m / kMm, std::string(meshes::wall_rule_name(d.sleeve.wall_rule)).c_str(),
                d.arm.outer_diameter_m / kMm, d.arm.wall_m / kMm,
                std::string(meshes::wall_rule_name(d.arm.wall_rule)).c_str());
    std::printf("  %-8s %9s %9s %14s %12s %16s %12s\n", "part", "mass kg", "nodes", "peak vM MPa", "at t s",
                "deformation mm", "equilibrium");
    for (std::size_t k = 0; k < part_summaries.size(); ++k) {
      const pipeline::PartSummary& ps = part_summaries[k];
      const mech::spatial::Body& body = *std::find_if(spatial_model.bodies.begin(), spatial_model.bodies.end(),
                                                      [&](const auto& b) { return b.name == ps.body; });
      std::printf("  %-8s %9.2f %9ld %14.3f %12.4f %16.4f %12.1e\n", ps.body.c_str(), body.mass_kg, ps.nodes,
                  ps.peak_von_mises_pa / units::kMpa, ps.peak_von_mises_time_s, ps.peak_displacement_m / kMm,
                  ps.worst_equilibrium_residual);
      summary.values.push_back({"peak_von_mises_" + ps.body + "_mpa", ps.peak_von_mises_pa / units::kMpa});
      summary.max_von_mises_pa = std::max(summary.max_von_mises_pa.value_or(0.0), ps.peak_von_mises_pa);
      summary.max_displacement_m = std::max(summary.max_displacement_m.value_or(0.0), ps.peak_displacement_m);
    }
  }
  if (assembly) {
    for (const pipeline::PointSummary& ps : assembly->points) {
      std::printf("  elastic assembly (column, sleeve and arm as one structure): M's positioning error up to %.4f mm "
                  "at t = %.4f s (x %.4f, y %.4f, z %.4f mm); compliance %.3g-%.3g mm/kN\n",
                  ps.max_displacement_m / kMm, ps.max_displacement_time_s, ps.displacement_at_max_m.x() / kMm,
                  ps.displacement_at_max_m.y() / kMm, ps.displacement_at_max_m.z() / kMm,
                  ps.min_compliance_m_per_n / kMm * 1e3, ps.max_compliance_m_per_n / kMm * 1e3);
      std::string split;
      for (const structure::PointContribution& share : ps.contributions_at_max)
        split += fmt::format("{}{} {:.4f} mm", split.empty() ? "" : ", ", share.name.substr(share.name.find('.') + 1),
                             share.displacement_m.dot(ps.displacement_at_max_m.normalized()) / kMm);
      std::printf("    its split along the error there: %s\n", split.c_str());
      summary.values.push_back({"M_error_mm", ps.max_displacement_m / kMm});
    }
    if (assembly->vibration) {
      const pipeline::SpatialAssemblySummary::Vibration& v = *assembly->vibration;
      std::printf("  natural frequencies (the structure frozen in each pose; %d modes): first %.3f Hz at t = %.4f s to "
                  "%.3f Hz at t = %.4f s; at the start %s Hz\n",
                  v.modes, v.lowest_first_hz, v.lowest_first_time_s, v.highest_first_hz, v.highest_first_time_s,
                  fmt::format("{:.2f}", fmt::join(v.frequency_hz.row(0), ", ")).c_str());
      std::printf("    %s\n", v.rule.c_str());
      summary.values.push_back({"first_frequency_min_hz", v.lowest_first_hz});
    }
  }
  std::printf("  results: %s (+ .xdmf)\n", summary.results_file.string().c_str());
  if (!part_fatigue.empty()) {
    report_fatigue(part_fatigue, summary.results_file);
    double min_life_s = std::numeric_limits<double>::infinity(), max_utilization = 0.0;
    for (const pipeline::PartFatigue& f : part_fatigue) {
      min_life_s = std::min(min_life_s, f.min_life_s);
      max_utilization = std::max(max_utilization, f.max_utilization);
    }
    summary.values.push_back({"fatigue_min_life_h", min_life_s / units::kHour});
    summary.values.push_back({"fatigue_max_utilization", max_utilization});
  }
  return summary;
}

}  // namespace kinetofem::app
