#include "kinetofem/pipeline/part_factors.hpp"

#include <utility>

#include "kinetofem/core/error.hpp"

namespace kinetofem::pipeline {

PartFactors::PartFactors(const std::vector<Part>& parts, const fem::StaticSolverOptions& solver, FactorStages stages,
                         std::string label, const Log& log)
    : parts_(parts), stages_(stages), label_(std::move(label)), log_(log) {
  supported_ = factorize_parts(parts, solver, log, &report_);
  if (stages_.assembly && !factors_fit_together())
    log_.info("elastic assembly: one part's factor in memory at a time (the factors exceed the limit together); "
              "each is freed after its interface and load-pattern solves{}",
              stages_.vibration ? " and made again, one at a time, for the vibration's reductions" : "");
}

PartFactors::~PartFactors() = default;

bool PartFactors::factors_fit_together() const { return report_.predicted_factor_bytes <= report_.limit_bytes; }

bool PartFactors::superpose_assembly_loads(std::size_t poses) const {
  return !factors_fit_together() || poses >= kMinSuperposedPoses;
}

const SupportedPart& PartFactors::lend(std::size_t k) {
  require(k < supported_.size(), "part factors: part {} of {}", k, supported_.size());
  require(supported_[k] != nullptr, "{}: its factorization was lent to its last user already", parts_[k].name());
  supported_[k]->analysis().factorize();  // a no-op when it is in memory
  return *supported_[k];
}

const fem::LinearStaticAnalysis* PartFactors::held(std::size_t k) const {
  return k < supported_.size() && supported_[k] ? &supported_[k]->analysis() : nullptr;
}

std::vector<fem::LinearStaticAnalysis*> PartFactors::lend_all() {
  std::vector<fem::LinearStaticAnalysis*> out;
  for (std::size_t k = 0; k < supported_.size(); ++k) out.push_back(&lend_analysis(k));
  return out;
}

bool PartFactors::needed_after(std::size_t k, FactorUser user, bool still_needed) const {
  switch (user) {
    case FactorUser::Stress: return stages_.assembly || stages_.vibration;
    // One at a time, the vibration makes the factor again when it needs it,
    // but starts with the last part (vibration::AssemblyModes), whose factor
    // is the one in memory now.
    case FactorUser::AssemblySetUp:
      return still_needed || (stages_.vibration && (factors_fit_together() || k + 1 == parts_.size()));
    case FactorUser::Assembly: return stages_.vibration;
    case FactorUser::Vibration: return false;
  }
  return true;
}

void PartFactors::done(std::size_t k, FactorUser user, bool still_needed) {
  if (k >= supported_.size() || !supported_[k]) return;
  if (needed_after(k, user, still_needed)) return;
  switch (user) {
    case FactorUser::Stress:
      supported_[k].reset();  // no second use: free the part's supported model and factor now
      return;
    case FactorUser::AssemblySetUp:
      // No later solve: a pose costs products with the solved columns only.
      supported_[k]->analysis().release_factor();
      log_.detail("elastic assembly: part '{}': columns solved, its factor freed", parts_[k].body());
      return;
    case FactorUser::Assembly:
    case FactorUser::Vibration: supported_[k].reset(); return;
  }
}

void PartFactors::done_all(FactorUser user) {
  for (std::size_t k = 0; k < supported_.size(); ++k) done(k, user);
}

std::size_t PartFactors::size() const { return supported_.size(); }

const PartFactorizationReport& PartFactors::report() const { return report_; }

vibration::PartFactorLender& PartFactors::vibration_lender() { return vibration_lender_; }

std::size_t PartFactors::VibrationLender::index(const std::string& body) const {
  for (std::size_t k = 0; k < factors_.parts_.size(); ++k)
    if (factors_.parts_[k].body() == body) return k;
  fail("{}: no part of body '{}' to lend the vibration", factors_.label_, body);
}

fem::LinearStaticAnalysis& PartFactors::VibrationLender::lend(const std::string& body) {
  return factors_.lend_analysis(index(body));
}

void PartFactors::VibrationLender::give_back(const std::string& body) {
  const std::size_t k = index(body);
  if (factors_.factors_fit_together() || !factors_.supported_[k]) return;
  factors_.supported_[k]->analysis().release_factor();
  factors_.log_.detail("vibration: part '{}': reductions' solves done for now, its factor freed", body);
}

}  // namespace kinetofem::pipeline
