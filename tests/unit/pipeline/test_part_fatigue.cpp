// Stage "fatigue over the work cycle" for one part (pipeline/part_fatigue.hpp)
// on the small test beam (HEX20, 10 x 2 x 1 cells; pipeline_fixtures.hpp)
// with stress histories made here, so each reference is known:
//   * constant amplitude, every node: D = 1 / N_R(gamma_Ff gamma_Mf range)
//     of EN 1993-1-9 7.1(3) (m = 3 above Delta sigma_D), life = 1/D cycles,
//     1/(D rate) s, u = gamma_Ff gamma_Mf range / Delta sigma_R(design
//     cycles) (closed form on the m = 3 line); round-off tolerance 1e-12;
//   * the superposition form (patterns x coefficients) and the step form of
//     the same history: identical results (the same doubles up to the GEMM's
//     round-off: 1e-12 relative);
//   * per node against fatigue::assess_node of that node's history (the
//     library is the reference: equal to the last bit);
//   * detail categories of a face set and an element set (lowest wins), the
//     critical node, ranges below the cut-off (D = 0, infinite life, u from
//     the cut-off), and the bad inputs of check_fatigue_details.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

constexpr double kMpa = units::kMpa;

Part beam() { return test::beam_part("beam", test::beam_pendulum_attachments()); }

// Uniaxial sxx(t) = amplitude(node) sin(2 pi t / T) over one period of T steps
// (step form), the amplitude growing along x so there is one critical node.
PartStressHistory sine_history(const Part& part, double amplitude_pa, int steps, bool graded = true) {
  const fem::Index n = part.model.mesh.node_count();
  const double x_max = part.model.mesh.nodes.col(0).maxCoeff();
  PartStressHistory h;
  h.step_stress_pa = Eigen::MatrixXd::Zero(6 * n, steps);
  for (fem::Index i = 0; i < n; ++i) {
    const double a = graded ? amplitude_pa * (0.5 + 0.5 * part.model.mesh.nodes(i, 0) / x_max) : amplitude_pa;
    for (int t = 0; t < steps; ++t) h.step_stress_pa(6 * i, t) = a * std::sin(2.0 * std::numbers::pi * t / steps);
  }
  return h;
}

FatigueSettings settings(double category_mpa = 71.0) {
  FatigueSettings s;
  s.detail_category_mpa = category_mpa;
  s.gamma_ff = 1.1;
  s.gamma_mf = 1.35;
  s.cycle_rate_per_s = 60.0 / units::kHour;
  s.design_cycles = 1e6;
  return s;
}

TEST(PartFatigue, ConstantAmplitudeDamageLifeAndUtilizationMatchTheClosedForm) {
  const Part part = beam();
  const double amplitude = 60 * kMpa;  // range 120 MPa at the tip: on the m = 3 line for 71 MPa
  const PartStressHistory h = sine_history(part, amplitude, 40, /*graded=*/false);
  const FatigueSettings s = settings();
  const PartFatigue r = assess_part_fatigue(part, h, s, Log::quiet());
  const double gamma = s.gamma_ff * s.gamma_mf;
  const double range = 2 * amplitude;  // exact: sin reaches +-1 at t = T/4, 3T/4 (40 steps)
  const double n_r = 2e6 * std::pow(71 * kMpa / (gamma * range), 3);  // EN 1993-1-9 7.1(3), m = 3
  ASSERT_GT(gamma * range, fatigue::SnCurve({.detail_category_mpa = 71}).constant_amplitude_limit_pa());
  const double u = gamma * range / (71 * kMpa * std::cbrt(2e6 / s.design_cycles));  // Delta sigma_R(1e6), m = 3
  for (fem::Index i = 0; i < part.model.mesh.node_count(); ++i) {
    EXPECT_NEAR(r.damage_per_cycle[i], 1.0 / n_r, 1e-12 / n_r) << i;
    EXPECT_NEAR(r.life_cycles[i], n_r, 1e-12 * n_r) << i;
    EXPECT_NEAR(r.life_s[i], n_r / s.cycle_rate_per_s, 1e-12 * n_r / s.cycle_rate_per_s) << i;
    EXPECT_NEAR(r.utilization[i], u, 1e-12 * u) << i;
    EXPECT_NEAR(r.max_range_pa[i], range, 1e-12 * range) << i;
  }
  EXPECT_EQ(r.critical_detail, "part default");
  EXPECT_EQ(r.planes_searched, 226);
  // The plane of the uniaxial stress: the normal along x.
  EXPECT_NEAR(std::abs(r.critical.normal.x()), 1.0, 1e-12);
}

