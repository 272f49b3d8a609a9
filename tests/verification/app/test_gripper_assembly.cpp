// The SPEC §6 gripper of cases/gripper_parts in the elastic assembly with
// rigid links: its only compliance is the slider's drive train, of axial
// stiffness k (a displacement drive held through a spring). Rigid: the
// case's parts with E x 1e9 (the links' loops are statically indeterminate
// out of the plane, so rigid bodies alone cannot carry them; at 1e9 the parts'
// share is ~1e-9 of the drive's, below the tolerance). The linkage has
// one degree of freedom, so the drive's stretch ds moves every body along
// it, and a point P by (v_P / s') ds (its velocity over the slider's, from
// the model's kinematics). By hand:
//     ds = -F_d / k   (F_d the drive's force on the slider, the multibody effort)
//     the jaws' relative opening = ((v_upper - v_lower) . e_y / s') ds
// References and tolerances: the drive's force equals the multibody effort
// (the structure is determinate: 1e-9 of it); each pad's displacement and
// the jaws' opening equal the hand values, 1e-6 (the tolerance; the
// same statics, measured at round-off).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/app/part_keys.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/mechanisms/motion_law_factory.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::app {
namespace {

// World velocity of a body point (body frame).
Eigen::Vector2d velocity_of(const mech::Frame& f, const std::string& body, const Eigen::Vector2d& p) {
  const auto b = std::find_if(f.bodies.begin(), f.bodies.end(), [&](const mech::BodyFrame& x) { return x.name == body; });
  const double c = std::cos(b->q(2)), s = std::sin(b->q(2));
  const Eigen::Vector2d r(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return b->q_dot.head<2>() + b->q_dot(2) * Eigen::Vector2d(-r.y(), r.x());
}

TEST(GripperAssembly, JawsOpenByTheDriveTrainsStretchMappedThroughTheLinkage) {
  const CaseFile c = CaseFile::load("cases/gripper_parts/case.toml", linkage_schema(), false,
                                    {"mesh.element_size_mm=6", "mesh.order=1"});
  mech::MultibodyModel m = read_linkage_model(c);
  const std::vector<pipeline::PartSpec> specs = read_parts(c, m);
  fem::IsotropicMaterial rigid;
  rigid.youngs_modulus_pa = c.number("material.youngs_modulus_mpa") * 1e9;
  rigid.poisson_ratio = c.number("material.poisson_ratio");
  rigid.density_kg_m3 = c.number("material.density_kg_m3");
  meshes::MeshOptions mesh;
  mesh.element_size_m = c.number("mesh.element_size_mm");
  mesh.order = int(c.integer("mesh.order"));
  const std::vector<pipeline::Part> parts = pipeline::build_part_models(specs, rigid, mesh, Log::quiet());
  pipeline::apply_mass_properties(m, parts, Log::quiet(), specs);
  // The stroke at a constant speed: the same poses, a slider speed at every
  // output time (the case's 3-4-5 law starts and ends at rest).
  mech::MotionDrive& drive = m.motion_drives.at(0);
  const std::vector<double> times =
      mech::equally_spaced_times(c.number("simulation.duration_s"), c.integer("simulation.output_times"));
  const double stroke = drive.law->at(times.back()).s - drive.law->at(0.0).s;
  drive.initial = drive.initial.value() + drive.law->at(0.0).s;
  drive.law = mech::make_motion_law({.law = "constant_velocity", .speed = stroke / times.back()});
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(m), {times[5], times[24], times[43]});

  const double k = 2.0e6;  // N/m
  structure::AssemblyOptions options;
  structure::DriveHold hold{drive.name};
  hold.axial_stiffness_n_per_m = k;
  options.drives = {hold};
  options.points = {{"upper", "jaw_upper", "grip", "pad"}, {"lower", "jaw_lower", "grip", "pad"}};
  options.recover_stress = false;
  structure::ElasticAssembly assembly(parts, m, options);
  auto grip_of = [&](const std::string& body) {
    const auto b = std::find_if(m.bodies.begin(), m.bodies.end(), [&](const mech::Body& x) { return x.name == body; });
    return b->points.at("grip");
  };
  for (const mech::Frame& f : motion.frames) {
    const structure::PoseSolution pose = assembly.solve(f);
    const structure::DriveResult& d = pose.drive(drive.name);
    const double effort = f.drives.at(0).effort, s_dot = f.drives.at(0).s_dot;
    EXPECT_NEAR(d.force_on_j_n, effort, 1e-9 * std::abs(effort));
    const double ds = -effort / k;
    EXPECT_NEAR(d.stretch_m, ds, 1e-9 * std::abs(ds));
    const Eigen::Vector2d v_up = velocity_of(f, "jaw_upper", grip_of("jaw_upper")) / s_dot;
    const Eigen::Vector2d v_lo = velocity_of(f, "jaw_lower", grip_of("jaw_lower")) / s_dot;
    const Eigen::Vector3d u_up = pose.point("upper").displacement_m, u_lo = pose.point("lower").displacement_m;
    const double opening = (u_up - u_lo).y(), hand = (v_up - v_lo).y() * ds;
    std::printf("  t = %.4f s: drive force %.3f N, stretch %.4e m; jaws open %.6e m, by hand %.6e m (%.1e)\n", f.t,
                effort, ds, opening, hand, std::abs(opening / hand - 1));
    EXPECT_LT((u_up.head<2>() - v_up * ds).norm(), 1e-6 * std::abs(hand));
    EXPECT_LT((u_lo.head<2>() - v_lo * ds).norm(), 1e-6 * std::abs(hand));
    EXPECT_NEAR(opening, hand, 1e-6 * std::abs(hand));
    // All of it is the drive train's, to the parts' 1e-9.
    for (const auto* p : {&pose.point("upper"), &pose.point("lower")})
      for (const auto& share : p->contributions)
        if (share.name == "drive." + drive.name)
          EXPECT_LT((share.displacement_m - p->displacement_m).norm(), 1e-6 * std::abs(hand));
  }
}

}  // namespace
}  // namespace kinetofem::app
