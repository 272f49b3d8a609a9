#include "kinetofem/vibration/assembly_modes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "assembly_modes_shared.hpp"

namespace kinetofem::vibration {

using structure::InterfaceInfo;
using structure::InterfaceStructure;
using structure::Vector6d;

namespace {

using structure::detail::Matrix6d;
using structure::detail::rotate6;
using structure::detail::skew;
using structure::detail::transfer;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

Eigen::Matrix3d rot_z(double theta) { return Eigen::AngleAxisd(theta, Vector3d::UnitZ()).toRotationMatrix(); }

using detail::CbInterface;
using detail::InterfaceMap;
using detail::point_mass_6x6;

}  // namespace

struct AssemblyModes::Impl {
  // One Craig-Bampton interface of a part per face set (CbInterface,
  // assembly_modes_shared.hpp).
  struct PartRed {
    std::string body, label;
    int body_index = -1;
    bool held = false;  // a part of the ground, held on its foundation
    const fem::Mesh* mesh = nullptr;
    const loads::LinkLoads* loads = nullptr;
    std::vector<CbInterface> interfaces;
    vibration::CraigBamptonModel cb;
    Index offset = 0, size = 0;  // in x
    MatrixXd basis_t_patterns;   // T^T P: reduced load patterns (n_r x patterns)
  };
  struct RigidRed {
    int body_index = -1;
    Index offset = 0;
    Matrix6d mass = Matrix6d::Zero();
  };
  const ElasticAssembly& assembly;
  AssemblyModesOptions options;
  Log log;
  std::vector<InterfaceInfo> infos;
  std::vector<PartRed> parts;
  std::vector<RigidRed> rigid;
  std::vector<InterfaceMap> map;
  std::vector<int> moving_index;  // per model body; -1: ground
  std::vector<std::string> body_names;
  std::vector<PartReduction> reports;
  Index n = 0;
  MatrixXd K, M;
  double length_scale = 1.0, cutoff = 0.0, fmax_estimate = 0.0;

  Impl(const ElasticAssembly& a, const std::vector<structure::Part>& given, const mech::MultibodyModel& model,
       const AssemblyModesOptions& o, const std::vector<mech::Frame>& poses, const Log& l, PartFactorLender* f);

  PartFactorLender* lender = nullptr;  // null: the assembly's factors, alive throughout

  fem::LinearStaticAnalysis& borrow(size_t p);
  void give_back(size_t p);
  vibration::CraigBamptonReducer make_reducer(size_t p);
  vibration::CraigBamptonOptions part_options(size_t p, const vibration::CraigBamptonOptions& given) const;
  void take(size_t p, vibration::CraigBamptonModel cb);
  void build_matrices();

  MatrixXd interface_map(const mech::Frame& frame) const {  // U: 6M x n
    std::vector<Eigen::Matrix3d> rotation;
    for (const mech::BodyFrame& body : frame.bodies) rotation.push_back(rot_z(body.q.z()));
    return detail::interface_map(map, rotation, n);
  }

  // An orthonormal basis (scaled back) of the motions C U x = 0 of a pose
  // (its structure and interface map, built once by the caller).
  MatrixXd admissible(const InterfaceStructure& is, const MatrixXd& U) const {
    // Rotations as length_scale x angle, so that rank decisions compare like with like.
    VectorXd scale = VectorXd::Ones(n);
    for (const auto& p : parts)
      for (Index b = 0; b < p.cb.boundary_count; ++b)
        if (b % 6 >= 3) scale(p.offset + b) = 1.0 / length_scale;
    for (const auto& r : rigid)
      for (int c = 3; c < 6; ++c) scale(r.offset + c) = 1.0 / length_scale;
    return detail::null_space_basis(is.constraints * U, scale);
  }

  PoseModes solve(const mech::Frame& frame, int count) const {
    const InterfaceStructure is = assembly.interface_structure(frame);
    const MatrixXd U = interface_map(frame);
    const MatrixXd N = admissible(is, U);
    require(N.cols() >= count,
            "vibration at t = {:.6g} s: the reduced assembly has {} free coordinates, fewer than the {} modes wanted",
            frame.t, N.cols(), count);
    MatrixXd Kc = N.transpose() * (K + U.transpose() * is.springs * U) * N;
    MatrixXd Mc = N.transpose() * M * N;
    return detail::modes_on_basis(std::move(Kc), std::move(Mc), N, count, frame.t);
  }
};

AssemblyModes::Impl::Impl(const ElasticAssembly& a, const std::vector<structure::Part>& given,
                          const mech::MultibodyModel& model, const AssemblyModesOptions& o,
                          const std::vector<mech::Frame>& poses, const Log& l, PartFactorLender* f)
    : assembly(a), options(o), log(l), infos(a.interfaces()), lender(f) {
  detail::check_options(options, poses.size());
  length_scale = model.characteristic_length_m > 0 ? model.characteristic_length_m : 1.0;
  auto body_index = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return int(b);
    fail("vibration: no body '{}' in the mechanism '{}'", name, model.name);
  };
  moving_index.assign(model.bodies.size(), -1);
  for (const auto& b : model.bodies) body_names.push_back(b.name);
  int moving = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (!model.bodies[b].fixed) moving_index[b] = moving++;

