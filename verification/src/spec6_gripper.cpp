#include "kinetofem/verification/spec6_gripper.hpp"

namespace kinetofem::verification::spec6 {

ComputedRanges operating_ranges(const PublishedRanges& design) {
  mech::GripperRangeOptions options;
  ComputedRanges ranges;
  ranges.free = mech::gripper_operating_ranges(design.sigma, design.gamma, options);
  options.pressure_limits = true;
  ranges.limited = mech::gripper_operating_ranges(design.sigma, design.gamma, options);
  return ranges;
}

}  // namespace kinetofem::verification::spec6
