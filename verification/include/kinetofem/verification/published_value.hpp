#pragma once
// A number printed in a source (SPEC section, paper, figure), with the
// tolerance its printing allows: the one copy that `kinetofem verify` and the
// tests compare against.
namespace kinetofem::verification {

struct PublishedValue {
  double value = 0.0;        // as printed, in `unit`
  double tolerance = 0.0;    // absolute, in `unit`
  const char* unit = "";     // "mm", "deg", "1" (dimensionless)
  const char* source = "";   // where it is printed, e.g. "SPEC §1 (1), example"
  const char* why = "";      // why this tolerance
};

// The usual reason: the printed digits.
inline constexpr const char* kHalfLastDigit = "half a unit of the last printed digit";

}  // namespace kinetofem::verification