  // Parts: their interfaces (shared where they coincide) and point masses.
  for (const structure::Part& part : given) {
    PartRed pr;
    pr.body = part.body();
    pr.label = part.label.empty() ? fmt::format("part '{}'", pr.body) : part.label;
    pr.body_index = body_index(pr.body);
    // A part of the ground (the frame) is held on its foundation: reduced
    // with its held model (no rigid-body modes), and its interfaces move by
    // its deformation alone, as in the assembly's statics.
    pr.held = model.bodies[size_t(pr.body_index)].fixed;
    pr.mesh = &assembly.supported_analysis(pr.body).model().mesh;
    pr.loads = &assembly.part_loads(pr.body);
    const MatrixXd& G = assembly.interface_columns(pr.body);
    // One coupling per face set: a second reference point on the same face
    // moves rigidly with the first (its columns are a rigid transfer of the
    // first's, so they would be dependent boundary coordinates).
    Index local = 0;
    for (const InterfaceInfo& info : infos) {
      if (info.body != pr.body) continue;
      detail::add_face_interface(pr.interfaces, pr.label, info.kind + "." + info.name, info.face_set,
                                 info.reference_body_m, G.middleCols(6 * local, 6));
      ++local;
    }
    require(6 * local == G.cols(), "vibration: {}: {} interface columns for {} interfaces", pr.label, G.cols(), local);
    const mech::Body& body = model.bodies[size_t(pr.body_index)];
    for (const auto& pm : part.attachments.point_masses) {
      const auto it = std::find_if(body.point_masses.begin(), body.point_masses.end(),
                                   [&](const mech::PointMass& m) { return m.name == pm.point_mass; });
      require(it != body.point_masses.end(), "vibration: {}: body '{}' has no point mass '{}'", pr.label, pr.body,
              pm.point_mass);
      const double z = fem::DistributingCoupling(*pr.mesh, pm.face_set).centroid().z();
      const Vector3d reference(it->position_body.x(), it->position_body.y(), z);
      // No rotary inertia: the planar model has none.
      detail::carry_point_mass(pr.interfaces, *pr.mesh, pm.face_set, reference, it->name, it->mass_kg,
                               Eigen::Matrix3d::Zero());
    }
    parts.push_back(std::move(pr));
  }

  // Rigid moving bodies: mass, centre of mass and I_zz of the multibody
  // model; I_xx = I_yy = I_zz / 2 (header).
  const mech::MultibodySystem system(model);
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].fixed) continue;
    if (std::any_of(parts.begin(), parts.end(), [&](const PartRed& p) { return p.body_index == int(b); })) continue;
    const mech::EffectiveBody& eff = system.effective(int(b));
    RigidRed rr;
    rr.body_index = int(b);
    const Vector3d c(eff.com_body.x(), eff.com_body.y(), 0.0);
    rr.mass = point_mass_6x6(eff.mass_kg, c);
    rr.mass.block<3, 3>(3, 3) += Eigen::Vector3d(0.5, 0.5, 1.0).asDiagonal() * eff.inertia_kgm2;
    require(eff.mass_kg > 0 && eff.inertia_kgm2 > 0,
            "vibration: rigid body '{}' has mass {} kg and inertia {} kg m^2: both must be positive for its modes",
            model.bodies[b].name, eff.mass_kg, eff.inertia_kgm2);
    log.info("vibration: rigid body '{}': {:.4g} kg, I_zz {:.4g} kg m^2 (I_xx = I_yy = I_zz / 2 assumed)",
             model.bodies[b].name, eff.mass_kg, eff.inertia_kgm2);
    rigid.push_back(rr);
  }

  // The part-mode rule.
  detail::PartRuleSteps steps;
  steps.parts = parts.size();
  steps.make_reducer = [this](size_t p) { return make_reducer(p); };
  steps.borrow = [this](size_t p) { borrow(p); };
  steps.give_back = [this](size_t p) { give_back(p); };
  steps.part_options = [this](size_t p, const vibration::CraigBamptonOptions& given) {
    return part_options(p, given);
  };
  steps.take = [this](size_t p, vibration::CraigBamptonModel cb) { take(p, std::move(cb)); };
  steps.static_fmax_hz = [&] {
    build_matrices();
    double fmax = 0.0;
    for (const mech::Frame& frame : poses)
      fmax = std::max(fmax, solve(frame, options.modes).frequency_hz(options.modes - 1));
    return fmax;
  };
  const detail::PartRuleResult rule = detail::reduce_parts_by_rule(options, poses.size(), steps, log);
  fmax_estimate = rule.fmax_estimate_hz;
  build_matrices();
  cutoff = rule.cutoff_hz;
}

