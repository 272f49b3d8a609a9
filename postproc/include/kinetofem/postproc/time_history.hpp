#pragma once
// Time histories from a results file: a nodal series field at one node (given
// by index or as the node nearest to a point of the body frame) and the
// mechanism histories (/mechanism/<name>), plus the units people read them in.
//
//   auto r = post::ResultsFile::open("results/lever_chain_manipulator.h5");
//   const fem::Mesh mesh = r.read_mesh("arm");
//   const fem::Index n = post::nearest_node(mesh.nodes, {0.1, 0.02, 0.0});     // m
//   post::TimeHistory vm = post::node_history(r, "arm", "von_mises", n);      // T x 1, Pa
//   post::TimeHistory tq = post::mechanism_history(r, "drive_torque");        // T_m x 1, N*m
//
// Values stay in the file's SI units; display_unit() gives the unit used in
// CSV files, tables and pictures (mm, MPa, deg).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

class ResultsFile;

struct TimeHistory {
  std::string quantity;     // field or history name, e.g. "von_mises", "drive_torque"
  std::string description;  // e.g. "von_mises at body 'arm' node 123 (10.0, 20.0, 0.0) mm"
  std::string units;        // SI units of values, from the file
  std::vector<std::string> component_names;  // empty for a scalar without names
  std::vector<double> time_s;                // T
  FieldMatrix values;                        // T x c

  // Euclidean norm of each row (for force vectors): T.
  Eigen::VectorXd magnitude() const;
};

// The node nearest to `point_m` (body frame, m); ties go to the lower index.
fem::Index nearest_node(const fem::NodeCoordinates& nodes_m, const Eigen::Vector3d& point_m);

// A series field of `body` at `node` over the body's output times. Throws
// Error naming the body, the field (and the fields present) or the node (and
// the node count) if any is unknown, or if the body has no time series.
TimeHistory node_history(const ResultsFile& results, const std::string& body,
                         const std::string& field, fem::Index node);

// /mechanism/<name> over /mechanism/time; Error naming the histories present if unknown.
TimeHistory mechanism_history(const ResultsFile& results, const std::string& name);

// The unit a value is shown in, and the factor from the SI value:
// m -> mm (1e3), Pa -> MPa (1e-6), rad -> deg (180/pi); any other unit unchanged (1).
struct DisplayUnit {
  std::string label;
  double factor = 1.0;
};
DisplayUnit display_unit(const std::string& si_units);

}  // namespace kinetofem::post
