#include "kinetofem/vibration/spatial_assembly_modes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "assembly_modes_shared.hpp"

namespace kinetofem::vibration {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using structure::InterfaceStructure;
using structure::SpatialInterfaceInfo;
using structure::detail::Matrix6d;
using structure::detail::rotate6;
namespace spatial = mech::spatial;

struct SpatialAssemblyModes::Impl {
  struct PartRed {
    std::string body, label;
    int body_index = -1;
    const fem::FeModel* model = nullptr;  // the assembly's 3-2-1-supported model
    std::vector<detail::CbInterface> interfaces;
    std::unique_ptr<fem::LinearStaticAnalysis> analysis;  // during the reductions only
    std::unique_ptr<loads::SpatialLinkLoads> loads;       // its own loads (no joints, drives, slides)
    CraigBamptonModel cb;
    Index offset = 0, size = 0;
    MatrixXd basis_t_patterns;  // T^T P: reduced load patterns
  };
  struct RigidRed {
    int body_index = -1;
    Index offset = 0;
    Matrix6d mass = Matrix6d::Zero();
  };

  const structure::SpatialElasticAssembly& assembly;
  AssemblyModesOptions options;
  Log log;
  std::vector<SpatialInterfaceInfo> infos;
  std::vector<std::string> body_names;
  std::vector<PartRed> parts;
  std::vector<RigidRed> rigid;
  std::vector<detail::InterfaceMap> map;
  std::vector<PartReduction> reports;
  Index n = 0;
  MatrixXd K, M;
  double length_scale = 1.0, cutoff = 0.0, fmax_estimate = 0.0;

  Impl(const structure::SpatialElasticAssembly& a, const spatial::Model& model, const AssemblyModesOptions& o,
       const std::vector<spatial::Frame>& poses, const Log& l);

  CraigBamptonReducer make_reducer(size_t p);
  void take(size_t p, CraigBamptonModel cb);
  void build_matrices();

  std::vector<Eigen::Matrix3d> rotations(const spatial::Frame& frame) const {
    require(frame.bodies.size() == body_names.size(),
            "vibration at t = {:.6g} s: the frame has {} bodies, the mechanism {}", frame.t, frame.bodies.size(),
            body_names.size());
    std::vector<Eigen::Matrix3d> R;
    for (const spatial::BodyState& body : frame.bodies) R.push_back(body.rotation);
    return R;
  }
  MatrixXd interface_map(const spatial::Frame& frame) const {  // U: 6M x n
    return detail::interface_map(map, rotations(frame), n);
  }
  // An orthonormal basis (scaled back) of the motions C U x = 0 of a pose.
  MatrixXd admissible(const InterfaceStructure& is, const MatrixXd& U) const {
    // Rotations as length_scale x angle, so that rank decisions compare like with like.
    VectorXd scale = VectorXd::Ones(n);
    for (const PartRed& p : parts)
      for (Index b = 0; b < p.cb.boundary_count; ++b)
        if (b % 6 >= 3) scale(p.offset + b) = 1.0 / length_scale;
    for (const RigidRed& r : rigid)
      for (int c = 3; c < 6; ++c) scale(r.offset + c) = 1.0 / length_scale;
    return detail::null_space_basis(is.constraints * U, scale);
  }
  PoseModes solve(const spatial::Frame& frame, int count) const {
    const InterfaceStructure is = assembly.interface_structure(frame);
    const MatrixXd U = interface_map(frame);
    const MatrixXd N = admissible(is, U);
    require(N.cols() >= count,
            "vibration at t = {:.6g} s: the reduced assembly has {} free coordinates, fewer than the {} modes wanted",
            frame.t, N.cols(), count);
    MatrixXd Kc = N.transpose() * (K + U.transpose() * is.springs * U) * N;  // the chains: springs
    MatrixXd Mc = N.transpose() * M * N;
    return detail::modes_on_basis(std::move(Kc), std::move(Mc), N, count, frame.t);
  }
};

SpatialAssemblyModes::Impl::Impl(const structure::SpatialElasticAssembly& a, const spatial::Model& model,
                                 const AssemblyModesOptions& o, const std::vector<spatial::Frame>& poses, const Log& l)
    : assembly(a), options(o), log(l), infos(a.interfaces()) {
  detail::check_options(options, poses.size());
  length_scale = model.characteristic_length_m > 0 ? model.characteristic_length_m : 1.0;
  for (const spatial::Body& b : model.bodies) body_names.push_back(b.name);
  auto body_index = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return int(b);
    fail("vibration: no body '{}' in the mechanism '{}' (the assembly is of another model)", name, model.name);
  };

