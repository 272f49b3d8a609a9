#pragma once
// SPEC §2: the hinged four-bar A0-A-B-B0 (the "lever manipulator")
// equivalent to the lever-chain example of SPEC §1 (spec1_lever_chain.hpp):
// crank a = A0A, coupler r = AB, rocker b0 = B0B, ground l0 = A0B0.
#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/verification/published_value.hpp"

namespace kinetofem::verification::spec2 {

// Non-Grashof: s + l - (p + q) = (a + r) - (b0 + l0) from the printed
// lengths 500 + 75 - (411.8 + 115.8) mm.
inline constexpr PublishedValue kGrashofExcess{47.4, 0.1, "mm", "SPEC §2, 500+75 > 411.8+115.8",
                                               "two lengths printed to 0.1 mm: +-0.1 mm"};

// Closed form: |A(phi) B0| = sqrt(a^2 + l0^2 - 2 a l0 cos(phi - alpha0)),
// phi the crank's absolute angle.
double crank_pin_to_b0_m(const mech::LeverChainGeometry& g, double phi_rad);

// The four-bar's assembly limits nearest to its design input on either side:
// the crank angles where |A B0| = l2 + l3 or |l2 - l3| (coupler and rocker
// collinear), solved in closed form from the formula above. Absolute crank
// angles, rad; +-inf when there is none on that side.
struct AssemblyLimits {
  double lo_rad = 0.0, hi_rad = 0.0;
};
AssemblyLimits closed_form_assembly_limits(const mech::LeverChainGeometry& g, const mech::FourBar& four_bar);

}  // namespace kinetofem::verification::spec2
