#include "kinetofem/mechanisms/multibody/sundials_check.hpp"

#include <cstdlib>
#include <memory>
#include <string_view>

#include <cvodes/cvodes.h>
#include <idas/idas.h>

namespace kinetofem::mech {

namespace {

// What a user of a linkage case can change, by kind of failure.
constexpr std::string_view kStepAdvice =
    "what can be changed: the first step or the largest step (simulation.initial_step_s, simulation.max_step_s), "
    "or the tolerances (simulation.relative_tolerance, simulation.absolute_tolerance); a singular position or a "
    "force that jumps also causes it";
constexpr std::string_view kToleranceAdvice =
    "what can be changed: looser tolerances (simulation.relative_tolerance, simulation.absolute_tolerance)";
constexpr std::string_view kWorkAdvice =
    "what can be changed: looser tolerances (simulation.relative_tolerance, simulation.absolute_tolerance) or a "
    "shorter simulation.duration_s; a very stiff spring, a fast motor or a singular position also cause it";
constexpr std::string_view kMatrixAdvice =
    "the iteration matrix is singular: redundant constraints, a singular position or a body without mass";
constexpr std::string_view kModelAdvice = "the model's equations could not be evaluated (the cause follows, if known)";

struct Meaning {
  std::string_view text, advice;
};

// Plain meanings of the failures a run can meet (not of misuse of the library,
// which the name alone identifies for a developer).
Meaning ida_meaning(int flag) {
  switch (flag) {
    case IDA_TOO_MUCH_WORK: return {"the integrator used up its allowed number of steps before the next output time", kWorkAdvice};
    case IDA_TOO_MUCH_ACC: return {"the tolerances ask for more accuracy than double precision gives", kToleranceAdvice};
    case IDA_ERR_FAIL: return {"the error test failed repeatedly or at the smallest step", kStepAdvice};
    case IDA_CONV_FAIL: return {"the corrector did not converge, repeatedly or at the smallest step", kStepAdvice};
    case IDA_LSETUP_FAIL:
    case IDA_LSOLVE_FAIL: return {"the linear solver failed", kMatrixAdvice};
    case IDA_RES_FAIL:
    case IDA_REP_RES_ERR:
    case IDA_FIRST_RES_FAIL:
    case IDA_QRHS_FAIL:
    case IDA_FIRST_QRHS_ERR:
    case IDA_REP_QRHS_ERR: return {"the residual function failed", kModelAdvice};
    case IDA_NO_RECOVERY: return {"the residual function failed and the step could not be recovered", kModelAdvice};
    default: return {};
  }
}

Meaning cvode_meaning(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK: return {"the integrator used up its allowed number of steps before the next output time", kWorkAdvice};
    case CV_TOO_MUCH_ACC: return {"the tolerances ask for more accuracy than double precision gives", kToleranceAdvice};
    case CV_ERR_FAILURE: return {"the error test failed repeatedly or at the smallest step", kStepAdvice};
    case CV_CONV_FAILURE: return {"the corrector did not converge, repeatedly or at the smallest step", kStepAdvice};
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL: return {"the linear solver failed", kMatrixAdvice};
    case CV_RHSFUNC_FAIL:
    case CV_FIRST_RHSFUNC_ERR:
    case CV_REPTD_RHSFUNC_ERR:
    case CV_UNREC_RHSFUNC_ERR:
    case CV_QRHSFUNC_FAIL:
    case CV_FIRST_QRHSFUNC_ERR:
    case CV_REPTD_QRHSFUNC_ERR:
    case CV_UNREC_QRHSFUNC_ERR: return {"the right-hand side function failed", kModelAdvice};
    default: return {};
  }
}

// SUNDIALS allocates the name with malloc.
std::string owned_name(char* name) {
  const std::unique_ptr<char, decltype(&std::free)> owner(name, &std::free);
  return name != nullptr ? std::string(name) : std::string();
}

Meaning meaning_of(std::string_view function, int flag) {
  if (function.starts_with("IDA")) return ida_meaning(flag);
  if (function.starts_with("CVode")) return cvode_meaning(flag);
  return {};
}

}  // namespace

std::string sundials_flag_text(const char* function, int flag) {
  const std::string_view f = function != nullptr ? function : "";
  std::string name;
  if (f.starts_with("IDA")) name = owned_name(IDAGetReturnFlagName(flag));
  if (f.starts_with("CVode")) name = owned_name(CVodeGetReturnFlagName(flag));
  if (name.empty() || name.starts_with("NONE")) return fmt::format("failed with flag {}", flag);
  const Meaning meaning = meaning_of(f, flag);
  if (meaning.text.empty()) return fmt::format("failed ({})", name);
  return fmt::format("{} ({})", meaning.text, name);
}

std::string sundials_flag_advice(const char* function, int flag) {
  return std::string(meaning_of(function != nullptr ? function : "", flag).advice);
}

}  // namespace kinetofem::mech
