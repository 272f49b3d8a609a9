#include "kinetofem/pipeline/assembly_over_motion.hpp"

#include "kinetofem/structure/rigid_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/pipeline/part_factors.hpp"  // kMinSuperposedPoses
#include "kinetofem/pipeline/part_model.hpp"    // write_solid_field
#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::pipeline {

using namespace kinetofem::structure;  // the library this stage runs

using detail::world_position;

namespace {

// Poses per call of the assembly's solve, and written ones among them (their
// full fields are in memory together; the others carry none).
constexpr size_t kPosesPerBlock = 256, kWrittenPerBlock = 32;

int body_index(const mech::MultibodyModel& model, const std::string& name) {
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == name) return int(b);
  fail("elastic assembly: no body '{}'", name);
}

// Largest and smallest eigenvalue of the in-plane block of a compliance.
Eigen::Vector2d in_plane_eigenvalues(const Eigen::Matrix3d& C) {
  const Eigen::Matrix2d S = 0.5 * (C.topLeftCorner<2, 2>() + C.topLeftCorner<2, 2>().transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S, Eigen::EigenvaluesOnly);
  return {eig.eigenvalues()(1), eig.eigenvalues()(0)};
}

// A part's contact pressure envelope (pins in contact only; the assembly
// folds the displacement and von Mises envelopes, MotionFields).
struct PressureEnvelope {
  Eigen::VectorXd max_p;
  post::IndexMatrix step_p;
};

// Whether a pin is in contact with a bore of the part.
bool has_pins_in_contact(const structure::Part& part) {
  return std::any_of(part.attachments.joints.begin(), part.attachments.joints.end(),
                     [](const loads::JointAttachment& j) { return j.distribution == loads::BoreLoad::Contact; });
}

// Records the solved poses of a motion into the results file and the
// summary: the parts' fields and envelopes, the histories of the tracked
// points, chains and drives (rows: output times), the static study.
struct AssemblyRecorder {
  const ElasticAssembly& assembly;
  const std::vector<structure::Part>& parts;
  const AssemblyOptions& options;
  post::ResultsWriter& writer;
  AssemblySummary& summary;
  size_t T = 0;  // output times
  size_t P = 0;  // tracked points

  // Per part: its assembly body's writer, contact pressure envelope and
  // multibody body index; the fields' envelopes and which poses get fields.
  std::vector<post::BodyWriter*> bodies;
  std::vector<PressureEnvelope> envelopes;
  std::vector<int> part_body;
  MotionFields fields;

  // Histories, filled pose by pose.
  post::FieldMatrix max_u;
  std::vector<post::FieldMatrix> point_u, point_mag, point_rot, point_compliance;
  std::vector<std::vector<post::FieldMatrix>> point_from;
  std::vector<std::vector<std::string>> point_from_names;
  std::vector<std::string> chain_names, drive_names;
  // A drive's effort and the change of its coordinate: moment (N m) and twist
  // (rad) of an angle drive, force (N) and stretch (m) of a displacement one.
  std::vector<post::FieldMatrix> chain_tension, chain_elongation, drive_effort, drive_change;
  std::vector<bool> drive_displacement;
  // Per transmission: moment on the output's body_j (N m), twist (rad), span
  // tensions (N, a belt's two spans).
  std::vector<post::FieldMatrix> transmission_moment, transmission_twist, transmission_spans;
  std::vector<post::FieldMatrix> pin_bending, pin_shear, pin_deflection;  // per elastic pin (summary.pins order)
  std::vector<post::FieldMatrix> contact_table;    // per pin in contact (summary.contacts order), T x 6
  std::vector<post::FieldMatrix> point_coupling;   // per point: its displacement with couplings (pins in contact)
  // Per part, its stress at every output time (AssemblyOptions::keep_part_stress), or none.
  std::vector<PartStressHistory>* stress_histories = nullptr;

  AssemblyRecorder(const ElasticAssembly& assembly_, const std::vector<structure::Part>& parts_,
                   const mech::MultibodyModel& model, post::ResultsWriter& writer_, const AssemblyOptions& options_,
                   size_t output_times, AssemblySummary& summary_)
      : assembly(assembly_), parts(parts_), options(options_), writer(writer_), summary(summary_), T(output_times),
        P(options_.points.size()), envelopes(parts_.size()), part_body(parts_.size()), max_u(output_times, 1),
        point_u(P, post::FieldMatrix(output_times, 3)), point_mag(P, post::FieldMatrix(output_times, 1)),
        point_rot(P, post::FieldMatrix(output_times, 3)), point_compliance(P, post::FieldMatrix(output_times, 9)),
        point_from(P), point_from_names(P), point_coupling(P, post::FieldMatrix(output_times, 3)) {
    begin_part_bodies(model);
    for (size_t i = 0; i < P; ++i) {
      summary.points.push_back({.name = options.points[i].name, .body = options.points[i].body});
      summary.points.back().min_compliance_m_per_n = std::numeric_limits<double>::infinity();
    }
  }

