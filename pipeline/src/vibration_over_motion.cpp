#include "kinetofem/pipeline/vibration_over_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "kinetofem/vibration/modal_response.hpp"

namespace kinetofem::pipeline {

using structure::AssemblyOptions;
using structure::ElasticAssembly;
using vibration::AssemblyModes;
using vibration::PoseModes;

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr int kSubstepsPerPeriod = 8;          // of the highest mode kept, during the stroke
constexpr Index kMaxSamplesAfterStop = 4000;   // of the settling window's history
constexpr double kWindowPeriods = 10.0;        // the window lasts at least this many first periods
constexpr double kMaxWindowS = 30.0;           // and at most this long (s)

std::vector<std::string> mode_names(int m) {
  std::vector<std::string> names;
  for (int i = 1; i <= m; ++i) names.push_back(post::layout::mode_name(i));
  return names;
}

// One point's response histories on the response time grid.
struct PointTrace {
  std::vector<Vector3d> dynamic, quasi_static;
};

// Mode shapes of one pose: per part a body whose mesh is placed in world
// coordinates at the pose (so the parts stand assembled in ParaView) with
// the static fields mode_<i> (N x 3, dimensionless, max |u| over the parts
// = 1) and mode_<i>_magnitude. Static fields, not a series: ParaView's time
// stays the motion's; a mode is animated by Warp By Vector's scale factor.
void write_mode_shapes(post::ResultsWriter& writer, const std::string& prefix,
                       const std::vector<structure::Part>& parts, const mech::MultibodyModel& model,
                       const AssemblyModes& modes, const PoseModes& pose, const mech::Frame& frame) {
  std::vector<post::BodyWriter*> bodies;
  for (const auto& part : parts) {
    int body = -1;
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == part.body()) body = int(b);
    fem::Mesh placed = part.model.mesh;
    placed.nodes = structure::detail::world_position(part.model.mesh, frame.bodies[size_t(body)]);
    bodies.push_back(&writer.add_body(prefix + part.body(), placed));
  }
  for (Index i = 0; i < pose.shapes.cols(); ++i) {
    std::vector<MatrixXd> fields = modes.part_fields(pose.shapes.col(i), frame);
    double largest = 0.0;
    for (const auto& f : fields) largest = std::max(largest, f.rowwise().norm().maxCoeff());
    if (!(largest > 0)) largest = 1.0;
    const std::string name = post::layout::mode_name(i + 1);
    for (size_t p = 0; p < parts.size(); ++p) {
      const post::FieldMatrix shape = fields[p] / largest;
      bodies[p]->write_static(name, post::layout::kDimensionless, shape, post::kVectorComponents);
      bodies[p]->write_static(post::layout::magnitude_name(name), post::layout::kDimensionless, shape.rowwise().norm());
    }
  }
}

post::FieldMatrix rows_of(const std::vector<Vector3d>& v) {
  post::FieldMatrix out(Index(v.size()), 3);
  for (size_t k = 0; k < v.size(); ++k) out.row(Index(k)) = v[k].transpose();
  return out;
}

post::FieldMatrix scalar(double value) {
  post::FieldMatrix out(1, 1);
  out(0, 0) = value;
  return out;
}

// The vibration options and the quasi-static summary must fit the motion and the assembly's options.
void check_vibration_inputs(const std::vector<mech::Frame>& motion, const AssemblyOptions& assembly_options,
                            const VibrationOptions& options, const AssemblySummary& quasi_static) {
  require(options.damping_ratio >= 0 && options.damping_ratio < 1,
          "vibration: damping ratio {} must lie in [0, 1)", options.damping_ratio);
  require(options.settling_tolerance_m > 0 && std::isfinite(options.settling_tolerance_m),
          "vibration: settling tolerance {} m must be positive", options.settling_tolerance_m);
  require(motion.size() >= 2, "vibration: the motion needs at least two output times, it has {}", motion.size());
  require(quasi_static.points.size() == assembly_options.points.size(),
          "vibration: the elastic assembly's summary has {} points, its options {}", quasi_static.points.size(),
          assembly_options.points.size());
}

