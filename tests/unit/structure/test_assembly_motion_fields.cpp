// ElasticAssembly::solve with MotionFields (structure/elastic_assembly.hpp):
// the envelopes, hot spots and written fields of a motion equal the full
// fields of every pose (ElasticAssembly::solve without it, folded here as the
// pipeline folded them before) within 1e-12 of the peak. The two-link arm of
// structure_fixtures.hpp with bars fine enough for several chunks of nodes,
// over more poses than one tile; with the loads superposed (the chunked
// kernel) and solved pose by pose (the full fields folded by the assembly).
#include <algorithm>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

struct FineArm {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
  std::vector<mech::Frame> frames;
};

// Bars of 40 x 4 x 2 HEX20 cells (2 000 to 3 000 nodes: three chunks) over
// 150 poses (two tiles of poses in a call of the assembly's solve).
FineArm fine_arm() {
  FineArm a;
  test::TwoLinkArm arm;
  test::BarSize size;
  size.cells = {40, 4, 2};
  size.length_m = arm.l1_m;
  loads::LinkDefinition link1{"link1", nullptr, {{"J1", "x0"}, {"J2", "x1"}}, {}, {{"d1", "x0"}, {"d2", "x1"}}};
  loads::LinkDefinition link2{"link2", nullptr, {{"J2", "x0"}}, {}, {{"d2", "x0"}}};
  link2.point_masses.push_back({"payload", "x1"});
  a.parts = {test::bar_part("link1", link1, size), test::bar_part("link2", link2, size)};
  a.model = test::two_link_arm(arm);
  pipeline::apply_mass_properties(a.model, a.parts, Log::quiet());
  std::vector<double> times;
  for (int k = 0; k < 150; ++k) times.push_back(arm.duration_s * k / 149.0);
  a.frames = mech::run_kinematics(mech::MultibodySystem(a.model), times).frames;
  return a;
}

// The envelope of full fields, as the assembly's stage folded them pose by pose.
PartEnvelope reference_envelope(const std::vector<PoseSolution>& poses, const std::string& body) {
  PartEnvelope e;
  const Eigen::Index N = poses.front().part(body).displacement_m.rows();
  e.max_displacement_m = e.max_von_mises_pa = Eigen::VectorXd::Constant(N, -1.0);
  e.displacement_step = e.von_mises_step = Eigen::VectorXi::Zero(N);
  for (size_t k = 0; k < poses.size(); ++k) {
    const PartField& field = poses[k].part(body);
    const Eigen::VectorXd magnitude = field.displacement_m.rowwise().norm();
    for (Eigen::Index i = 0; i < N; ++i) {
      if (magnitude(i) > e.max_displacement_m(i))
        e.max_displacement_m(i) = magnitude(i), e.displacement_step(i) = int(k);
      if (field.von_mises_pa(i) > e.max_von_mises_pa(i))
        e.max_von_mises_pa(i) = field.von_mises_pa(i), e.von_mises_step(i) = int(k);
    }
  }
  return e;
}

// Each node's maximum within `tolerance`, and its step the reference's, or one
// whose value (in the reference's fields) ties with the maximum within it.
void expect_same_envelope(const Eigen::VectorXd& got, const Eigen::VectorXi& got_step, const Eigen::VectorXd& expected,
                          const Eigen::VectorXi& expected_step, const std::vector<Eigen::VectorXd>& reference_fields,
                          double tolerance, const std::string& what) {
  ASSERT_EQ(got.size(), expected.size()) << what;
  double worst = 0.0;
  int moved = 0;
  for (Eigen::Index i = 0; i < got.size(); ++i) {
    worst = std::max(worst, std::abs(got(i) - expected(i)));
    if (got_step(i) != expected_step(i)) {
      ++moved;
      EXPECT_LE(std::abs(reference_fields[size_t(got_step(i))](i) - expected(i)), tolerance)
          << what << ": node " << i << " step " << got_step(i) << " against " << expected_step(i);
    }
  }
  EXPECT_LE(worst, tolerance) << what;
  std::cout << what << ": largest difference " << worst / (tolerance / 1e-12) << " of the peak, " << moved
            << " steps moved by ties\n";
}

