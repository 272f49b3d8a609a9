#pragma once
// A part's nodal stress at every output time of the motion, kept by the
// stress stage (analyse_part_over_motion, part_stress.hpp) for a stage that
// needs the whole history of every node (the fatigue check,
// part_fatigue.hpp).
//
// Units: Pa. Layout: node-major Voigt, 6 N rows (node i's xx, yy, zz, xy,
// yz, zx at rows 6i .. 6i+5, tensor shear; fem::StressField order), one
// column per load pattern or output time.
//
// Two forms, the same values (to round-off; tests/regression):
//   * unit-load superposition: stress(t) = pattern_stress_pa * coefficients.col(t),
//     so a node's 6 x T history is a 6 x m block times the m x T
//     coefficients; T full fields are never stored;
//   * step by step: step_stress_pa.col(t), every output time stored.
// Output times only (the static pose study is not part of the history).
#include <Eigen/Core>

namespace kinetofem::pipeline {

// Where a part's stress history comes from: the per-part stage (the part as
// a free body under the planar multibody reactions, or under the spatial
// ones for a part of a spatial mechanism, part_stress.hpp) or the elastic
// assembly (its 3D joint loads, the moments between parts in several planes
// included; assembly_over_motion.hpp).
enum class StressHistorySource { FreeBodyPart, SpatialFreeBodyPart, ElasticAssembly };

// "the part as a free body (planar reactions)", "the elastic assembly (3D joint loads)".
inline const char* describe(StressHistorySource source) {
  switch (source) {
    case StressHistorySource::FreeBodyPart: return "the part as a free body under the planar multibody reactions";
    case StressHistorySource::SpatialFreeBodyPart:
      return "the part as a free body under the spatial multibody reactions";
    case StressHistorySource::ElasticAssembly: return "the elastic assembly (its 3D joint loads)";
  }
  return "?";
}

struct PartStressHistory {
  StressHistorySource source = StressHistorySource::FreeBodyPart;
  Eigen::MatrixXd pattern_stress_pa;  // 6 N x m (superposition), else empty
  Eigen::MatrixXd coefficients;       // m x T (superposition), else empty
  Eigen::MatrixXd step_stress_pa;     // 6 N x T (step by step), else empty

  // (coefficients has T columns even when no pattern is kept, m = 0.)
  bool superposed() const { return coefficients.cols() > 0; }
  Eigen::Index nodes() const { return (superposed() ? pattern_stress_pa.rows() : step_stress_pa.rows()) / 6; }
  Eigen::Index times() const { return superposed() ? coefficients.cols() : step_stress_pa.cols(); }
  bool empty() const { return times() == 0; }

  // Node i's history, 6 x T (Voigt rows, one column per output time).
  template <typename Out>
  void node_history(Eigen::Index node, Out& out) const {
    if (superposed())
      out.noalias() = pattern_stress_pa.middleRows(6 * node, 6) * coefficients;
    else
      out = step_stress_pa.middleRows(6 * node, 6);
  }
};

}  // namespace kinetofem::pipeline
