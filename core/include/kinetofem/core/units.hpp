#pragma once
// The unit table: factors from the units users write (case files, printed
// summaries) to SI. Everything inside kinetofem is SI (m, kg, s, N, Pa, rad);
// a value crosses this table once on the way in (value * factor) and once on
// the way out (value / factor). Use these names instead of local constants.
#include <numbers>

namespace kinetofem::units {

inline constexpr double kMm = 1e-3;                              // mm -> m
inline constexpr double kMpa = 1e6;                              // MPa -> Pa
inline constexpr double kGpa = 1e9;                              // GPa -> Pa
inline constexpr double kDeg = std::numbers::pi / 180.0;         // deg -> rad
inline constexpr double kRpm = 2.0 * std::numbers::pi / 60.0;    // rpm -> rad/s
inline constexpr double kGramsPerCm3 = 1e3;                      // g/cm^3 -> kg/m^3
inline constexpr double kHour = 3600.0;                          // h -> s

// Standard gravity (ISO 80000-3), m/s^2: the one default for every case type.
inline constexpr double kStandardGravity = 9.80665;

}  // namespace kinetofem::units
