#pragma once
// The vibration of the manipulator over the motion in a results file (written by
// pipeline/vibration_over_motion.hpp, names in results_layout.hpp, layout::kVibration*,
// docs/results.md "Vibration"): what the file holds, and checked reads of it shared by the
// `kinetofem post` summary and the pictures (png_plots.hpp, 6. and 7.).
//
//   mechanism history vibration.frequency (T_m x m, Hz): the m lowest natural frequencies in
//     each pose over the motion;
//   table vibration.static_frequency (m x 1, Hz): the same in the static pose study (optional);
//   tables vibration.response.time (n x 1, s: the motion's output times, then the settling
//     window after the stop) and vibration.response.stop_time (1 x 1, s);
//   per tracked point P: tables vibration.response.point.<P>.displacement and .quasi_static
//     (n x 3, m, world axes) and the scalars vibration.point.<P>.settling_time (s after the
//     stop; inf: does not settle), .settling_tolerance (m), .amplitude_at_stop (m),
//     .dynamic_amplification (1); optional table vibration.damping_ratio (1 x 1, 1);
//   bodies vibration.static.<b>, vibration.lowest.<b>: mode shapes (series over the mode number).
//
// Values stay in SI (Hz, s, m). A missing or misshapen history or table is an Error naming
// the file and it.
#include <string>
#include <vector>

#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::post {

class ResultsFile;

// Whether a body is one of the vibration stage's mode-shape bodies ("vibration.<...>").
bool is_vibration_body(const std::string& body);

struct VibrationContents {
  bool frequencies = false;         // history vibration.frequency
  bool static_frequencies = false;  // table vibration.static_frequency
  std::vector<std::string> points;  // P of every table vibration.response.point.<P>.displacement, name order
  std::vector<std::string> bodies;  // the "vibration.*" bodies, name order
};
VibrationContents vibration_contents(const ResultsFile& results);

struct NaturalFrequencies {
  std::vector<double> time_s;     // T_m, the mechanism times
  FieldMatrix hz;                 // T_m x m: column k is mode k + 1
  std::vector<double> static_hz;  // m, the static pose study; empty: none in the file
  double lowest_first_hz = 0, lowest_first_time_s = 0;    // of mode 1 over the motion (first on a tie)
  double highest_first_hz = 0, highest_first_time_s = 0;
  int modes() const { return int(hz.cols()); }
};
NaturalFrequencies read_natural_frequencies(const ResultsFile& results);

struct PointVibrationData {
  std::string point;
  std::vector<double> time_s;  // n
  double stop_time_s = 0;
  FieldMatrix dynamic_m;       // n x 3: the elastic displacement with the vibration
  FieldMatrix quasi_static_m;  // n x 3: without it
  double settling_time_s = 0;  // after the stop; +inf: does not settle
  double settling_tolerance_m = 0, amplitude_at_stop_m = 0, dynamic_amplification = 0;
  double damping_ratio;        // NaN: not in the file
  // Largest |u| over the stroke (t <= stop time), as the file's dynamic_amplification
  // = peak_dynamic_m / peak_quasi_static_m; first on a tie.
  double peak_dynamic_m = 0, peak_dynamic_time_s = 0;
  double peak_quasi_static_m = 0, peak_quasi_static_time_s = 0;
};
PointVibrationData read_point_vibration(const ResultsFile& results, const std::string& point);

}  // namespace kinetofem::post
