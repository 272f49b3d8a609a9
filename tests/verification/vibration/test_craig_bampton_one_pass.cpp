// The one-pass Craig-Bampton reduction with the block fixed-interface modes
// (vibration::CraigBamptonReducer, FixedInterfaceSolver::BlockDavidson,
// docs/vibration.md) against the reduction it replaced: the single-vector
// shift-invert Lanczos of fem::solve_eigen (Spectra, FixedInterfaceSolver::
// Lanczos), one solve per Lanczos vector. Both start from the same static
// pass, so the part-mode rule's bound and cutoff are the same numbers; the
// rest differs only by the eigen solver's convergence.
// Models: the SPEC §1 lever-chain manipulator with box parts and the two-link
// arm with its payload (structure_fixtures.hpp), at poses over their motion.
// Reference and tolerances (what the new reduction must keep):
//   * frequencies of the assembly in every pose: 1e-6 relative;
//   * mode shapes (the parts' nodal fields, sign aligned, relative to their
//     largest entry): 1e-6;
//   * the part-mode rule: the same cutoff (1e-12 relative), the same modes
//     kept per part, the first dropped mode within 1e-6;
//   * the reduced model's static response to the pose's loads (nodal
//     fields): 1e-8 of its largest entry (the elastic assembly's own is matched to 3e-10 by the
//     reduced model in the vibration stage, which prints the check).
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"

