#include "kinetofem/postproc/load_patterns.hpp"

#include "kinetofem/core/error.hpp"

namespace kinetofem::post {

SuperposedFields superpose(const LoadPatternData& patterns, Eigen::Index step) {
  const Eigen::Index T = patterns.coefficients.cols();
  require(step >= 0 && step < T, "load patterns: output time index {} out of range (0..{})", step, T - 1);
  const Eigen::Index nodes = patterns.stress_pa.rows() / 6;
  const Eigen::VectorXd u = patterns.elastic_displacement_m * patterns.coefficients.col(step);
  const Eigen::VectorXd s = patterns.stress_pa * patterns.coefficients.col(step);
  SuperposedFields out;
  out.elastic_displacement_m = Eigen::Map<const fem::DisplacementField>(u.data(), nodes, 3);
  out.stress_pa = Eigen::Map<const fem::StressField>(s.data(), nodes, 6);
  out.von_mises_pa.resize(nodes);
  for (Eigen::Index i = 0; i < nodes; ++i) out.von_mises_pa[i] = fem::von_mises(out.stress_pa.row(i).transpose());
  return out;
}

}  // namespace kinetofem::post
