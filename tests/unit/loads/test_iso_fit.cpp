// ISO 286 clearance fits: the limits of published fits (ISO 286-2 tables
// of fits, e.g. H7/g6 at 40 mm: clearance 9 .. 50 um), exact in um.
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/iso_fit.hpp"

namespace kinetofem::loads {
namespace {

TEST(IsoFit, PublishedClearancesOfCommonFits) {
  struct Case {
    const char* fit;
    double diameter_mm, min_um, max_um;
  };
  // ISO 286-2 (hole H: 0 .. IT; shaft: es .. es - IT), values as tabulated.
  for (const Case& c : {Case{"H7/g6", 40, 9, 50}, Case{"H8/f7", 20, 20, 74}, Case{"H7/h6", 25, 0, 34},
                        Case{"H9/d9", 50, 80, 204}, Case{"H11/h11", 100, 0, 440}, Case{"H7/f7", 8, 13, 43}}) {
    const FitClearance f = fit_clearance(c.fit, c.diameter_mm * 1e-3);
    EXPECT_NEAR(f.min_m * 1e6, c.min_um, 1e-9) << c.fit << " at " << c.diameter_mm << " mm";
    EXPECT_NEAR(f.max_m * 1e6, c.max_um, 1e-9) << c.fit << " at " << c.diameter_mm << " mm";
    EXPECT_NEAR(f.mean_radial_m(), 0.25 * (c.min_um + c.max_um) * 1e-6, 1e-15);
  }
}

TEST(IsoFit, TheRangeBoundaryBelongsToTheLowerRange) {
  // ISO 286: "over 30 up to and including 50": 30 mm is in 18 .. 30.
  EXPECT_NEAR(fit_clearance("H7/g6", 0.030).max_m * 1e6, 21 + 20, 1e-9);
  EXPECT_NEAR(fit_clearance("H7/g6", 0.0300001).max_m * 1e6, 25 + 25, 1e-9);
}

TEST(IsoFit, UnsupportedFitsAndDiametersAreErrors) {
  for (const char* bad : {"H7", "G7/h6", "H7/p6", "H10/g6", "H7/g", "h7/g6", "H7/g66x", ""})
    EXPECT_THROW(check_fit(bad), Error) << bad;
  EXPECT_THROW(fit_clearance("H7/g6", 0.0005), Error);
  EXPECT_THROW(fit_clearance("H7/g6", 0.6), Error);
}

}  // namespace
}  // namespace kinetofem::loads
