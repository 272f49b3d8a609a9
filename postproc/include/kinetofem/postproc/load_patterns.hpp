#pragma once
// LoadPatternData — a body's motion by unit-load superposition, as stored in
// a results file: the fields of the m load patterns (loads::LinkLoads) and
// the coefficient of each pattern at every output time, so that any output
// time's field is their combination, exactly (to round-off):
//     u(t_k) = elastic_displacement * coefficients.col(k)     (3 N, m)
//     s(t_k) = stress * coefficients.col(k)                   (6 N, Pa)
// Written by BodyWriter::write_load_patterns at /bodies/<body>/load_patterns
// (names attribute; time (T), coefficients (T x m), elastic_displacement
// (m x N x 3), stress (m x N x 6)); read by ResultsFile::read_load_patterns;
// `kinetofem post --at` reconstructs a time's fields with superpose(). Not in
// the XDMF (ParaView shows the written steps). docs/results.md.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::post {

struct LoadPatternData {
  std::vector<std::string> names;          // m, e.g. "body_force.c_x", "bore_A.F_y"
  std::vector<double> time_s;              // T output times (every one of the motion)
  Eigen::MatrixXd coefficients;            // m x T, units of each pattern's unit load
  Eigen::MatrixXd elastic_displacement_m;  // 3 N x m, node-major (x, y, z), rigid-body motion removed
  Eigen::MatrixXd stress_pa;               // 6 N x m, node-major Voigt (fem::StressField order)
};

// One output time's fields from the patterns.
struct SuperposedFields {
  fem::DisplacementField elastic_displacement_m;  // N x 3
  fem::StressField stress_pa;                     // N x 6
  Eigen::VectorXd von_mises_pa;                   // N
};

// The fields at output time index `step` (0 <= step < T; else Error).
SuperposedFields superpose(const LoadPatternData& patterns, Eigen::Index step);

}  // namespace kinetofem::post
