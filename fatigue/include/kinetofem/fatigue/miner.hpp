#pragma once
// Palmgren-Miner linear damage accumulation of a counted stress spectrum,
// EN 1993-1-9:2005 annex A (damage D_d = sum n_Ei / N_Ri) with the S-N curve of
// sn_curve.hpp.
//
// Units: ranges in Pa, counts and endurance in cycles, damage dimensionless.
//
//   D = sum_i n_i / N_i,   N_i = N_R(gamma_Ff Delta sigma_i) on the curve
//                          Delta sigma_R / gamma_Mf (SnCurve::endurance),
// with Delta sigma_i the (effective, mean_stress.hpp) range of counted cycle
// i and n_i its count (0.5 or 1). Ranges below the cut-off limit add nothing.
// The check is D <= 1. If the cycles are one repetition of a load history
// (e.g. one motion cycle of the robot), D is the damage per repetition and
// the life is 1/D repetitions.
#include <span>

#include "kinetofem/fatigue/mean_stress.hpp"
#include "kinetofem/fatigue/rainflow.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"

namespace kinetofem::fatigue {

// D of the cycles. Error on a negative or non-finite range or count.
double miner_damage(std::span<const Cycle> cycles, const SnCurve& curve,
                    MeanStressTreatment mean_stress = MeanStressTreatment::None);

// 1 / D: repetitions of the counted history to D = 1; infinity for D = 0.
// Error if D is negative or not finite.
double life_repetitions(double damage);

}  // namespace kinetofem::fatigue