  // Writers and envelopes of every part's assembly body, and its summary line.
  void begin_part_bodies(const mech::MultibodyModel& model) {
    for (size_t p = 0; p < parts.size(); ++p) {
      const fem::Mesh& mesh = parts[p].model.mesh;
      post::BodyWriter& w = writer.add_body(post::layout::kAssemblyBodyPrefix + parts[p].body(), mesh);
      write_solid_field(w, mesh);
      std::vector<post::SeriesField> series{
          {.name = post::layout::kPosition, .units = "m", .components = 3, .component_names = post::kVectorComponents,
           .geometry = true},
          {post::layout::kDisplacement, "m", 3, post::kVectorComponents},
          {post::layout::kDisplacementMagnitude, "m", 1, {}},
          {post::layout::kVonMises, "Pa", 1, {}}};
      if (has_pins_in_contact(parts[p])) series.push_back({post::layout::kContactPressure, "Pa", 1, {}});
      w.begin_series(series);
      bodies.push_back(&w);
      const fem::Index N = mesh.node_count();
      envelopes[p] = {Eigen::VectorXd::Constant(has_pins_in_contact(parts[p]) ? N : 0, -1.0),
                      post::IndexMatrix::Zero(has_pins_in_contact(parts[p]) ? N : 0, 1)};
      part_body[p] = body_index(model, parts[p].body());
      summary.parts.push_back({parts[p].body(), 0.0, 0.0});
    }
  }

  // Records the pose of output time k (frame: its multibody frame).
  void record(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    max_u(Eigen::Index(k), 0) = pose.max_displacement_m;
    if (pose.max_displacement_m > summary.max_displacement_m || k == 0) {
      summary.max_displacement_m = pose.max_displacement_m;
      summary.max_displacement_time_s = frame.t;
      summary.max_displacement_body = pose.max_displacement_body;
    }
    record_part_fields(pose, k, frame);
    record_points(pose, k, frame);
    record_chains_and_drives(pose, k, frame);
    record_pins(pose, k, frame);
    record_contacts(pose, k, frame);
  }

  // The contact pressure of a part's pins at every node (0 off their bores).
  post::FieldMatrix nodal_contact_pressure(const PoseSolution& pose, size_t p) const {
    post::FieldMatrix out = post::FieldMatrix::Zero(parts[p].model.mesh.node_count(), 1);
    for (const BoreContactResult& c : pose.contacts) {
      if (c.body != parts[p].body()) continue;
      const fem::BoreContactSurface& surface = assembly.contact_surface(c.body, c.joint);
      const Eigen::VectorXd values = surface.nodal_pressure(c.pressure_pa);
      for (size_t a = 0; a < surface.nodes().size(); ++a) out(surface.nodes()[a], 0) = values[Eigen::Index(a)];
    }
    return out;
  }

