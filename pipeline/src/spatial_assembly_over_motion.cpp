#include "kinetofem/pipeline/spatial_assembly_over_motion.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/pipeline/part_model.hpp"  // write_solid_field
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/vibration/spatial_assembly_modes.hpp"

namespace kinetofem::pipeline {

namespace {

int body_index(const mech::spatial::Model& model, const std::string& name) {
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == name) return int(b);
  fail("spatial elastic assembly: the mechanism has no body '{}'", name);
}

}  // namespace

SpatialAssemblySummary analyse_spatial_assembly_over_motion(
    const std::vector<structure::SpatialPart>& parts, const mech::spatial::Model& model,
    const std::vector<mech::spatial::Frame>& motion, post::ResultsWriter& writer,
    const structure::SpatialAssemblyOptions& options, const std::vector<bool>& field_steps, const Log& log,
    const std::vector<fem::LinearStaticAnalysis*>& factorized, const vibration::AssemblyModesOptions* vibration) {
  require(!motion.empty(), "spatial elastic assembly: no output times");
  require(field_steps.empty() || field_steps.size() == motion.size(),
          "spatial elastic assembly: the field output mask has {} entries for {} output times", field_steps.size(),
          motion.size());
  log.info("spatial elastic assembly: {} parts, {} output times", parts.size(), motion.size());
  structure::SpatialElasticAssembly assembly(parts, model, options, log, factorized);
  SpatialAssemblySummary summary;
  summary.setup_seconds = assembly.setup_seconds();

  const size_t np = parts.size(), P = options.points.size(), T = motion.size();
  std::vector<post::BodyWriter*> bodies;
  std::vector<int> part_body;
  struct Envelope {
    Eigen::VectorXd max_u, max_vm;
    post::IndexMatrix step_u, step_vm;
  };
  std::vector<Envelope> envelopes(np);
  for (size_t p = 0; p < np; ++p) {
    const fem::Mesh& mesh = assembly.supported_model(parts[p].body()).mesh;
    post::BodyWriter& w = writer.add_body(post::layout::kAssemblyBodyPrefix + parts[p].body(), mesh);
    write_solid_field(w, mesh);
    w.begin_series({{.name = post::layout::kPosition,
                     .units = "m",
                     .components = 3,
                     .component_names = post::kVectorComponents,
                     .geometry = true},
                    {post::layout::kDisplacement, "m", 3, post::kVectorComponents},
                    {post::layout::kDisplacementMagnitude, "m", 1, {}},
                    {post::layout::kVonMises, "Pa", 1, {}}});
    bodies.push_back(&w);
    const fem::Index N = mesh.node_count();
    envelopes[p] = {Eigen::VectorXd::Constant(N, -1.0), Eigen::VectorXd::Constant(N, -1.0),
                    post::IndexMatrix::Zero(N, 1), post::IndexMatrix::Zero(N, 1)};
    part_body.push_back(body_index(model, parts[p].body()));
    summary.parts.push_back({parts[p].body(), 0.0, 0.0});
  }
  Eigen::MatrixXd max_u(T, 1);
  std::vector<Eigen::MatrixXd> point_u(P, Eigen::MatrixXd(T, 3)), point_mag(P, Eigen::MatrixXd(T, 1)),
      point_rot(P, Eigen::MatrixXd(T, 3)), point_compliance(P, Eigen::MatrixXd(T, 9));
  std::vector<std::vector<Eigen::MatrixXd>> point_from(P);  // per point: per contributor (parts, chains), T x 3
  std::vector<std::vector<std::string>> point_from_names(P);
  for (size_t i = 0; i < P; ++i) {
    PointSummary ps;
    ps.name = options.points[i].name;
    ps.body = options.points[i].body;
    ps.min_compliance_m_per_n = std::numeric_limits<double>::infinity();
    summary.points.push_back(ps);
  }

  Stopwatch clock;
  Progress progress(log, "spatial elastic assembly", long(T));
  for (size_t k = 0; k < T; ++k) {
    const mech::spatial::Frame& frame = motion[k];
    const structure::SpatialPoseSolution pose = assembly.solve(frame);
    summary.worst_relative_residual = std::max(summary.worst_relative_residual, pose.relative_residual);
    max_u(Eigen::Index(k), 0) = pose.max_displacement_m;
    if (pose.max_displacement_m > summary.max_displacement_m || k == 0) {
      summary.max_displacement_m = pose.max_displacement_m;
      summary.max_displacement_time_s = frame.t;
      summary.max_displacement_body = pose.max_displacement_body;
    }
    for (size_t p = 0; p < np; ++p) {
      const structure::PartField& field = pose.parts[p];
      const Eigen::VectorXd magnitude = field.displacement_m.rowwise().norm();
      require(magnitude.allFinite() && field.von_mises_pa.allFinite(),
              "spatial elastic assembly at t = {:.6g} s: part '{}': the field is not finite", frame.t, field.body);
      Envelope& env = envelopes[p];
      for (Eigen::Index n = 0; n < magnitude.size(); ++n) {
        if (magnitude(n) > env.max_u(n)) {
          env.max_u(n) = magnitude(n);
          env.step_u(n, 0) = fem::Index(k);
        }
        if (field.von_mises_pa(n) > env.max_vm(n)) {
          env.max_vm(n) = field.von_mises_pa(n);
          env.step_vm(n, 0) = fem::Index(k);
        }
      }
      const double peak = field.von_mises_pa.maxCoeff();
      if (peak > summary.parts[p].max_von_mises_pa) {
        summary.parts[p].max_von_mises_pa = peak;
        summary.parts[p].max_von_mises_time_s = frame.t;
      }
      if (field_steps.empty() || field_steps[k]) {
        const fem::Mesh& mesh = assembly.supported_model(parts[p].body()).mesh;
        const mech::spatial::BodyState& body = frame.bodies[size_t(part_body[p])];
        post::FieldMatrix position(mesh.node_count(), 3);
        for (fem::Index n = 0; n < mesh.node_count(); ++n)
          position.row(n) = (body.origin + body.rotation * mesh.nodes.row(n).transpose()).transpose();
        bodies[p]->write_step(frame.t, {{post::layout::kPosition, position},
                                        {post::layout::kDisplacement, field.displacement_m},
                                        {post::layout::kDisplacementMagnitude, magnitude},
                                        {post::layout::kVonMises, field.von_mises_pa}});
      }
    }
    for (size_t i = 0; i < P; ++i) {
      const structure::PointResult& pr = pose.points[i];
      const Eigen::Index r = Eigen::Index(k);
      require(pr.displacement_m.allFinite() && pr.compliance_m_per_n.allFinite(),
              "spatial elastic assembly at t = {:.6g} s: point '{}': not finite", frame.t, pr.name);
      point_u[i].row(r) = pr.displacement_m.transpose();
      point_mag[i](r, 0) = pr.displacement_m.norm();
      point_rot[i].row(r) = pr.rotation_rad.transpose();
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) point_compliance[i](r, 3 * a + b) = pr.compliance_m_per_n(a, b);
      if (k == 0)
        for (const structure::PointContribution& share : pr.contributions) {
          point_from[i].push_back(Eigen::MatrixXd(T, 3));
          point_from_names[i].push_back(share.name);
        }
      require(pr.contributions.size() == point_from[i].size(),
              "spatial elastic assembly at t = {:.6g} s: point '{}': the contributors changed", frame.t, pr.name);
      for (size_t c = 0; c < pr.contributions.size(); ++c)
        point_from[i][c].row(r) = pr.contributions[c].displacement_m.transpose();
      PointSummary& ps = summary.points[i];
      if (pr.displacement_m.norm() > ps.max_displacement_m || k == 0) {
        ps.max_displacement_m = pr.displacement_m.norm();
        ps.max_displacement_time_s = frame.t;
        ps.displacement_at_max_m = pr.displacement_m;
        ps.contributions_at_max = pr.contributions;
      }
      if (options.unit_load_split) {
        const Eigen::Matrix3d C = 0.5 * (pr.compliance_m_per_n + pr.compliance_m_per_n.transpose());
        const Eigen::Vector3d eig =
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly).eigenvalues();
        if (eig.maxCoeff() > ps.max_compliance_m_per_n) {
          ps.max_compliance_m_per_n = eig.maxCoeff();
          ps.max_compliance_time_s = frame.t;
        }
        if (eig.minCoeff() < ps.min_compliance_m_per_n) {
          ps.min_compliance_m_per_n = eig.minCoeff();
          ps.min_compliance_time_s = frame.t;
        }
      }
    }
    progress.advance(long(k + 1));
  }
  progress.finish();
  summary.poses_seconds = clock.seconds();

  std::vector<double> step_times;  // fields at some output times only: the envelope's steps index all of them
  if (!field_steps.empty())
    for (const auto& frame : motion) step_times.push_back(frame.t);
  for (size_t p = 0; p < np; ++p) {
    bodies[p]->write_envelope(post::layout::kDisplacementMagnitude, "m", envelopes[p].max_u, envelopes[p].step_u,
                              post::layout::kEnvelopeMax, step_times);
    bodies[p]->write_envelope(post::layout::kVonMises, "Pa", envelopes[p].max_vm, envelopes[p].step_vm,
                              post::layout::kEnvelopeMax, step_times);
  }
  writer.write_history(post::layout::kAssemblyMaxDisplacement, "m", max_u);
  for (size_t i = 0; i < P; ++i) {
    summary.points[i].displacement_history_m = point_u[i];
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
  }
  if (vibration) {
    Stopwatch watch;
    log.info("spatial vibration: Craig-Bampton reduction of {} parts, {} modes per pose", np, vibration->modes);
    const vibration::SpatialAssemblyModes modes(assembly, model, *vibration, motion, log);
    SpatialAssemblySummary::Vibration v;
    v.modes = vibration->modes;
    v.frequency_hz.resize(Eigen::Index(T), vibration->modes);
    Progress progress_modes(log, "spatial vibration", long(T));
    for (size_t k = 0; k < T; ++k) {
      const vibration::PoseModes pose = modes.modes(motion[k]);
      require(pose.frequency_hz.allFinite() && pose.frequency_hz.size() == vibration->modes,
              "spatial vibration at t = {:.6g} s: the frequencies are not finite", motion[k].t);
      v.frequency_hz.row(Eigen::Index(k)) = pose.frequency_hz.transpose();
      const double first = pose.frequency_hz(0);
      if (k == 0 || first < v.lowest_first_hz) {
        v.lowest_first_hz = first;
        v.lowest_first_time_s = motion[k].t;
      }
      if (k == 0 || first > v.highest_first_hz) {
        v.highest_first_hz = first;
        v.highest_first_time_s = motion[k].t;
      }
      progress_modes.advance(long(k + 1));
    }
    progress_modes.finish();
    v.reductions = modes.reductions();
    v.rule = modes.check_rule(v.frequency_hz.maxCoeff());
    v.seconds = watch.seconds();
    std::vector<std::string> names;
    for (int i = 0; i < v.modes; ++i) names.push_back(fmt::format("mode_{}", i + 1));
    writer.write_history("vibration.frequency", "Hz", v.frequency_hz, names);
    log.info("spatial vibration: first natural frequency {:.3f}-{:.3f} Hz over the motion; {}; {:.2f} s",
             v.lowest_first_hz, v.highest_first_hz, v.rule, v.seconds);
    summary.vibration = std::move(v);
  }
  log.info(
      "spatial elastic assembly: set-up {:.2f} s, {} poses {:.2f} s; max displacement {:.4f} mm in '{}' at "
      "t = {:.4f} s",
      summary.setup_seconds, T, summary.poses_seconds, summary.max_displacement_m / units::kMm,
      summary.max_displacement_body, summary.max_displacement_time_s);
  return summary;
}

}  // namespace kinetofem::pipeline
