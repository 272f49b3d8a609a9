#include "kinetofem/app/vibration_keys.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"

namespace kinetofem::app {

namespace {

using Type = KeySpec::Type;

const pipeline::VibrationOptions kDefaults{};  // the defaults, declared in pipeline/

}  // namespace

void add_vibration_keys(std::vector<KeySpec>& s) {
  s.push_back({.path = "vibration.enabled", .type = Type::Boolean, .default_number = 0.0,
               .doc = "natural frequencies of the elastic assembly in every pose and the tracked points' elastic "
                      "vibration during and after the motion (needs assembly.enabled; docs/vibration.md)"});
  s.push_back({.path = "vibration.modes", .type = Type::Integer, .default_number = double(kDefaults.modes.modes),
               .min = 1, .max = 100, .doc = "natural frequencies (and modes) wanted per pose, the lowest first"});
  s.push_back({.path = "vibration.part_mode_cutoff_hz", .type = Type::Number, .unit = "Hz",
               .default_number = kDefaults.modes.part_mode_cutoff_hz, .min = 0,
               .doc = "each part keeps its fixed-interface modes up to this frequency (plus residual vectors); 0: "
                      "automatic, cutoff_factor x the highest assembly frequency wanted (an upper bound from the "
                      "parts' static reduction)"});
  s.push_back({.path = "vibration.cutoff_factor", .type = Type::Number,
               .default_number = kDefaults.modes.cutoff_factor, .min = 1,
               .doc = "automatic cutoff = factor x the highest assembly frequency wanted (docs/vibration.md: 2 gives "
                      "the first frequencies within 1e-4 of the unreduced assembly)"});
  s.push_back({.path = "vibration.damping_ratio", .type = Type::Number, .default_number = kDefaults.damping_ratio,
               .min = 0, .max = 1,
               .doc = "modal damping ratio zeta of every mode, 0 <= zeta < 1 (default 0.02: welded steel at working "
                      "stress, Newmark & Hall 1982)"});
  s.push_back({.path = "vibration.settling_tolerance_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm,
               .default_number = kDefaults.settling_tolerance_m / units::kMm, .min = 0, .min_exclusive = true,
               .doc = "a tracked point has settled when its elastic displacement stays within this of its final "
                      "value after the stop"});
}

std::optional<pipeline::VibrationOptions> read_vibration(const CaseFile& c,
                                                          const std::optional<structure::AssemblyOptions>& assembly) {
  if (!c.boolean("vibration.enabled")) {
    // A key without `enabled` would be silently unused: a mistake. With
    // `enabled = false` written (or --set) the stage is off on purpose and its
    // settings are kept for when it is on again.
    if (!c.has("vibration.enabled"))
      for (const char* key : {"vibration.modes", "vibration.part_mode_cutoff_hz", "vibration.cutoff_factor",
                              "vibration.damping_ratio", "vibration.settling_tolerance_mm"})
        require(!c.has(key), "{}: set vibration.enabled = true to use it", c.where(key));
    return std::nullopt;
  }
  require(assembly.has_value(),
          "{} = true needs the elastic assembly: set assembly.enabled = true (the modes are the assembly's)",
          c.where("vibration.enabled"));
  require(assembly->coupling == structure::BoreCoupling::Distributing,
          "{} = true needs assembly.coupling = \"distributing\" (the parts are reduced on their couplings' motion)",
          c.where("vibration.enabled"));
  pipeline::VibrationOptions o;
  o.modes.modes = int(c.integer("vibration.modes"));
  o.modes.part_mode_cutoff_hz = c.number("vibration.part_mode_cutoff_hz");
  o.modes.cutoff_factor = c.number("vibration.cutoff_factor");
  o.damping_ratio = c.number("vibration.damping_ratio");
  require(o.damping_ratio < 1.0,
          "{} = {:g}: the modal damping ratio must be below 1 (1 is critical damping: no vibration to report)",
          c.where("vibration.damping_ratio"), o.damping_ratio);
  o.settling_tolerance_m = c.number("vibration.settling_tolerance_mm");
  for (const char* key : {"vibration.part_mode_cutoff_hz", "vibration.cutoff_factor", "vibration.settling_tolerance_mm"})
    require(std::isfinite(c.number(key)), "{} = {}: must be a finite number", c.where(key), c.number(key));
  return o;
}

}  // namespace kinetofem::app
