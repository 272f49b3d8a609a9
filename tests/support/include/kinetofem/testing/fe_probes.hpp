#pragma once
// Moved to the verification library (kinetofem/verification/fe_probes.hpp),
// which `kinetofem verify` and tests/verification/ share. These names stay
// for the unit tests and large checks that use them.
#include "kinetofem/verification/fe_probes.hpp"

namespace kinetofem::testing {
using verification::consistent_face_forces;
using verification::face_integral;
using verification::nodes_where;
using verification::observed_order;
using verification::prescribe_field;
using verification::SurfaceIntegrand;
using verification::TractionField;
}  // namespace kinetofem::testing