// The modes of every pose of the motion (and of the static pose), the pose
// of the lowest first frequency and the highest frequency wanted (Hz).
struct ModesOverMotion {
  std::vector<PoseModes> pose_modes;
  std::optional<PoseModes> static_modes;
  Index lowest_pose = 0;
  double highest_wanted = 0.0;
};

// Solves the modes pose by pose; the summary takes the frequencies and the
// extremes of the first one. A pose whose lowest frequency is not positive
// (a mechanism) is an error.
ModesOverMotion modes_over_motion(const AssemblyModes& modes, const std::vector<mech::Frame>& motion,
                                  const std::optional<mech::Frame>& static_pose, int m, VibrationSummary& summary) {
  const Index T = Index(motion.size());
  ModesOverMotion out;
  std::vector<PoseModes>& pose_modes = out.pose_modes;
  pose_modes.reserve(size_t(T));
  summary.frequency_hz.resize(T, m);
  double highest_wanted = 0.0;
  Index lowest_pose = 0;
  for (Index k = 0; k < T; ++k) {
    pose_modes.push_back(modes.modes(motion[size_t(k)]));
    const PoseModes& pm = pose_modes.back();
    require(pm.omega_rad_s(0) > 0,
            "vibration at t = {:.6g} s: the lowest frequency is {:.3g} Hz: the structure is a mechanism", pm.t,
            pm.frequency_hz(0));
    summary.frequency_hz.row(k) = pm.frequency_hz.transpose();
    summary.time_s.push_back(pm.t);
    highest_wanted = std::max(highest_wanted, pm.frequency_hz(m - 1));
    if (k == 0 || pm.frequency_hz(0) < summary.lowest_first_hz) {
      summary.lowest_first_hz = pm.frequency_hz(0);
      summary.lowest_first_time_s = pm.t;
      lowest_pose = k;
    }
    if (k == 0 || pm.frequency_hz(0) > summary.highest_first_hz) {
      summary.highest_first_hz = pm.frequency_hz(0);
      summary.highest_first_time_s = pm.t;
    }
  }
  if (static_pose) {
    out.static_modes = modes.modes(*static_pose);
    summary.has_static_study = true;
    summary.static_frequency_hz = out.static_modes->frequency_hz;
    highest_wanted = std::max(highest_wanted, out.static_modes->frequency_hz(m - 1));
  }
  out.lowest_pose = lowest_pose;
  out.highest_wanted = highest_wanted;
  return out;
}

// What the response steps read: the reduced model, the motion with its
// modes and reduced loads (one per output time), the tracked points'
// quasi-static histories (m, world axes).
struct ResponseInputs {
  const AssemblyModes& modes;
  const std::vector<mech::Frame>& motion;
  const std::vector<PoseModes>& pose_modes;
  const std::vector<VectorXd>& load;
  const AssemblyOptions& assembly_options;
  const AssemblySummary& quasi_static;
  double zeta = 0.0;  // modal damping ratio
  int m = 0;          // modes kept
  Index T = 0;        // output times
  size_t P = 0;       // tracked points

  // Quasi-static displacement of point i at output time k (m).
  Vector3d point_quasi_static(size_t i, Index k) const {
    return quasi_static.points[i].displacement_history_m.row(k).transpose();
  }
};

// The modal state (q, v) and the tracked points' response on the response
// time grid (s), sample by sample.
struct ModalResponse {
  VectorXd q, v;
  std::vector<MatrixXd> point_shapes;  // C Phi of the current pose, 3 x m
  std::vector<PointTrace> traces;
  std::vector<std::vector<Vector3d>> at_outputs;
  std::vector<double> response_time;

  // One sample at time t in the modes pm: the quasi-static displacements
  // y_qs plus the modal deviation from the quasi-static state of modal_load.
  void record(double t, const PoseModes& pm, const VectorXd& modal_load, const std::vector<Vector3d>& y_qs) {
    const VectorXd deviation = q - modal_load.cwiseQuotient(pm.omega_rad_s.array().square().matrix());
    response_time.push_back(t);
    for (size_t i = 0; i < y_qs.size(); ++i) {
      const Vector3d y = y_qs[i] + point_shapes[i] * deviation;
      traces[i].dynamic.push_back(y);
      traces[i].quasi_static.push_back(y_qs[i]);
    }
  }
};

