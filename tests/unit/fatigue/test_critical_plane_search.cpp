// assess_node's critical plane search against the search written out here
// (every candidate plane counted, the rule of critical_plane.hpp: largest
// damage, ties within 1e-12 to the larger largest range, then the first
// plane), for histories whose ranges are all below the cut-off limit (where
// assess_node counts only the plane of the widest range: the same result must
// come out, to the last bit) and for histories above it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/critical_plane.hpp"
#include "kinetofem/fatigue/miner.hpp"

namespace kinetofem::fatigue {
namespace {

struct Searched {
  int plane = -1;
  double damage = 0.0, max_range_pa = 0.0;
};

Searched search_every_plane(const StressHistory& history, const SnCurve& curve, const FatigueOptions& o,
                            const CandidatePlanes& planes) {
  const PlaneHistories sigma = normal_stress_histories(planes, history);
  Searched best;
  for (Eigen::Index k = 0; k < sigma.rows(); ++k) {
    const std::vector<double> row(sigma.row(k).data(), sigma.row(k).data() + sigma.cols());
    const std::vector<Cycle> cycles = rainflow_count(row, o.residue);
    const double d = miner_damage(cycles, curve, o.mean_stress);
    double r = 0.0;
    for (const auto& c : cycles) r = std::max(r, c.range_pa);
    const double scale = std::max(d, best.damage);
    const bool better = best.plane < 0 || (std::abs(d - best.damage) > 1e-12 * scale ? d > best.damage : r > best.max_range_pa);
    if (better) best = {int(k), d, r};
  }
  return best;
}

void expect_same_search(double amplitude_pa, bool expect_damage) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const SnCurve curve({.detail_category_mpa = 71, .gamma_ff = 1.0, .gamma_mf = 1.35});
  const CandidatePlanes planes = hemisphere_planes(10.0);
  for (const auto treatment : {MeanStressTreatment::None, MeanStressTreatment::ReducedCompression}) {
    FatigueOptions o;
    o.residue = Residue::Periodic;
    o.mean_stress = treatment;
    for (int trial = 0; trial < 40; ++trial) {
      StressHistory h = StressHistory::NullaryExpr(6, 30, [&] { return amplitude_pa * uniform(rng); });
      const NodeFatigue found = assess_node(h, curve, o, planes);
      const Searched ref = search_every_plane(h, curve, o, planes);
      EXPECT_EQ(found.plane, ref.plane) << trial;
      EXPECT_EQ(found.damage, ref.damage) << trial;
      EXPECT_EQ(found.max_range_pa, ref.max_range_pa) << trial;
      EXPECT_EQ(found.damage > 0.0, expect_damage) << trial;
    }
  }
}

TEST(CriticalPlaneSearch, BelowTheCutOffTheWidestPlaneIsTheFullSearchsChoice) {
  // |sigma_ij| <= 2 MPa: plane ranges <= 12 MPa, 1.35 x 12 < Delta sigma_L = 28.8 MPa of category 71.
  expect_same_search(2.0 * units::kMpa, false);
}

TEST(CriticalPlaneSearch, AboveTheCutOffTheSameAsTheFullSearch) { expect_same_search(60.0 * units::kMpa, true); }

}  // namespace
}  // namespace kinetofem::fatigue