fem::LinearStaticAnalysis& AssemblyModes::Impl::borrow(size_t p) {
  if (lender) return lender->lend(parts[p].body);
  fem::LinearStaticAnalysis& analysis = assembly.supported_analysis(parts[p].body);
  analysis.factorize();  // a no-op: the assembly's factor is alive
  return analysis;
}

void AssemblyModes::Impl::give_back(size_t p) {
  if (lender) lender->give_back(parts[p].body);
}

vibration::CraigBamptonReducer AssemblyModes::Impl::make_reducer(size_t p) {
  const PartRed& pr = parts[p];
  std::vector<vibration::PartInterface> interfaces;
  for (const CbInterface& i : pr.interfaces) interfaces.push_back({i.name, i.columns});
  // A part of the ground is reduced held: modes over the free equations. No
  // solve here: the factor is borrowed around the reductions.
  return vibration::CraigBamptonReducer(assembly.supported_analysis(pr.body), interfaces, pr.label, pr.held);
}

vibration::CraigBamptonOptions AssemblyModes::Impl::part_options(size_t p,
                                                                 const vibration::CraigBamptonOptions& given) const {
  vibration::CraigBamptonOptions cbo = given;
  cbo.eigen.label = parts[p].label;
  cbo.solver = options.fixed_interface_solver;
  return cbo;
}

void AssemblyModes::Impl::take(size_t p, vibration::CraigBamptonModel cb) {
  PartRed& pr = parts[p];
  pr.cb = std::move(cb);
  if (pr.held) {
    // Held: modes over the free equations, taken to the mesh's 3N DoFs
    // (zero on the foundation) like a free part's.
    const fem::DofMap& dofs = assembly.supported_analysis(pr.body).dofs();
    pr.cb.constraint_modes = vibration::expand_to_mesh_dofs(pr.cb.constraint_modes, dofs);
    pr.cb.normal_modes = vibration::expand_to_mesh_dofs(pr.cb.normal_modes, dofs);
    pr.cb.residual_vectors = vibration::expand_to_mesh_dofs(pr.cb.residual_vectors, dofs);
  }
  require(pr.cb.constraint_modes.rows() == 3 * pr.mesh->node_count(),
          "vibration: {}: the reduction is over {} equations, the mesh has {} DoFs", pr.label,
          pr.cb.constraint_modes.rows(), 3 * pr.mesh->node_count());
  MatrixXd T(pr.cb.constraint_modes.rows(), pr.cb.stiffness.rows());
  T << pr.cb.constraint_modes, pr.cb.normal_modes, pr.cb.residual_vectors;
  pr.basis_t_patterns = T.transpose() * pr.loads->pattern_forces();
  reports.resize(parts.size());
  reports[p] = {pr.body, pr.cb.free_dofs, pr.cb.boundary_count, pr.cb.mode_count, pr.cb.residual_count,
                pr.cb.cutoff_hz, pr.cb.first_dropped_hz, pr.cb.seconds};
}

void AssemblyModes::Impl::build_matrices() {
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
  for (const InterfaceInfo& info : infos) {
    InterfaceMap im;
    im.reference = info.reference_body_m;
    for (size_t p = 0; p < parts.size(); ++p)
      if (parts[p].body == info.body) {
        const PartRed& pr = parts[p];
        im.body_index = pr.body_index;
        im.part = int(p);
        for (size_t i = 0; i < pr.interfaces.size(); ++i)
          if (pr.interfaces[i].face_set == info.face_set) {
            im.column = pr.offset + pr.cb.interface_offset[i];
            im.arm = info.reference_body_m - pr.interfaces[i].reference;
          }
      }
    if (im.part < 0) {
      for (const RigidRed& r : rigid)
        if (body_names[size_t(r.body_index)] == info.body) {
          im.body_index = r.body_index;
          im.column = r.offset;
          im.arm = info.reference_body_m;
        }
      require(im.body_index >= 0, "vibration: interface '{}' is on body '{}', which is neither a part nor a rigid "
              "moving body", info.name, info.body);
    }
    map.push_back(im);
  }
}

