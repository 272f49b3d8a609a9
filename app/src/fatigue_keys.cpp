#include "kinetofem/app/fatigue_keys.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"

namespace kinetofem::app {

namespace {

using Type = KeySpec::Type;
using fatigue::MeanStressTreatment;

// The defaults of pipeline::FatigueSettings, written once there.
const pipeline::FatigueSettings kDefaults{};
constexpr double kDefaultServiceLifeH = 80000.0;  // 20 years x 4000 h (two shifts)

const char* kMeanStressDoc =
    "EN 1993-1-9 7.2.1(1): 'none' (the full range; as-welded details: the standard allows no other) or "
    "'reduced_compression' (the compressive part of the range to 60 %; only non-welded or stress-relieved details)";

std::string category_list() {
  std::string out;
  for (double c : fatigue::detail_categories_mpa()) out += (out.empty() ? "" : ", ") + fmt::format("{:g}", c);
  return out;
}

double category(const CaseFile& c, const std::string& key, std::size_t k = 0) {
  const double value = c.number(key, k) / units::kMpa;
  const auto all = fatigue::detail_categories_mpa();
  require(std::find(all.begin(), all.end(), value) != all.end(),
          "{} = {:g}: not a detail category of EN 1993-1-9 tables 8.1 to 8.10 (MPa: {})", c.where(key, k), value,
          category_list());
  return value;
}

MeanStressTreatment mean_stress(const CaseFile& c, const std::string& key, std::size_t k = 0) {
  return c.text_value(key, k) == "reduced_compression" ? MeanStressTreatment::ReducedCompression
                                                       : MeanStressTreatment::None;
}

}  // namespace

void add_fatigue_keys(std::vector<KeySpec>& s) {
  s.push_back({.path = "fatigue.enabled", .type = Type::Boolean, .default_number = 0.0,
               .doc = "fatigue check of every part over the work cycle (the motion, repeated): rainflow, EN 1993-1-9 "
                      "S-N curve, Miner; damage, life and utilization per node (docs/fatigue.md)"});
  s.push_back({.path = "fatigue.stress_measure", .type = Type::String, .default_text = "critical_plane",
               .allowed = {"critical_plane", "max_principal", "signed_von_mises"},
               .doc = "stress counted per node: the normal stress on the critical plane (226 planes, within 7.07 deg), "
                      "the signed largest principal stress, or von Mises signed by the dominant principal stress"});
  s.push_back({.path = "fatigue.detail_category_mpa", .type = Type::Number, .unit = "MPa", .to_si = units::kMpa,
               .default_number = kDefaults.detail_category_mpa, .min = 0, .min_exclusive = true,
               .doc = "detail category Delta sigma_C of every part's nodes outside [[fatigue.detail]] sets, one of EN "
                      "1993-1-9 tables 8.1-8.10: " + category_list()});
  s.push_back({.path = "fatigue.mean_stress", .type = Type::String, .default_text = "none",
               .allowed = {"none", "reduced_compression"}, .doc = std::string("of the default detail: ") + kMeanStressDoc});
  s.push_back({.path = "fatigue.gamma_ff", .type = Type::Number, .default_number = kDefaults.gamma_ff, .min = 1.0,
               .doc = "partial factor gamma_Ff on the stress ranges (EN 1993-1-9 3(7): 1.0)"});
  s.push_back({.path = "fatigue.gamma_mf", .type = Type::Number, .default_number = kDefaults.gamma_mf, .min = 1.0,
               .doc = "partial factor gamma_Mf on the fatigue strength (EN 1993-1-9 table 3.1: 1.00/1.15 damage "
                      "tolerant, 1.15/1.35 safe life, low/high consequence)"});
  s.push_back({.path = "fatigue.cycles_per_hour", .type = Type::Number, .unit = "1/h", .to_si = 1.0 / units::kHour,
               .default_number = kDefaults.cycle_rate_per_s * units::kHour, .min = 0, .min_exclusive = true,
               .doc = "work cycles (motions) per hour of operation"});
  s.push_back({.path = "fatigue.service_life_h", .type = Type::Number, .unit = "h", .to_si = units::kHour,
               .default_number = kDefaultServiceLifeH, .min = 0, .min_exclusive = true,
               .doc = "hours of operation over the service life (design cycles = cycles_per_hour x service_life_h)"});
  s.push_back({.path = "fatigue.cycles", .type = Type::Number, .min = 0, .min_exclusive = true,
               .doc = "design number of work cycles, instead of service_life_h (life in hours still uses cycles_per_hour)"});
  s.push_back({.path = "fatigue.detail", .type = Type::TableArray,
               .doc = "detail categories of element sets or face sets of a part (a weld toe region, the base metal); "
                      "a node in several sets takes the lowest category"});
  s.push_back({.path = "fatigue.detail[].part", .type = Type::String, .doc = "body of the part", .required = true});
  s.push_back({.path = "fatigue.detail[].set", .type = Type::String,
               .doc = "element set or face set of the part's mesh", .required = true});
  s.push_back({.path = "fatigue.detail[].category_mpa", .type = Type::Number, .unit = "MPa", .to_si = units::kMpa,
               .min = 0, .min_exclusive = true, .doc = "detail category Delta sigma_C of the set's nodes",
               .required = true});
  s.push_back({.path = "fatigue.detail[].mean_stress", .type = Type::String, .default_text = "none",
               .allowed = {"none", "reduced_compression"}, .doc = kMeanStressDoc});
}

std::optional<pipeline::FatigueSettings> read_fatigue(const CaseFile& c, const std::vector<std::string>& bodies_with_parts) {
  if (!c.boolean("fatigue.enabled")) {
    // Keys without the check would be silently unused: a mistake, unless
    // `enabled = false` is written (or --set): the check is off on purpose
    // and its settings are kept for when it is on again.
    if (c.has("fatigue.enabled")) return std::nullopt;
    for (const char* key : {"fatigue.stress_measure", "fatigue.detail_category_mpa", "fatigue.mean_stress",
                            "fatigue.gamma_ff", "fatigue.gamma_mf", "fatigue.cycles_per_hour", "fatigue.service_life_h",
                            "fatigue.cycles"})
      require(!c.has(key), "{}: set fatigue.enabled = true to use it", c.where(key));
    require(c.count("fatigue.detail") == 0, "{}: [[fatigue.detail]] needs fatigue.enabled = true",
            c.where("fatigue.detail[].part", 0));
    return std::nullopt;
  }
  require(!bodies_with_parts.empty(), "{} = true, but no body has a part: the fatigue check needs FE parts",
          c.where("fatigue.enabled"));
  pipeline::FatigueSettings s;
  const std::string measure = c.text_value("fatigue.stress_measure");
  s.measure = measure == "max_principal"      ? fatigue::StressMeasure::MaxPrincipal
              : measure == "signed_von_mises" ? fatigue::StressMeasure::SignedVonMises
                                              : fatigue::StressMeasure::CriticalPlane;
  s.detail_category_mpa = category(c, "fatigue.detail_category_mpa");
  s.mean_stress = mean_stress(c, "fatigue.mean_stress");
  s.gamma_ff = c.number("fatigue.gamma_ff");
  s.gamma_mf = c.number("fatigue.gamma_mf");
  for (const char* key : {"fatigue.gamma_ff", "fatigue.gamma_mf"})
    require(std::isfinite(c.number(key)), "{} = {}: a partial factor must be a finite number >= 1", c.where(key),
            c.number(key));
  s.cycle_rate_per_s = c.number("fatigue.cycles_per_hour");
  require(std::isfinite(s.cycle_rate_per_s), "{} = {}: the cycle rate must be a finite number of cycles per hour",
          c.where("fatigue.cycles_per_hour"), s.cycle_rate_per_s * units::kHour);
  if (c.has("fatigue.cycles")) {
    require(!c.has("fatigue.service_life_h"), "{}: give either fatigue.service_life_h or fatigue.cycles, not both",
            c.where("fatigue.cycles"));
    s.design_cycles = c.number("fatigue.cycles");
    require(std::isfinite(s.design_cycles) && s.design_cycles >= 1.0,
            "{} = {:g}: the service life is shorter than one work cycle", c.where("fatigue.cycles"), s.design_cycles);
  } else {
    const double life_s = c.number("fatigue.service_life_h");
    s.design_cycles = s.cycle_rate_per_s * life_s;
    const std::string key = c.has("fatigue.service_life_h") ? "fatigue.service_life_h" : "fatigue.cycles_per_hour";
    require(std::isfinite(s.design_cycles) && s.design_cycles >= 1.0,
            "{}: service_life_h = {:g} h at cycles_per_hour = {:g} is {:.3g} work cycles: the service life is shorter "
            "than one work cycle",
            c.where(key), life_s / units::kHour, s.cycle_rate_per_s * units::kHour, s.design_cycles);
  }
  for (std::size_t k = 0; k < c.count("fatigue.detail"); ++k) {
    pipeline::FatigueDetail d;
    d.body = c.text_value("fatigue.detail[].part", k);
    d.set = c.text_value("fatigue.detail[].set", k);
    d.detail_category_mpa = category(c, "fatigue.detail[].category_mpa", k);
    d.mean_stress = mean_stress(c, "fatigue.detail[].mean_stress", k);
    d.source = c.where("fatigue.detail[].set", k);
    if (std::find(bodies_with_parts.begin(), bodies_with_parts.end(), d.body) == bodies_with_parts.end()) {
      std::string bodies;
      for (const auto& b : bodies_with_parts) bodies += (bodies.empty() ? "" : ", ") + b;
      fail("{} = \"{}\": no part on that body (parts: {})", c.where("fatigue.detail[].part", k), d.body, bodies);
    }
    s.details.push_back(std::move(d));
  }
  return s;
}

std::filesystem::path report_fatigue(const std::vector<pipeline::PartFatigue>& fatigue,
                                     const std::filesystem::path& results_file) {
  if (fatigue.empty()) return {};
  std::filesystem::path csv = results_file;
  csv.replace_extension(".fatigue.csv");
  write_file_atomically(csv, pipeline::fatigue_critical_csv(fatigue));
  std::printf("%s  fatigue: critical nodes' counted ranges in %s\n", pipeline::format_fatigue_table(fatigue).c_str(),
              csv.string().c_str());
  return csv;
}

}  // namespace kinetofem::app