  // The pins in contact at output time k: their tables and peaks.
  void record_contacts(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    constexpr double kDegree = std::numbers::pi / 180.0;
    if (k == 0)
      for (const BoreContactResult& c : pose.contacts) {
        AssemblySummary::ContactPeak peak;
        peak.body = c.body;
        peak.pin.joint = c.joint;
        peak.pin.face_set = c.face_set;
        peak.pin.clearance_m = c.clearance_m;
        peak.pin.diameter_m = 2.0 * assembly.contact_surface(c.body, c.joint).radius_m();
        for (const structure::Part& part : parts)
          if (part.body() == c.body)
            for (const auto& j : part.attachments.joints)
              if (j.joint == c.joint) peak.pin.fit = j.fit;
        peak.pin.min_arc_rad = std::numeric_limits<double>::infinity();
        summary.contacts.push_back(std::move(peak));
        contact_table.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 6));
      }
    for (size_t i = 0; i < pose.contacts.size() && i < summary.contacts.size(); ++i) {
      const BoreContactResult& c = pose.contacts[i];
      PinContactSummary& s = summary.contacts[i].pin;
      if (c.state.peak_pressure_pa > s.peak_pressure_pa) {
        s.peak_pressure_pa = c.state.peak_pressure_pa;
        s.peak_time_s = frame.t;
        s.peak_angle_rad = c.state.peak_angle_rad;
        s.arc_at_peak_rad = c.state.arc_rad;
      }
      s.max_arc_rad = std::max(s.max_arc_rad, c.state.arc_rad);
      s.min_arc_rad = std::min(s.min_arc_rad, c.state.arc_rad);
      summary.contacts[i].max_pin_motion_m = std::max(summary.contacts[i].max_pin_motion_m, c.pin_motion.head<2>().norm());
      contact_table[i].row(Eigen::Index(k)) << frame.t, c.state.peak_pressure_pa, c.state.peak_angle_rad / kDegree,
          c.state.arc_rad / kDegree, c.pin_motion(0), c.pin_motion(1);
    }
    if (!pose.contacts.empty()) {
      summary.worst_contact_penetration_m = std::max(summary.worst_contact_penetration_m, pose.contact.worst_penetration_m);
      summary.worst_contact_resultant_error = std::max(summary.worst_contact_resultant_error, pose.contact.resultant_error);
      summary.worst_contact_reciprocity = std::max(summary.worst_contact_reciprocity, pose.contact.reciprocity_error);
    }
  }

  // The elastic pins' section stresses and deflection at output time k, and their peaks.
  void record_pins(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    if (k == 0)
      for (const auto& p : pose.pins) {
        summary.pins.push_back({.joint = p.joint, .diameter_m = p.diameter_m, .length_m = p.length_m});
        for (auto* h : {&pin_bending, &pin_shear, &pin_deflection}) h->push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
      }
    for (size_t i = 0; i < pose.pins.size() && i < summary.pins.size(); ++i) {
      const structure::PinLoads& l = pose.pins[i].loads;
      pin_bending[i](Eigen::Index(k), 0) = l.bending_stress_pa;
      pin_shear[i](Eigen::Index(k), 0) = l.shear_stress_pa;
      pin_deflection[i](Eigen::Index(k), 0) = l.deflection_m;
      AssemblySummary::PinPeak& peak = summary.pins[i];
      if (l.bending_stress_pa > peak.max_bending_stress_pa)
        peak.max_bending_stress_pa = l.bending_stress_pa, peak.max_bending_time_s = frame.t;
      if (l.shear_stress_pa > peak.max_shear_stress_pa) peak.max_shear_stress_pa = l.shear_stress_pa, peak.max_shear_time_s = frame.t;
      peak.max_deflection_m = std::max(peak.max_deflection_m, l.deflection_m);
    }
  }

  // The parts' fields at output time k (where field_steps asks for them; the
  // assembly solved the others without them), their contact pressure
  // envelope and largest von Mises.
  void record_part_fields(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    for (size_t p = 0; p < parts.size(); ++p) {
      const PartField& field = pose.part(parts[p].body());
      const bool contact = has_pins_in_contact(parts[p]);
      const post::FieldMatrix pressure = contact ? nodal_contact_pressure(pose, p) : post::FieldMatrix();
      if (options.field_steps.empty() || options.field_steps.at(k)) {
        const Eigen::VectorXd magnitude = field.displacement_m.rowwise().norm();
        const post::FieldMatrix position = world_position(parts[p].model.mesh, frame.bodies[size_t(part_body[p])]);
        if (contact)
          bodies[p]->write_step(frame.t, {{post::layout::kPosition, position},
                                          {post::layout::kDisplacement, field.displacement_m},
                                          {post::layout::kDisplacementMagnitude, magnitude},
                                          {post::layout::kVonMises, field.von_mises_pa},
                                          {post::layout::kContactPressure, pressure}});
        else
          bodies[p]->write_step(frame.t, {{post::layout::kPosition, position},
                                          {post::layout::kDisplacement, field.displacement_m},
                                          {post::layout::kDisplacementMagnitude, magnitude},
                                          {post::layout::kVonMises, field.von_mises_pa}});
      }
      PressureEnvelope& e = envelopes[p];
      for (Eigen::Index i = 0; i < e.max_p.size(); ++i)
        if (pressure(i, 0) > e.max_p(i)) e.max_p(i) = pressure(i, 0), e.step_p(i, 0) = fem::Index(k);
      summary.parts[p].max_von_mises_pa = std::max(summary.parts[p].max_von_mises_pa, field.max_von_mises_pa);
      if (stress_histories) record_part_stress(field, (*stress_histories)[p], k);
    }
  }

  // The part's stress tensor at output time k into its history: the
  // coefficients of its stress patterns (superposed loads) or the field.
  void record_part_stress(const PartField& field, PartStressHistory& history, size_t k) const {
    const Eigen::Index t = Eigen::Index(k), times = Eigen::Index(T);
    if (field.stress_coefficients.size() > 0) {
      if (history.coefficients.cols() != times) history.coefficients.resize(field.stress_coefficients.size(), times);
      history.coefficients.col(t) = field.stress_coefficients;
    } else {
      require(field.stress_pa.size() > 0, "elastic assembly: part '{}' kept no stress (keep_part_stress)", field.body);
      if (history.step_stress_pa.cols() != times) history.step_stress_pa.resize(field.stress_pa.size(), times);
      history.step_stress_pa.col(t) = field.stress_pa;
    }
  }

  // The tracked points at output time k: displacement (m), rotation (rad),
  // compliance (m/N) and its split, their largest and in-plane extremes.
  void record_points(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    for (size_t i = 0; i < P; ++i) {
      const PointResult& pr = pose.points[i];
      const Eigen::Index r = Eigen::Index(k);
      point_u[i].row(r) = pr.displacement_m.transpose();
      point_mag[i](r, 0) = pr.displacement_m.norm();
      point_rot[i].row(r) = pr.rotation_rad.transpose();
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) point_compliance[i](r, 3 * a + b) = pr.compliance_m_per_n(a, b);
      if (point_from[i].empty())
        for (const auto& c : pr.contributions) {
          point_from[i].push_back(post::FieldMatrix::Zero(Eigen::Index(T), 3));
          point_from_names[i].push_back(c.name);
        }
      for (size_t c = 0; c < pr.contributions.size(); ++c)
        point_from[i][c].row(r) = pr.contributions[c].displacement_m.transpose();
      PointSummary& ps = summary.points[i];
      point_coupling[i].row(r) = pr.coupling_displacement_m.transpose();
      if (!pose.contacts.empty()) {
        ps.has_pins_in_contact = true;
        const Eigen::Vector3d share = pr.displacement_m - pr.coupling_displacement_m;
        if (share.norm() > ps.max_pin_share_m || k == 0)
          ps.max_pin_share_m = share.norm(), ps.max_pin_share_time_s = frame.t, ps.pin_share_at_max_m = share;
      }
      if (pr.displacement_m.norm() > ps.max_displacement_m || k == 0) {
        ps.max_displacement_m = pr.displacement_m.norm();
        ps.max_displacement_time_s = frame.t;
        ps.displacement_at_max_m = pr.displacement_m;
        ps.contributions_at_max = pr.contributions;
      }
      if (options.unit_load_split) {
        const Eigen::Vector2d ev = in_plane_eigenvalues(pr.compliance_m_per_n);
        if (ev(0) > ps.max_compliance_m_per_n) ps.max_compliance_m_per_n = ev(0), ps.max_compliance_time_s = frame.t;
        if (ev(1) < ps.min_compliance_m_per_n) ps.min_compliance_m_per_n = ev(1), ps.min_compliance_time_s = frame.t;
      }
    }
  }

  // The chains' tension (N) and elongation (m), the drives' effort and
  // coordinate change at output time k; the worst relative mismatch of a chain's
  // tension against the dynamics'.
  void record_chains_and_drives(const PoseSolution& pose, size_t k, const mech::Frame& frame) {
    if (chain_names.empty() && drive_names.empty()) {
      for (const auto& c : pose.chains) {
        chain_names.push_back(c.chain);
        chain_tension.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
        chain_elongation.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
      }
      for (const auto& d : pose.drives) {
        drive_names.push_back(d.drive);
        drive_displacement.push_back(d.displacement);
        drive_effort.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
        drive_change.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
      }
    }
    for (size_t c = 0; c < pose.chains.size(); ++c) {
      chain_tension[c](Eigen::Index(k), 0) = pose.chains[c].tension_n;
      chain_elongation[c](Eigen::Index(k), 0) = pose.chains[c].elongation_m;
      for (const auto& cf : frame.chains)
        if (cf.name == pose.chains[c].chain && cf.tension_N > 0)
          summary.worst_chain_mismatch = std::max(summary.worst_chain_mismatch,
                                                  std::abs(pose.chains[c].tension_n - cf.tension_N) / cf.tension_N);
    }
    if (summary.transmissions.empty())
      for (const auto& t : pose.transmissions) {
        summary.transmissions.push_back({.name = t.transmission, .has_spans = t.has_spans,
                                         .min_span_tension_n = std::numeric_limits<double>::infinity()});
        transmission_moment.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
        transmission_twist.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 1));
        transmission_spans.push_back(post::FieldMatrix::Zero(Eigen::Index(T), 2));
      }
    double largest_moment = 0.0;
    for (const auto& tf : frame.transmissions) largest_moment = std::max(largest_moment, std::abs(tf.moment_output_Nm));
    for (size_t t = 0; t < pose.transmissions.size(); ++t) {
      const TransmissionResult& tr = pose.transmissions[t];
      auto& peak = summary.transmissions[t];
      transmission_moment[t](Eigen::Index(k), 0) = tr.moment_output_nm;
      transmission_twist[t](Eigen::Index(k), 0) = tr.twist_rad;
      transmission_spans[t](Eigen::Index(k), 0) = tr.span_tension_n[0];
      transmission_spans[t](Eigen::Index(k), 1) = tr.span_tension_n[1];
      if (std::abs(tr.moment_output_nm) > peak.max_moment_nm)
        peak.max_moment_nm = std::abs(tr.moment_output_nm), peak.max_moment_time_s = frame.t;
      peak.max_twist_rad = std::max(peak.max_twist_rad, std::abs(tr.twist_rad));
      const double least = std::min(tr.span_tension_n[0], tr.span_tension_n[1]);
      if (least < peak.min_span_tension_n) peak.min_span_tension_n = least, peak.min_span_tension_time_s = frame.t;
      if (largest_moment > 0)
        summary.worst_transmission_mismatch =
            std::max(summary.worst_transmission_mismatch,
                     std::abs(tr.moment_output_nm - frame.transmissions.at(t).moment_output_Nm) / largest_moment);
    }
    for (size_t d = 0; d < pose.drives.size(); ++d) {
      const DriveResult& dr = pose.drives[d];
      drive_effort[d](Eigen::Index(k), 0) = dr.displacement ? dr.force_on_j_n : dr.moment_on_j_nm;
      drive_change[d](Eigen::Index(k), 0) = dr.displacement ? dr.stretch_m : dr.twist_rad;
    }
  }

  // The parts' envelopes over the motion (steps index all output times).
  void write_envelopes(const std::vector<mech::Frame>& motion) {
    std::vector<double> step_times;  // fields at some output times only: the envelope's steps index all of them
    if (!options.field_steps.empty())
      for (const auto& frame : motion) step_times.push_back(frame.t);
    for (size_t p = 0; p < parts.size(); ++p) {
      const PartEnvelope& e = fields.envelopes.at(p);
      bodies[p]->write_envelope(post::layout::kDisplacementMagnitude, "m", e.max_displacement_m,
                                e.displacement_step.cast<fem::Index>(), post::layout::kEnvelopeMax, step_times);
      bodies[p]->write_envelope(post::layout::kVonMises, "Pa", e.max_von_mises_pa, e.von_mises_step.cast<fem::Index>(),
                                post::layout::kEnvelopeMax, step_times);
      if (envelopes[p].max_p.size() > 0)
        bodies[p]->write_envelope(post::layout::kContactPressure, "Pa", envelopes[p].max_p, envelopes[p].step_p,
                                  post::layout::kEnvelopeMax, step_times);
    }
  }

  // The static study: the parts' fields and the points' results at the static pose.
  void record_static_study(const PoseSolution& pose, const mech::Frame& static_pose) {
    summary.has_static_study = true;
    summary.static_max_displacement_m = pose.max_displacement_m;
    summary.static_max_displacement_body = pose.max_displacement_body;
    for (size_t p = 0; p < parts.size(); ++p) {
      const PartField& field = pose.part(parts[p].body());
      post::BodyWriter& w = *bodies[p];
      w.write_static(post::layout::static_name(post::layout::kPosition), "m",
                     world_position(parts[p].model.mesh, static_pose.bodies[size_t(part_body[p])]),
                     post::kVectorComponents);
      w.write_static(post::layout::static_name(post::layout::kDisplacement), "m", field.displacement_m, post::kVectorComponents);
      w.write_static(post::layout::static_name(post::layout::kDisplacementMagnitude), "m", field.displacement_m.rowwise().norm());
      w.write_static(post::layout::static_name(post::layout::kVonMises), "Pa", field.von_mises_pa);
      if (has_pins_in_contact(parts[p]))
        w.write_static(post::layout::static_name(post::layout::kContactPressure), "Pa", nodal_contact_pressure(pose, p));
      summary.parts[p].static_von_mises_pa = field.von_mises_pa.maxCoeff();
    }
    for (size_t i = 0; i < P; ++i) {
      PointSummary& ps = summary.points[i];
      ps.has_static_study = true;
      ps.static_displacement_m = pose.points[i].displacement_m;
      ps.static_contributions = pose.points[i].contributions;
      ps.static_compliance_m_per_n = pose.points[i].compliance_m_per_n;
    }
  }

  // The histories over the motion: largest |u|, the points', chains' and drives'.
  void write_histories() {
    writer.write_history(post::layout::kAssemblyMaxDisplacement, "m", max_u);
    for (size_t i = 0; i < P; ++i) summary.points[i].displacement_history_m = point_u[i];
    for (size_t i = 0; i < P; ++i) {
      const std::string base = post::layout::kAssemblyPointPrefix + options.points[i].name;
      writer.write_history(base + ".displacement", "m", point_u[i], post::kVectorComponents);
      writer.write_history(base + ".displacement_magnitude", "m", point_mag[i]);
      writer.write_history(base + ".rotation", "rad", point_rot[i], post::kVectorComponents);
      if (options.unit_load_split) {
        writer.write_history(base + ".compliance", "m/N", point_compliance[i],
                             {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"});
        for (size_t c = 0; c < point_from[i].size(); ++c)
          writer.write_history(base + ".from." + point_from_names[i][c], "m", point_from[i][c], post::kVectorComponents);
      }
      if (summary.points[i].has_pins_in_contact)
        writer.write_history(base + ".coupling_displacement", "m", point_coupling[i], post::kVectorComponents);
    }
    for (size_t c = 0; c < summary.contacts.size(); ++c)
      writer.write_table(fmt::format("assembly.contact.{}.{}", summary.contacts[c].body, summary.contacts[c].pin.joint),
                         "s, Pa, deg, deg, m, m", contact_table[c],
                         {"time", "peak_pressure", "peak_angle", "arc", "pin_x", "pin_y"});
    for (size_t c = 0; c < chain_names.size(); ++c) {
      writer.write_history("assembly.chain." + chain_names[c] + ".tension", "N", chain_tension[c]);
      writer.write_history("assembly.chain." + chain_names[c] + ".elongation", "m", chain_elongation[c]);
    }
    for (size_t d = 0; d < drive_names.size(); ++d) {
      const std::string base = "assembly.drive." + drive_names[d];
      if (drive_displacement[d]) {
        writer.write_history(base + ".force", "N", drive_effort[d]);
        writer.write_history(base + ".stretch", "m", drive_change[d]);
      } else {
        writer.write_history(base + ".moment", "N*m", drive_effort[d]);
        writer.write_history(base + ".twist", "rad", drive_change[d]);
      }
    }
    for (size_t t = 0; t < summary.transmissions.size(); ++t) {
      const std::string base = "assembly.transmission." + summary.transmissions[t].name;
      writer.write_history(base + ".moment", "N*m", transmission_moment[t]);
      writer.write_history(base + ".twist", "rad", transmission_twist[t]);
      if (summary.transmissions[t].has_spans)
        writer.write_history(base + ".span_tension", "N", transmission_spans[t], {"span1", "span2"});
    }
    for (size_t i = 0; i < summary.pins.size(); ++i) {
      const std::string base = post::layout::kAssemblyPinPrefix + summary.pins[i].joint + ".";
      writer.write_history(base + post::layout::kPinBendingStress, "Pa", pin_bending[i]);
      writer.write_history(base + post::layout::kPinShearStress, "Pa", pin_shear[i]);
      writer.write_history(base + post::layout::kPinDeflection, "m", pin_deflection[i]);
    }
  }
};

// Solves the motion's poses in blocks (kPosesPerBlock, kWrittenPerBlock) and records each;
// the summary takes the indeterminacy of the first pose.
void solve_motion_in_blocks(ElasticAssembly& assembly, const std::vector<mech::Frame>& motion, const Log& log,
                            AssemblyRecorder& recorder) {
  const size_t T = motion.size();
  Progress progress(log, "  elastic assembly: output times", long(T));
  const std::vector<bool>& field_steps = recorder.options.field_steps;
  for (size_t first = 0, count = 0; first < T; first += count) {
    size_t written = 0;
    for (count = 0; first + count < T && count < kPosesPerBlock; ++count) {
      const bool write = field_steps.empty() || field_steps[first + count];
      if (write && written == kWrittenPerBlock) break;
      written += write ? 1 : 0;
    }
    const std::vector<mech::Frame> block(motion.begin() + long(first), motion.begin() + long(first + count));
    MotionFields& fields = recorder.fields;
    fields.first_step = first;
    fields.write.clear();
    if (!field_steps.empty())
      fields.write.assign(field_steps.begin() + long(first), field_steps.begin() + long(first + count));
    const std::vector<PoseSolution> poses = assembly.solve(block, fields);
    if (first == 0) recorder.summary.indeterminacy = poses.front().indeterminacy;
    for (size_t f = 0; f < count; ++f) recorder.record(poses[f], first + f, motion[first + f]);
    progress.advance(long(first + count));
  }
  progress.finish();
}

}  // namespace