  // Parts: one coupling per face set their interfaces use, and point masses.
  for (const structure::SpatialPart& part : assembly.parts()) {
    PartRed pr;
    pr.body = part.body();
    pr.label = part.label.empty() ? fmt::format("part '{}'", pr.body) : part.label;
    pr.body_index = body_index(pr.body);
    pr.model = &assembly.supported_model(pr.body);
    const fem::Mesh& mesh = pr.model->mesh;
    for (const SpatialInterfaceInfo& info : infos) {
      if (info.body != pr.body) continue;
      const MatrixXd columns = coupling_interface(mesh, info.face_set, info.reference_body_m, info.name).columns;
      detail::add_face_interface(pr.interfaces, pr.label, info.name, info.face_set, info.reference_body_m, columns);
    }
    const spatial::Body& body = model.bodies[size_t(pr.body_index)];
    for (const loads::SpatialAttachment& pm : part.attachments.point_masses) {
      const auto it = std::find_if(body.point_masses.begin(), body.point_masses.end(),
                                   [&](const spatial::PointMass& m) { return m.name == pm.name; });
      require(it != body.point_masses.end(), "vibration: {}: body '{}' has no point mass '{}'", pr.label, pr.body,
              pm.name);
      detail::carry_point_mass(pr.interfaces, mesh, pm.face_set, it->position_body, it->name, it->mass_kg,
                               it->inertia_kgm2);
    }
    // Its own loads as the assembly's statics take them (load()).
    loads::SpatialLinkDefinition own = part.attachments;
    own.model = pr.model;
    own.joints.clear();
    own.slides.clear();
    pr.loads = std::make_unique<loads::SpatialLinkLoads>(own, model, std::numeric_limits<double>::infinity());
    parts.push_back(std::move(pr));
  }

  // Rigid moving bodies: mass, centre of mass and inertia tensor with their
  // point masses.
  const spatial::System system(model);
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].fixed) continue;
    if (std::any_of(parts.begin(), parts.end(), [&](const PartRed& p) { return p.body_index == int(b); })) continue;
    const spatial::EffectiveBody& eff = system.effective(int(b));
    require(eff.mass_kg > 0, "vibration: rigid body '{}' has mass {} kg: it must be positive for its modes",
            model.bodies[b].name, eff.mass_kg);
    RigidRed rr;
    rr.body_index = int(b);
    rr.mass = detail::point_mass_6x6(eff.mass_kg, eff.com_body);
    rr.mass.bottomRightCorner<3, 3>() += eff.inertia_kgm2;
    const Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(eff.inertia_kgm2).eigenvalues();
    log.info("vibration: rigid body '{}': {:.4g} kg, principal moments {:.4g}, {:.4g}, {:.4g} kg m^2",
             model.bodies[b].name, eff.mass_kg, moments(0), moments(1), moments(2));
    rigid.push_back(rr);
  }

  // The part-mode rule; each part's factor made for its reductions and
  // freed after (the assembly frees its own after its set-up).
  detail::PartRuleSteps steps;
  steps.parts = parts.size();
  steps.make_reducer = [this](size_t p) { return make_reducer(p); };
  steps.borrow = [this](size_t p) { parts[p].analysis->factorize(); };
  steps.give_back = [this](size_t p) { parts[p].analysis->release_factor(); };
  steps.part_options = [this](size_t p, const CraigBamptonOptions& given) {
    CraigBamptonOptions cbo = given;
    cbo.eigen.label = parts[p].label;
    cbo.solver = options.fixed_interface_solver;
    return cbo;
  };
  steps.take = [this](size_t p, CraigBamptonModel cb) { take(p, std::move(cb)); };
  steps.static_fmax_hz = [&] {
    build_matrices();
    double fmax = 0.0;
    for (const spatial::Frame& frame : poses)
      fmax = std::max(fmax, solve(frame, options.modes).frequency_hz(options.modes - 1));
    return fmax;
  };
  const detail::PartRuleResult rule = detail::reduce_parts_by_rule(options, poses.size(), steps, log);
  for (PartRed& pr : parts) pr.analysis.reset();
  fmax_estimate = rule.fmax_estimate_hz;
  cutoff = rule.cutoff_hz;
  build_matrices();
}

