#pragma once
// Case-file keys of a motion law, declared once for every case type that
// prescribes a motion (manipulator: [motion]; linkage: [[motion_drive]] and a
// pd_servo's reference), and their reader, which builds the law with the one
// factory mech::make_motion_law.
//
// Keys under `prefix` (e.g. "motion." or "motion_drive[]."): <law_key>,
// stroke_deg | stroke_mm, duration_s, accel_fraction, decel_fraction,
// speed_deg_s | speed_mm_s, file (csv). An angle coordinate takes the _deg
// keys, a displacement the _mm keys; giving the other one is an error.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"

namespace kinetofem::app {

struct MotionLawKeyOptions {
  std::optional<std::string> default_law;  // default of <law_key>
  std::optional<double> default_stroke_deg, default_duration_s;
  bool angles_only = false;                // no _mm keys, no constant_velocity (a bounded motion)
};

void add_motion_law_keys(std::vector<KeySpec>& schema, const std::string& prefix, const std::string& law_key,
                         const MotionLawKeyOptions& options);

// The law of element k; `angle`: the coordinate is an angle (else a
// displacement). Errors name the key.
std::shared_ptr<const mech::MotionLaw> read_motion_law(const CaseFile& c, const std::string& prefix,
                                                       const std::string& law_key, bool angle, std::size_t k = 0);

// A number key given in the coordinate's unit: <prefix><base><suffix_deg> for
// angles, <prefix><base><suffix_mm> for displacements (SI value); nullopt if
// absent; Error if the key of the other unit is given.
std::optional<double> coordinate_number(const CaseFile& c, const std::string& prefix, const std::string& base,
                                        const std::string& suffix_deg, const std::string& suffix_mm, bool angle,
                                        std::size_t k);

}  // namespace kinetofem::app