// The reduced load of every output time.
std::vector<VectorXd> reduced_loads(const AssemblyModes& modes, const std::vector<mech::Frame>& motion) {
  const Index T = Index(motion.size());
  std::vector<VectorXd> load(static_cast<size_t>(T));
  for (Index k = 0; k < T; ++k) load[size_t(k)] = modes.load(motion[size_t(k)]);
  return load;
}

// The points' summaries, named; each point needs a quasi-static displacement per output time.
void start_point_summaries(const ResponseInputs& in, VibrationSummary& summary) {
  for (size_t i = 0; i < in.P; ++i) {
    summary.points.push_back({.name = in.assembly_options.points[i].name});
    require(in.quasi_static.points[i].displacement_history_m.rows() == in.T,
            "vibration: point '{}' has {} quasi-static displacements for {} output times",
            in.assembly_options.points[i].name, in.quasi_static.points[i].displacement_history_m.rows(), in.T);
  }
}

// The reduced model's static deflection of each point against the
// assembly's (a check of the reduction, printed): the largest difference
// relative to the largest quasi-static deflection.
void compare_reduced_statics(const ResponseInputs& in, VibrationSummary& summary) {
  std::vector<double> static_mismatch(in.P, 0.0), qs_peak(in.P, 0.0);
  for (Index k = 0; k < in.T; ++k) {
    const VectorXd xs = in.modes.static_response(in.motion[size_t(k)], in.load[size_t(k)]);
    for (size_t i = 0; i < in.P; ++i) {
      const Vector3d reduced = in.modes.point_rows(in.assembly_options.points[i].name, in.motion[size_t(k)]) * xs;
      static_mismatch[i] = std::max(static_mismatch[i], (reduced - in.point_quasi_static(i, k)).norm());
      qs_peak[i] = std::max(qs_peak[i], in.point_quasi_static(i, k).norm());
    }
  }
  for (size_t i = 0; i < in.P; ++i)
    summary.points[i].reduced_static_mismatch = qs_peak[i] > 0 ? static_mismatch[i] / qs_peak[i] : static_mismatch[i];
}

