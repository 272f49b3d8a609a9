#pragma once
// The SPEC §1/§2 manipulator cases on a coarse mesh (20 mm TET10, 11 output
// times over 1.5 s): fast enough for unit and regression tests of the whole
// manipulator job (`element_size_mm` makes it coarser or finer). `extra` is
// appended TOML (tables not used above, e.g.
// "[assembly]\nenabled = false\n").
#include <string>

namespace kinetofem::testing {

inline std::string coarse_manipulator_case(const std::string& type, double stroke_deg, const std::string& extra = "",
                                           double element_size_mm = 20.0) {
  return "[case]\nname = \"m\"\ntype = \"manipulator\"\n[mechanism]\ntype = \"" + type +
         "\"\n[motion]\nstroke_deg = " + std::to_string(stroke_deg) +
         "\nduration_s = 1.5\noutput_times = 11\n[mesh]\nelement_size_mm = " + std::to_string(element_size_mm) + "\n" +
         extra;
}

}  // namespace kinetofem::testing