CraigBamptonReducer SpatialAssemblyModes::Impl::make_reducer(size_t p) {
  PartRed& pr = parts[p];
  fem::StaticSolverOptions solver;
  solver.method = fem::LinearSolverMethod::Direct;
  solver.defer_factorization = true;  // factorized when lent (steps.borrow)
  pr.analysis = std::make_unique<fem::LinearStaticAnalysis>(*pr.model, log, solver);
  std::vector<PartInterface> interfaces;
  for (const detail::CbInterface& i : pr.interfaces) interfaces.push_back({i.name, i.columns});
  return CraigBamptonReducer(*pr.analysis, interfaces, pr.label, false);
}

void SpatialAssemblyModes::Impl::take(size_t p, CraigBamptonModel cb) {
  PartRed& pr = parts[p];
  pr.cb = std::move(cb);
  require(pr.cb.constraint_modes.rows() == 3 * pr.model->mesh.node_count(),
          "vibration: {}: the reduction is over {} equations, the mesh has {} DoFs", pr.label,
          pr.cb.constraint_modes.rows(), 3 * pr.model->mesh.node_count());
  MatrixXd T(pr.cb.constraint_modes.rows(), pr.cb.stiffness.rows());
  T << pr.cb.constraint_modes, pr.cb.normal_modes, pr.cb.residual_vectors;
  pr.basis_t_patterns = T.transpose() * pr.loads->pattern_forces();
  reports.resize(parts.size());
  reports[p] = {pr.body,         pr.cb.free_dofs,        pr.cb.boundary_count, pr.cb.mode_count, pr.cb.residual_count,
                pr.cb.cutoff_hz, pr.cb.first_dropped_hz, pr.cb.seconds};
}

void SpatialAssemblyModes::Impl::build_matrices() {
  n = 0;
  for (PartRed& pr : parts) {
    pr.offset = n;
    pr.size = pr.cb.stiffness.rows();
    n += pr.size;
  }
  for (RigidRed& r : rigid) {
    r.offset = n;
    n += 6;
  }
  K = MatrixXd::Zero(n, n);
  M = MatrixXd::Zero(n, n);
  for (const PartRed& pr : parts) {
    K.block(pr.offset, pr.offset, pr.size, pr.size) = pr.cb.stiffness;
    M.block(pr.offset, pr.offset, pr.size, pr.size) = pr.cb.mass;
    for (size_t i = 0; i < pr.interfaces.size(); ++i) {
      const Index j = pr.offset + pr.cb.interface_offset[i];
      M.block<6, 6>(j, j) += pr.interfaces[i].mass;
    }
  }
  for (const RigidRed& r : rigid) M.block<6, 6>(r.offset, r.offset) = r.mass;

  map.clear();
  for (const SpatialInterfaceInfo& info : infos) {
    detail::InterfaceMap im;
    im.reference = info.reference_body_m;
    for (size_t p = 0; p < parts.size(); ++p) {
      if (parts[p].body != info.body) continue;
      const PartRed& pr = parts[p];
      const int i = detail::find_face_interface(pr.interfaces, info.face_set);
      im.body_index = pr.body_index;
      im.part = int(p);
      im.column = pr.offset + pr.cb.interface_offset[size_t(i)];
      im.arm = info.reference_body_m - pr.interfaces[size_t(i)].reference;
    }
    if (im.part < 0) {
      for (const RigidRed& r : rigid)
        if (body_names[size_t(r.body_index)] == info.body) {
          im.body_index = r.body_index;
          im.column = r.offset;
          im.arm = info.reference_body_m;
        }
      require(im.body_index >= 0,
              "vibration: interface {} is on body '{}', which is neither a part nor a rigid moving body", info.name,
              info.body);
    }
    map.push_back(im);
  }
}