AssemblySummary analyse_assembly_over_motion(const std::vector<structure::Part>& parts,
                                             const mech::MultibodyModel& model,
                                             const std::vector<mech::Frame>& motion,
                                             const std::optional<mech::Frame>& static_pose,
                                             post::ResultsWriter& writer, const AssemblyOptions& options,
                                             const Log& log,
                                             const std::vector<fem::LinearStaticAnalysis*>& factorized) {
  require(!motion.empty(), "elastic assembly: no output times to analyse");
  require(!parts.empty(),
          "elastic assembly: the linkage has no part: an assembly needs at least one body with an FE part "
          "(set assembly.enabled = false for a rigid-body run)");
  ElasticAssembly assembly(parts, model, assembly_run_options(options, motion.size() + (static_pose ? 1 : 0)), log,
                           factorized);
  return analyse_assembly_over_motion(assembly, parts, model, motion, static_pose, writer, options, log);
}

AssemblyOptions assembly_run_options(const AssemblyOptions& options, size_t poses) {
  // The load patterns cost 12 + 6 k solves and stress recoveries per part,
  // besides the 6 m interface columns' stresses (30 to 40 for the SPEC
  // manipulators): below kMinSuperposedPoses poses one solve per pose is
  // cheaper, and exact either way.
  AssemblyOptions run_options = options;
  if (poses < kMinSuperposedPoses) run_options.superpose_loads = false;
  return run_options;
}

