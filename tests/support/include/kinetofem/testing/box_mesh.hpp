#pragma once
// Moved to the verification library (kinetofem/verification/box_mesh.hpp),
// which `kinetofem verify` and tests/verification/ share. These names stay
// for the unit tests, benches and MPI/large checks that use them.
#include "kinetofem/verification/box_mesh.hpp"

namespace kinetofem::testing {
using verification::box_mesh;
using verification::box_node_count;
using verification::BoxMeshOptions;
using verification::sine_warp;
}  // namespace kinetofem::testing
