#pragma once
// The published stress analyses of the two manipulators (SPEC §3; source 002,
// ch. IV, figs. IV.9-10 and IV.21-22): the one copy of these numbers, used by
// the manipulator cases' summary, `kinetofem verify` and the tests. SI units.
//
// The text says "max deformations about 0.1 mm" for both, which disagrees
// with the figures' legends: both readings are kept and reported.
#include "kinetofem/mechanisms/manipulator_models.hpp"

namespace kinetofem::mech {

struct PublishedAnalysis {
  const char* model;             // "lever-chain manipulator"
  long elements = 0, nodes = 0;  // of the published FE model
  double von_mises_pa = 0.0;     // max von Mises
  const char* von_mises_source;  // where the number is read ("fig. IV.9: 23.1 MPa")
  double deformation_figure_m = 0.0;  // max total deformation, figure legend
  const char* deformation_figure_source;
  double deformation_text_m = 0.0;    // "about 0.1 mm" (text)
};

inline PublishedAnalysis published_analysis(ManipulatorType type) {
  if (type == ManipulatorType::LeverChain)
    return {"lever-chain manipulator", 73653, 326077, 23.1e6, "SPEC §3, fig. IV.9: 23.1 MPa (text: below 24 MPa)",
            0.86e-3, "SPEC §3, fig. IV.10: 0.86 mm", 0.1e-3};
  return {"lever manipulator", 187271, 833633, 16e6, "SPEC §3, text: below 16 MPa", 0.89e-3,
          "SPEC §3, fig. IV.22: 0.89 mm", 0.1e-3};
}

}  // namespace kinetofem::mech
