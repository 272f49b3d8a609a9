#pragma once
// PartFactors — the one owner of every part's factorization in a run: each
// part's stiffness with its 3-2-1 support (SupportedPart), analysed once,
// factorized side by side or one part at a time, lent to the stages that
// solve with it (the per-part stress, the elastic assembly's set-up and
// poses, the vibration's reductions) and freed after its last user.
//
// The factor's life as a call order (like Eigen's CholmodSupport:
// analyzePattern, factorize, solve):
//   PartFactors factors(parts, solver, stages, label, log);  // analyse; side by side when they fit
//   for each part k:
//     analyse_part_over_motion(..., &factors.lend(k));       // factorized here when one at a time
//     factors.done(k, FactorUser::Stress);                   // freed unless a later stage needs it
//     assembly.set_up_part(body, factors.lend_analysis(k));
//     factors.done(k, FactorUser::AssemblySetUp, assembly.solves_with_factor(body));
//   analyse_assembly_over_motion(...); factors.done_all(FactorUser::Assembly);
//   analyse_vibration_over_motion(..., &factors.vibration_lender()); factors.done_all(FactorUser::Vibration);
// (the stages that do this for the driver: factor_sharing_stages.hpp)
//
// Side by side or one at a time (factorize_parts, part_factorization.hpp):
// the factors live together when their predicted size (CHOLMOD's symbolic
// analysis, summed over the parts on the direct solver) is within the
// factor memory limit (fem::factor_memory_limit_bytes, solver.max_factor_gb);
// otherwise one factor at a time: each is made right before its part's
// stress stage and freed after its last use in that part's turn, and the
// elastic assembly then superposes its loads (no pose may need a freed
// factor). The vibration's reductions borrow each part's factor twice (the
// part-mode rule's set-up, then the fixed-interface modes;
// vibration::AssemblyModes): with factors that fit together they stay from
// the stress stage to the vibration; otherwise each is freed after the
// assembly's set-up (but the last part's, which the vibration uses first)
// and made again for the vibration, one at a time (vibration_lender).
// Stages borrow; they never free a factor.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/pipeline/part_factorization.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"

namespace kinetofem::pipeline {

// The stages of a run that solve with the parts' factors, in run order.
struct FactorStages {
  bool stress = true;      // analyse_part_over_motion, per part
  bool assembly = false;   // the elastic assembly: set-up per part, then its poses
  bool vibration = false;  // the assembly's modes (one reduction per part), after the assembly
};

// Who gives a factor back (PartFactors::done).
enum class FactorUser { Stress, AssemblySetUp, Assembly, Vibration };

// Unit-load superposition in the elastic assembly only from this many poses
// (output times + the static study): below, one solve per pose is cheaper
// (the load patterns cost 12 + 6 k solves and stress recoveries per part);
// exact either way.
inline constexpr std::size_t kMinSuperposedPoses = 64;

class PartFactors {
 public:
  // Analyses every part (one SupportedPart each, in the order of `parts`,
  // which must outlive this) and factorizes them side by side when they fit
  // together (factorize_parts); `label` names the case in messages. Errors
  // (a factor above the limit on the direct path, a matrix that is not
  // positive definite) name the part.
  PartFactors(const std::vector<Part>& parts, const fem::StaticSolverOptions& solver, FactorStages stages,
              std::string label, const Log& log);
  // Keeps references to the parts and the log: temporaries would dangle.
  PartFactors(std::vector<Part>&&, const fem::StaticSolverOptions&, FactorStages, std::string, const Log&) = delete;
  PartFactors(const std::vector<Part>&, const fem::StaticSolverOptions&, FactorStages, std::string, Log&&) = delete;
  PartFactors(const PartFactors&) = delete;
  PartFactors& operator=(const PartFactors&) = delete;
  ~PartFactors();

  // predicted <= limit: every factor may stay in memory until its last user.
  bool factors_fit_together() const;
  // Whether the elastic assembly superposes its loads over `poses` poses:
  // forced when the factors live one at a time, else from kMinSuperposedPoses.
  bool superpose_assembly_loads(std::size_t poses) const;

  // Part k's supported model and factorization, factorized now when it was
  // not (one at a time) or was freed. Error once every user is done with it.
  const SupportedPart& lend(std::size_t k);
  fem::LinearStaticAnalysis& lend_analysis(std::size_t k) { return lend(k).analysis(); }
  // Part k's factorization as it is (not factorized now; nullptr once freed),
  // e.g. to report its size after an allocation failed.
  const fem::LinearStaticAnalysis* held(std::size_t k) const;
  // Every part's factorization, made now where it was not.
  std::vector<fem::LinearStaticAnalysis*> lend_all();
  // Part k's last use by `user`; `still_needed` (assembly set-up): the
  // assembly's poses still solve with it (loads not superposed). The factor
  // is freed when no later stage needs it.
  void done(std::size_t k, FactorUser user, bool still_needed = false);
  void done_all(FactorUser user);
  // Lends the parts' factors to the vibration's reductions by body name;
  // each given back is freed when the factors do not fit together (made
  // again when lent again), kept otherwise.
  vibration::PartFactorLender& vibration_lender();

  std::size_t size() const;
  const PartFactorizationReport& report() const;  // the run.factorization report

 private:
  bool needed_after(std::size_t k, FactorUser user, bool still_needed) const;

  const std::vector<Part>& parts_;
  FactorStages stages_;
  std::string label_;
  const Log& log_;
  PartFactorizationReport report_;
  std::vector<std::unique_ptr<SupportedPart>> supported_;

  class VibrationLender final : public vibration::PartFactorLender {
   public:
    explicit VibrationLender(PartFactors& factors) : factors_(factors) {}
    fem::LinearStaticAnalysis& lend(const std::string& body) override;
    void give_back(const std::string& body) override;

   private:
    std::size_t index(const std::string& body) const;
    PartFactors& factors_;
  };
  VibrationLender vibration_lender_{*this};
};

}  // namespace kinetofem::pipeline
