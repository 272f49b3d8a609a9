#pragma once
// A pin in a conforming hole of a large plate of the same material,
// frictionless, plane (docs/contact.md, "Persson's solution"): the
// reference and its FE probe, shared by `kinetofem verify` and
// tests/verification/loads/test_pin_contact_persson.cpp.
//
// Reference (Persson 1964; in closed form for elastic similarity as derived
// in docs/contact.md): P the load per unit length of the pin (N/m), R its
// radius, dR the radial clearance, E* the plane modulus, eps the contact
// half-angle:
//   E* dR / P = (2 / pi) [cos^4(eps/2) / sin^2(eps/2) (1 + ln cos(eps/2)) - sin^2(eps/2)]
//   p(0) R / P = (1 / pi) [2 sin(eps/2) + cos^4(eps/2) / (2 sin^2(eps/2)) ln((1 + sin(eps/2)) / (1 - sin(eps/2)))]
//
// The FE probe: an annular plate, hole radius R = 10 mm, outer radius 20 R
// (held there in its plane: the infinite plate's solution differs by
// O((R / 20 R)^2) in the uniform mode, and its rigid translation is the
// pin's), 1 mm thick, free faces: generalized plane stress, E* = E; the pin
// spans the plate (1 mm), free, balanced by its body force (the plane
// problem's pin loaded at its centre). Structured HEX20, 192 elements around
// the hole (corner spacing 1.875 deg), 38 graded across (156 000 DoFs, 384
// contact corners); the pin meshed by fem::ElasticPin with 100 around (the
// mortar map between non-matching meshes is exercised), 6 across. SI units.
#include <memory>

#include "kinetofem/core/log.hpp"

namespace kinetofem::verification {

// E* dR / P of the half-angle eps (rad).
double persson_clearance_ratio(double eps);
// p(0) R / P of the half-angle eps.
double persson_peak_ratio(double eps);
// eps for E* dR / P (the ratio falls monotonically from +inf at 0 to -0.46
// at 120 deg); 84.83 deg line-to-line.
double persson_half_angle(double clearance_ratio);

// The tolerance of the FE probe against the reference (issue-level checks
// 1 and 2): 5 % on the peak pressure and on the half-angle.
inline constexpr double kPerssonTolerance = 0.05;

struct PerssonPinResult {
  double clearance_m = 0.0, force_n = 0.0;
  double reference_half_angle_rad = 0.0, reference_peak_pa = 0.0;  // Persson
  // The elastic pin's contact: its peak, its half-angle (the midpoint between
  // the last corner in contact and the first open one: within half a corner
  // spacing, 0.94 deg) and those two corners' angles.
  double peak_pa = 0.0, half_angle_rad = 0.0, last_in_rad = 0.0, first_out_rad = 0.0;
  double rigid_peak_pa = 0.0, rigid_half_angle_rad = 0.0;  // a rigid pin's, for comparison
  double resultant_error = 0.0;                             // worst of the two contact solves
  double pin_mapping_error = 0.0;                           // the elastic pin's mortar map
};

// The plate of the FE probe, factorized and condensed on its hole once.
class PerssonPlate {
 public:
  explicit PerssonPlate(const Log& log);
  PerssonPlate(const Log&&) = delete;  // keeps a reference to the log
  ~PerssonPlate();
  // The plate pushed along +x by force_n through a pin of that radial
  // clearance: Persson's numbers and the FE contact's.
  PerssonPinResult solve(double clearance_m, double force_n) const;
  static double hole_radius_m();
  static double thickness_m();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::verification