namespace kinetofem::structure {
namespace {

using namespace kinetofem::vibration;  // the reductions compared

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kFrequencyTolerance = 1e-6;  // relative, every mode and pose
constexpr double kShapeTolerance = 1e-6;      // of the shape's largest entry
constexpr double kStaticTolerance = 1e-8;     // of the static response's largest entry

// Every part's nodal displacement field of x (world axes), stacked.
VectorXd nodal_shape(const AssemblyModes& modes, const VectorXd& x, const mech::Frame& frame) {
  const std::vector<MatrixXd> fields = modes.part_fields(x, frame);
  Index size = 0;
  for (const MatrixXd& f : fields) size += f.size();
  VectorXd out(size);
  Index at = 0;
  for (const MatrixXd& f : fields) {
    out.segment(at, f.size()) = f.reshaped();
    at += f.size();
  }
  return out;
}

void expect_block_matches_lanczos(const std::vector<pipeline::Part>& parts, const mech::MultibodyModel& model,
                                  const AssemblyOptions& options, const std::vector<mech::Frame>& poses) {
  AssemblyOptions ao = options;
  ao.recover_stress = false;
  ao.superpose_loads = false;
  const ElasticAssembly assembly(parts, model, ao);
  AssemblyModesOptions reference_options;
  reference_options.modes = 6;
  reference_options.fixed_interface_solver = FixedInterfaceSolver::Lanczos;
  AssemblyModesOptions block_options = reference_options;
  block_options.fixed_interface_solver = FixedInterfaceSolver::BlockDavidson;
  const AssemblyModes reference(assembly, parts, model, reference_options, poses, Log::quiet());
  const AssemblyModes block(assembly, parts, model, block_options, poses, Log::quiet());

  EXPECT_NEAR(block.cutoff_hz() / reference.cutoff_hz(), 1.0, 1e-12);
  ASSERT_EQ(block.reductions().size(), reference.reductions().size());
  for (size_t p = 0; p < block.reductions().size(); ++p) {
    const PartReduction &b = block.reductions()[p], &r = reference.reductions()[p];
    std::printf("  %s part %s: modes kept %lld (Lanczos %lld), first dropped %.8g Hz (Lanczos %.8g Hz)\n",
                model.name.c_str(), b.body.c_str(), static_cast<long long>(b.modes), static_cast<long long>(r.modes),
                b.first_dropped_hz, r.first_dropped_hz);
    EXPECT_EQ(b.modes, r.modes) << b.body;
    EXPECT_NEAR(b.first_dropped_hz / r.first_dropped_hz, 1.0, kFrequencyTolerance) << b.body;
    EXPECT_GT(b.first_dropped_hz, b.cutoff_hz) << b.body;
  }
  ASSERT_EQ(block.size(), reference.size());

  double worst_frequency = 0.0, worst_shape = 0.0, worst_static = 0.0;
  for (const mech::Frame& frame : poses) {
    const PoseModes b = block.modes(frame), r = reference.modes(frame);
    for (Index i = 0; i < b.frequency_hz.size(); ++i) {
      const double error = std::abs(b.frequency_hz(i) / r.frequency_hz(i) - 1.0);
      worst_frequency = std::max(worst_frequency, error);
      EXPECT_LT(error, kFrequencyTolerance) << "mode " << i + 1 << " at t = " << frame.t;
      // Physical shapes (the reduced coordinates q and r differ by the modes'
      // and residual vectors' signs and bases).
      const VectorXd rs = nodal_shape(reference, r.shapes.col(i), frame);
      const VectorXd bs = nodal_shape(block, b.shapes.col(i), frame);
      const double sign = bs.dot(rs) < 0 ? -1.0 : 1.0;
      const double shape = (sign * bs - rs).cwiseAbs().maxCoeff() / rs.cwiseAbs().maxCoeff();
      worst_shape = std::max(worst_shape, shape);
      EXPECT_LT(shape, kShapeTolerance) << "mode " << i + 1 << " at t = " << frame.t;
    }
    const VectorXd xr = nodal_shape(reference, reference.static_response(frame, reference.load(frame)), frame);
    const VectorXd xb = nodal_shape(block, block.static_response(frame, block.load(frame)), frame);
    const double statics = (xb - xr).cwiseAbs().maxCoeff() / xr.cwiseAbs().maxCoeff();
    worst_static = std::max(worst_static, statics);
    EXPECT_LT(statics, kStaticTolerance) << "t = " << frame.t;
  }
  std::printf("  %s, %zu poses: block vs single-vector Lanczos: frequencies %.2e, shapes %.2e, static response "
              "%.2e (largest relative differences)\n",
              model.name.c_str(), poses.size(), worst_frequency, worst_shape, worst_static);
}

TEST(CraigBamptonOnePass, LeverChainManipulatorBlockModesEqualTheSingleVectorLanczosInEveryPose) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  AssemblyOptions options;
  options.chains = {{"chain", 5e6}};
  options.points = {{"H", "arm", "H", "x0"}};
  std::vector<mech::Frame> poses;
  for (int k = 0; k <= 6; ++k) poses.push_back(pipeline::solve_static_pose(model, {k * 12 * test::kDeg}));
  expect_block_matches_lanczos(parts, model, options, poses);
}

TEST(CraigBamptonOnePass, TwoLinkArmBlockModesEqualTheSingleVectorLanczosInEveryPose) {
  mech::MultibodyModel model = test::two_link_arm();
  const std::vector<pipeline::Part> parts = test::two_link_parts();
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  std::vector<mech::Frame> poses;
  for (int k = 0; k <= 6; ++k)
    poses.push_back(pipeline::solve_static_pose(model, {k * 7 * test::kDeg, -k * 8 * test::kDeg}));
  expect_block_matches_lanczos(parts, model, AssemblyOptions{}, poses);
}

// Frees each part's factor whenever the reductions give it back, as
// pipeline::PartFactors does with factors that do not fit together, and
// checks that no other part's factor is alive when one is lent.
class OneAtATime final : public PartFactorLender {
 public:
  explicit OneAtATime(const ElasticAssembly& assembly, std::vector<std::string> bodies)
      : assembly_(assembly), bodies_(std::move(bodies)) {
    for (const auto& b : bodies_) assembly_.supported_analysis(b).release_factor();
  }
  fem::LinearStaticAnalysis& lend(const std::string& body) override {
    for (const auto& b : bodies_)
      if (b != body) EXPECT_FALSE(assembly_.supported_analysis(b).is_factorized()) << b << " while " << body;
    fem::LinearStaticAnalysis& analysis = assembly_.supported_analysis(body);
    if (!analysis.is_factorized()) ++factorizations;
    analysis.factorize();
    return analysis;
  }
  void give_back(const std::string& body) override { assembly_.supported_analysis(body).release_factor(); }
  int factorizations = 0;

