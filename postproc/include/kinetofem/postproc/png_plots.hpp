#pragma once
// PNG pictures of a results file, drawn with cairo (image surface, ARGB32).
//
// 1. write_stress_picture — a scalar field (von Mises) on the deformed
//    boundary surface of every link body at the critical time (the output time
//    of the largest envelope value over those bodies; a body without a series
//    shows its static field). Bodies of the elastic assembly (`assembly.*`,
//    world-axes displacement, see 4.) are left out. One panel per body, in its
//    own body frame, all at one scale in mm. View: oblique (cabinet-like)
//    projection of the x-y plane,
//        X = x + k z cos(a),  Y = y + k z sin(a)   (k = oblique_depth, a = oblique_angle),
//    i.e. seen along v = (-k cos a, -k sin a, 1) from +z; boundary faces
//    facing away from the viewer are culled and the rest drawn far to near
//    (painter's algorithm), each quadratic face split into flat triangles,
//    shaded lightly for depth. Deformed position = x + scale * u; the scale
//    is stated in the title. Colour map "turbo" from 0 to the largest shown
//    value, colour bar labelled in MPa; the peak is marked.
// 2. write_mechanism_loads_picture — mechanism histories over time: every
//    history in N (joint reactions as magnitudes |R|, chain tension) in one
//    panel, every history in N*m (drive torque) in a second one.
// 3. write_path_picture — a 2-component history in m (the gripper point H) as
//    an x-y path in mm, equal aspect, start and end marked, dots at tenths of
//    the motion time.
// 4. write_assembly_picture — the manipulator as one elastic structure: every
//    body `assembly.<b>` in ONE panel in world axes (the same oblique view of
//    the world x-y plane as 1.; oblique_depth = 0 gives the plain x-y view
//    from +z), the boundary surface at position + scale * displacement
//    coloured by displacement_magnitude in mm, the rigid configuration
//    (position alone) as a thin grey outline behind it (silhouette and crease
//    edges). One output step: the static pose study (static_* fields), a given
//    step, or by default the step of the largest |u| of a tracked point
//    (history assembly.point.<P>.displacement_magnitude; fallback
//    assembly.max_displacement, then the largest displacement_magnitude of the
//    series). Automatic scale: the 1/2/5 x 10^k factor (at least 1) nearest,
//    on a log scale, to the one that draws the largest |u| at 8 % of the
//    larger side of the undeformed drawing. Marked: the node of the largest
//    |u|, and the tracked point where its rigid path point.<body>.<P> (x, y;
//    z = 0) is in the file (not for the static pose, whose position of P is
//    not written): rigid (small hollow circle) and deflected (labelled ring).
// 5. write_point_deflection_picture — a tracked point's elastic displacement
//    in the assembly (assembly.point.<P>.displacement, world axes) over the
//    motion in mm: x, y, z and |u| against time, the maximum marked; below,
//    each contribution assembly.point.<P>.from.<contributor> as its component
//    along the total's direction at each time, c_i . u/|u| (0 where u = 0),
//    so the lines add up to |u| (drawn dashed with them).
// 6. write_frequency_picture — the m lowest natural frequencies of the
//    manipulator over the motion (history vibration.frequency, Hz against t
//    in s; vibration_results.hpp), one line per mode ("mode k"), 0 Hz
//    included; the static pose study's frequencies (table
//    vibration.static_frequency, when there) as short ticks in the modes'
//    colours just right of the panel, labelled "static pose"; the lowest
//    value of mode 1 marked with its value and time.
// 7. write_point_vibration_picture — a tracked point's elastic displacement
//    |u| in mm over the motion and the settling window after the stop (table
//    vibration.response.time): with the vibration solid, quasi-static dashed,
//    the stop as a vertical line, the peak over the stroke marked; below,
//    after the stop, the deviation |u(t) - u_rest| from the rest position
//    (the quasi-static u at the end, from which the settling time is
//    measured) in mm on a LOG scale (values below the panel's lowest decade
//    drawn at its bottom edge), the settling tolerance as a horizontal dashed
//    line and the settling time as a vertical line ("does not settle" when
//    it is inf). Title: the case, the point, the dynamic amplification and,
//    where the file has it (vibration.damping_ratio), the modal damping.
//
// Every function throws Error naming the file or the missing data.
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::post {

class ResultsFile;

struct PictureOptions {
  std::string title_name;  // case name in the titles; empty: the results file's stem
  int width_px = 1400;
  int height_px = 900;
};

// The oblique view of 1. and 4. (k and a above).
inline constexpr double kObliqueDepth = 0.5;
inline constexpr double kObliqueAngleDeg = 40.0;

struct StressPictureOptions : PictureOptions {
  std::string field = layout::kVonMises;  // scalar, Pa
  std::string displacement_field = layout::kDisplacement;
  double deformation_scale = 0.0;    // 0: automatic (a "nice" 1/2/5 x 10^k factor)
  double oblique_depth = kObliqueDepth;
  double oblique_angle_deg = kObliqueAngleDeg;
  // What the field is of, in the title, instead of "at t = ..." / "static
  // load case" (e.g. "over the work cycle" for the fatigue fields).
  std::string caption;
};

struct StressPictureInfo {
  double time_s;             // NaN: static fields
  double deformation_scale;  // as drawn
  double max_value;          // of the shown field, its units (Pa)
  std::string peak_body;
  fem::Index peak_node;
};

StressPictureInfo write_stress_picture(const ResultsFile& results, const std::filesystem::path& png,
                                       const StressPictureOptions& options = {});

// Throws Error if the file has no history in N or N*m.
void write_mechanism_loads_picture(const ResultsFile& results, const std::filesystem::path& png,
                                   const PictureOptions& options = {});

void write_path_picture(const ResultsFile& results, const std::filesystem::path& png,
                        const std::string& history = "gripper_point_H",
                        const PictureOptions& options = {});

// What a results file holds of the elastic assembly (docs/results.md).
struct AssemblyContents {
  std::vector<std::string> bodies;  // "assembly.<b>", name order
  bool has_static = false;          // every assembly body has static_position, static_displacement(_magnitude)
  std::vector<std::string> points;  // P of every history assembly.point.<P>.displacement
};
AssemblyContents assembly_contents(const ResultsFile& results);

struct AssemblyPictureOptions : PictureOptions {
  enum class Pose {
    LargestDeflection,  // the output step of the largest |u| of `point` (fallbacks: see 4.)
    Step,               // the output step `step`
    Static,             // the static pose study; Error naming the file if it has none
  };
  Pose pose = Pose::LargestDeflection;
  fem::Index step = 0;
  std::string point = "H";
  double deformation_scale = 0.0;  // 0: automatic
  double oblique_depth = kObliqueDepth;
  double oblique_angle_deg = kObliqueAngleDeg;
};

struct AssemblyPictureInfo {
  double time_s;             // NaN: the static pose study
  fem::Index step;           // index into the series times; -1: static
  std::string chosen_by;     // why this step, e.g. "largest |u| of H", "step 3", "static pose study"
  double deformation_scale;  // as drawn
  double max_value;          // largest displacement_magnitude shown, m
  std::string max_body;      // its body ("assembly.<b>") and node
  fem::Index max_node;
};

AssemblyPictureInfo write_assembly_picture(const ResultsFile& results, const std::filesystem::path& png,
                                           const AssemblyPictureOptions& options = {});

struct PointDeflectionInfo {
  double max_m;                           // largest |u| of the point over the motion, m
  double time_s;                          // when (first on a tie)
  std::vector<std::string> contributors;  // as in the file: "part.<b>", "chain.<c>", "drive.<d>"
};

// Throws Error naming the file and the tracked points it has if there is no
// history assembly.point.<point>.displacement.
PointDeflectionInfo write_point_deflection_picture(const ResultsFile& results, const std::filesystem::path& png,
                                                   const std::string& point = "H",
                                                   const PictureOptions& options = {});

struct FrequencyPictureInfo {
  double lowest_first_hz;      // lowest frequency of mode 1 over the motion, Hz
  double lowest_first_time_s;  // when (first on a tie)
  double highest_first_hz;     // highest frequency of mode 1 over the motion, Hz
  int modes;                   // m, the lines drawn
  double static_first_hz;      // mode 1 in the static pose study; NaN: the file has none
};

// Throws Error naming the file if it has no history vibration.frequency (or a misshapen one).
FrequencyPictureInfo write_frequency_picture(const ResultsFile& results, const std::filesystem::path& png,
                                             const PictureOptions& options = {});

struct PointVibrationPictureInfo {
  double peak_dynamic_m;         // largest |u| with the vibration over the stroke, m
  double peak_quasi_static_m;    // largest quasi-static |u| over the stroke, m
  double dynamic_amplification;  // from the file (peak_dynamic_m / peak_quasi_static_m)
  double settling_time_s;        // after the stop; +inf: does not settle
};

// Throws Error naming the file and the missing table (and the points that have a
// response) if any table of the point's response is missing or misshapen.
PointVibrationPictureInfo write_point_vibration_picture(const ResultsFile& results, const std::filesystem::path& png,
                                                        const std::string& point = "H",
                                                        const PictureOptions& options = {});

struct ContactPictureInfo {
  double peak_pressure_pa = 0.0;  // largest peak contact pressure of any pin over the motion, Pa
  double peak_time_s = 0.0;       // when
  std::string peak_pin;           // "<body>.<joint>"
  std::vector<std::string> pins;  // every pin drawn, "<body>.<joint>"
};

// Where the pin contact tables come from: the per-part stage (contact.<body>.<joint>) or the
// elastic assembly (assembly.contact.<body>.<joint>).
enum class ContactTables { PerPart, Assembly };
// The result file's pin contact tables of that stage, in file order; empty when none.
std::vector<std::string> contact_tables(const ResultsFile& results, ContactTables stage = ContactTables::PerPart);
// Each pin's peak contact pressure and arc over the motion. Throws Error naming the file if it
// has no contact tables of that stage (or a misshapen one).
ContactPictureInfo write_contact_picture(const ResultsFile& results, const std::filesystem::path& png,
                                         const PictureOptions& options = {},
                                         ContactTables stage = ContactTables::PerPart);

}  // namespace kinetofem::post