TEST(PartFatigue, SuperposedAndStepFormsGiveTheSameResultsEqualToAssessNode) {
  const Part part = beam();
  const fem::Index n = part.model.mesh.node_count();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  PartStressHistory superposed;
  superposed.pattern_stress_pa = Eigen::MatrixXd::NullaryExpr(6 * n, 4, [&] { return 40 * kMpa * uniform(rng); });
  superposed.coefficients = Eigen::MatrixXd::NullaryExpr(4, 25, [&] { return uniform(rng); });
  PartStressHistory steps;
  steps.step_stress_pa = superposed.pattern_stress_pa * superposed.coefficients;
  const FatigueSettings s = settings();
  const PartFatigue a = assess_part_fatigue(part, superposed, s, Log::quiet());
  const PartFatigue b = assess_part_fatigue(part, steps, s, Log::quiet());
  EXPECT_TRUE(a.superposed);
  EXPECT_FALSE(b.superposed);
  ASSERT_GT(a.max_damage_per_cycle, 0.0);
  EXPECT_LT((a.damage_per_cycle - b.damage_per_cycle).cwiseAbs().maxCoeff(), 1e-12 * a.max_damage_per_cycle);
  EXPECT_LT((a.utilization - b.utilization).cwiseAbs().maxCoeff(), 1e-12 * a.max_utilization);
  EXPECT_EQ(a.critical_node, b.critical_node);
  // Each node as the library assesses its history (one period: Residue::Periodic).
  const fatigue::SnCurve curve({.detail_category_mpa = 71, .gamma_ff = s.gamma_ff, .gamma_mf = s.gamma_mf});
  fatigue::FatigueOptions o;
  o.residue = fatigue::Residue::Periodic;
  const fatigue::CandidatePlanes planes = fatigue::hemisphere_planes(10.0);
  for (fem::Index i = 0; i < n; i += 7) {
    const fatigue::StressHistory node = steps.step_stress_pa.middleRows(6 * i, 6);
    const fatigue::NodeFatigue ref = fatigue::assess_node(node, curve, o, planes);
    EXPECT_EQ(b.damage_per_cycle[i], ref.damage) << i;
    EXPECT_EQ(b.max_range_pa[i], ref.max_range_pa) << i;
    EXPECT_EQ(b.plane_normal.row(i), ref.normal.transpose()) << i;
  }
  EXPECT_EQ(b.critical.damage, b.max_damage_per_cycle);
  EXPECT_EQ(b.min_life_cycles, 1.0 / b.max_damage_per_cycle);
}

TEST(PartFatigue, SetsTakeTheirCategoryTheLowestWinsAndTheCriticalNodeFollows) {
  Part part = beam();
  fem::Mesh& mesh = part.model.mesh;
  // The elements touching x = 0 (global indices: one block).
  ASSERT_EQ(mesh.blocks.size(), 1u);
  std::vector<fem::Index>& first_cells = mesh.element_sets["first_cells"];
  for (fem::Index e = 0; e < mesh.blocks[0].size(); ++e)
    for (fem::Index node : mesh.blocks[0].element(e))
      if (mesh.nodes(node, 0) == 0.0) {
        first_cells.push_back(e);
        break;
      }
  ASSERT_FALSE(first_cells.empty());
  const PartStressHistory h = sine_history(part, 25 * kMpa, 40, /*graded=*/false);
  FatigueSettings s = settings(160.0);
  s.details = {{.body = "beam", .set = "x1", .detail_category_mpa = 90.0},
               {.body = "beam", .set = "first_cells", .detail_category_mpa = 36.0},
               {.body = "beam", .set = "x0", .detail_category_mpa = 56.0},
               {.body = "other", .set = "x0", .detail_category_mpa = 36.0}};  // another part: not this one's
  const PartFatigue r = assess_part_fatigue(part, h, s, Log::quiet());
  const auto x1 = fem::nodes_of_faces(mesh.face_set("x1")), x0 = fem::nodes_of_faces(mesh.face_set("x0"));
  for (fem::Index i : x1) EXPECT_EQ(r.detail_category_pa[i], 90 * kMpa) << i;
  for (fem::Index i : x0) EXPECT_EQ(r.detail_category_pa[i], 36 * kMpa) << i;  // x0 lies in first_cells: 36 < 56
  EXPECT_EQ(r.detail_category_pa.minCoeff(), 36 * kMpa);
  EXPECT_EQ(r.detail_category_pa.maxCoeff(), 160 * kMpa);
  // Uniform stress: the lowest category has the largest damage.
  EXPECT_EQ(r.detail_category_pa[r.critical_node], 36 * kMpa);
  EXPECT_EQ(r.critical_detail, "first_cells");
  EXPECT_GT(r.max_damage_per_cycle, 0.0);
}