// The response along the stroke: from the quasi-static state at t_0, each
// interval between output times integrated with its first pose's modes
// frozen and the load linear, then passed into the next pose's modes.
ModalResponse respond_over_stroke(const ResponseInputs& in) {
  const std::vector<PoseModes>& pose_modes = in.pose_modes;
  const std::vector<VectorXd>& load = in.load;
  const Index T = in.T;
  const int m = in.m;
  const size_t P = in.P;
  const MatrixXd& M = in.modes.mass();
  ModalResponse r;
  r.point_shapes.resize(P);
  r.traces.resize(P);
  r.at_outputs.resize(P);
  VectorXd& q = r.q;
  VectorXd& v = r.v;
  q = pose_modes[0].shapes.transpose() * load[0];  // modal load at t_0
  q = q.cwiseQuotient(pose_modes[0].omega_rad_s.array().square().matrix());
  v = VectorXd::Zero(m);
  for (Index k = 0; k < T; ++k) {
    const PoseModes& pm = pose_modes[size_t(k)];
    for (size_t i = 0; i < P; ++i)
      r.point_shapes[i] = in.modes.point_rows(in.assembly_options.points[i].name, in.motion[size_t(k)]) * pm.shapes;
    const VectorXd f0 = pm.shapes.transpose() * load[size_t(k)];
    std::vector<Vector3d> y0(P);
    for (size_t i = 0; i < P; ++i) y0[i] = in.point_quasi_static(i, k);
    r.record(pm.t, pm, f0, y0);
    for (size_t i = 0; i < P; ++i) r.at_outputs[i].push_back(r.traces[i].dynamic.back());
    if (k == T - 1) break;
    // The interval to the next output time, pose frozen, load linear.
    const double dt = in.motion[size_t(k + 1)].t - pm.t;
    const VectorXd f1 = pm.shapes.transpose() * load[size_t(k + 1)];
    const double period = 2 * std::numbers::pi / pm.omega_rad_s(m - 1);
    const int substeps = std::max(1, int(std::ceil(dt * kSubstepsPerPeriod / period)));
    const double h = dt / substeps;
    std::vector<vibration::ModalStepper> steppers;
    for (int j = 0; j < m; ++j) steppers.emplace_back(pm.omega_rad_s(j), in.zeta);
    for (int s = 1; s <= substeps; ++s) {
      const double a = double(s - 1) / substeps, b = double(s) / substeps;
      const VectorXd fa = (1 - a) * f0 + a * f1, fb = (1 - b) * f0 + b * f1;
      for (int j = 0; j < m; ++j) steppers[size_t(j)].step(h, fa(j), fb(j), q(j), v(j));
      if (s < substeps) {
        std::vector<Vector3d> y(P);
        for (size_t i = 0; i < P; ++i)
          y[i] = (1 - b) * in.point_quasi_static(i, k) + b * in.point_quasi_static(i, k + 1);
        r.record(pm.t + b * dt, pm, fb, y);
      }
    }
    // Into the next pose's modes: the quasi-static part is the new pose's
    // own, the dynamic part (q - f / w^2) and the velocity pass by the
    // mass-orthogonal projection (a state that only follows the load stays
    // quasi-static whatever the modes' turning).
    const PoseModes& next = pose_modes[size_t(k + 1)];
    const MatrixXd transfer = next.shapes.transpose() * (M * pm.shapes);
    const VectorXd dynamic = q - f1.cwiseQuotient(pm.omega_rad_s.array().square().matrix());
    q = (next.shapes.transpose() * load[size_t(k + 1)]).cwiseQuotient(next.omega_rad_s.array().square().matrix()) +
        transfer * dynamic;
    v = transfer * v;
  }
  return r;
}

// After the stop (the last pose and load stay): each point's settling time,
// the window after the stop (s) and the response over it. Returns the
// points' final quasi-static displacements (m).
std::vector<Vector3d> ring_after_stop(const ResponseInputs& in, const VibrationOptions& options, ModalResponse& r,
                                      VibrationSummary& summary) {
  const int m = in.m;
  const size_t P = in.P;
  VectorXd& q = r.q;
  VectorXd& v = r.v;
  const PoseModes& last = in.pose_modes.back();
  const VectorXd f_end = last.shapes.transpose() * in.load.back();
  std::vector<Vector3d> y_end(P);
  for (size_t i = 0; i < P; ++i) y_end[i] = in.point_quasi_static(i, in.T - 1);
  double longest_settling = 0.0;
  for (size_t i = 0; i < P; ++i) {
    const vibration::Settling settling = vibration::settling_after_stop(
        last.omega_rad_s, in.zeta, q, v, f_end, r.point_shapes[i], options.settling_tolerance_m);
    summary.points[i].settling_time_s = settling.time_after_stop_s;
    longest_settling = std::max(longest_settling, settling.time_after_stop_s);
  }
  const double first_period = 2 * std::numbers::pi / last.omega_rad_s(0);
  double window = kWindowPeriods * first_period;
  if (std::isfinite(longest_settling)) window = std::max(window, 1.25 * longest_settling);
  window = std::min(window, std::max(kMaxWindowS, kWindowPeriods * first_period));
  summary.window_after_stop_s = window;
  const double shortest_period = 2 * std::numbers::pi / last.omega_rad_s(m - 1);
  const Index samples =
      std::min<Index>(kMaxSamplesAfterStop, Index(std::ceil(window * kSubstepsPerPeriod / shortest_period)) + 1);
  const double h = window / double(std::max<Index>(samples, 1));
  std::vector<vibration::ModalStepper> steppers;
  for (int j = 0; j < m; ++j) steppers.emplace_back(last.omega_rad_s(j), in.zeta);
  for (Index s = 1; s <= samples; ++s) {
    for (int j = 0; j < m; ++j) steppers[size_t(j)].step(h, f_end(j), f_end(j), q(j), v(j));
    r.record(summary.stop_time_s + double(s) * h, last, f_end, y_end);
  }
  return y_end;
}

