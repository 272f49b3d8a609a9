#include "kinetofem/app/motion_keys.hpp"

#include <algorithm>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/motion_law_factory.hpp"

namespace kinetofem::app {

using units::kDeg;
using units::kMm;
using Type = KeySpec::Type;

void add_motion_law_keys(std::vector<KeySpec>& s, const std::string& prefix, const std::string& law_key,
                         const MotionLawKeyOptions& o) {
  const mech::MotionLawSpec defaults;
  std::vector<std::string> laws = mech::motion_law_names();
  if (o.angles_only) std::erase(laws, std::string("constant_velocity"));
  KeySpec law{.path = prefix + law_key, .type = Type::String, .allowed = laws,
              .doc = "motion law s(t): rises by the stroke over [0, duration] and dwells outside"
                     + std::string(o.angles_only ? "" : " (constant_velocity: s = speed t)") + "; csv: a table"};
  law.default_text = o.default_law;
  s.push_back(law);
  KeySpec stroke{.path = prefix + "stroke_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg,
                 .doc = "stroke of an angle law (counter-clockwise positive)"};
  if (o.default_stroke_deg) stroke.default_number = *o.default_stroke_deg;
  s.push_back(stroke);
  if (!o.angles_only)
    s.push_back({.path = prefix + "stroke_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .doc = "stroke of a displacement law"});
  KeySpec duration{.path = prefix + "duration_s", .type = Type::Number, .unit = "s", .min = 0, .min_exclusive = true,
                   .doc = "duration of the rise (polynomial345, cycloidal, trapezoidal)"};
  if (o.default_duration_s) duration.default_number = *o.default_duration_s;
  s.push_back(duration);
  s.push_back({.path = prefix + "accel_fraction", .type = Type::Number, .default_number = defaults.accel_fraction, .min = 0,
               .max = 1, .min_exclusive = true, .doc = "trapezoidal: acceleration time fraction kP (SPEC §5)"});
  s.push_back({.path = prefix + "decel_fraction", .type = Type::Number, .default_number = defaults.decel_fraction, .min = 0,
               .max = 1, .min_exclusive = true, .doc = "trapezoidal: deceleration time fraction kT (SPEC §5)"});
  if (!o.angles_only) {
    s.push_back({.path = prefix + "speed_deg_s", .type = Type::Number, .unit = "deg/s", .to_si = kDeg, .doc = "constant_velocity: rate of an angle"});
    s.push_back({.path = prefix + "speed_mm_s", .type = Type::Number, .unit = "mm/s", .to_si = kMm, .doc = "constant_velocity: rate of a displacement"});
  }
  s.push_back({.path = prefix + "file", .type = Type::String,
               .doc = std::string("csv: file of rows 't_s, s' (s in deg") + (o.angles_only ? "" : " or mm") + "), relative to the case file"});
}

namespace {

// The key's value, else its schema default, else nullopt.
std::optional<double> number_or_default(const CaseFile& c, const std::string& key, std::size_t k) {
  if (c.has(key, k)) return c.number(key, k);
  try {
    return c.number(key, k);
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace

std::optional<double> coordinate_number(const CaseFile& c, const std::string& prefix, const std::string& base,
                                        const std::string& suffix_deg, const std::string& suffix_mm, bool angle,
                                        std::size_t k) {
  const std::string mine = prefix + base + (angle ? suffix_deg : suffix_mm);
  const std::string other = prefix + base + (angle ? suffix_mm : suffix_deg);
  require(!c.has(other, k), "{}: this drive's coordinate is {}: use '{}{}'", c.where(other, k),
          angle ? "an angle" : "a displacement", base, angle ? suffix_deg : suffix_mm);
  return number_or_default(c, mine, k);
}

std::shared_ptr<const mech::MotionLaw> read_motion_law(const CaseFile& c, const std::string& prefix,
                                                       const std::string& law_key, bool angle, std::size_t k) {
  mech::MotionLawSpec spec;
  spec.law = c.text_value(prefix + law_key, k);
  const std::string at = c.where(prefix + law_key, k);
  if (spec.law == "csv") {
    require(c.has(prefix + "file", k), "{} = \"csv\": needs 'file' (rows t_s, s in {})", at, angle ? "deg" : "mm");
    std::filesystem::path file = c.text_value(prefix + "file", k);
    if (file.is_relative()) file = c.path().parent_path() / file;
    const std::string problem = input_file_problem(file);
    require(problem.empty(), "{} = \"{}\": {} ({})", c.where(prefix + "file", k), c.text_value(prefix + "file", k),
            problem, file.string());
    spec.table_file = file;
    spec.table_to_si = angle ? kDeg : kMm;
    try {
      return mech::make_motion_law(spec);
    } catch (const Error& e) {
      fail("{}: {}", c.where(prefix + "file", k), e.what());
    }
  }
  if (spec.law == "constant_velocity") {
    spec.speed = coordinate_number(c, prefix, "speed", "_deg_s", "_mm_s", angle, k);
    require(spec.speed.has_value(), "{} = \"constant_velocity\": needs '{}'", at, angle ? "speed_deg_s" : "speed_mm_s");
  } else {
    spec.stroke = coordinate_number(c, prefix, "stroke", "_deg", "_mm", angle, k);
    require(spec.stroke.has_value(), "{} = \"{}\": needs '{}'", at, spec.law, angle ? "stroke_deg" : "stroke_mm");
    spec.duration_s = number_or_default(c, prefix + "duration_s", k);
    require(spec.duration_s.has_value(), "{} = \"{}\": needs 'duration_s'", at, spec.law);
    spec.accel_fraction = c.number(prefix + "accel_fraction", k);
    spec.decel_fraction = c.number(prefix + "decel_fraction", k);
  }
  try {
    return mech::make_motion_law(spec);
  } catch (const Error& e) {
    fail("{}: {}", at, e.what());
  }
}

}  // namespace kinetofem::app