TEST(PartFatigue, BelowTheCutOffNoDamageInfiniteLifeAndTheUtilizationOfTheCutOff) {
  const Part part = beam();
  FatigueSettings s = settings();
  s.design_cycles = 4e8;  // beyond N_L = 1e8: u is the ratio to the cut-off limit
  const fatigue::SnCurve curve({.detail_category_mpa = 71});
  const double amplitude = 0.4 * curve.cut_off_limit_pa() / (2 * s.gamma_ff * s.gamma_mf);  // tip range 0.4 Delta sigma_L
  const PartFatigue r = assess_part_fatigue(part, sine_history(part, amplitude, 40), s, Log::quiet());
  EXPECT_EQ(r.max_damage_per_cycle, 0.0);
  EXPECT_TRUE(std::isinf(r.min_life_cycles));
  EXPECT_TRUE(std::isinf(r.min_life_s));
  // The critical node: the largest utilization, at the tip x = L (largest amplitude).
  EXPECT_NEAR(part.model.mesh.nodes(r.critical_node, 0), part.model.mesh.nodes.col(0).maxCoeff(), 1e-12);
  EXPECT_NEAR(r.max_utilization, 0.4, 1e-12);
}

TEST(PartFatigue, DetailsNamingAMissingSetOrPartAreErrorsListingWhatExists) {
  std::vector<Part> parts;
  parts.push_back(beam());
  FatigueSettings s;
  s.details = {{.body = "beam", .set = "weld_toe", .detail_category_mpa = 71.0, .source = "case.toml:40: key 'fatigue.detail[0].set'"}};
  const std::string missing_set = test::error_of([&] { check_fatigue_details(s, parts); });
  EXPECT_NE(missing_set.find("case.toml:40: key 'fatigue.detail[0].set' = \"weld_toe\""), std::string::npos) << missing_set;
  EXPECT_NE(missing_set.find("face sets: x0, x1"), std::string::npos) << missing_set;
  s.details = {{.body = "crank", .set = "x0", .detail_category_mpa = 71.0, .source = "here"}};
  const std::string missing_part = test::error_of([&] { check_fatigue_details(s, parts); });
  EXPECT_NE(missing_part.find("no part on that body (parts: beam)"), std::string::npos) << missing_part;
  s.details = {{.body = "beam", .set = "x0", .detail_category_mpa = 71.0}};
  EXPECT_NO_THROW(check_fatigue_details(s, parts));
}

TEST(PartFatigue, BadHistoriesAndSettingsAreErrorsNamingThePart) {
  const Part part = beam();
  FatigueSettings s = settings();
  EXPECT_NE(test::error_of([&] { assess_part_fatigue(part, PartStressHistory{}, s, Log::quiet()); }).find("no stress history"),
            std::string::npos);
  PartStressHistory h = sine_history(part, 10 * kMpa, 8);
  h.step_stress_pa(6 * 3 + 1, 2) = std::nan("");
  EXPECT_NE(test::error_of([&] { assess_part_fatigue(part, h, s, Log::quiet()); }).find("fatigue at node 3"),
            std::string::npos);
  s.design_cycles = 0.5;
  EXPECT_NE(test::error_of([&] { assess_part_fatigue(part, sine_history(part, 1e6, 8), s, Log::quiet()); })
                .find("less than one"),
            std::string::npos);
  s = settings(75.0);
  EXPECT_NE(test::error_of([&] { assess_part_fatigue(part, sine_history(part, 1e6, 8), s, Log::quiet()); }).find("75"),
            std::string::npos);
}

TEST(PartFatigue, UtilizationOfConstantAmplitudeIsTheRatioToTheDesignStrength) {
  const fatigue::SnCurve curve({.detail_category_mpa = 80, .gamma_ff = 1.0, .gamma_mf = 1.15});
  // m = 5 branch: design cycles 2e7 (between N_D and N_L), Delta sigma_R = Delta sigma_D (5e6 / 2e7)^(1/5).
  const std::vector<fatigue::Cycle> one{{.range_pa = 30 * kMpa, .mean_pa = 0, .count = 1}};
  const double strength = curve.constant_amplitude_limit_pa() * std::pow(5e6 / 2e7, 0.2) / 1.15;
  EXPECT_NEAR(fatigue_utilization(one, curve, fatigue::MeanStressTreatment::None, 2e7), 30 * kMpa / strength, 1e-12);
  EXPECT_EQ(fatigue_utilization({}, curve, fatigue::MeanStressTreatment::None, 2e7), 0.0);
}

}  // namespace
}  // namespace kinetofem::pipeline
