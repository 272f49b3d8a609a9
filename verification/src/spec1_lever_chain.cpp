#include "kinetofem/verification/spec1_lever_chain.hpp"

#include "kinetofem/core/units.hpp"

namespace kinetofem::verification::spec1 {

mech::LeverChainGeometry example_geometry(double h_m) {
  return mech::make_lever_chain_geometry(0.5, 0.35, h_m, 0.075);
}

PathStudy path_study() {
  PathStudy study;
  study.range = mech::lever_chain_published_range();
  const mech::LeverChain lc_c(example_geometry(0.0));
  const mech::LeverChain lc_h(example_geometry(0.1));
  const std::size_t n = 16301;  // 0.01 deg steps
  const auto pc = mech::sample_lever_chain_path(lc_c, study.range.lo_rad, study.range.hi_rad, n);
  const auto ph = mech::sample_lever_chain_path(lc_h, study.range.lo_rad, study.range.hi_rad, n);
  study.extent_c_mm = mech::horizontal_extent(pc.c_m) / units::kMm;
  study.extent_h_mm = mech::horizontal_extent(ph.h_m) / units::kMm;
  study.c = mech::horizontal_straightness(pc.c_m, 0.8, 0.5);
  study.h = mech::horizontal_straightness(ph.h_m, 0.8, 0.6);
  return study;
}

}  // namespace kinetofem::verification::spec1