// ---------------------------------------------------------------------------

SpatialAssemblyModes::SpatialAssemblyModes(const structure::SpatialElasticAssembly& assembly,
                                           const spatial::Model& model, const AssemblyModesOptions& options,
                                           const std::vector<spatial::Frame>& poses, const Log& log)
    : impl_(std::make_unique<Impl>(assembly, model, options, poses, log)) {}
SpatialAssemblyModes::~SpatialAssemblyModes() = default;
SpatialAssemblyModes::SpatialAssemblyModes(SpatialAssemblyModes&&) noexcept = default;
SpatialAssemblyModes& SpatialAssemblyModes::operator=(SpatialAssemblyModes&&) noexcept = default;

PoseModes SpatialAssemblyModes::modes(const spatial::Frame& frame) const {
  return impl_->solve(frame, impl_->options.modes);
}

Index SpatialAssemblyModes::size() const { return impl_->n; }
const MatrixXd& SpatialAssemblyModes::mass() const { return impl_->M; }
const MatrixXd& SpatialAssemblyModes::stiffness() const { return impl_->K; }

VectorXd SpatialAssemblyModes::load(const spatial::Frame& frame) const {
  const Impl& im = *impl_;
  const std::vector<Eigen::Matrix3d> R = im.rotations(frame);
  VectorXd F = VectorXd::Zero(im.n);
  for (const Impl::PartRed& pr : im.parts)
    F.segment(pr.offset, pr.size) = pr.basis_t_patterns * pr.loads->coefficients_at(frame).coefficients;
  // A rigid body's applied minus inertia loads: minus the sum of what its
  // joints and drives apply on it (the multibody solution balances them),
  // about its origin, turned into its body axes.
  for (const Impl::RigidRed& r : im.rigid) {
    const std::string& name = im.body_names[size_t(r.body_index)];
    const Vector3d origin = frame.bodies[size_t(r.body_index)].origin;
    structure::Vector6d world = structure::Vector6d::Zero();
    auto add = [&](const spatial::Reaction& reaction) {
      if (reaction.body != name) return;
      world.head<3>() -= reaction.force_world;
      world.tail<3>() -= reaction.moment_world + (reaction.point_world - origin).cross(reaction.force_world);
    };
    for (const spatial::JointState& j : frame.joints) {
      add(j.on_i);
      add(j.on_j);
    }
    for (const spatial::DriveState& d : frame.drives) {
      add(d.on_i);
      add(d.on_j);
    }
    F.segment<6>(r.offset) = rotate6(R[size_t(r.body_index)]).transpose() * world;
  }
  return F;
}

VectorXd SpatialAssemblyModes::static_response(const spatial::Frame& frame, const VectorXd& load) const {
  const Impl& im = *impl_;
  require(load.size() == im.n, "vibration: a load of {} coordinates for a reduced model of {}", load.size(), im.n);
  const InterfaceStructure is = im.assembly.interface_structure(frame);
  const MatrixXd U = im.interface_map(frame);
  const MatrixXd N = im.admissible(is, U);
  const MatrixXd Kc = N.transpose() * (im.K + U.transpose() * is.springs * U) * N;
  return N * Kc.ldlt().solve(N.transpose() * load);
}

MatrixXd SpatialAssemblyModes::point_rows(const std::string& point, const spatial::Frame& frame) const {
  const Impl& im = *impl_;
  const std::string name = fmt::format("point '{}'", point);
  for (size_t k = 0; k < im.infos.size(); ++k)
    if (im.infos[k].name == name) return im.interface_map(frame).middleRows(6 * Index(k), 3);
  fail("vibration: no tracked point '{}' in the spatial elastic assembly", point);
}

const std::vector<PartReduction>& SpatialAssemblyModes::reductions() const { return impl_->reports; }
double SpatialAssemblyModes::cutoff_hz() const { return impl_->cutoff; }
double SpatialAssemblyModes::estimated_fmax_hz() const { return impl_->fmax_estimate; }

std::string SpatialAssemblyModes::check_rule(double highest_frequency_seen_hz) const {
  return detail::format_rule(impl_->options, impl_->cutoff, highest_frequency_seen_hz);
}

}  // namespace kinetofem::vibration
