#pragma once
// SpatialPartFactors — the one owner of the factorizations of a spatial
// mechanism's parts (structure::SpatialPart), each with the 3-2-1 support of
// structure::spatial_supported_model, made once and lent to every stage that
// solves with it (the spatial elastic assembly, the per-part stress over the
// motion): one factorization per part for the whole run.
#include <memory>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/spatial_part.hpp"

namespace kinetofem::pipeline {

class SpatialPartFactors {
 public:
  // Assembles and factorizes every part (in order). The log must outlive this.
  SpatialPartFactors(const std::vector<structure::SpatialPart>& parts, const fem::StaticSolverOptions& solver,
                     const Log& log);
  SpatialPartFactors(const std::vector<structure::SpatialPart>&, const fem::StaticSolverOptions&, Log&&) = delete;
  // Per part, in order: its factorized analysis (owned here).
  std::vector<fem::LinearStaticAnalysis*> lent() const;
  fem::LinearStaticAnalysis& of(std::size_t part) const { return *analyses_.at(part); }

 private:
  std::vector<std::unique_ptr<fem::FeModel>> models_;
  std::vector<std::unique_ptr<fem::LinearStaticAnalysis>> analyses_;
};

}  // namespace kinetofem::pipeline
