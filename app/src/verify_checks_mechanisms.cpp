// `kinetofem verify`: closed-form mechanism checks against the numbers of
// SPEC §1, §2, §4, §5, §6. The published numbers with their tolerances and
// reasons, and the computations, are those of tests/verification/mechanisms/:
// both take them from the verification library (spec*_*.hpp).
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/crank_slider_gripper.hpp"
#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"
#include "kinetofem/verification/spec2_four_bar.hpp"
#include "kinetofem/verification/spec4_q_manipulator.hpp"
#include "kinetofem/verification/spec5_spherical.hpp"
#include "kinetofem/verification/spec6_gripper.hpp"

namespace kinetofem::app {

namespace {

namespace km = kinetofem::mech;
namespace kv = kinetofem::verification;
using units::kDeg;
using units::kMm;

// A row against a published value: its source, unit, tolerance and reason.
CheckRow against(const std::string& name, const kv::PublishedValue& published, double computed) {
  return compare_absolute(name, published.source, published.unit, published.value, computed, published.tolerance,
                          published.why);
}

std::vector<CheckRow> spec1_design_geometry(const CheckContext&) {
  const auto g = kv::spec1::example_geometry();
  return {against("b0 = a c / (c + r)", kv::spec1::kB0, g.b0_m / kMm),
          against("l0 = sqrt((a - b0)^2 + r^2)", kv::spec1::kL0, g.l0_m / kMm),
          against("alpha0 = arccos(r / l0)", kv::spec1::kAlpha0, g.alpha0_rad / kDeg)};
}

std::vector<CheckRow> spec1_transfer_function(const CheckContext&) {
  const km::LeverChain lc(kv::spec1::example_geometry());
  return {against("d(dpsi)/d(dphi) at dphi = 0", kv::spec1::kTransferAt0, lc.ctm(0.0).dpsi_d1),
          against("d(dpsi)/d(dphi) at dphi = 20 deg", kv::spec1::kTransferAt20,
                  lc.ctm(kv::spec1::kTransferSecondAngle_deg * kDeg).dpsi_d1)};
}

std::vector<CheckRow> spec1_paths(const CheckContext&) {
  const kv::spec1::PathStudy study = kv::spec1::path_study();
  require(study.c.window_found && study.h.window_found, "no 800 mm window on the paths of C and H");
  return {against("horizontal extent of the path of C (h = 0)", kv::spec1::kExtentC, study.extent_c_mm),
          against("horizontal extent of the path of H (h = 100 mm)", kv::spec1::kExtentH, study.extent_h_mm),
          against("deviation of C above the tangent over 800 mm", kv::spec1::kDeviationC, study.c.max_above_m / kMm),
          against("deviation of H above the tangent over 800 mm", kv::spec1::kDeviationH, study.h.max_above_m / kMm),
          against("deviation of C below the tangent", kv::spec1::kDeviationBelow, study.c.max_below_m / kMm),
          against("deviation of H below the tangent", kv::spec1::kDeviationBelow, study.h.max_below_m / kMm)};
}

std::vector<CheckRow> spec2_four_bar(const CheckContext&) {
  const auto g = kv::spec1::example_geometry();
  const km::LeverChain lc(g);
  const km::FourBar fb = km::make_equivalent_four_bar(g);
  const km::LeverChainPose p = lc.pose(0.0);
  const km::FourBarPose q = fb.pose_at_rotation(0.0);
  std::vector<CheckRow> rows;
  // Both are closed forms of the same design position: round-off (1e-12 of the
  // O(1) values).
  const char* round_off = "closed forms: round-off";
  rows.push_back(compare_absolute("four-bar vs lever-chain: theta' at design", "SPEC §2, equal to 2nd order", "1",
                                  p.theta_d1, q.coupler_d1, 1e-12, round_off));
  rows.push_back(compare_absolute("four-bar vs lever-chain: theta'' at design", "SPEC §2, equal to 2nd order",
                                  "1/rad", p.theta_d2, q.coupler_d2, 1e-12, round_off));
  rows.push_back(compare_absolute("four-bar vs lever-chain: |H''| difference at design", "SPEC §2, equal to 2nd order",
                                  "m/rad^2", 0.0, (p.h.d2 - q.coupler_points.at(1).d2).norm(), 1e-12, round_off));
  rows.push_back(against("Grashof excess (a + r) - (b0 + l0)", kv::spec2::kGrashofExcess,
                         (g.a_m + g.r_m - g.b0_m - g.l0_m) / kMm));
  // Assembly limits by bisection against the closed form |A B0| = l2 +- l3.
  const km::AssemblyRange range = fb.assembly_range();
  require(!range.full_rotation, "the SPEC §2 four-bar should not turn fully");
  const double design = fb.design_input_rad();
  const kv::spec2::AssemblyLimits exact = kv::spec2::closed_form_assembly_limits(g, fb);
  // Bisection to 1e-12 rad: 1e-8 deg is far above that and far below any
  // meaningful difference.
  const char* limit_source = "closed form |A B0| = l2 + l3, |l2 - l3|";
  rows.push_back(compare_absolute("four-bar lower assembly limit dphi", limit_source, "deg",
                                  (exact.lo_rad - design) / kDeg, (range.lo_rad - design) / kDeg, 1e-8,
                                  "bisection to 1e-12 rad"));
  rows.push_back(compare_absolute("four-bar upper assembly limit dphi", limit_source, "deg",
                                  (exact.hi_rad - design) / kDeg, (range.hi_rad - design) / kDeg, 1e-8,
                                  "bisection to 1e-12 rad"));
  return rows;
}

std::vector<CheckRow> spec4_isokinematic(const CheckContext&) {
  const km::QManipulator q = kv::spec4::rose();
  const km::IsokinematicEquivalent eq = km::isokinematic_equivalent(q);
  const int n = 2000;  // samples over 2 pi
  return {compare_absolute("isokinematic pair: |H(P) - H'((1 - i) P)|", "SPEC §4, l1' = l2, l2' = l1, 1-i' = 1/(1-i)",
                           "m", 0.0, kv::spec4::pointwise_distance(q, eq, 200, 0.0314), 1e-12,
                           "same curve: round-off"),
          compare_absolute("isokinematic pair: Hausdorff distance of the paths", "SPEC §4, same point set", "m", 0.0,
                           kv::spec4::rose_pair_hausdorff(q, eq, n), kv::spec4::rose_sampling_chord(n),
                           "sampling chord |H'|max * step"),
          compare_absolute("ratio i' of the equivalent", "SPEC §4, 1 - i' = 1/(1 - i), i = 4", "1",
                           kv::spec4::kRoseEquivalentRatio, eq.manipulator.ratios().at(0), 1e-14, "round-off")};
}

std::vector<CheckRow> spec5_energy(const CheckContext&) {
  const kv::spec5::WorkEnergyBalance b = kv::spec5::work_energy_balance('A');
  return {compare_absolute("variant A, 20 kg: drive work vs potential energy gained", "SPEC §5, work-energy theorem",
                           "J", b.potential_gain_J, b.work_J, kv::spec5::kWorkEnergyTolerance * b.scale_J,
                           "1e-8 of peak power x duration (Simpson)")};
}

std::vector<CheckRow> spec6_gripper(const CheckContext&) {
  namespace s6 = kv::spec6;
  std::vector<CheckRow> rows;
  // One row per published range end (deg).
  auto end_row = [&](const std::string& what, const s6::PublishedRanges& design, double published,
                     const km::PhiInterval& hull, bool from, const char* note) {
    rows.push_back(compare_absolute(what, fmt::format("{}: {:g} deg", design.source, published), "deg", published,
                                    (from ? hull.lo_rad : hull.hi_rad) / kDeg, s6::kRangeTolerance_deg, note));
  };
  for (const s6::PublishedRanges* design : {&s6::kREqualsE, &s6::kBestDesign}) {
    const s6::ComputedRanges ranges = s6::operating_ranges(*design);
    const km::PhiInterval free = km::operating_hull(ranges.free), limited = km::operating_hull(ranges.limited);
    const bool r_equals_e = design == &s6::kREqualsE;
    const std::string label = r_equals_e ? "r = e" : "best design";
    end_row(label + ": |U_V - 1| <= 0.05 from", *design, design->from_deg, free, true,
            r_equals_e ? s6::kRangeWhy : "hull of the ranges (shallow dip to 0.9493 at 152.7 deg); 1 deg");
    end_row(label + ": |U_V - 1| <= 0.05 to", *design, design->to_deg, free, false, s6::kRangeWhy);
    const std::string limits = r_equals_e ? "r = e, with theta12 <= 30 deg" : "best design, pressure limits";
    end_row(limits + ": from", *design, design->limited_from_deg, limited, true, s6::kRangeWhy);
    end_row(limits + ": to", *design, design->limited_to_deg, limited, false, s6::kRangeWhy);
  }
  const auto dims = km::gripper_dimensions_from_offset(s6::kExampleOffset_m, s6::kBestDesign.sigma,
                                                       s6::kBestDesign.gamma);
  rows.push_back(against("design example: connecting rod l = e / gamma", s6::kRodLength, dims.l_m / kMm));
  rows.push_back(against("design example: crank r = sigma l", s6::kCrankRadius, dims.r_m / kMm));
  rows.push_back(against("jaw travel h / r", s6::kJawTravel,
                         km::gripper_jaw_travel_m(1.0, s6::kTravelFrom_deg * kDeg, s6::kTravelTo_deg * kDeg)));
  return rows;
}

}  // namespace

std::vector<Check> mechanism_checks() {
  return {
      {"spec1.design_geometry", "SPEC §1", true, spec1_design_geometry},
      {"spec1.transfer_function", "SPEC §1", true, spec1_transfer_function},
      {"spec1.paths", "SPEC §1", true, spec1_paths},
      {"spec2.four_bar", "SPEC §2", true, spec2_four_bar},
      {"spec4.isokinematic", "SPEC §4", true, spec4_isokinematic},
      {"spec5.drive_work", "SPEC §5", true, spec5_energy},
      {"spec6.gripper", "SPEC §6", true, spec6_gripper},
  };
}

}  // namespace kinetofem::app
