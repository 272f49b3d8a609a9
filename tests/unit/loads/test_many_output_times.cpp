// The superposition path's envelope over many output times against a
// straightforward reference: every frame's full stress and displacement
// fields formed from the pattern fields (field = fields * c(t)), von Mises
// and magnitude node by node, folded in frame order (a later frame replaces
// a maximum only when strictly larger). The envelope kernel forms no full
// field for a frame that is not written; it is the same linear algebra in
// another order, so values agree to round-off (1e-12 of the peak) and the
// frames of the maxima agree wherever the reference does not tie them.
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::loads {
namespace {

struct Reference {
  Eigen::VectorXd von_mises, magnitude;
  Eigen::VectorXi von_mises_step, magnitude_step;
};

// Node i's von Mises stress and displacement magnitude at frame t.
std::pair<double, double> node_at(const LinkLoadPatterns& p, Eigen::Index i, Eigen::Index t) {
  const fem::Vector6d s = p.stress_pa.middleRows(6 * i, 6) * p.coefficients.col(t);
  return {fem::von_mises(s), (p.elastic_displacement_m.middleRows(3 * i, 3) * p.coefficients.col(t)).norm()};
}

Reference reference_envelope(const LinkLoadPatterns& p, Eigen::Index frames) {
  const Eigen::Index nodes = p.stress_pa.rows() / 6;
  Reference r{Eigen::VectorXd::Constant(nodes, -1.0), Eigen::VectorXd::Constant(nodes, -1.0),
              Eigen::VectorXi::Zero(nodes), Eigen::VectorXi::Zero(nodes)};
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::VectorXd s = p.stress_pa * p.coefficients.col(t);
    const Eigen::VectorXd e = p.elastic_displacement_m * p.coefficients.col(t);
    for (Eigen::Index i = 0; i < nodes; ++i) {
      const double vm = fem::von_mises(s.segment<6>(6 * i)), magnitude = e.segment<3>(3 * i).norm();
      if (vm > r.von_mises[i]) r.von_mises[i] = vm, r.von_mises_step[i] = int(t);
      if (magnitude > r.magnitude[i]) r.magnitude[i] = magnitude, r.magnitude_step[i] = int(t);
    }
  }
  return r;
}

// The double pendulum's far link over 2000 frames, a field written every
// 97th frame, the first `envelope_steps` frames in the envelope (0: all).
void check_against_reference(std::size_t envelope_steps) {
  const mech::MultibodyModel model = testing::double_pendulum();
  std::vector<double> times;
  for (int k = 0; k < 2000; ++k) times.push_back(0.5 * k / 1999.0);
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times);
  const LinkLoads loads({"link2", &testing::two_bore_link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}},
                         {{"D2", "bore_1"}}},
                        model);
  ASSERT_TRUE(loads.superposable());
  const fem::FeModel fe = testing::supported_two_bore_link();
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  LinkStressOptions options;
  options.load_path = LoadPath::Superposition;
  options.envelope_steps = envelope_steps;
  options.callback_steps.assign(times.size(), false);
  for (std::size_t t = 0; t < times.size(); t += 97) options.callback_steps[t] = true;
  std::vector<std::size_t> called;
  std::vector<fem::DisplacementField> fields;
  std::vector<fem::NodalStress> stresses;
  const LinkEnvelope env = analyse_link_over_motion(
      analysis, loads, results.frames, log, options,
      [&](std::size_t step, const fem::DisplacementField& u, const fem::NodalStress& s) {
        called.push_back(step);
        fields.push_back(u);
        stresses.push_back(s);
      });

  ASSERT_TRUE(env.patterns.has_value());
  const LinkLoadPatterns& p = *env.patterns;
  const Eigen::Index frames = Eigen::Index(times.size());
  const Eigen::Index folded = envelope_steps == 0 ? frames : Eigen::Index(envelope_steps);
  const Reference r = reference_envelope(p, folded);
  const double peak_vm = r.von_mises.maxCoeff(), peak_u = r.magnitude.maxCoeff();
  ASSERT_GT(peak_vm, 0.0);
  ASSERT_GT(peak_u, 0.0);
  const double vm_error = (env.max_von_mises_pa - r.von_mises).cwiseAbs().maxCoeff() / peak_vm;
  const double u_error = (env.max_displacement_m - r.magnitude).cwiseAbs().maxCoeff() / peak_u;
  EXPECT_LT(vm_error, 1e-12);
  EXPECT_LT(u_error, 1e-12);
  // A different frame only where the reference's value there ties its maximum.
  long differing = 0;
  for (Eigen::Index i = 0; i < r.von_mises.size(); ++i) {
    if (env.max_von_mises_step[i] != r.von_mises_step[i]) {
      ++differing;
      EXPECT_LT(r.von_mises[i] - node_at(p, i, env.max_von_mises_step[i]).first, 1e-12 * peak_vm) << "node " << i;
    }
    if (env.max_displacement_step[i] != r.magnitude_step[i]) {
      ++differing;
      EXPECT_LT(r.magnitude[i] - node_at(p, i, env.max_displacement_step[i]).second, 1e-12 * peak_u)
          << "node " << i;
    }
  }
  EXPECT_LT(differing, 10);
  EXPECT_EQ(env.peak_von_mises_step, r.von_mises_step[env.peak_von_mises_node]);

  // The written frames, in order, with their full fields.
  std::vector<std::size_t> expected;
  for (std::size_t t = 0; t < times.size(); t += 97) expected.push_back(t);
  ASSERT_EQ(called, expected);
  double worst_u = 0.0, worst_s = 0.0, worst_vm = 0.0;
  for (std::size_t w = 0; w < called.size(); ++w) {
    const Eigen::Index t = Eigen::Index(called[w]);
    const Eigen::VectorXd s = p.stress_pa * p.coefficients.col(t);
    const Eigen::VectorXd e = p.elastic_displacement_m * p.coefficients.col(t);
    const fem::DisplacementField u = Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(e.data(), 3,
                                                                                                e.size() / 3)
                                         .transpose();
    const Eigen::MatrixXd stress =
        Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>(s.data(), 6, s.size() / 6).transpose();
    worst_u = std::max(worst_u, (fields[w] - u).cwiseAbs().maxCoeff());
    worst_s = std::max(worst_s, (stresses[w].stress_pa - stress).cwiseAbs().maxCoeff());
    for (Eigen::Index i = 0; i < stress.rows(); ++i)
      worst_vm = std::max(worst_vm, std::abs(stresses[w].von_mises_pa[i] - fem::von_mises(s.segment<6>(6 * i))));
  }
  std::printf("  %ld nodes, %ld frames (%ld in the envelope): envelope von Mises %.1e and displacement %.1e of "
              "the peak, %ld frames of maxima differ; written fields: displacement %.1e, stress %.1e, von Mises %.1e\n",
              long(r.von_mises.size()), long(frames), long(folded), vm_error, u_error, differing, worst_u / peak_u,
              worst_s / peak_vm, worst_vm / peak_vm);
  EXPECT_LT(worst_u, 1e-12 * peak_u);
  EXPECT_LT(worst_s, 1e-12 * peak_vm);
  EXPECT_LT(worst_vm, 1e-12 * peak_vm);
}

TEST(ManyOutputTimes, EnvelopeAndWrittenFieldsEqualFullFieldsPerFrame) { check_against_reference(0); }

TEST(ManyOutputTimes, FramesPastTheEnvelopeStepsAreWrittenButNotFolded) { check_against_reference(1234); }

}  // namespace
}  // namespace kinetofem::loads
