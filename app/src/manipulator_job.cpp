#include "kinetofem/app/manipulator_job.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/meshes/arm.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/solver/couplings.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
constexpr double kMm = 1e-3, kMpa = 1e6, kDeg = std::numbers::pi / 180.0;

// SPEC §3: the published stress analyses (source 002, ch. IV).
struct Published {
  double von_mises_pa;
  const char* von_mises_note;
  double deformation_figure_m;
  double deformation_text_m;
};
Published published_values(mech::ManipulatorType type) {
  if (type == mech::ManipulatorType::LeverChain)
    return {23.1e6, "23.1 MPa (fig. IV.9; text: below 24 MPa)", 0.86e-3, 0.1e-3};
  return {16e6, "below 16 MPa (text)", 0.89e-3, 0.1e-3};
}
}  // namespace

const std::vector<KeySpec>& manipulator_schema() {
  static const meshes::LeverDimensions lever;
  static const meshes::ArmDimensions arm;
  static const fem::IsotropicMaterial steel;
  static const std::vector<KeySpec> schema = with_common_keys({
      {.path = "case.name", .type = Type::String, .doc = "name of the run; results/<name>.h5 (default: the case folder's name)"},
      {.path = "case.type", .type = Type::String, .allowed = {"manipulator"}, .doc = "kind of analysis", .required = true},
      {.path = "case.description", .type = Type::String, .doc = "free text"},
      {.path = "mechanism.type", .type = Type::String, .allowed = {"lever_chain", "lever"}, .doc = "SPEC §1 lever-chain or SPEC §2 lever (four-bar) manipulator", .required = true},
      {.path = "mechanism.a_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 500, .min = 0, .min_exclusive = true, .doc = "lever length a = |A0 A| (SPEC §1)"},
      {.path = "mechanism.c_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 350, .min = 0, .min_exclusive = true, .doc = "c = |A C| along link 2"},
      {.path = "mechanism.h_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 100, .min = 0, .doc = "h: offset of the gripper point H from C"},
      {.path = "mechanism.r_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 75, .min = 0, .min_exclusive = true, .doc = "roller radius r (lever-chain) = coupler length AB (lever)"},
      {.path = "mechanism.gravity_m_s2", .type = Type::Vector3, .unit = "m/s^2", .default_number = 0.0,
       .doc = "gravity in the mechanism frame (x, y in the plane; z must be 0); default [0, -9.80665, 0]"},
      {.path = "payload.gripper_mass_kg", .type = Type::Number, .unit = "kg", .default_number = 20, .min = 0, .doc = "gripper mass, lumped at H"},
      {.path = "payload.casting_mass_kg", .type = Type::Number, .unit = "kg", .default_number = 15, .min = 0, .doc = "casting mass, lumped at H"},
      {.path = "motion.law", .type = Type::String, .default_text = "polynomial345", .allowed = {"polynomial345", "cycloidal", "trapezoidal"},
       .doc = "motion law of the lever angle dphi(t)"},
      {.path = "motion.stroke_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 80, .min = -180, .max = 180,
       .doc = "lever rotation over the motion, from the design position (counter-clockwise positive)"},
      {.path = "motion.duration_s", .type = Type::Number, .unit = "s", .default_number = 2.0, .min = 0, .min_exclusive = true, .doc = "duration of the motion"},
      {.path = "motion.accel_fraction", .type = Type::Number, .default_number = 0.25, .min = 0, .max = 1, .doc = "trapezoidal law: acceleration time fraction kP"},
      {.path = "motion.decel_fraction", .type = Type::Number, .default_number = 0.25, .min = 0, .max = 1, .doc = "trapezoidal law: deceleration time fraction kT"},
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
      {.path = "mesh.element_size_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 8.0, .min = 0, .min_exclusive = true, .doc = "target element edge length"},
      {.path = "mesh.order", .type = Type::Integer, .default_number = 2, .min = 1, .max = 2, .doc = "element order: 1 (TET4) or 2 (TET10)"},
      {.path = "mesh.cache", .type = Type::Boolean, .default_number = 1,
       .doc = "keep meshes in <output dir>/mesh_cache, keyed by a hash of the geometry, dimensions and mesh options, and reuse them"},
      {.path = "loads.bore_load", .type = Type::String, .default_text = "coupling", .allowed = {"coupling", "bearing"},
       .doc = "pin loads on bores: 'coupling' (distributing, RBE3-like: exact resultant, any reaction) or 'bearing' (cosine pressure)"},
      {.path = "static_study.enabled", .type = Type::Boolean, .default_number = 1, .doc = "also solve the static pose study (gravity and payload, at rest)"},
      {.path = "static_study.dphi_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0, .min = -180, .max = 180,
       .doc = "lever angle of the static pose from the design position"},
      {.path = "solver.block_size", .type = Type::Integer, .default_number = 32, .min = 1, .max = 100000, .doc = "right-hand sides per block solve"},
  });
  return schema;
}

namespace {

struct Link {
  std::string name;
  fem::FeModel model;  // body frame, with the 3-2-1 support
  loads::LinkDefinition definition;
};

std::shared_ptr<const mech::MotionLaw> motion_law(const CaseFile& c) {
  const std::string law = c.text_value("motion.law");
  const double stroke = c.number("motion.stroke_deg"), duration = c.number("motion.duration_s");
  if (law == "cycloidal") return std::make_shared<mech::CycloidalLaw>(stroke, duration);
  if (law == "trapezoidal")
    return std::make_shared<mech::TrapezoidalLaw>(stroke, duration, c.number("motion.accel_fraction"),
                                                  c.number("motion.decel_fraction"));
  return std::make_shared<mech::Polynomial345Law>(stroke, duration);
}

}  // namespace

ManipulatorSummary run_manipulator(const CaseFile& c, const RunOptions& options) {
  Log log(options.quiet ? Log::Level::Quiet : Log::Level::Normal);
  Stopwatch total;
  const std::string name =
      c.has("case.name") ? c.text_value("case.name")
                         : std::filesystem::absolute(c.path()).parent_path().filename().string();
  const bool chain = c.text_value("mechanism.type") == "lever_chain";
  const mech::ManipulatorType type = chain ? mech::ManipulatorType::LeverChain : mech::ManipulatorType::Lever;
  log.info("kinetofem: case '{}' ({}), {} manipulator", name, c.path().string(), chain ? "lever-chain" : "lever");
  std::error_code ec;
  std::filesystem::create_directories(options.output_dir, ec);
  if (ec) fail("{}: cannot create the output directory: {}", options.output_dir.string(), ec.message());

  // ---- mechanism geometry, material, meshes -------------------------------
  mech::ManipulatorDefinition def;
  def.type = type;
  try {
    def.geometry = mech::make_lever_chain_geometry(c.number("mechanism.a_mm"), c.number("mechanism.c_mm"),
                                                   c.number("mechanism.h_mm"), c.number("mechanism.r_mm"));
  } catch (const Error& e) {
    fail("{}: [mechanism]: {}", c.path().string(), e.what());
  }
  const auto& g = def.geometry;
  log.info("  synthesis (SPEC §1): a = {:.3f} mm, c = {:.3f}, h = {:.3f}, r = {:.3f}; b0 = {:.3f} mm, "
           "l0 = {:.3f} mm, alpha0 = {:.3f} deg",
           g.a_m / kMm, g.c_m / kMm, g.h_m / kMm, g.r_m / kMm, g.b0_m / kMm, g.l0_m / kMm, g.alpha0_rad / kDeg);
  if (c.has("mechanism.gravity_m_s2")) {
    const Eigen::Vector3d gravity = c.vector3("mechanism.gravity_m_s2");
    require(gravity.z() == 0.0, "{} = [{}, {}, {}]: the z component (along the pins) must be 0 for the planar model",
            c.where("mechanism.gravity_m_s2"), gravity.x(), gravity.y(), gravity.z());
    def.gravity_m_s2 = gravity.head<2>();
  }
  def.gripper_mass_kg = c.number("payload.gripper_mass_kg");
  def.casting_mass_kg = c.number("payload.casting_mass_kg");
  try {
    def.lever_motion = motion_law(c);
  } catch (const Error& e) {
    fail("{}: [motion]: {}", c.path().string(), e.what());
  }

  const fem::IsotropicMaterial material = read_material(c);

  meshes::MeshOptions mesh_options;
  mesh_options.element_size_m = c.number("mesh.element_size_mm");
  mesh_options.order = int(c.integer("mesh.order"));
  if (c.boolean("mesh.cache")) mesh_options.cache_dir = options.output_dir / "mesh_cache";

  meshes::LeverDimensions lever_dims;
  lever_dims.length_m = g.a_m;
  lever_dims.width_m = c.number("links.lever_width_mm");
  lever_dims.thickness_m = c.number("links.lever_thickness_mm");
  lever_dims.bore_diameter_m = c.number("links.bore_diameter_mm");
  lever_dims.boss_diameter_m = c.number("links.boss_diameter_mm");
  lever_dims.boss_length_m = c.number("links.boss_length_mm");
  meshes::ArmDimensions arm_dims = chain ? meshes::lever_chain_arm(g.c_m, g.h_m, g.r_m)
                                         : meshes::lever_coupler(g.c_m, g.h_m, g.r_m);
  arm_dims.arm_depth_m = c.number("links.arm_depth_mm");
  arm_dims.arm_thickness_m = c.number("links.arm_thickness_mm");
  arm_dims.bore_diameter_m = lever_dims.bore_diameter_m;
  arm_dims.boss_diameter_m = lever_dims.boss_diameter_m;
  arm_dims.boss_length_m = lever_dims.boss_length_m;
  meshes::LeverDimensions rocker_dims = lever_dims;
  rocker_dims.length_m = g.b0_m;
  try {
    lever_dims.validate();
    arm_dims.validate();
    if (!chain) rocker_dims.validate();
  } catch (const Error& e) {
    fail("{}: [links]: {}", c.path().string(), e.what());
  }

  // The motion must be possible before anything is meshed: a four-bar driven
  // past its limit of assembly or through a dead centre, or a slack chain,
  // stops here with the time (the links' inertias only scale the loads, so
  // nominal ones do for this check).
  const long n_times = c.integer("motion.output_times");
  const double duration = c.number("motion.duration_s");
  std::vector<double> times;
  for (long k = 0; k < n_times; ++k) times.push_back(duration * double(k) / double(n_times - 1));
  {
    mech::ManipulatorDefinition nominal = def;
    const double a = def.geometry.a_m;
    nominal.lever = {10.0, {0.0, 0.5 * a}, 10.0 * a * a / 12.0};
    nominal.arm = {10.0, {-0.5 * def.geometry.c_m, 0.0}, 10.0 * def.geometry.c_m * def.geometry.c_m / 12.0};
    nominal.rocker = {10.0, {0.0, 0.5 * def.geometry.b0_m}, 10.0 * def.geometry.b0_m * def.geometry.b0_m / 12.0};
    try {
      mech::KinematicOptions check;
      check.slack_is_error = false;  // the chain tension is checked with the real masses below
      mech::run_kinematics(mech::MultibodySystem(mech::make_manipulator_model(nominal)), times, check);
    } catch (const Error& e) {
      fail("{}: the motion cannot be run: {}", c.path().string(), e.what());
    }
  }

  std::vector<Link> links;
  auto add_link = [&](const std::string& link_name, fem::Mesh mesh) {
    Link link;
    link.name = link_name;
    link.model.mesh = std::move(mesh);
    link.model.material = material;
    log.info("  mesh of {}: {} nodes, {} TET{} elements, {} DoFs", link_name, link.model.mesh.node_count(),
             link.model.mesh.element_count(), mesh_options.order == 2 ? 10 : 4, 3 * link.model.mesh.node_count());
    links.push_back(std::move(link));
  };
  Stopwatch clock;
  log.info("meshing links (element size {:.1f} mm, order {})", mesh_options.element_size_m / kMm, mesh_options.order);
  add_link("lever", meshes::mesh_lever(lever_dims, mesh_options));
  add_link("arm", meshes::mesh_arm(arm_dims, mesh_options));
  if (!chain) add_link("rocker", meshes::mesh_lever(rocker_dims, mesh_options));
  log.info("  meshing: {:.2f} s", clock.seconds());
  const double meshing_seconds = clock.seconds();

  // ---- multibody model with the meshes' mass properties ------------------
  auto inertia_of = [&](const Link& link) {
    const fem::MassProperties mp = fem::mass_properties(link.model.mesh, link.model.material);
    log.info("  {}: mass {:.3f} kg, centre of mass ({:.1f}, {:.1f}) mm, I_zz {:.4f} kg m^2", link.name, mp.mass_kg,
             mp.centre_of_mass_m.x() / kMm, mp.centre_of_mass_m.y() / kMm, mp.inertia_about_com_kgm2(2, 2));
    return mech::LinkInertia{mp.mass_kg, mp.centre_of_mass_m.head<2>(), mp.inertia_about_com_kgm2(2, 2)};
  };
  def.lever = inertia_of(links[0]);
  def.arm = inertia_of(links[1]);
  if (!chain) def.rocker = inertia_of(links[2]);
  const mech::MultibodyModel model = mech::make_manipulator_model(def);
  const mech::MultibodySystem system(model);

  log.info("dynamics: {} over {:.3f} s, {} output times ({})", def.lever_motion->describe(), duration, n_times,
           c.text_value("dynamics.method"));
  clock.restart();
  mech::Results motion;
  try {
    motion = c.text_value("dynamics.method") == "idas" ? mech::simulate_ggl(system, times)
                                                       : mech::run_kinematics(system, times);
  } catch (const Error& e) {
    fail("{}: the motion cannot be run: {}", c.path().string(), e.what());
  }
  const double dynamics_seconds = clock.seconds();
  log.info("  dynamics: {:.3f} s", dynamics_seconds);
  log.info("{}", motion.format_checks());

  // Static pose study: gravity and payload, at rest, at the chosen pose.
  const bool with_static = c.boolean("static_study.enabled");
  mech::Frame static_frame;
  if (with_static) {
    // The pose is reached by continuation from the design position (Newton
    // from the design pose alone diverges far from it): a 3-4-5 rise ends
    // with zero speed and acceleration, so its last frame is the static state.
    mech::ManipulatorDefinition at_rest = def;
    at_rest.lever_motion = std::make_shared<mech::Polynomial345Law>(c.number("static_study.dphi_deg"), 1.0);
    const mech::MultibodySystem rest_system(mech::make_manipulator_model(at_rest));
    std::vector<double> ramp;
    for (int k = 0; k <= 40; ++k) ramp.push_back(k / 40.0);
    try {
      mech::KinematicOptions ramp_options;
      ramp_options.slack_is_error = false;  // only the final, static state counts
      static_frame = mech::run_kinematics(rest_system, ramp, ramp_options).frames.back();
      for (const auto& chain : static_frame.chains)
        require(chain.tension_N > 0, "chain '{}' is slack at rest in this pose (tension {:.4g} N)",
                chain.name, chain.tension_N);
    } catch (const Error& e) {
      fail("{}: the static study's pose cannot be reached: {}", c.where("static_study.dphi_deg"), e.what());
    }
  }

  // ---- link loads and FE over the motion ------------------------------------
  const loads::BoreLoad bore_load = c.text_value("loads.bore_load") == "bearing" ? loads::BoreLoad::BearingPressure
                                                                                : loads::BoreLoad::DistributingCoupling;
  links[0].definition = {"lever", nullptr, {{"A0", "bore_A0", bore_load}, {"A", "bore_A", bore_load}}, {}, {{"lever drive", "bore_A0"}}};
  if (chain)
    links[1].definition = {"arm", nullptr,
                           {{"A", "bore_A", bore_load}, {"chain", "roller_rim", loads::BoreLoad::DistributingCoupling}},
                           {}, {}};
  else
    links[1].definition = {"arm", nullptr, {{"A", "bore_A", bore_load}, {"B", "bore_B", bore_load}}, {}, {}};
  for (const char* mass : {"gripper", "casting"})
    for (const auto& pm : model.bodies[2].point_masses)
      if (pm.name == mass) links[1].definition.point_masses.push_back({mass, "gripper_mount"});
  if (!chain)
    links[2].definition = {"rocker", nullptr, {{"B0", "bore_A0", bore_load}, {"B", "bore_A", bore_load}}, {}, {}};

  std::vector<mech::Frame> frames = motion.frames;
  if (with_static) {
    static_frame.t = frames.back().t + 1.0;  // marks the static study in messages
    frames.push_back(static_frame);
  }

  ManipulatorSummary summary;
  summary.mechanism = chain ? "lever_chain" : "lever";
  summary.meshing_seconds = meshing_seconds;
  summary.dynamics_seconds = dynamics_seconds;
  summary.results_file = options.output_dir / (name + ".h5");
  post::Provenance provenance;
  provenance.case_path = c.path().string();
  provenance.case_text = c.text();
  provenance.command_line = options.command_line;
  post::ResultsWriter writer(summary.results_file, provenance);

  loads::LinkStressOptions stress_options;
  stress_options.block_size = int(c.integer("solver.block_size"));
  stress_options.solver = read_solver_options(c);
  stress_options.envelope_steps = motion.frames.size();
  for (auto& link : links) {
    link.definition.model = &link.model;
    std::vector<fem::Index> all(size_t(link.model.mesh.node_count()));
    for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
    link.model.supports = fem::three_two_one_support(link.model.mesh, all);
    const loads::LinkLoads link_loads(link.definition, model);
    post::BodyWriter& body = writer.add_body(link.name, link.model.mesh);
    body.begin_series({{"displacement", "m", 3, post::kVectorComponents}, {"von_mises", "Pa", 1, {}}});
    LinkSummary ls;
    ls.link = link.name;
    ls.nodes = link.model.mesh.node_count();
    ls.dofs = 3 * ls.nodes;
    const auto on_step = [&](std::size_t step, const fem::DisplacementField& raw, const fem::NodalStress& s) {
      // Written and reported: the elastic deformation, rigid-body part removed.
      const fem::DisplacementField u = fem::remove_rigid_body_motion(link.model.mesh, raw);
      if (step < motion.frames.size()) {
        body.write_step(motion.frames[step].t, {{"displacement", u}, {"von_mises", s.von_mises_pa}});
        return;
      }
      body.write_static("static_displacement", "m", u, post::kVectorComponents);
      body.write_static("static_von_mises", "Pa", s.von_mises_pa);
      body.write_static("static_stress", "Pa", s.stress_pa, post::kVoigtComponents);
      ls.static_von_mises_pa = s.von_mises_pa.maxCoeff();
      ls.static_displacement_m = fem::displacement_magnitude(u).maxCoeff();
    };
    const loads::LinkEnvelope env =
        loads::analyse_link_over_motion(link.model, link_loads, frames, log, stress_options, on_step);
    post::IndexMatrix vm_step = env.max_von_mises_step.cast<fem::Index>();
    post::IndexMatrix u_step = env.max_displacement_step.cast<fem::Index>();
    body.write_envelope("von_mises", "Pa", env.max_von_mises_pa, vm_step, "max");
    body.write_envelope("displacement_magnitude", "m", env.max_displacement_m, u_step, "max");
    ls.peak_von_mises_pa = env.peak_von_mises_pa;
    ls.peak_von_mises_time_s = motion.frames[size_t(env.peak_von_mises_step)].t;
    ls.peak_displacement_m = env.peak_displacement_m;
    ls.peak_displacement_time_s = motion.frames[size_t(env.peak_displacement_step)].t;
    ls.factorize_seconds = env.solver.factorize_seconds;
    ls.solve_seconds = env.solve_seconds;
    ls.assembly_seconds = env.assembly_seconds;
    ls.recovery_seconds = env.recovery_seconds;
    ls.analyze_seconds = env.solver.analyze_seconds;
    ls.factor_nonzeros = env.solver.factor_nonzeros;
    ls.factor_bytes = env.solver.factor_bytes;
    ls.factorization_flops = env.solver.factorization_flops;
    ls.right_hand_sides = long(frames.size());
    ls.iterative_solver = env.iterative_solver;
    ls.solver_summary = env.solver_summary;
    const auto at = link.model.mesh.nodes.row(env.peak_von_mises_node) / kMm;
    log.info("  {}: peak von Mises {:.3f} MPa at t = {:.4f} s, node {} ({:.1f}, {:.1f}, {:.1f}) mm (body frame); "
             "loads in equilibrium to {:.1e}, support reactions {:.1e}",
             link.name, env.peak_von_mises_pa / kMpa, ls.peak_von_mises_time_s, env.peak_von_mises_node, at[0], at[1],
             at[2], env.worst_equilibrium_residual, env.worst_support_reaction);
    summary.links.push_back(ls);
    summary.max_von_mises_pa = std::max(summary.max_von_mises_pa, ls.peak_von_mises_pa);
    summary.max_displacement_m = std::max(summary.max_displacement_m, ls.peak_displacement_m);
    summary.static_max_von_mises_pa = std::max(summary.static_max_von_mises_pa, ls.static_von_mises_pa);
    summary.static_max_displacement_m = std::max(summary.static_max_displacement_m, ls.static_displacement_m);
  }

  // ---- mechanism histories ---------------------------------------------------
  const size_t T = motion.frames.size();
  writer.set_mechanism_time(times);
  post::FieldMatrix torque(T, 1), power(T, 1), angle(T, 1), tension(T, 1), h_path(T, 2);
  summary.min_chain_tension_n = 1e300;
  summary.max_chain_tension_n = -1e300;
  for (size_t k = 0; k < T; ++k) {
    const mech::Frame& f = motion.frames[k];
    torque(k, 0) = f.drives[0].effort;
    power(k, 0) = f.drives[0].power_W;
    angle(k, 0) = f.drives[0].s;
    summary.max_drive_torque_nm = std::max(summary.max_drive_torque_nm, std::abs(f.drives[0].effort));
    if (!f.chains.empty()) {
      tension(k, 0) = f.chains[0].tension_N;
      summary.min_chain_tension_n = std::min(summary.min_chain_tension_n, tension(k, 0));
      summary.max_chain_tension_n = std::max(summary.max_chain_tension_n, tension(k, 0));
    }
    const Eigen::Vector3d q = f.bodies[2].q;
    const Eigen::Vector2d H_body(-g.c_m, g.h_m);
    h_path.row(k) = (q.head<2>() + Eigen::Rotation2Dd(q.z()) * H_body).transpose();
  }
  writer.write_history("lever_angle", "rad", angle);
  writer.write_history("drive_torque", "N*m", torque);
  writer.write_history("drive_power", "W", power);
  writer.write_history("gripper_point_H", "m", h_path, {"x", "y"});
  if (chain) writer.write_history("chain_tension", "N", tension);
  for (size_t j = 0; j < model.joints.size(); ++j) {
    post::FieldMatrix force(T, 2);
    for (size_t k = 0; k < T; ++k) force.row(k) = motion.frames[k].joints[j].on_j.force_world.transpose();
    writer.write_history("reaction_" + model.joints[j].name + "_on_" + model.joints[j].body_j, "N", force, {"x", "y"});
  }
  writer.commit();

  // ---- summary -----------------------------------------------------------------
  const Published pub = published_values(type);
  std::printf("\nSummary of '%s' (%s manipulator, %zu output times over %.3f s)\n", name.c_str(),
              chain ? "lever-chain" : "lever", T, duration);
  std::printf("  %-8s %9s %14s %10s %14s %10s %12s %12s\n", "link", "DoFs", "max vM [MPa]", "at t [s]",
              "max |u| [mm]", "at t [s]", "static vM", "static |u|");
  for (const auto& ls : summary.links)
    std::printf("  %-8s %9ld %14.3f %10.4f %14.5f %10.4f %12.3f %12.5f\n", ls.link.c_str(), ls.dofs,
                ls.peak_von_mises_pa / kMpa, ls.peak_von_mises_time_s, ls.peak_displacement_m / kMm,
                ls.peak_displacement_time_s, ls.static_von_mises_pa / kMpa, ls.static_displacement_m / kMm);
  for (const auto& ls : summary.links)
    std::printf("  %-8s solver: %s\n", ls.link.c_str(), ls.solver_summary.c_str());
  std::printf("  drive torque: max |M| %.2f N m", summary.max_drive_torque_nm);
  if (chain) std::printf("; chain tension %.1f .. %.1f N", summary.min_chain_tension_n, summary.max_chain_tension_n);
  std::printf("\n\n  Comparison with the published analysis (SPEC §3; the published load case is static: the casting's weight)\n");
  std::printf("  %-34s %-40s %12s %12s %10s\n", "quantity", "published", "static", "over motion", "ratio*");
  const double s_vm = summary.static_max_von_mises_pa, d_vm = summary.max_von_mises_pa;
  const double s_u = summary.static_max_displacement_m, d_u = summary.max_displacement_m;
  std::printf("  %-34s %-40s %9.3f MPa %9.3f MPa %10.3f\n", "max von Mises", pub.von_mises_note, s_vm / kMpa,
              d_vm / kMpa, (with_static ? s_vm : d_vm) / pub.von_mises_pa);
  std::printf("  %-34s %-40s %10.4f mm %10.4f mm %10.3f\n", "max deformation (figure reading)",
              fmt::format("{:.2f} mm (figure legend)", pub.deformation_figure_m / kMm).c_str(), s_u / kMm, d_u / kMm,
              (with_static ? s_u : d_u) / pub.deformation_figure_m);
  std::printf("  %-34s %-40s %10.4f mm %10.4f mm %10.3f\n", "max deformation (text reading)", "about 0.1 mm (text)",
              s_u / kMm, d_u / kMm, (with_static ? s_u : d_u) / pub.deformation_text_m);
  std::printf("  * ratio = computed (static study when enabled) / published. Deformation here is each link's elastic\n"
              "    deformation in its own body frame (rigid-body motion removed), not the assembly's total deformation.\n"
              "  results: %s (+ .xdmf)\n  wall time: %.2f s\n",
              summary.results_file.string().c_str(), total.seconds());
  // Key results for `kinetofem batch`: OUTPUT_DIR/<name>.summary.toml.
  write_run_summary(options.output_dir,
                    {.name = name, .type = "manipulator", .results_file = summary.results_file,
                     .wall_time_s = total.seconds(), .max_von_mises_pa = summary.max_von_mises_pa,
                     .max_displacement_m = summary.max_displacement_m,
                     .extra = {{"static_max_von_mises_mpa", summary.static_max_von_mises_pa / kMpa},
                               {"static_max_displacement_mm", summary.static_max_displacement_m / kMm},
                               {"max_drive_torque_nm", summary.max_drive_torque_nm}}});
  summary.total_seconds = total.seconds();
  return summary;
}

}  // namespace kinetofem::app
