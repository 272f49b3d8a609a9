#include "kinetofem/pipeline/spatial_part_factors.hpp"

namespace kinetofem::pipeline {

SpatialPartFactors::SpatialPartFactors(const std::vector<structure::SpatialPart>& parts,
                                       const fem::StaticSolverOptions& solver, const Log& log) {
  for (const structure::SpatialPart& part : parts) {
    models_.push_back(std::make_unique<fem::FeModel>(structure::spatial_supported_model(part)));
    log.info("part '{}': stiffness assembly and factorization (once for the whole run)", part.body());
    analyses_.push_back(std::make_unique<fem::LinearStaticAnalysis>(*models_.back(), log, solver));
    analyses_.back()->factorize();
  }
}

std::vector<fem::LinearStaticAnalysis*> SpatialPartFactors::lent() const {
  std::vector<fem::LinearStaticAnalysis*> out;
  for (const auto& a : analyses_) out.push_back(a.get());
  return out;
}

}  // namespace kinetofem::pipeline