 private:
  const ElasticAssembly& assembly_;
  std::vector<std::string> bodies_;
};

TEST(CraigBamptonOnePass, PartByPartEqualsAllAtOnce) {
  // The reductions with one factor in memory at a time (each freed and made
  // again between its two uses, the last part's kept) against those with
  // every factor alive. Reference: the all-at-once frequencies in every pose;
  // tolerance 1e-12 relative (the same factor made twice: the same
  // arithmetic).
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  AssemblyOptions options;
  options.chains = {{"chain", 5e6}};
  options.points = {{"H", "arm", "H", "x0"}};
  options.recover_stress = false;
  options.superpose_loads = false;
  std::vector<mech::Frame> poses;
  for (int k = 0; k <= 6; ++k) poses.push_back(pipeline::solve_static_pose(model, {k * 12 * test::kDeg}));
  const ElasticAssembly assembly(parts, model, options);
  AssemblyModesOptions mo;
  mo.modes = 6;
  const AssemblyModes all_at_once(assembly, parts, model, mo, poses, Log::quiet());
  std::vector<std::string> bodies;
  for (const auto& p : parts) bodies.push_back(p.body());
  OneAtATime lender(assembly, bodies);
  const AssemblyModes part_by_part(assembly, parts, model, mo, poses, Log::quiet(), &lender);
  EXPECT_EQ(lender.factorizations, 2 * int(parts.size()) - 1) << "each part twice, the last once";
  double worst = 0.0;
  for (const mech::Frame& frame : poses) {
    const VectorXd a = all_at_once.modes(frame).frequency_hz, b = part_by_part.modes(frame).frequency_hz;
    for (Index i = 0; i < a.size(); ++i) {
      worst = std::max(worst, std::abs(b(i) / a(i) - 1.0));
      EXPECT_NEAR(b(i) / a(i), 1.0, 1e-12) << "mode " << i + 1 << " at t = " << frame.t;
    }
  }
  std::printf("  part by part (%d factorizations) vs all at once: largest relative frequency difference %.2e\n",
              lender.factorizations, worst);
}

TEST(CraigBamptonOnePass, StaticThenFinalReductionEqualsTheFinalAlone) {
  // One reducer making the part-mode rule's static reduction and then the
  // final one against a fresh reducer making the final one only: the static
  // pass must leave nothing behind. Reference: the fresh reduction's
  // frequencies; tolerance 1e-12 relative (the same arithmetic).
  const std::vector<pipeline::Part> parts = test::two_link_parts();
  const fem::FeModel& part = parts[0].model;
  const std::vector<PartInterface> interfaces = {
      coupling_interface(part.mesh, "x0", fem::DistributingCoupling(part.mesh, "x0").centroid(), "x0"),
      coupling_interface(part.mesh, "x1", fem::DistributingCoupling(part.mesh, "x1").centroid(), "x1")};
  CraigBamptonOptions final_options;
  final_options.highest_frequency_of_interest_hz = 2000.0;
  CraigBamptonOptions static_options = final_options;
  static_options.fixed_interface_modes = false;
  CraigBamptonReducer twice(part, interfaces, "link1 (static, then final)");
  const CraigBamptonModel bound = twice.reduce(static_options);
  const CraigBamptonModel second = twice.reduce(final_options);
  const CraigBamptonModel alone = CraigBamptonReducer(part, interfaces, "link1 (final)").reduce(final_options);
  EXPECT_EQ(bound.mode_count, 0);
  EXPECT_EQ(bound.lanczos_solves, alone.lanczos_solves - second.lanczos_solves)
      << "the static reduction solves nothing beyond the set-up";
  ASSERT_EQ(second.mode_count, alone.mode_count);
  const Index count = std::min<Index>(12, second.stiffness.rows() - 6);
  const VectorXd fs = dense_frequencies_hz(second.stiffness, second.mass, count + 6);
  const VectorXd fa = dense_frequencies_hz(alone.stiffness, alone.mass, count + 6);
  for (Index i = 6; i < count + 6; ++i) EXPECT_NEAR(fs(i) / fa(i), 1.0, 1e-12) << "mode " << i + 1;
  std::printf("  link1: %lld fixed-interface modes; set-up solves %lld, fixed-interface solves %lld\n",
              static_cast<long long>(alone.mode_count), static_cast<long long>(bound.lanczos_solves),
              static_cast<long long>(second.lanczos_solves));
}

}  // namespace
}  // namespace kinetofem::structure
