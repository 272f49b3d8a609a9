#pragma once
// Envelopes and hot spots of a scalar field (von Mises stress) in a results file.
//
// Envelope: per node of one body, the maximum of a scalar field over the
// body's time series and the step where it occurred,
//
//   value(n) = max_k f(k, n),   step(n) = argmax_k f(k, n)   (first k on a tie).
//
// It is read from /bodies/<body>/envelopes/<field> when the writer stored it
// (operation "max"), recomputed from /series/<field> step by step when not,
// and for a body without a time series (a static run) it is the static field
// itself (no time). The static pose study of a manipulator run is a separate
// load case (static_von_mises) and is not mixed into the envelope.
//
// Hot spots: the N highest envelope values over all bodies (each naming the
// solid and the weld seam of a welded part it lies on), spatially
// separated — nodes are taken in decreasing value, and a node within
// `separation_m` of an already listed hot spot of the same body is skipped, so
// one stress concentration is listed once, not as its N neighbouring nodes.
//
// Frames and units: node positions are the undeformed coordinates of the
// body's mesh, in its body frame (m); values in the field's units (Pa);
// times in s. Conversion to mm / MPa is for display only (time_history.hpp).
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::post {

class ResultsFile;

struct BodyEnvelope {
  enum class Source { FileEnvelope, Series, Static };

  std::string body;
  std::string field;               // e.g. "von_mises"
  std::string units;               // the field's units, e.g. "Pa"
  Source source = Source::FileEnvelope;
  fem::NodeCoordinates nodes_m;    // undeformed, body frame
  std::vector<double> times_s;     // the body's series times; empty for Source::Static
  Eigen::VectorXd max_value;       // N
  std::vector<fem::Index> max_step;  // N, index into times_s; -1 for Source::Static
  // A part welded from several solids: the sorted nodes of each solid (of the elements of its set
  // "solid.<name>") and of each seam (node set "weld.<a>.<b>"), by name; empty for one solid.
  std::vector<std::pair<std::string, std::vector<fem::Index>>> solid_nodes, seam_nodes;

  fem::Index peak_node() const;    // node of the largest value (first on a tie)
  double peak_value() const;
  // Time of node n's maximum (s); NaN for a static field.
  double time_of(fem::Index node) const;
  const char* source_name() const;  // "envelope in file", "recomputed from series", "static field"
};

// The max envelope of a scalar field of one body, from the file's envelope,
// else its series, else its static field. Throws Error naming the body and
// the fields it has if none holds `field`, or if the field is not scalar.
BodyEnvelope max_envelope(const ResultsFile& results, const std::string& body,
                          const std::string& field = layout::kVonMises);
// Always recomputed from /series/<field> (one step in memory at a time).
BodyEnvelope envelope_from_series(const ResultsFile& results, const std::string& body,
                                  const std::string& field = layout::kVonMises);

// The max envelopes of every body that has `field` (bodies without it are skipped).
std::vector<BodyEnvelope> max_envelopes(const ResultsFile& results,
                                        const std::string& field = layout::kVonMises);

struct HotSpot {
  std::string body;
  fem::Index node = -1;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // undeformed, body frame
  fem::Index step = -1;                                  // -1: static field
  double time_s = std::numeric_limits<double>::quiet_NaN();
  double value = 0.0;                                    // field units (Pa)
  // On a welded part: the solid the node belongs to (the first by name on a seam) and the seam
  // ("weld.<a>.<b>") it lies on; empty when none.
  std::string solid;
  std::string seam;
};

struct HotSpotOptions {
  int count = 5;                 // at most this many hot spots
  double separation_m = 0.010;   // skip nodes this close to a listed hot spot of the same body
};

// Hot spots in decreasing value (see the top of this file). Fewer than
// options.count come back only if the bodies run out of separated nodes.
std::vector<HotSpot> find_hot_spots(const std::vector<BodyEnvelope>& envelopes,
                                    const HotSpotOptions& options = {});

}  // namespace kinetofem::post