AssemblySummary analyse_assembly_over_motion(ElasticAssembly& assembly, const std::vector<structure::Part>& parts,
                                             const mech::MultibodyModel& model,
                                             const std::vector<mech::Frame>& motion,
                                             const std::optional<mech::Frame>& static_pose,
                                             post::ResultsWriter& writer, const AssemblyOptions& options,
                                             const Log& log, std::vector<PartStressHistory>* stress_histories) {
  require(!motion.empty(), "elastic assembly: no output times to analyse");
  require(assembly.is_set_up(), "elastic assembly: not every part is set up (ElasticAssembly::set_up_part)");
  require(!stress_histories || options.keep_part_stress,
          "elastic assembly: the parts' stress histories need keep_part_stress in the assembly's options");
  AssemblySummary summary;
  AssemblyRecorder recorder(assembly, parts, model, writer, options, motion.size(), summary);
  if (stress_histories) {
    stress_histories->assign(parts.size(), PartStressHistory{.source = StressHistorySource::ElasticAssembly});
    recorder.stress_histories = stress_histories;
  }
  solve_motion_in_blocks(assembly, motion, log, recorder);
  if (stress_histories)
    for (size_t p = 0; p < parts.size(); ++p)
      if ((*stress_histories)[p].superposed())
        (*stress_histories)[p].pattern_stress_pa = assembly.stress_patterns(parts[p].body());
  if (!summary.pins.empty())
    log.info(
        "  parts in their own planes ({} pin(s) between bores at different z): the per-part stress above uses the "
        "planar multibody reactions (without the moments of the offsets between bores); the elastic assembly carries "
        "them (its fields {}<body>, its pins' histories {}<joint>.*{})",
        summary.pins.size(), post::layout::kAssemblyBodyPrefix, post::layout::kAssemblyPinPrefix,
        stress_histories ? "; the fatigue check takes each part's stress from it" : "");
  const bool determinate = summary.indeterminacy.in_plane == 0;
  if (determinate && summary.worst_chain_mismatch > 1e-6)
    fail(
        "elastic assembly: the chain force of the statically determinate assembly differs from the dynamics' tension by "
        "{:.2e} of it (tolerance 1e-6)",
        summary.worst_chain_mismatch);
  if (determinate && summary.worst_transmission_mismatch > 1e-6)
    fail(
        "elastic assembly: a transmission's moment in the statically determinate assembly differs from the dynamics' by "
        "{:.2e} of the largest (tolerance 1e-6)",
        summary.worst_transmission_mismatch);

  recorder.write_envelopes(motion);
  if (static_pose) recorder.record_static_study(assembly.solve(*static_pose), *static_pose);
  recorder.write_histories();
  summary.statistics = assembly.statistics();
  return summary;
}