// ---------------------------------------------------------------------------

AssemblyModes::AssemblyModes(const ElasticAssembly& assembly, const std::vector<structure::Part>& parts,
                             const mech::MultibodyModel& model, const AssemblyModesOptions& options,
                             const std::vector<mech::Frame>& poses, const Log& log, PartFactorLender* lender)
    : impl_(std::make_unique<Impl>(assembly, parts, model, options, poses, log, lender)) {}
AssemblyModes::~AssemblyModes() = default;
AssemblyModes::AssemblyModes(AssemblyModes&&) noexcept = default;
AssemblyModes& AssemblyModes::operator=(AssemblyModes&&) noexcept = default;

PoseModes AssemblyModes::modes(const mech::Frame& frame) const { return impl_->solve(frame, impl_->options.modes); }

Index AssemblyModes::size() const { return impl_->n; }
const MatrixXd& AssemblyModes::mass() const { return impl_->M; }

VectorXd AssemblyModes::load(const mech::Frame& frame) const {
  const Impl& im = *impl_;
  VectorXd F = VectorXd::Zero(im.n);
  for (const auto& pr : im.parts)
    F.segment(pr.offset, pr.size) = pr.basis_t_patterns * pr.loads->coefficients_at(frame).coefficients;
  if (!im.rigid.empty()) {
    const std::vector<Vector6d> loads = im.assembly.body_loads(frame);
    for (const auto& r : im.rigid)
      F.segment<6>(r.offset) = rotate6(rot_z(frame.bodies[size_t(r.body_index)].q.z())).transpose() *
                               loads[size_t(im.moving_index[size_t(r.body_index)])];
  }
  return F;
}

MatrixXd AssemblyModes::point_rows(const std::string& point, const mech::Frame& frame) const {
  const Impl& im = *impl_;
  for (size_t k = 0; k < im.infos.size(); ++k)
    if (im.infos[k].kind == "point" && im.infos[k].name == point)
      return im.interface_map(frame).middleRows(6 * Index(k), 3);
  fail("vibration: no tracked point '{}' in the elastic assembly", point);
}

VectorXd AssemblyModes::static_response(const mech::Frame& frame, const VectorXd& load) const {
  const Impl& im = *impl_;
  const InterfaceStructure is = im.assembly.interface_structure(frame);
  const MatrixXd U = im.interface_map(frame);
  const MatrixXd N = im.admissible(is, U);
  const MatrixXd Kc = N.transpose() * (im.K + U.transpose() * is.springs * U) * N;
  return N * Kc.ldlt().solve(N.transpose() * load);
}

std::vector<MatrixXd> AssemblyModes::part_fields(const VectorXd& x, const mech::Frame& frame) const {
  const Impl& im = *impl_;
  std::vector<MatrixXd> out;
  for (const auto& pr : im.parts) {
    const VectorXd xp = x.segment(pr.offset, pr.size);
    const Index nb = pr.cb.boundary_count, nq = pr.cb.mode_count, nx = pr.cb.residual_count;
    VectorXd u = pr.cb.constraint_modes * xp.head(nb);
    if (nq > 0) u += pr.cb.normal_modes * xp.segment(nb, nq);
    if (nx > 0) u += pr.cb.residual_vectors * xp.tail(nx);
    const Eigen::Matrix3d R = rot_z(frame.bodies[size_t(pr.body_index)].q.z());
    const Index N = pr.mesh->node_count();
    MatrixXd field(N, 3);
    for (Index i = 0; i < N; ++i) field.row(i) = (R * u.segment<3>(3 * i)).transpose();
    out.push_back(std::move(field));
  }
  return out;
}

const std::vector<PartReduction>& AssemblyModes::reductions() const { return impl_->reports; }
double AssemblyModes::cutoff_hz() const { return impl_->cutoff; }
double AssemblyModes::estimated_fmax_hz() const { return impl_->fmax_estimate; }

std::string AssemblyModes::check_rule(double highest_frequency_seen_hz) const {
  return detail::format_rule(impl_->options, impl_->cutoff, highest_frequency_seen_hz);
}

}  // namespace kinetofem::vibration
