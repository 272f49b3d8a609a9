#pragma once
// Stage "fatigue over the work cycle" for one part: from the
// part's nodal stress at every output time of the motion (PartStressHistory,
// kept by analyse_part_over_motion), per node
//   1. the stress history reduced to a scalar: the normal stress on the
//      critical plane (default; 226 candidate planes, every plane within
//      7.07 deg of one, docs/fatigue.md), or the signed maximum principal or
//      signed von Mises stress (FatigueSettings::measure);
//   2. rainflow counting of ONE period (ASTM E1049-85 5.4.4,
//      fatigue::Residue::Periodic): the motion is the work cycle, repeated;
//   3. Palmgren-Miner damage per cycle D with the EN 1993-1-9 S-N curve of
//      the node's detail category and the partial factors gamma_Ff, gamma_Mf;
//   4. life in cycles 1/D and in time 1/(D x cycle rate) (infinite for
//      D = 0: every range below the cut-off limit), and the utilization u
//      (below).
// The part's nodes take the part default detail category unless they belong
// to an element set or face set given a category of its own (a weld toe
// region, the base metal); a node in several takes the lowest (the most
// severe) category, the first listed on a tie.
//
// Utilization u (for every node, also where D = 0): the factor on the stress
// ranges of the critical plane's counted cycles that gives exactly the design
// damage design_cycles x D = 1, inverted: u = 1 / s*, s* = inf{ s :
// design_cycles x D(s x ranges) >= 1 } (bisection; D is non-decreasing in
// s). u <= 1 passes the check over the service life; for constant amplitude
// u = gamma_Ff gamma_Mf Delta sigma / Delta sigma_R(design_cycles), the
// EN 1993-1-9 8(1) ratio at the design number of cycles. For D = 0 it says
// how far the ranges are below the cut-off.
//
// Mean stress: only EN 1993-1-9 7.2.1(1)'s reduction of the compressive part
// to 60 % for non-welded or stress-relieved details (a detail's
// mean_stress = ReducedCompression); as-welded details: None.
//
// Memory: on the superposition path each node's 6 x T history is its 6 x m
// pattern block times the m x T coefficients, formed per node; no T fields.
// Nodes are processed in parallel (OpenMP), in chunks, with a progress line.
//
// Units: SI (Pa, s; cycle rate 1/s); detail categories in MPa
// where named _mpa (as the standard's tables write them).
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/fatigue/critical_plane.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress_history.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::pipeline {

// A detail category for the nodes of one element set or face set of a part.
struct FatigueDetail {
  std::string body;                 // the part's body
  std::string set;                  // an element set or face set of its mesh
  double detail_category_mpa = 0;   // EN 1993-1-9 Delta sigma_C (tables 8.1 to 8.10)
  fatigue::MeanStressTreatment mean_stress = fatigue::MeanStressTreatment::None;
  std::string source;               // for messages: where the case gave it ("case.toml:40: key ...")
};

struct FatigueSettings {
  fatigue::StressMeasure measure = fatigue::StressMeasure::CriticalPlane;
  double detail_category_mpa = 71.0;  // every part's default detail
  fatigue::MeanStressTreatment mean_stress = fatigue::MeanStressTreatment::None;  // of the default detail
  std::vector<FatigueDetail> details;  // per set, override the default
  double gamma_ff = 1.0;   // EN 1993-1-9 3(7)
  double gamma_mf = 1.35;  // EN 1993-1-9 table 3.1: safe life, high consequence
  // The work cycle (the motion) repeated at cycle_rate_per_s (1/s; the case
  // gives cycles_per_hour) over the service life: design_cycles = rate x
  // service life, or a number of cycles given directly.
  double cycle_rate_per_s = 60.0 / 3600.0;
  double design_cycles = 60.0 * 80000.0;
  double plane_spacing_deg = 10.0;  // critical plane search
};

struct PartFatigue {
  std::string body;
  // Per node (N).
  Eigen::VectorXd damage_per_cycle, life_cycles, life_s, utilization;  // life: inf where D = 0
  Eigen::VectorXd detail_category_pa, max_range_pa;  // the node's category; largest counted range
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> plane_normal;  // critical plane (0: no plane)
  // The critical node: the largest damage per cycle, or where every node has
  // D = 0, the largest utilization.
  long critical_node = 0;
  Eigen::Vector3d critical_at_m = Eigen::Vector3d::Zero();  // body frame
  std::string critical_detail;                              // its set, or "part default"
  fatigue::NodeFatigue critical;                            // its plane, counted cycles
  double design_cycles = 0, cycle_rate_per_s = 0;
  double max_damage_per_cycle = 0, min_life_cycles = 0, min_life_s = 0, max_utilization = 0;
  int planes_searched = 0;
  bool superposed = false;
  StressHistorySource stress_source = StressHistorySource::FreeBodyPart;
  double seconds = 0;
};

// The settings' details against the parts: each names a part body and an
// element set or face set of its mesh. Error naming the detail's source, the
// set and the sets the part has. Run before the motion (no FE work lost).
void check_fatigue_details(const FatigueSettings& settings, const std::vector<Part>& parts);

// The stage. Prints one line: critical node, damage, life, time. Error on an
// empty history, one that does not fit the part's mesh, or non-finite
// stresses (naming the part and node).
PartFatigue assess_part_fatigue(const Part& part, const PartStressHistory& history, const FatigueSettings& settings,
                                const Log& log);

// The per-node fields into the part's body of the results file, static
// fields (docs/results.md): fatigue_damage_per_cycle (1), fatigue_life_cycles
// (cycles, inf where D = 0), fatigue_life_h (h), fatigue_utilization (1),
// fatigue_detail_category (Pa), fatigue_max_range (Pa),
// fatigue_plane_normal (3).
void write_part_fatigue(post::BodyWriter& body, const PartFatigue& result);

// The printed summary: one row per part (critical node, detail, damage, life,
// utilization) and the critical nodes' counted ranges.
std::string format_fatigue_table(const std::vector<PartFatigue>& parts);
// The same as CSV: one row per counted range (merged) of each part's critical node.
std::string fatigue_critical_csv(const std::vector<PartFatigue>& parts);

// u = 1 / s* of the header comment for counted (effective) cycles, >= 0.
double fatigue_utilization(std::span<const fatigue::Cycle> cycles, const fatigue::SnCurve& curve,
                           fatigue::MeanStressTreatment mean_stress, double design_cycles);

}  // namespace kinetofem::pipeline