// Per point: the peaks during the stroke (the first stroke_samples samples),
// the amplitude after the stop about y_end (m), the dynamic amplification.
void summarise_peaks(const ModalResponse& r, size_t stroke_samples, const std::vector<Vector3d>& y_end,
                     VibrationSummary& summary) {
  const std::vector<double>& response_time = r.response_time;
  for (size_t i = 0; i < y_end.size(); ++i) {
    const PointTrace& trace = r.traces[i];
    PointVibration& pv = summary.points[i];
    for (size_t s = stroke_samples - 1; s < response_time.size(); ++s)
      pv.amplitude_at_stop_m = std::max(pv.amplitude_at_stop_m, (trace.dynamic[s] - y_end[i]).norm());
    for (size_t s = 0; s < stroke_samples; ++s) {
      const double yd = trace.dynamic[s].norm(), yq = trace.quasi_static[s].norm();
      const double ring = (trace.dynamic[s] - trace.quasi_static[s]).norm();
      if (yd > pv.peak_dynamic_m) pv.peak_dynamic_m = yd, pv.peak_dynamic_time_s = response_time[s];
      if (yq > pv.peak_quasi_static_m) pv.peak_quasi_static_m = yq, pv.peak_quasi_static_time_s = response_time[s];
      if (ring > pv.peak_vibration_m) pv.peak_vibration_m = ring, pv.peak_vibration_time_s = response_time[s];
    }
    pv.dynamic_amplification = pv.peak_quasi_static_m > 0 ? pv.peak_dynamic_m / pv.peak_quasi_static_m : 0.0;
  }
}

// The frequencies over the motion and the points' response and settling
// into the results file.
void write_response(post::ResultsWriter& writer, const VibrationSummary& summary, const ModalResponse& r,
                    const VibrationOptions& options) {
  const std::vector<double>& response_time = r.response_time;
  writer.write_history(post::layout::kVibrationFrequency, "Hz", summary.frequency_hz, mode_names(summary.modes));
  for (size_t i = 0; i < summary.points.size(); ++i) {
    const std::string& name = summary.points[i].name;
    writer.write_history(post::layout::kVibrationPointPrefix + name + ".displacement", "m", rows_of(r.at_outputs[i]),
                         post::kVectorComponents);
    writer.write_table(post::layout::kVibrationResponsePointPrefix + name + ".displacement", "m", rows_of(r.traces[i].dynamic),
                       post::kVectorComponents);
    writer.write_table(post::layout::kVibrationResponsePointPrefix + name + ".quasi_static", "m", rows_of(r.traces[i].quasi_static),
                       post::kVectorComponents);
    const PointVibration& pv = summary.points[i];
    writer.write_table(post::layout::kVibrationPointPrefix + name + ".settling_time", "s", scalar(pv.settling_time_s));
    writer.write_table(post::layout::kVibrationPointPrefix + name + ".settling_tolerance", "m", scalar(options.settling_tolerance_m));
    writer.write_table(post::layout::kVibrationPointPrefix + name + ".amplitude_at_stop", "m", scalar(pv.amplitude_at_stop_m));
    writer.write_table(post::layout::kVibrationPointPrefix + name + ".dynamic_amplification", post::layout::kDimensionless,
                       scalar(pv.dynamic_amplification));
  }
  post::FieldMatrix time(Index(response_time.size()), 1);
  for (size_t s = 0; s < response_time.size(); ++s) time(Index(s), 0) = response_time[s];
  writer.write_table(post::layout::kVibrationResponseTime, "s", time);
  writer.write_table(post::layout::kVibrationStopTime, "s", scalar(summary.stop_time_s));
  writer.write_table(post::layout::kVibrationDampingRatio, post::layout::kDimensionless, scalar(summary.damping_ratio));
}

}  // namespace

