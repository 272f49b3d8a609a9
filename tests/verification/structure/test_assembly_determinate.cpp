// Verification 4: a statically determinate assembly (the two-link arm of
// structure_fixtures.hpp: pins J1, J2, rigid drives d1, d2) at three poses of
// its motion. The structure's joint loads are then fixed by equilibrium alone,
// so they must equal the multibody reactions (mech::Frame joints' on_i/on_j,
// drive efforts), and each part carries exactly the loads of the per-link
// analysis (reactions through the same couplings), so its stress must equal
// loads::analyse_link_over_motion's (stress does not see the rigid motion).
//
// References and tolerances: reactions 1e-8 of the largest reaction (the
// structure's are solved from a dense system of ~100 unknowns; measured
// ~1e-13); von Mises 1e-6 of the part's peak (two solves of the same loads
// with the same factorization; measured ~1e-12).
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

struct ArmRun {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
  std::vector<mech::Frame> frames;
  std::vector<PoseSolution> poses;
};

const ArmRun& run() {
  static const ArmRun r = [] {
    ArmRun r;
    r.parts = test::two_link_parts();
    r.model = test::two_link_arm();
    pipeline::apply_mass_properties(r.model, r.parts, Log::quiet());
    r.frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.1, 0.25, 0.4}).frames;
    ElasticAssembly assembly(r.parts, r.model);
    r.poses = assembly.solve(r.frames);
    return r;
  }();
  return r;
}

TEST(ElasticAssemblyDeterminate, JointLoadsEqualTheMultibodyReactions) {
  const ArmRun& r = run();
  for (size_t f = 0; f < r.frames.size(); ++f) {
    const mech::Frame& frame = r.frames[f];
    const PoseSolution& pose = r.poses[f];
    double scale = 0.0, worst = 0.0;
    for (const auto& jf : frame.joints)
      scale = std::max({scale, jf.on_i.force_world.norm(), jf.on_j.force_world.norm()});
    for (const auto& jf : frame.joints) {
      const JointLoad& jl = pose.joint(jf.name);
      // In-plane force on each side; no moment about z at a pin (the multibody
      // revolute's moment_Nm is zero); no out-of-plane force or moment (the
      // bars and loads are symmetric about z = 0).
      worst = std::max(worst, (jl.force_on_i_n.head<2>() - jf.on_i.force_world).norm());
      worst = std::max(worst, (jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm());
      worst = std::max(worst, std::abs(jl.moment_on_i_nm.z() - jf.on_i.moment_Nm) / 0.3);
      worst = std::max(worst, std::abs(jl.moment_on_j_nm.z() - jf.on_j.moment_Nm) / 0.3);
      worst = std::max({worst, std::abs(jl.force_on_j_n.z()), jl.moment_on_j_nm.head<2>().norm() / 0.3});
    }
    for (const auto& df : frame.drives) {
      scale = std::max(scale, std::abs(df.effort) / 0.3);
      worst = std::max(worst, std::abs(pose.drive(df.name).moment_on_j_nm - df.effort) / 0.3);
    }
    std::printf("  t = %.2f s: joint loads vs multibody reactions %.2e relative (largest reaction %.4g N)\n", frame.t,
                worst / scale, scale);
    EXPECT_LT(worst / scale, 1e-8) << "t = " << frame.t;
  }
}

TEST(ElasticAssemblyDeterminate, VonMisesEqualsThePerLinkAnalysis) {
  const ArmRun& r = run();
  for (const pipeline::Part& part : r.parts) {
    fem::FeModel supported = part.model;
    std::vector<fem::Index> all(size_t(supported.mesh.node_count()));
    for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
    supported.supports = fem::three_two_one_support(supported.mesh, all);
    loads::LinkDefinition def = part.attachments;
    def.model = &supported;
    const loads::LinkLoads link_loads(def, r.model);
    std::vector<Eigen::VectorXd> per_link;
    loads::analyse_link_over_motion(supported, link_loads, r.frames, Log::quiet(), {},
                                    [&](std::size_t, const fem::DisplacementField&, const fem::NodalStress& s) {
                                      per_link.push_back(s.von_mises_pa);
                                    });
    ASSERT_EQ(per_link.size(), r.frames.size());
    for (size_t f = 0; f < r.frames.size(); ++f) {
      const Eigen::VectorXd& assembly = r.poses[f].part(part.body()).von_mises_pa;
      const double peak = per_link[f].maxCoeff();
      const double error = (assembly - per_link[f]).cwiseAbs().maxCoeff() / peak;
      std::printf("  %s, t = %.2f s: peak von Mises %.4f MPa, assembly vs per-link %.2e of the peak\n",
                  part.body().c_str(), r.frames[f].t, peak * 1e-6, error);
      EXPECT_LT(error, 1e-6) << part.body() << " at t = " << r.frames[f].t;
    }
  }
}

TEST(ElasticAssemblyDeterminate, GroundHoldsTheWholeLoad) {
  // Global equilibrium, a consequence of the joint equations: the ground's
  // pin J1 carries the resultant of all the loads (both bodies'
  // applied minus inertia loads) -> its force equals the multibody's to 1e-8.
  const ArmRun& r = run();
  for (size_t f = 0; f < r.frames.size(); ++f) {
    const JointLoad& j1 = r.poses[f].joint("J1");
    const mech::JointFrame& ref = r.frames[f].joints[0];
    EXPECT_LT((j1.force_on_i_n.head<2>() - ref.on_i.force_world).norm(), 1e-8 * ref.on_i.force_world.norm());
  }
}

TEST(ElasticAssemblyDeterminate, SuperposedLoadsEqualOneSolvePerPose) {
  // Reference: the same assembly with one part solve and one stress recovery
  // per pose (superpose_loads = false). Superposition is exact in exact
  // arithmetic: 1e-10 of the peak (displacement, von Mises, every part).
  const ArmRun& r = run();
  AssemblyOptions per_pose;
  per_pose.superpose_loads = false;
  ElasticAssembly reference(r.parts, r.model, per_pose);
  const std::vector<PoseSolution> expected = reference.solve(r.frames);
  for (size_t f = 0; f < r.frames.size(); ++f)
    for (const pipeline::Part& part : r.parts) {
      const PartField& a = r.poses[f].part(part.body());
      const PartField& b = expected[f].part(part.body());
      const double u = (a.displacement_m - b.displacement_m).cwiseAbs().maxCoeff() / b.displacement_m.cwiseAbs().maxCoeff();
      const double vm = (a.von_mises_pa - b.von_mises_pa).cwiseAbs().maxCoeff() / b.von_mises_pa.maxCoeff();
      std::printf("  %s, t = %.2f s: superposed vs per-pose solve: displacement %.2e, von Mises %.2e of the peak\n",
                  part.body().c_str(), r.frames[f].t, u, vm);
      EXPECT_LT(u, 1e-10);
      EXPECT_LT(vm, 1e-10);
    }
}

}  // namespace
}  // namespace kinetofem::structure
