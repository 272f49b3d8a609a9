#pragma once
// The worst nodes of the fatigue check in a results file: every body with the
// static field fatigue_damage_per_cycle (results_layout.hpp, written by
// pipeline/part_fatigue.hpp), its nodes ranked by damage per cycle, ties
// (e.g. every node below the cut-off, D = 0) by utilization. Units as in the
// file: damage per cycle (1), life in cycles and hours (inf: no damage),
// utilization (1), detail category and largest range in Pa.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post {

class ResultsFile;

struct FatigueNode {
  std::string body;
  fem::Index node = 0;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double damage_per_cycle = 0, life_cycles = 0, life_h = 0, utilization = 0;
  double detail_category_pa = 0, max_range_pa = 0;
};

// True if some body has the fatigue fields.
bool has_fatigue(const ResultsFile& results);
// The `count` worst nodes over all bodies, worst first. Error naming the
// body if a fatigue field is missing or has the wrong size.
std::vector<FatigueNode> worst_fatigue_nodes(const ResultsFile& results, int count = 10);

}  // namespace kinetofem::post