void expect_motion_fields_equal_full_fields(bool superpose_loads) {
  const FineArm a = fine_arm();
  AssemblyOptions options;
  options.superpose_loads = superpose_loads;
  options.keep_part_stress = true;
  ElasticAssembly assembly(a.parts, a.model, options);
  const std::vector<PoseSolution> full = assembly.solve(a.frames);

  // The motion in two calls (as the stage's blocks), every 10th pose and the last written.
  MotionFields fields;
  std::vector<bool> write(a.frames.size());
  for (size_t k = 0; k < write.size(); ++k) write[k] = k % 10 == 3 || k + 1 == write.size();
  std::vector<PoseSolution> fused;
  for (const auto& [first, count] : {std::pair<size_t, size_t>{0, 140}, {140, 10}}) {
    fields.first_step = first;
    fields.write.assign(write.begin() + long(first), write.begin() + long(first + count));
    const std::vector<mech::Frame> frames(a.frames.begin() + long(first), a.frames.begin() + long(first + count));
    for (PoseSolution& pose : assembly.solve(frames, fields)) fused.push_back(std::move(pose));
  }
  ASSERT_EQ(fused.size(), full.size());
  ASSERT_EQ(fields.envelopes.size(), 2u);

  for (size_t p = 0; p < 2; ++p) {
    const std::string body = a.parts[p].body();
    const PartEnvelope expected = reference_envelope(full, body);
    const PartEnvelope& got = fields.envelopes[p];
    EXPECT_EQ(got.body, body);
    const double u_tol = 1e-12 * expected.max_displacement_m.maxCoeff();
    const double vm_tol = 1e-12 * expected.max_von_mises_pa.maxCoeff();
    ASSERT_GT(u_tol, 0.0);
    ASSERT_GT(vm_tol, 0.0);
    std::vector<Eigen::VectorXd> magnitude, von_mises;
    for (const PoseSolution& pose : full) {
      magnitude.push_back(pose.part(body).displacement_m.rowwise().norm());
      von_mises.push_back(pose.part(body).von_mises_pa);
    }
    expect_same_envelope(got.max_displacement_m, got.displacement_step, expected.max_displacement_m,
                         expected.displacement_step, magnitude, u_tol, body + "_displacement");
    expect_same_envelope(got.max_von_mises_pa, got.von_mises_step, expected.max_von_mises_pa, expected.von_mises_step,
                         von_mises, vm_tol, body + "_von_mises");
    // The hot spots: the peak's node and step.
    Eigen::Index node_expected = 0, node_got = 0;
    expected.max_von_mises_pa.maxCoeff(&node_expected);
    got.max_von_mises_pa.maxCoeff(&node_got);
    EXPECT_EQ(node_got, node_expected) << body;
    EXPECT_EQ(got.von_mises_step(node_got), expected.von_mises_step(node_expected)) << body;
    expected.max_displacement_m.maxCoeff(&node_expected);
    got.max_displacement_m.maxCoeff(&node_got);
    EXPECT_EQ(node_got, node_expected) << body;
    EXPECT_EQ(got.displacement_step(node_got), expected.displacement_step(node_expected)) << body;

    // Per pose: the written fields, every pose's largest values and stress coefficients.
    for (size_t k = 0; k < full.size(); ++k) {
      const PartField& ref = full[k].part(body);
      const PartField& f = fused[k].part(body);
      EXPECT_NEAR(f.max_displacement_m, ref.max_displacement_m, u_tol) << body << " pose " << k;
      EXPECT_EQ(f.max_displacement_node, ref.max_displacement_node) << body << " pose " << k;
      EXPECT_NEAR(f.max_von_mises_pa, ref.von_mises_pa.maxCoeff(), vm_tol) << body << " pose " << k;
      EXPECT_EQ(fused[k].max_displacement_body, full[k].max_displacement_body) << "pose " << k;
      EXPECT_TRUE(f.stress_coefficients.size() == ref.stress_coefficients.size() &&
                  f.stress_coefficients == ref.stress_coefficients)
          << body << " pose " << k;
      // The nodal stress tensor (poses solved one by one): the same recovery,
      // whose threads may sum in another order.
      ASSERT_EQ(f.stress_pa.size(), ref.stress_pa.size()) << body << " pose " << k;
      if (ref.stress_pa.size() > 0) {
        EXPECT_LE((f.stress_pa - ref.stress_pa).cwiseAbs().maxCoeff(), 1e-12 * ref.stress_pa.cwiseAbs().maxCoeff())
            << body << " pose " << k;
      }
      if (!write[k]) {
        EXPECT_EQ(f.displacement_m.rows(), 0) << body << " pose " << k;
        EXPECT_EQ(f.von_mises_pa.size(), 0) << body << " pose " << k;
        continue;
      }
      ASSERT_EQ(f.displacement_m.rows(), ref.displacement_m.rows()) << body << " pose " << k;
      ASSERT_EQ(f.von_mises_pa.size(), ref.von_mises_pa.size()) << body << " pose " << k;
      EXPECT_LE((f.displacement_m - ref.displacement_m).cwiseAbs().maxCoeff(), u_tol) << body << " pose " << k;
      EXPECT_LE((f.von_mises_pa - ref.von_mises_pa).cwiseAbs().maxCoeff(), vm_tol) << body << " pose " << k;
    }
  }
}

TEST(AssemblyMotionFields, ChunkedSuperposedFieldsEqualTheFullFieldsOfEveryPose) {
  expect_motion_fields_equal_full_fields(true);
}

TEST(AssemblyMotionFields, PosesSolvedOneByOneFoldTheirFullFieldsTheSame) {
  expect_motion_fields_equal_full_fields(false);
}

TEST(AssemblyMotionFields, WriteFlagsOfAnotherLengthAreAnError) {
  const FineArm a = fine_arm();
  ElasticAssembly assembly(a.parts, a.model);
  MotionFields fields;
  fields.write.assign(3, true);
  EXPECT_THROW(assembly.solve({a.frames[0], a.frames[1]}, fields), Error);
}

}  // namespace
}  // namespace kinetofem::structure