VibrationSummary analyse_vibration_over_motion(const std::vector<structure::Part>& parts,
                                               const mech::MultibodyModel& model,
                                               const std::vector<mech::Frame>& motion,
                                               const std::optional<mech::Frame>& static_pose,
                                               post::ResultsWriter& writer, const AssemblyOptions& assembly_options,
                                               const VibrationOptions& options, const AssemblySummary& quasi_static,
                                               const Log& log,
                                               const std::vector<fem::LinearStaticAnalysis*>& factorized) {
  // The reduced assembly needs the interface columns and the factorizations
  // only: no stress, no load patterns (the frequencies and loads come from the
  // reduced model).
  AssemblyOptions structure_options = assembly_options;
  structure_options.recover_stress = false;
  structure_options.keep_part_stress = false;
  structure_options.superpose_loads = false;
  structure_options.unit_load_split = false;
  structure_options.field_steps.clear();
  const ElasticAssembly assembly(parts, model, structure_options, log, factorized);
  return analyse_vibration_over_motion(assembly, parts, model, motion, static_pose, writer, assembly_options, options,
                                       quasi_static, log);
}

VibrationSummary analyse_vibration_over_motion(const ElasticAssembly& assembly,
                                               const std::vector<structure::Part>& parts,
                                               const mech::MultibodyModel& model,
                                               const std::vector<mech::Frame>& motion,
                                               const std::optional<mech::Frame>& static_pose,
                                               post::ResultsWriter& writer, const AssemblyOptions& assembly_options,
                                               const VibrationOptions& options, const AssemblySummary& quasi_static,
                                               const Log& log, vibration::PartFactorLender* lender) {
  check_vibration_inputs(motion, assembly_options, options, quasi_static);
  const Index T = Index(motion.size());
  const int m = options.modes.modes;
  VibrationSummary summary;
  summary.modes = m;
  summary.damping_ratio = options.damping_ratio;
  summary.settling_tolerance_m = options.settling_tolerance_m;
  summary.stop_time_s = motion.back().t;

  // 1. The reduced assembly: one reduction per part, with the part's own
  // factorization (lent part by part when there is a lender).
  Stopwatch clock;
  // The automatic part-mode rule bounds the frequencies wanted in every pose
  // (Rayleigh-Ritz holds pose by pose): estimate over all of them (0.3 ms each).
  std::vector<mech::Frame> estimate_poses = motion;
  if (static_pose) estimate_poses.push_back(*static_pose);
  const AssemblyModes modes(assembly, parts, model, options.modes, estimate_poses, log, lender);
  summary.reductions = modes.reductions();
  summary.cutoff_hz = modes.cutoff_hz();
  summary.reduced_size = modes.size();
  summary.reduction_seconds = clock.seconds();

  // 2. Modes in every pose.
  clock.restart();
  const ModesOverMotion over_motion = modes_over_motion(modes, motion, static_pose, m, summary);
  summary.rule_check = modes.check_rule(over_motion.highest_wanted);
  log.info("vibration: {} modes at {} poses{} in {:.2f} s; {}", m, T, static_pose ? " + the static pose" : "",
           clock.seconds(), summary.rule_check);
  for (const auto& r : modes.reductions())  // the run's summary gives each part's reduction too
    log.detail("  part '{}': {} DoFs -> {} boundary + {} modes + {} residual; first mode dropped {:.5g} Hz", r.body,
               r.dofs, r.boundary, r.modes, r.residual, r.first_dropped_hz);
  summary.modes_seconds = clock.seconds();

  // 3. Response along the motion and after the stop.
  clock.restart();
  const std::vector<VectorXd> load = reduced_loads(modes, motion);
  const ResponseInputs in{.modes = modes,
                          .motion = motion,
                          .pose_modes = over_motion.pose_modes,
                          .load = load,
                          .assembly_options = assembly_options,
                          .quasi_static = quasi_static,
                          .zeta = options.damping_ratio,
                          .m = m,
                          .T = T,
                          .P = assembly_options.points.size()};
  start_point_summaries(in, summary);
  compare_reduced_statics(in, summary);
  ModalResponse response = respond_over_stroke(in);
  const size_t stroke_samples = response.response_time.size();
  const std::vector<Vector3d> y_end = ring_after_stop(in, options, response, summary);
  summarise_peaks(response, stroke_samples, y_end, summary);
  summary.response_seconds = clock.seconds();

  // 4. Results.
  write_response(writer, summary, response, options);
  if (over_motion.static_modes) {
    writer.write_table(post::layout::kVibrationStaticFrequency, "Hz",
                       post::FieldMatrix(over_motion.static_modes->frequency_hz));
    write_mode_shapes(writer, post::layout::kVibrationStaticBodyPrefix, parts, model, modes, *over_motion.static_modes,
                      *static_pose);
  }
  write_mode_shapes(writer, post::layout::kVibrationLowestBodyPrefix, parts, model, modes,
                    over_motion.pose_modes[size_t(over_motion.lowest_pose)], motion[size_t(over_motion.lowest_pose)]);
  return summary;
}

