#pragma once
// make_motion_law — the one place where a motion law is built from its named
// parameters (case files of every type, verify, the static pose ramp). The
// laws themselves are in motion_law.hpp.
//
//   law               needs                      SI units
//   polynomial345     stroke, duration           rad or m, s
//   cycloidal         stroke, duration
//   trapezoidal       stroke, duration, accel_fraction kP, decel_fraction kT
//                     (0 < kP, kT; kP + kT <= 1)
//   constant_velocity speed                      rad/s or m/s
//   csv               table_file, table_to_si (factor from the table's unit)
// A missing or invalid parameter is an Error naming the law and the parameter.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "kinetofem/mechanisms/motion_law.hpp"

namespace kinetofem::mech {

struct MotionLawSpec {
  std::string law = "polynomial345";
  std::optional<double> stroke;      // rad or m
  std::optional<double> duration_s;
  double accel_fraction = 0.25;      // trapezoidal kP (SPEC §5)
  double decel_fraction = 0.25;      // trapezoidal kT
  std::optional<double> speed;       // constant_velocity, rad/s or m/s
  std::filesystem::path table_file;  // csv rows "t_s, s"
  double table_to_si = 1.0;          // factor from the table's s unit (deg, mm) to SI
};

// The laws make_motion_law knows, in the order of the table above.
const std::vector<std::string>& motion_law_names();

std::shared_ptr<const MotionLaw> make_motion_law(const MotionLawSpec& spec);

}  // namespace kinetofem::mech
