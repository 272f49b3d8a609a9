#include "kinetofem/app/manipulator_job.hpp"

#include <array>
#include <cstdio>

#include <fmt/format.h>

#include "kinetofem/app/assembly_keys.hpp"
#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/fatigue_keys.hpp"
#include "kinetofem/app/vibration_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/motion_case_keys.hpp"
#include "kinetofem/app/motion_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/iso_fit.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/mechanisms/published_analyses.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/pipeline/manipulator_preset.hpp"
#include "kinetofem/driver/motion_to_stress.hpp"
#include "kinetofem/pipeline/rotary_module_stage.hpp"
#include "kinetofem/pipeline/run_report.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
using units::kMpa;
}  // namespace

const std::vector<KeySpec>& manipulator_schema() {
  static const meshes::LeverDimensions lever;
  static const meshes::ArmDimensions arm;
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = {
      case_name_key(),
      {.path = "case.type", .type = Type::String, .allowed = {"manipulator"}, .doc = "kind of analysis", .required = true},
      {.path = "case.description", .type = Type::String, .doc = "free text"},
      {.path = "mechanism.type", .type = Type::String, .allowed = {"lever_chain", "lever"}, .doc = "SPEC §1 lever-chain or SPEC §2 lever (four-bar) manipulator", .required = true},
      {.path = "mechanism.gravity_m_s2", .type = Type::Vector3, .unit = "m/s^2",
       .default_vector = std::array<double, 3>{0.0, -units::kStandardGravity, 0.0},
       .doc = "gravity in the mechanism frame (x, y in the plane; z must be 0)"},
      {.path = "payload.gripper_mass_kg", .type = Type::Number, .unit = "kg", .default_number = 20, .min = 0, .doc = "gripper mass, lumped at H"},
      {.path = "payload.casting_mass_kg", .type = Type::Number, .unit = "kg", .default_number = 15, .min = 0, .doc = "casting mass, lumped at H"},
      {.path = "motion.output_times", .type = Type::Integer, .default_number = 101, .min = 2, .max = 100000, .doc = "number of output times over the motion (both ends included)"},
      {.path = "dynamics.method", .type = Type::String, .default_text = "idas", .allowed = {"idas", "kinetostatic"},
       .doc = "'idas': SUNDIALS IDAS on the index-2 GGL form; 'kinetostatic': kinematics + inverse dynamics at each output time"},
      {.path = "links.lever_width_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.width_m / kMm, .min = 0, .min_exclusive = true, .doc = "lever 1 (and rocker 3) plate width"},
      {.path = "links.lever_thickness_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.thickness_m / kMm, .min = 0, .min_exclusive = true, .doc = "lever 1 (and rocker 3) plate thickness"},
      {.path = "links.arm_depth_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = arm.arm_depth_m / kMm, .min = 0, .min_exclusive = true, .doc = "link 2 arm plate depth (in the plane)"},
      {.path = "links.arm_thickness_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = arm.arm_thickness_m / kMm, .min = 0, .min_exclusive = true, .doc = "link 2 arm plate thickness (along the pins)"},
      {.path = "links.bore_diameter_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.bore_diameter_m / kMm, .min = 0, .min_exclusive = true, .doc = "pin bore diameter (all joints)"},
      {.path = "links.boss_diameter_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.boss_diameter_m / kMm, .min = 0, .min_exclusive = true, .doc = "boss outer diameter (all joints)"},
      {.path = "links.boss_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = lever.boss_length_m / kMm, .min = 0, .min_exclusive = true, .doc = "boss length along the pins"},
      {.path = "loads.bore_load", .type = Type::String, .default_text = "coupling", .allowed = {"coupling", "bearing", "contact"},
       .doc = "pin loads on bores: 'coupling' (distributing, RBE3-like: exact resultant, any reaction), 'bearing' (cosine "
              "pressure) or 'contact' (rigid round pins in frictionless contact with the bores: docs/contact.md)"},
      {.path = "loads.clearance_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0, .max = 10,
       .doc = "bore_load = 'contact': the pins' radial clearance in their bores (default 0: line-to-line)",
       .range_note = "an interference fit (negative) is not supported"},
      {.path = "loads.fit", .type = Type::String,
       .doc = "bore_load = 'contact': an ISO 286 clearance fit such as \"H7/g6\" instead of clearance_mm (its mean radial "
              "clearance at the bore's diameter)"},
      {.path = "loads.pin_youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = kMpa, .min = 1e-3, .max = 1e7,
       .doc = "bore_load = 'contact': elastic pins of this modulus (meshed from the bore's diameter less the clearance "
              "and its span; docs/contact.md); absent: rigid pins"},
      {.path = "loads.pin_poisson_ratio", .type = Type::Number, .default_number = 0.3, .min = -0.999, .max = 0.499,
       .doc = "the elastic pins' Poisson ratio (with pin_youngs_modulus_mpa)"},
      {.path = "static_study.enabled", .type = Type::Boolean, .default_number = 1, .doc = "also solve the static pose study (gravity and payload, at rest)"},
      {.path = "static_study.dphi_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0, .min = -180, .max = 180,
       .doc = "lever angle of the static pose from the design position"},
      {.path = "rotary_module.enabled", .type = Type::Boolean, .default_number = 0,
       .doc = "after the motion, the gripper turns the casting about the arm's axis (out of the plane): the spatial multibody "
              "core and every part's stress over the motion and the turn (docs/multibody.md, rotary module)"},
      {.path = "rotary_module.angle_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 90, .min = -360, .max = 360,
       .doc = "the turn about the arm's axis A -> C (cycloidal law)"},
      {.path = "rotary_module.start_s", .type = Type::Number, .unit = "s", .min = 0,
       .doc = "when the turn starts (default: at the end of the lever's motion)"},
      {.path = "rotary_module.duration_s", .type = Type::Number, .unit = "s", .default_number = 1.0, .min = 0, .max = 1e4, .min_exclusive = true,
       .doc = "how long the turn takes"},
      {.path = "rotary_module.gripper_inertia_kgm2", .type = Type::Vector3, .unit = "kg*m^2",
       .default_vector = std::array<double, 3>{0.15, 0.15, 0.15},
       .doc = "the turning gripper's principal inertias about H in the arm's axes (x along A -> C, y in the plane, z along the pins)"},
      {.path = "rotary_module.casting_offset_mm", .type = Type::Vector3, .unit = "mm", .to_si = kMm,
       .default_vector = std::array<double, 3>{0.0, -120.0, 0.0},
       .doc = "the casting's centre of mass from H, arm axes at the start"},
      {.path = "rotary_module.casting_inertia_kgm2", .type = Type::Vector3, .unit = "kg*m^2",
       .default_vector = std::array<double, 3>{0.05, 0.05, 0.05},
       .doc = "the casting's principal inertias about its centre, arm axes at the start"},
    };
    for (auto&& k : lever_chain_dimension_keys("mechanism.")) s.push_back(std::move(k));
    add_manipulator_assembly_keys(s);
    add_fatigue_keys(s);
    add_vibration_keys(s);
    add_motion_law_keys(s, "motion.", "law",
                        {.default_law = "polynomial345", .default_stroke_deg = 80.0, .default_duration_s = 2.0, .angles_only = true});
    for (auto&& k : part_mesh_keys()) s.push_back(std::move(k));
    for (auto&& k : motion_solver_keys()) s.push_back(std::move(k));
    return with_common_keys(std::move(s));
  }();
  return schema;
}

namespace {

// The SPEC §1/§2 definition from [mechanism], [payload] and [motion]; the
// links' mass properties come from their meshes later (placeholders here).
mech::ManipulatorDefinition read_definition(const CaseFile& c) {
  mech::ManipulatorDefinition def;
  def.type = c.text_value("mechanism.type") == "lever_chain" ? mech::ManipulatorType::LeverChain : mech::ManipulatorType::Lever;
  def.geometry = read_lever_chain_geometry(c, "mechanism.");
  const Eigen::Vector3d gravity = c.vector3("mechanism.gravity_m_s2");
  require(gravity.z() == 0.0, "{} = [{}, {}, {}]: the z component (along the pins) must be 0 for the planar model",
          c.where("mechanism.gravity_m_s2"), gravity.x(), gravity.y(), gravity.z());
  def.gravity_m_s2 = gravity.head<2>();
  def.gripper_mass_kg = c.number("payload.gripper_mass_kg");
  def.casting_mass_kg = c.number("payload.casting_mass_kg");
  def.lever_motion = read_motion_law(c, "motion.", "law", /*angle=*/true);
  def.lever = def.arm = def.rocker = {1.0, {0.0, 0.0}, 1.0};  // replaced by the meshes' (apply_mass_properties)
  return def;
}

pipeline::ManipulatorLinks read_links(const CaseFile& c) {
  pipeline::ManipulatorLinks links;
  links.lever.width_m = c.number("links.lever_width_mm");
  links.lever.thickness_m = c.number("links.lever_thickness_mm");
  links.lever.bore_diameter_m = c.number("links.bore_diameter_mm");
  links.lever.boss_diameter_m = c.number("links.boss_diameter_mm");
  links.lever.boss_length_m = c.number("links.boss_length_mm");
  links.arm.arm_depth_m = c.number("links.arm_depth_mm");
  links.arm.arm_thickness_m = c.number("links.arm_thickness_mm");
  const std::string bore_load = c.text_value("loads.bore_load");
  links.bore_load = bore_load == "bearing"   ? loads::BoreLoad::BearingPressure
                    : bore_load == "contact" ? loads::BoreLoad::Contact
                                             : loads::BoreLoad::DistributingCoupling;
  const bool clearance = c.has("loads.clearance_mm"), fit = c.has("loads.fit");
  require(links.bore_load == loads::BoreLoad::Contact || (!clearance && !fit),
          "{}: a pin clearance or fit needs loads.bore_load = \"contact\"", c.where(clearance ? "loads.clearance_mm" : "loads.fit"));
  require(!(clearance && fit), "{}: give loads.clearance_mm or loads.fit, not both", c.where("loads.fit"));
  const bool elastic = c.has("loads.pin_youngs_modulus_mpa");
  require(links.bore_load == loads::BoreLoad::Contact || !elastic,
          "{}: an elastic pin needs loads.bore_load = \"contact\"", c.where("loads.pin_youngs_modulus_mpa"));
  require(elastic || !c.has("loads.pin_poisson_ratio"), "{}: a pin's Poisson ratio needs loads.pin_youngs_modulus_mpa",
          c.where("loads.pin_poisson_ratio"));
  if (elastic) {
    fem::IsotropicMaterial pin;
    pin.name = "pin";
    pin.youngs_modulus_pa = c.number("loads.pin_youngs_modulus_mpa");
    pin.poisson_ratio = c.number("loads.pin_poisson_ratio");
    links.pin_fit.pin_material = pin;
  }
  if (clearance) links.pin_fit.clearance_m = c.number("loads.clearance_mm");
  if (fit) {
    links.pin_fit.fit = c.text_value("loads.fit");
    try {
      loads::check_fit(links.pin_fit.fit);
    } catch (const Error& e) {
      fail("{}: {}", c.where("loads.fit"), e.what());
    }
  }
  return links;
}

void print_published_comparison(const ManipulatorSummary& s, mech::ManipulatorType type, bool with_static) {
  const mech::PublishedAnalysis pub = mech::published_analysis(type);
  std::printf("\n  Comparison with the published analysis (SPEC §3; the published load case is static: the casting's weight)\n");
  std::printf("  %-44s %-52s %12s %12s %10s\n", "quantity", "published", "static", "over motion", "ratio*");
  const auto statics = [&](double v, double unit, const char* name, int digits) {
    return with_static ? fmt::format("{:.{}f} {}", v / unit, digits, name) : std::string("-");
  };
  const auto row = [&](const char* quantity, const char* source, double published, double static_value, double motion,
                       double unit, const char* unit_name, int digits) {
    std::printf("  %-44s %-52s %13s %9.*f %s %10.3f\n", quantity, source, statics(static_value, unit, unit_name, digits).c_str(),
                digits, motion / unit, unit_name, (with_static ? static_value : motion) / published);
  };
  row("max von Mises (per-link)", pub.von_mises_source, pub.von_mises_pa, s.static_max_von_mises_pa, s.max_von_mises_pa,
      kMpa, "MPa", 3);
  if (s.assembly) {
    const pipeline::AssemblySummary& a = *s.assembly;
    row("total deformation, assembly (figure reading)", pub.deformation_figure_source, pub.deformation_figure_m,
        a.static_max_displacement_m, a.max_displacement_m, kMm, "mm", 4);
    row("total deformation, assembly (text reading)", "SPEC §3, text: about 0.1 mm", pub.deformation_text_m,
        a.static_max_displacement_m, a.max_displacement_m, kMm, "mm", 4);
  }
  row("per-link elastic deformation (figure)", pub.deformation_figure_source, pub.deformation_figure_m,
      s.static_max_displacement_m, s.max_displacement_m, kMm, "mm", 4);
  row("per-link elastic deformation (text)", "SPEC §3, text: about 0.1 mm", pub.deformation_text_m,
      s.static_max_displacement_m, s.max_displacement_m, kMm, "mm", 4);
  std::printf("  * ratio = computed (static study when enabled) / published. Total deformation: the assembly held by its\n"
              "    frame, max |u| over every node, world axes (ANSYS's \"Total Deformation\"); per-link: each link's elastic\n"
              "    deformation in its own body frame (rigid-body motion removed).%s\n",
              s.assembly ? "" : " The assembly is off (assembly.enabled = false).");
}

// The manipulator's own half of the motion case: the preset's model and
// parts, the output times, the dynamics, the static pose and H's path.
driver::MotionStressCase read_preset(const CaseFile& c, const mech::ManipulatorDefinition& def) {
  driver::MotionStressCase run_case;
  run_case.model = mech::make_manipulator_model(def);
  for (auto& body : run_case.model.bodies)  // the placeholders: no case values, the meshes give them
    if (!body.fixed) body.mass_kg = body.inertia_kgm2 = 0.0, body.com_body.setZero();
  const pipeline::ManipulatorLinks links = read_links(c);  // its key errors name their keys
  try {
    run_case.parts = pipeline::manipulator_parts(def, links);
  } catch (const Error& e) {
    fail("{}: [links]: {}", c.path().string(), e.what());
  }
  run_case.times = mech::equally_spaced_times(c.number("motion.duration_s"), c.integer("motion.output_times"));
  run_case.dynamics.method = c.text_value("dynamics.method") == "idas" ? pipeline::DynamicsMethod::Idas
                                                                      : pipeline::DynamicsMethod::Kinematic;
  if (c.boolean("static_study.enabled")) run_case.static_pose = std::vector<double>{c.number("static_study.dphi_deg")};
  run_case.tracked_points = {{mech::manipulator::kArm, mech::manipulator::kPointH}};
  return run_case;
}

}  // namespace

ManipulatorSummary run_manipulator(const CaseFile& c, const RunOptions& options) {
  Stopwatch total;
  const std::string name = mechanism_case_name(c);

  // ---- read the case: the SPEC §1/§2 preset, then the keys every motion case shares
  const mech::ManipulatorDefinition def = read_definition(c);
  const bool chain = def.type == mech::ManipulatorType::LeverChain;
  const Log log = start_case_log(c, options, name, fmt::format("{} manipulator", chain ? "lever-chain" : "lever"));
  const auto& g = def.geometry;
  log.info("  synthesis (SPEC §1): a = {:.3f} mm, c = {:.3f}, h = {:.3f}, r = {:.3f}; b0 = {:.3f} mm, l0 = {:.3f} mm, "
           "alpha0 = {:.3f} deg",
           g.a_m / kMm, g.c_m / kMm, g.h_m / kMm, g.r_m / kMm, g.b0_m / kMm, g.l0_m / kMm, g.alpha0_rad / kDeg);
  driver::MotionStressCase run_case = read_preset(c, def);
  read_shared_motion_keys(c, options, name, [&](const std::vector<std::string>&) {
    return read_manipulator_assembly(c, chain);
  }, run_case);

  // The rotary module's keys, read before any work.
  std::optional<pipeline::RotaryModuleSettings> rotary;
  if (c.boolean("rotary_module.enabled")) {
    pipeline::RotaryModuleSettings r;
    r.angle_rad = c.number("rotary_module.angle_deg");
    r.start_s = c.has("rotary_module.start_s") ? c.number("rotary_module.start_s") : run_case.times.back();
    r.duration_s = c.number("rotary_module.duration_s");
    for (const char* key : {"rotary_module.gripper_inertia_kgm2", "rotary_module.casting_inertia_kgm2"}) {
      const Eigen::Vector3d v = c.vector3(key);
      require(v.minCoeff() > 0 && v.allFinite(), "{} = [{}, {}, {}]: principal inertias must be positive",
              c.where(key), v.x(), v.y(), v.z());
    }
    r.gripper_inertia_kgm2 = c.vector3("rotary_module.gripper_inertia_kgm2").asDiagonal();
    r.casting_offset_m = c.vector3("rotary_module.casting_offset_mm");
    r.casting_inertia_kgm2 = c.vector3("rotary_module.casting_inertia_kgm2").asDiagonal();
    require(!run_case.parts.empty(), "{}: the rotary module's stage needs the links as FE parts", c.where("rotary_module.enabled"));
    // What the spatial loads and the spatial assembly do not take yet, refused
    // before any work (the stage runs after the planar pipeline).
    require(c.text_value("loads.bore_load") == "coupling",
            "{} = \"{}\": with the rotary module the pins' loads enter through distributing couplings only (the "
            "spatial loads have no bearing pressure or contact yet)",
            c.where("loads.bore_load"), c.text_value("loads.bore_load"));
    if (run_case.assembly) {
      require(run_case.assembly->drives.empty(),
              "{}: with the rotary module the spatial elastic assembly holds the drives rigidly (a compliant drive is "
              "not taken yet): leave it out, or set assembly.enabled = false",
              c.where("assembly.drive_stiffness_n_m_per_rad"));
      require(run_case.assembly->coupling == structure::BoreCoupling::Distributing,
              "{} = \"rigid_bore\": with the rotary module the spatial elastic assembly has distributing couplings only",
              c.where("assembly.coupling"));
    }
    rotary = r;
  }

  // ---- run the pipeline --------------------------------------------------------
  const driver::MotionStressRun run = driver::run_motion_to_stress(run_case, log);
  std::optional<pipeline::RotaryModuleSummary> turned;
  if (rotary) {
    try {
      const std::vector<pipeline::Part> parts =
          pipeline::build_part_models(run_case.parts, run_case.material, run_case.mesh, log);
      std::filesystem::path file = run.results_file;
      file.replace_filename(file.stem().string() + ".rotary_module.h5");
      turned = pipeline::analyse_rotary_module(run.model, parts, run_case.times, *rotary, file, run_case.provenance,
                                               run_case.stress, log,
                                               run_case.assembly ? &*run_case.assembly : nullptr,
                                               run_case.vibration ? &run_case.vibration->modes : nullptr,
                                               run_case.fatigue ? &*run_case.fatigue : nullptr);
    } catch (const Error& e) {
      fail("{}: rotary module: {}", c.path().string(), e.what());
    }
  }

  // ---- summary -----------------------------------------------------------------
  const pipeline::PartExtremes pe = pipeline::part_extremes(run.parts);
  const pipeline::MechanismExtremes me = pipeline::mechanism_extremes(run.model, run.motion);
  ManipulatorSummary summary{
      .mechanism = chain ? "lever_chain" : "lever", .links = run.parts,
      .max_von_mises_pa = pe.max_von_mises_pa, .max_displacement_m = pe.max_displacement_m,
      .static_max_von_mises_pa = pe.static_max_von_mises_pa, .static_max_displacement_m = pe.static_max_displacement_m,
      .max_drive_torque_nm = me.max_abs_drive_effort, .min_chain_tension_n = me.min_chain_tension_n,
      .max_chain_tension_n = me.max_chain_tension_n, .assembly = run.assembly, .vibration = run.vibration,
      .factorization = run.factorization, .fatigue = run.fatigue, .results_file = run.results_file,
      .meshing_seconds = run.meshing_seconds, .dynamics_seconds = run.dynamics_seconds};
  std::printf("\nSummary of '%s' (%s manipulator, %zu output times over %.3f s)\n%s%s", name.c_str(),
              chain ? "lever-chain" : "lever", run.motion.frames.size(), run_case.times.back(),
              pipeline::format_part_table(run.parts).c_str(), me.text.c_str());
  print_stage_summaries(run);
  print_published_comparison(summary, def.type, run_case.static_pose.has_value());
  summary.total_seconds = total.seconds();
  if (turned) {
    std::printf("  rotary module: the casting turned %.1f deg about the arm; peak torque %.3f N m at t = %.4f s (the arm's "
                "torsion); parts under the spatial loads over the motion and the turn:\n",
                rotary->angle_rad / kDeg, turned->peak_torque_nm, turned->peak_torque_time_s);
    for (const pipeline::PartSummary& p : turned->parts)
      std::printf("    %-8s peak von Mises %.3f MPa at t = %.4f s, deformation %.4f mm; equilibrium %.1e\n", p.body.c_str(),
                  p.peak_von_mises_pa / kMpa, p.peak_von_mises_time_s, p.peak_displacement_m / kMm,
                  p.worst_equilibrium_residual);
    if (turned->assembly)
      for (const pipeline::PointSummary& ps : turned->assembly->points) {
        std::string split;
        for (const structure::PointContribution& share : ps.contributions_at_max)
          split += fmt::format("{}{} {:.4f}", split.empty() ? "" : ", ", share.name,
                               share.displacement_m.dot(ps.displacement_at_max_m.normalized()) / kMm);
        std::printf("    elastic assembly, point %-8s deflection up to %.4f mm at t = %.4f s (x %.4f, y %.4f, z %.4f "
                    "mm); split along it (mm): %s\n",
                    ps.name.c_str(), ps.max_displacement_m / kMm, ps.max_displacement_time_s,
                    ps.displacement_at_max_m.x() / kMm, ps.displacement_at_max_m.y() / kMm,
                    ps.displacement_at_max_m.z() / kMm, split.c_str());
      }
    for (const pipeline::PartFatigue& f : turned->fatigue)
      std::printf("    %-8s fatigue over the stroke and the turn: utilization %.3f, life %s (critical node %ld)\n",
                  f.body.c_str(), f.max_utilization,
                  std::isinf(f.min_life_s) ? "infinite" : fmt::format("{:.3g} h", f.min_life_s / 3600.0).c_str(),
                  f.critical_node);
    if (turned->assembly && turned->assembly->vibration) {
      const pipeline::SpatialAssemblySummary::Vibration& v = *turned->assembly->vibration;
      std::printf("    natural frequencies with the module (frozen in each pose): first %.3f Hz at t = %.4f s to %.3f "
                  "Hz at t = %.4f s\n",
                  v.lowest_first_hz, v.lowest_first_time_s, v.highest_first_hz, v.highest_first_time_s);
    }
    std::printf("    results: %s (+ .xdmf)\n", turned->results_file.string().c_str());
  }
  std::printf("  results: %s (+ .xdmf)\n  wall time: %.2f s\n", summary.results_file.string().c_str(), summary.total_seconds);
  return summary;
}

}  // namespace kinetofem::app
