#pragma once
// Output time grids.
//
// equally_spaced_times(end_time_s, count): count >= 2 times from 0 to
// end_time_s (s), equally spaced. times[0] is exactly 0 and times[count - 1] is
// exactly end_time_s: the last time is set, not computed, because the usual
// formula end * k / (count - 1) evaluated at k = count - 1 rounds twice and can
// miss the end by an ulp (0.1 * 3 / 3 = 0.10000000000000002), so that a run
// "to the end time" stops short of it or goes past it and a time lookup by
// equality fails. The interior times are end_time_s * k / (count - 1) (the same
// values as that formula), strictly increasing.
// Throws kinetofem::Error for count < 2 or an end time that is not finite and
// positive.
#include <vector>

namespace kinetofem::mech {

std::vector<double> equally_spaced_times(double end_time_s, long count);

}  // namespace kinetofem::mech
