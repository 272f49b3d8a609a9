// Bad inputs of the fatigue module (each an Error naming the value), the
// turning-point reduction and empty histories.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "kinetofem/core/error.hpp"
#include "kinetofem/fatigue/critical_plane.hpp"
#include "kinetofem/fatigue/mean_stress.hpp"
#include "kinetofem/fatigue/miner.hpp"
#include "kinetofem/fatigue/rainflow.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"

namespace kinetofem::fatigue {
namespace {

std::string message_of(const auto& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FatigueInputs, CategoryNotInTheListNamesItAndTheAllowedOnes) {
  const std::string m = message_of([] { SnCurve({.detail_category_mpa = 70}); });
  EXPECT_NE(m.find("detail category 70 MPa"), std::string::npos) << m;
  EXPECT_NE(m.find("160, 140, 125, 112, 100, 90, 80, 71, 63, 56, 50, 45, 40, 36"),
            std::string::npos)
      << m;
  EXPECT_NO_THROW(SnCurve({.detail_category_mpa = 36}));
  EXPECT_THROW(SnCurve({.detail_category_mpa = 0}), Error);
  EXPECT_THROW(SnCurve({.detail_category_mpa = std::nan("")}), Error);
}

TEST(FatigueInputs, PartialFactorsBelowOneAreErrors) {
  const std::string ff =
      message_of([] { SnCurve({.detail_category_mpa = 71, .gamma_ff = 0.9}); });
  EXPECT_NE(ff.find("gamma_Ff = 0.9"), std::string::npos) << ff;
  const std::string mf =
      message_of([] { SnCurve({.detail_category_mpa = 71, .gamma_mf = 0.99}); });
  EXPECT_NE(mf.find("gamma_Mf = 0.99"), std::string::npos) << mf;
  EXPECT_NO_THROW(SnCurve({.detail_category_mpa = 71, .gamma_ff = 1.0, .gamma_mf = 1.35}));
  EXPECT_THROW(SnCurve({.detail_category_mpa = 71, .size_factor = 1.2}), Error);
  EXPECT_THROW(SnCurve({.detail_category_mpa = 71, .size_factor = 0.0}), Error);
  EXPECT_THROW(thickness_size_factor(0.0), Error);
  EXPECT_EQ(thickness_size_factor(0.020), 1.0);
  EXPECT_EQ(thickness_size_factor(0.025), 1.0);
  EXPECT_NEAR(thickness_size_factor(0.050), std::pow(0.5, 0.2), 1e-15);
}

TEST(FatigueInputs, NegativeRangeIsAnError) {
  const SnCurve curve({.detail_category_mpa = 71});
  const std::string m = message_of([&] { curve.endurance(-1e6); });
  EXPECT_NE(m.find("stress range -1000000 Pa"), std::string::npos) << m;
  EXPECT_THROW(curve.characteristic_endurance(-1.0), Error);
  EXPECT_THROW(curve.endurance(std::numeric_limits<double>::infinity()), Error);
  const std::vector<Cycle> bad = {{.range_pa = -5e6, .mean_pa = 0.0, .count = 1.0}};
  EXPECT_THROW(miner_damage(bad, curve), Error);
  EXPECT_THROW(effective_range(bad[0], MeanStressTreatment::ReducedCompression), Error);
  const std::vector<Cycle> bad_count = {{.range_pa = 5e6, .mean_pa = 0.0, .count = -1.0}};
  EXPECT_THROW(miner_damage(bad_count, curve), Error);
  EXPECT_THROW(life_repetitions(-1.0), Error);
  EXPECT_THROW(merge_ranges(bad, -1.0), Error);
}

TEST(FatigueInputs, NonFiniteHistoryIsAnError) {
  const std::vector<double> h = {0.0, 1.0, std::nan(""), 2.0};
  const std::string m = message_of([&] { rainflow_count(h); });
  EXPECT_NE(m.find("index 2"), std::string::npos) << m;
  StressHistory s = StressHistory::Zero(6, 3);
  s(4, 1) = std::numeric_limits<double>::infinity();
  const SnCurve curve({.detail_category_mpa = 71});
  const std::string ms = message_of([&] { assess_node(s, curve); });
  EXPECT_NE(ms.find("component 4 at time step 1"), std::string::npos) << ms;
}

TEST(FatigueInputs, TurningPointsDropPlateausAndKeepTheEnds) {
  using V = std::vector<double>;
  EXPECT_EQ(turning_points(V{0, 1, 1, 2, 2, 1, 0, 0, 3}), (V{0, 2, 0, 3}));
  EXPECT_EQ(turning_points(V{1, 2, 3, 4}), (V{1, 4}));          // monotone: the ends
  EXPECT_EQ(turning_points(V{5, 5, 5}), (V{5}));                // constant: one point
  EXPECT_EQ(turning_points(V{3, 1, 1, 1, 2, 2}), (V{3, 1, 2}));  // plateau valley
  EXPECT_EQ(turning_points(V{0, 2, 2, 4, 1}), (V{0, 4, 1}));    // plateau on a rise
  EXPECT_EQ(turning_points(V{7}), (V{7}));
  EXPECT_TRUE(turning_points(V{}).empty());
}

TEST(FatigueInputs, EmptyAndConstantHistoriesHaveNoCycles) {
  const SnCurve curve({.detail_category_mpa = 71});
  EXPECT_TRUE(rainflow_count(std::vector<double>{}).empty());
  EXPECT_TRUE(rainflow_count(std::vector<double>{}, Residue::Periodic).empty());
  EXPECT_TRUE(rainflow_count(std::vector<double>{4e6}).empty());
  EXPECT_TRUE(rainflow_count(std::vector<double>{4e6, 4e6, 4e6}, Residue::Periodic).empty());
  EXPECT_EQ(miner_damage(std::vector<Cycle>{}, curve), 0.0);
  EXPECT_EQ(life_repetitions(0.0), std::numeric_limits<double>::infinity());
  const std::string m = message_of([&] { assess_node(StressHistory(6, 0), curve); });
  EXPECT_NE(m.find("no time steps"), std::string::npos) << m;
  // A constant stress state: no damage on any plane.
  StressHistory s(6, 4);
  s.colwise() = (Eigen::Matrix<double, 6, 1>() << 300e6, -10e6, 5e6, 40e6, 1e6, -2e6).finished();
  const NodeFatigue r = assess_node(s, curve);
  EXPECT_EQ(r.damage, 0.0);
  EXPECT_TRUE(r.cycles.empty());
  EXPECT_EQ(r.plane, 0);  // all tie at zero damage and zero range: the first plane
}

TEST(FatigueInputs, MeanStressTreatmentSplitsTheRange) {
  const auto eff = [](double range, double mean) {
    return effective_range({.range_pa = range, .mean_pa = mean, .count = 1},
                           MeanStressTreatment::ReducedCompression);
  };
  EXPECT_EQ(eff(100, 60), 100);           // tensile: unchanged
  EXPECT_EQ(eff(100, -60), 60);           // compressive: 0.6
  EXPECT_NEAR(eff(100, 0), 80, 1e-12);    // 50 + 0.6 * 50
  EXPECT_EQ(effective_range({.range_pa = 100, .mean_pa = -60, .count = 1},
                            MeanStressTreatment::None),
            100);
  const std::vector<Cycle> c = {{.range_pa = 100, .mean_pa = -60, .count = 0.5}};
  const std::vector<Cycle> out = apply_mean_stress(c, MeanStressTreatment::ReducedCompression);
  EXPECT_EQ(out[0].range_pa, 60);
  EXPECT_EQ(out[0].mean_pa, -60);
  EXPECT_EQ(out[0].count, 0.5);
}

TEST(FatigueInputs, MergeRangesSumsCountsPerRange) {
  const std::vector<Cycle> c = {{.range_pa = 4, .count = 0.5},
                                {.range_pa = 2, .count = 1.0},
                                {.range_pa = 4, .count = 1.0},
                                {.range_pa = 4.4, .count = 0.5}};
  const std::vector<RangeCount> exact = merge_ranges(c);
  ASSERT_EQ(exact.size(), 3u);
  EXPECT_EQ(exact[1].range_pa, 4);
  EXPECT_EQ(exact[1].count, 1.5);
  const std::vector<RangeCount> loose = merge_ranges(c, 0.5);
  ASSERT_EQ(loose.size(), 2u);
  EXPECT_EQ(loose[1].count, 2.0);
}

TEST(FatigueInputs, CandidatePlanesCoverTheHemisphereWithinTheStatedBound) {
  EXPECT_THROW(hemisphere_planes(0.0), Error);
  EXPECT_THROW(hemisphere_planes(91.0), Error);
  for (double spacing : {10.0, 5.0, 7.5}) {
    SCOPED_TRACE(spacing);
    const CandidatePlanes p = hemisphere_planes(spacing);
    EXPECT_LE(p.polar_spacing_deg, spacing + 1e-12);
    const Eigen::Index n = p.normals.rows();
    for (Eigen::Index k = 0; k < n; ++k) {
      EXPECT_NEAR(p.normals.row(k).norm(), 1.0, 1e-14);
      EXPECT_GE(p.normals(k, 2), -1e-15);
    }
    // The measured covering radius over pseudo-random normals (deterministic
    // sequence), against the bound.
    unsigned state = 12345u;
    const auto uniform = [&] {
      state = state * 1664525u + 1013904223u;
      return (state >> 8) / 16777216.0;
    };
    double worst = 0.0;
    for (int s = 0; s < 20000; ++s) {
      const double z = 2.0 * uniform() - 1.0, phi = 2.0 * std::numbers::pi * uniform();
      const double r = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d v(r * std::cos(phi), r * std::sin(phi), z);
      const double best_cos = (p.normals * v).cwiseAbs().maxCoeff();
      worst = std::max(worst, std::acos(std::min(1.0, best_cos)) * 180.0 / std::numbers::pi);
    }
    EXPECT_LE(worst, p.covering_radius_deg);
    std::printf("spacing %.1f deg: %ld planes, bound %.4f deg, measured %.4f deg\n", spacing,
                static_cast<long>(n), p.covering_radius_deg, worst);
  }
  EXPECT_EQ(hemisphere_planes(10.0).normals.rows(), 226);
}

TEST(FatigueInputs, ProjectionIsTheNormalStressOfTheVoigtOrder) {
  // (xx, yy, zz, xy, yz, zx) as solver/stress_recovery.hpp.
  Eigen::Matrix<double, 6, 1> v;
  v << 1, 2, 3, 4, 5, 6;
  Eigen::Matrix3d s;
  s << 1, 4, 6, 4, 2, 5, 6, 5, 3;
  StressHistory h(6, 1);
  h.col(0) = v;
  const CandidatePlanes p = hemisphere_planes(10.0);
  const PlaneHistories sn = normal_stress_histories(p, h);
  for (Eigen::Index k = 0; k < p.normals.rows(); ++k) {
    const Eigen::Vector3d n = p.normals.row(k).transpose();
    EXPECT_NEAR(sn(k, 0), n.dot(s * n), 1e-13);
  }
}

TEST(FatigueInputs, SignedVonMisesAndMaxPrincipal) {
  StressHistory h = StressHistory::Zero(6, 3);
  h(0, 0) = -100e6;           // uniaxial compression
  h(1, 1) = 100e6;            // uniaxial tension along y
  h(3, 2) = 50e6;             // pure shear xy: sigma_1 + sigma_3 = 0 -> + (round-off aside)
  const Eigen::VectorXd vm = signed_von_mises_history(h);
  EXPECT_NEAR(vm(0), -100e6, 1e-6);
  EXPECT_NEAR(vm(1), 100e6, 1e-6);
  EXPECT_NEAR(std::abs(vm(2)), std::sqrt(3.0) * 50e6, 1e-6);
  const Eigen::VectorXd s1 = max_principal_history(h);
  EXPECT_NEAR(s1(0), 0.0, 1e-6);
  EXPECT_NEAR(s1(1), 100e6, 1e-6);
  EXPECT_NEAR(s1(2), 50e6, 1e-6);
  const SnCurve curve({.detail_category_mpa = 71});
  const NodeFatigue r = assess_node(h, curve, {.measure = StressMeasure::MaxPrincipal});
  EXPECT_NEAR(r.normal.y(), 1.0, 1e-12);  // sigma_1's direction at its largest value
  EXPECT_EQ(r.plane, -1);
}

}  // namespace
}  // namespace kinetofem::fatigue