namespace {

// "part.lever 12.3 %, chain.chain 80.1 %": each contribution's component
// along the total displacement, in % of its length (they add up to 100 %).
std::string split_text(const Eigen::Vector3d& total, const std::vector<PointContribution>& contributions) {
  const double length = total.norm();
  if (!(length > 0)) return "-";
  std::string s;
  for (const auto& c : contributions)
    s += fmt::format("{}{} {:.1f} %", s.empty() ? "" : ", ", c.name, 100.0 * c.displacement_m.dot(total) / (length * length));
  return s;
}

}  // namespace

std::string format_assembly_summary(const AssemblySummary& s) {
  using units::kMm;
  std::string out = "  elastic assembly (the linkage as one structure held by the ground; world axes, from the rigid pose):\n";
  out += fmt::format(
      "    statically {} in the plane{}; out of the plane {}\n",
      s.indeterminacy.in_plane == 0 ? "determinate" : "indeterminate",
      s.indeterminacy.in_plane == 0 ? std::string()
                                    : fmt::format(" (degree {}: joint loads depend on the stiffness of the parts)",
                                                  s.indeterminacy.in_plane),
      s.indeterminacy.out_of_plane == 0
          ? std::string("determinate")
          : fmt::format("indeterminate (degree {}: out-of-plane joint loads depend on the parts' stiffness; the "
                        "per-link analysis splits them equally between the pins)",
                        s.indeterminacy.out_of_plane));
  out += fmt::format("    total deformation (max |u|, all nodes): {:.4f} mm at t = {:.4f} s ({})", s.max_displacement_m / kMm,
                     s.max_displacement_time_s, s.max_displacement_body);
  out += s.has_static_study ? fmt::format("; static study {:.4f} mm ({})\n", s.static_max_displacement_m / kMm,
                                          s.static_max_displacement_body)
                            : std::string("\n");
  for (const auto& p : s.parts)
    out += fmt::format("    {:<12} max von Mises {:.3f} MPa over the motion{}\n", p.body, p.max_von_mises_pa / units::kMpa,
                       s.has_static_study ? fmt::format(", {:.3f} MPa static", p.static_von_mises_pa / units::kMpa)
                                          : std::string());
  for (const auto& p : s.pins)
    out += fmt::format("    pin {} (d {:.1f} mm, {:.1f} mm between its bores): peak bending {:.3f} MPa at t = {:.4f} s, "
                       "shear {:.3f} MPa at t = {:.4f} s, own deflection {:.4f} mm\n",
                       p.joint, p.diameter_m / kMm, p.length_m / kMm, p.max_bending_stress_pa / units::kMpa,
                       p.max_bending_time_s, p.max_shear_stress_pa / units::kMpa, p.max_shear_time_s,
                       p.max_deflection_m / kMm);
  for (const auto& t : s.transmissions)
    out += fmt::format("    transmission {}: largest moment {:.4g} N m at t = {:.4f} s, twist up to {:.4g} mrad{}\n", t.name,
                       t.max_moment_nm, t.max_moment_time_s, t.max_twist_rad * 1e3,
                       t.has_spans ? fmt::format("; least span tension {:.4g} N at t = {:.4f} s", t.min_span_tension_n,
                                                 t.min_span_tension_time_s)
                                   : std::string());
  for (const auto& c : s.contacts)
    out += fmt::format("    pin {} in contact with bore '{}' of {} (d {:.2f} mm, radial clearance {:.1f} um{}): peak "
                       "pressure {:.3f} MPa at t = {:.4f} s, {:.0f} deg from the part's x axis, arc {:.0f} deg there; "
                       "the pin moves up to {:.1f} um in the bore\n",
                       c.pin.joint, c.pin.face_set, c.body, c.pin.diameter_m / kMm, c.pin.clearance_m * 1e6,
                       c.pin.fit.empty() ? std::string() : ", " + c.pin.fit, c.pin.peak_pressure_pa / units::kMpa,
                       c.pin.peak_time_s, c.pin.peak_angle_rad * 180.0 / std::numbers::pi,
                       c.pin.arc_at_peak_rad * 180.0 / std::numbers::pi, c.max_pin_motion_m * 1e6);
  for (const auto& p : s.points) {
    const Eigen::Vector3d& u = p.displacement_at_max_m;
    out += fmt::format("    point {} ({}): max |u| {:.4f} mm at t = {:.4f} s, u = ({:+.4f}, {:+.4f}, {:+.4f}) mm\n", p.name,
                       p.body, p.max_displacement_m / kMm, p.max_displacement_time_s, u.x() / kMm, u.y() / kMm,
                       u.z() / kMm);
    if (!p.contributions_at_max.empty())
      out += fmt::format("      split (unit-load method, along u): {}\n", split_text(u, p.contributions_at_max));
    if (p.has_pins_in_contact)
      out += fmt::format("      the pins' share (clearance and contact, against couplings at those pins): up to {:.4f} mm "
                         "at t = {:.4f} s, ({:+.4f}, {:+.4f}, {:+.4f}) mm\n",
                         p.max_pin_share_m / kMm, p.max_pin_share_time_s, p.pin_share_at_max_m.x() / kMm,
                         p.pin_share_at_max_m.y() / kMm, p.pin_share_at_max_m.z() / kMm);
    if (p.max_compliance_m_per_n > 0)
      out += fmt::format(
          "      in-plane compliance: largest eigenvalue {:.4g} um/N (t = {:.4f} s), smallest {:.4g} um/N (t = {:.4f} s) "
          "over the motion\n",
          p.max_compliance_m_per_n * 1e6, p.max_compliance_time_s, p.min_compliance_m_per_n * 1e6,
          p.min_compliance_time_s);
    if (p.has_static_study) {
      const Eigen::Vector3d& v = p.static_displacement_m;
      out += fmt::format("      static study: |u| {:.4f} mm, u = ({:+.4f}, {:+.4f}, {:+.4f}) mm; split {}\n", v.norm() / kMm,
                         v.x() / kMm, v.y() / kMm, v.z() / kMm, split_text(v, p.static_contributions));
    }
  }
  const AssemblyStatistics& st = s.statistics;
  const double per_pose = st.poses > 0 ? 1e3 / double(st.poses) : 0.0;
  if (st.contact_corners > 0)
    out += fmt::format("    contact: {} corners, condensation {:.2f} s, {:.2f} ms per pose ({} poses by the interior-point "
                       "fallback, at most {} active-set steps); penetration <= {:.1e} m, resultant error <= {:.1e}\n",
                       st.contact_corners, st.contact_setup_seconds, st.contact_seconds * per_pose,
                       st.contact_interior_point_poses, st.most_contact_active_set_steps, s.worst_contact_penetration_m,
                       s.worst_contact_resultant_error);
  out += fmt::format("    cost: setup {:.2f} s (factorizations {:.2f} s, interface and load-pattern solves), {:.2f} ms "
                     "per pose (loads {:.2f}, load fields {:.2f}, system {:.2f}, fields {:.2f})\n",
                     st.setup_seconds, st.factorize_seconds, 1e3 * st.pose_seconds(), st.loads_seconds * per_pose,
                     st.load_solve_seconds * per_pose, st.system_seconds * per_pose, st.recovery_seconds * per_pose);
  return out;
}

}  // namespace kinetofem::pipeline