std::string format_vibration_summary(const VibrationSummary& s) {
  using units::kMm;
  std::string out = fmt::format(
      "  vibration (modes of the elastic assembly in every pose, modal damping {:.1f} %):\n", 100 * s.damping_ratio);
  out += fmt::format("    first natural frequency over the motion: {:.3f} Hz (t = {:.4f} s) .. {:.3f} Hz (t = {:.4f} s)",
                     s.lowest_first_hz, s.lowest_first_time_s, s.highest_first_hz, s.highest_first_time_s);
  out += s.has_static_study ? fmt::format("; static pose {:.3f} Hz\n", s.static_frequency_hz(0)) : std::string("\n");
  auto list = [](const Eigen::VectorXd& f) {
    std::string t;
    for (Index i = 0; i < f.size(); ++i) t += fmt::format("{}{:.2f}", i ? ", " : "", f(i));
    return t;
  };
  if (s.has_static_study) out += fmt::format("    modes 1..{} in the static pose: {} Hz\n", s.modes, list(s.static_frequency_hz));
  if (s.frequency_hz.rows() > 0)
    out += fmt::format("    modes 1..{} at the start: {} Hz\n", s.modes, list(s.frequency_hz.row(0).transpose()));
  for (const auto& p : s.points) {
    out += fmt::format(
        "    point {}: peak elastic displacement {:.4f} mm at t = {:.4f} s (quasi-static {:.4f} mm at t = {:.4f} s): "
        "dynamic amplification {:.3f}; vibration up to {:.3g} mm (t = {:.4f} s)\n",
        p.name, p.peak_dynamic_m / kMm, p.peak_dynamic_time_s, p.peak_quasi_static_m / kMm, p.peak_quasi_static_time_s,
        p.dynamic_amplification, p.peak_vibration_m / kMm, p.peak_vibration_time_s);
    out += fmt::format("      after the stop (t = {:.4f} s): rings up to {:.3g} mm about its final deflection; ", s.stop_time_s,
                       p.amplitude_at_stop_m / kMm);
    out += std::isfinite(p.settling_time_s)
               ? fmt::format("stays below {:.3f} mm from {:.4f} s after the stop\n", s.settling_tolerance_m / kMm,
                             p.settling_time_s)
               : fmt::format("never settles below {:.3f} mm (no damping)\n", s.settling_tolerance_m / kMm);
    out += fmt::format("      reduced model's static deflection vs the elastic assembly's: {:.2e} of its peak\n",
                       p.reduced_static_mismatch);
  }
  std::string parts;
  for (const auto& r : s.reductions)
    parts += fmt::format("{}{} {} DoFs -> {} + {} + {}", parts.empty() ? "" : "; ", r.body, r.dofs, r.boundary, r.modes,
                         r.residual);
  out += fmt::format("    reduction (boundary + part modes + residual vectors): {}; {} coordinates; part modes up to "
                     "{:.4g} Hz\n",
                     parts, s.reduced_size, s.cutoff_hz);
  out += fmt::format("    cost: reduction {:.2f} s, modes {:.2f} s, response {:.2f} s\n", s.reduction_seconds,
                     s.modes_seconds, s.response_seconds);
  return out;
}

}  // namespace kinetofem::pipeline
