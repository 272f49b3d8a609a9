#pragma once
// What several PNG pictures (png_plots.hpp) read from a results file or show
// the same way: the case name in titles, the names of the elastic assembly's
// histories (postproc/results_layout.hpp), number formats and scale factors.
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/postproc/png_plots.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/postproc/time_history.hpp"

namespace kinetofem::post::drawing {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The case name in the titles: options.title_name, else the results file's stem.
std::string case_name(const ResultsFile& results, const PictureOptions& options);

// The 1/2/5 x 10^k value at or below x (> 0).
double round_down_125(double x);
// The 1/2/5 x 10^k value nearest to x (> 0) on a log scale.
double nearest_125(double x);

// Bodies of the elastic assembly ("assembly.<b>"): world-axes displacement, drawn by write_assembly_picture.
bool is_assembly_body(const std::string& body);

// A shown value: 2 decimals, or 3 significant digits for small ones (e.g. a
// fatigue damage per cycle of 1e-5).
std::string value_text(double v);

// A length given in m, shown in mm with three significant digits (at least two decimals): 1.00, 0.0300, 12.30.
std::string mm_text(double metres);

// Names the pipeline's assembly stage writes (docs/results.md, "The elastic assembly").
inline constexpr const char* kMaxDisplacement = layout::kAssemblyMaxDisplacement;
// "assembly.point.<point>.<what>"
std::string point_history(const std::string& point, const std::string& what);

bool has(const std::vector<std::string>& names, const std::string& name);
// "a, b, c", or "none".
std::string joined(const std::vector<std::string>& names);

// The index of the time nearest t (first on a tie); `times` not empty.
size_t nearest_index(const std::vector<double>& times, double t);
// The index of the largest value (first on a tie).
size_t argmax(const Eigen::VectorXd& v);

// |u| of a tracked point over the mechanism times: its magnitude history, else the norm of
// its displacement; nullopt if the file has neither.
std::optional<TimeHistory> point_magnitude(const ResultsFile& results, const std::string& point);

std::vector<double> as_vector(const Eigen::VectorXd& v);

}  // namespace kinetofem::post::drawing
