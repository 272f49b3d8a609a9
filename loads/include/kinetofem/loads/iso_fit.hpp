#pragma once
// Clearance of a hole-basis ISO 286 fit ("H7/g6"): the limits of a pin in its
// bore from the standard's tolerance grades and fundamental deviations
// (ISO 286-1:2010, tables 1 and 2 (shafts); ISO 286-2 for the fits), for
// nominal diameters from 1 to 500 mm.
//
// Supported: holes H6 .. H9 and H11 (lower deviation 0, upper the grade IT6,
// IT7, IT8, IT9, IT11); shafts d, e, f, g, h with grades 6 .. 9 and 11 (upper
// deviation the fundamental deviation, lower that less the grade): the
// clearance fits. Interference and transition fits (shafts j .. zc) are not
// supported (the contact model has no interference).
#include <optional>
#include <string>

#include "kinetofem/solver/material.hpp"

namespace kinetofem::loads {

struct FitClearance {
  double min_m = 0.0, max_m = 0.0;  // diametral clearance, m
  double mean_m() const { return 0.5 * (min_m + max_m); }
  double mean_radial_m() const { return 0.25 * (min_m + max_m); }
};

// A pin in contact as a case gives it: radial clearance, or a fit (not
// empty) resolved at the bore's diameter; its material when it is elastic
// (none: a rigid pin).
struct ContactFit {
  double clearance_m = 0.0;
  std::string fit;
  std::optional<fem::IsotropicMaterial> pin_material;
};

// Throws Error naming `fit` when it is not "H<grade>/<letter><grade>" of the
// supported ones (the message lists them).
void check_fit(const std::string& fit);

// The fit's clearance at nominal diameter `diameter_m`; throws Error for a
// fit check_fit refuses or a diameter outside 1 .. 500 mm.
FitClearance fit_clearance(const std::string& fit, double diameter_m);
// The radial clearance of a pin in contact as a case gives it: clearance_m,
// or (fit not empty) the fit's mean radial clearance at the bore's
// diameter. Throws Error like fit_clearance.
double radial_clearance(double clearance_m, const std::string& fit, double bore_diameter_m);

}  // namespace kinetofem::loads
