#include "kinetofem/structure/spatial_elastic_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/LU>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "condensation_tools.hpp"

namespace kinetofem::structure {

using detail::Matrix6d;
using detail::rotate6;
using detail::skew;
using detail::transfer;
using Eigen::Vector3d;
namespace spatial = mech::spatial;

namespace {

const spatial::Joint& joint_named(const spatial::Model& model, const std::string& name) {
  for (const spatial::Joint& joint : model.joints)
    if (joint.name == name) return joint;
  fail("spatial elastic assembly: the mechanism has no joint '{}'", name);
}

}  // namespace

struct SpatialElasticAssembly::Impl {
  struct Interface {
    int body = -1, part = -1, local = -1;
    std::string name, face_set;
    Vector3d reference = Vector3d::Zero();  // body frame
  };
  struct PartData {
    std::string body, label;
    int body_index = -1;
    fem::FeModel supported;
    std::unique_ptr<fem::LinearStaticAnalysis> analysis;  // own, during set-up only
    fem::LinearStaticAnalysis* lent = nullptr;            // or the caller's
    loads::SpatialLinkDefinition load_definition;         // point masses and forces only
    std::unique_ptr<loads::SpatialLinkLoads> loads;
    std::vector<std::unique_ptr<fem::DistributingCoupling>> couplings;  // per local interface
    std::vector<int> interfaces;                                        // global, local order
    Eigen::MatrixXd G, ZG, F, Zp, GtZp, SG, Sp;
    Eigen::Matrix<double, 6, Eigen::Dynamic> Rp;  // patterns' resultants about the origin, body axes
  };
  // One side of a tie: interfaces and weights whose motions, carried rigidly
  // to the tie's point, are averaged (one interface, or a slider's two
  // bracketing stations); empty: the ground.
  using Side = std::vector<std::pair<int, double>>;
  struct SlideData {
    loads::SpatialSlideAttachment attachment;
    int drive = -1;             // model motion drive taken by the slide, or -1
    int land[2] = {-1, -1};     // guide interfaces: front, rear (-1: the ground)
    std::vector<int> stations;  // slider interfaces (elastic slider), station order
    int slider = -1;            // rigid slider: its interface at P_j
  };
  struct JointData {
    int joint = -1, body_i = -1, body_j = -1;
    int if_i = -1, if_j = -1;  // plain tie (-1: ground)
    const spatial::ConstraintBlock* block = nullptr;
    std::optional<SlideData> slide;
  };
  struct DriveData {
    int drive = -1, body_i = -1, body_j = -1, if_i = -1, if_j = -1;
    const spatial::ConstraintBlock* block = nullptr;
  };
  struct PointData {
    int body = -1, iface = -1;
  };
  struct Pose {
    std::vector<Eigen::Matrix3d> R;
    std::vector<Vector3d> origin;
    std::vector<Vector3d> P, arm;  // per interface: reference (world), offset from its body's origin (world axes)
  };
  struct Rows {
    std::vector<Eigen::RowVectorXd> C;
    std::vector<bool> rotation;
    std::vector<std::string> owner;
    std::vector<int> drive_row;  // per DriveData: its row
    // Springs (the chains): elongation g u, stiffness k; the chain's pose.
    std::vector<Eigen::RowVectorXd> spring_g;
    std::vector<double> spring_k;
    std::vector<ChainResult> chain;
  };
  // A chain (mech::spatial::JointType::Chain): a tension-only axial member
  // from the hinge (body_i's P_i, -1: the ground) to its tangent point on the
  // roller (body_j, centre P_j), in the plane normal to h_i.
  struct ChainData {
    int joint = -1, body_i = -1, body_j = -1, if_i = -1, if_j = -1;
    const spatial::ConstraintBlock* block = nullptr;
    double ea = 0.0;
  };

  Log log;
  SpatialAssemblyOptions options;
  spatial::System system;
  double length_scale = 1.0;
  std::vector<std::unique_ptr<PartData>> parts;
  std::vector<int> part_of_body, moving;
  int moving_count = 0;
  std::vector<Interface> interfaces;
  std::vector<std::vector<int>> interfaces_of_body;
  std::vector<JointData> joints;
  std::vector<ChainData> chains;
  std::vector<DriveData> drives;
  std::vector<PointData> points;
  std::vector<SpatialPart> given_parts;
  double setup_seconds = 0.0;

  Impl(const std::vector<SpatialPart>& given, const spatial::Model& model, SpatialAssemblyOptions o, const Log& l,
       const std::vector<fem::LinearStaticAnalysis*>& factorized);

  bool ground(int body) const { return moving[size_t(body)] < 0; }
  const std::string& body_name(int body) const { return system.model().bodies[size_t(body)].name; }
  int add_interface(int body, const std::string& name, const std::string& face_set, const Vector3d& reference);
  // The interface of attachment `item` (a joint or drive) on `body` at `point`
  // (body frame): its part's face set for it, or the rigid body's point; -1
  // on the ground.
  int attach(int body, const std::string& item, const Vector3d& point, const char* what);
  void add_joint(int j);
  void add_slide(JointData& jd, const loads::SpatialSlideAttachment& slide);
  void add_drive(int d);
  void add_point(const SpatialAssemblyPoint& point);
  void set_up_part(PartData& part);

  Pose pose_of(const spatial::Frame& frame) const;
  Rows rows_of(const spatial::Frame& frame, const Pose& pose) const;
  // The motion of a side carried to world point X: sum of w transfer(X - P_k) over its interfaces.
  void add_side(Eigen::RowVectorXd& row, const Side& side, const Eigen::Matrix<double, 1, 6>& e, const Vector3d& X,
                const Pose& pose, double sign) const;
  Side slider_side(const JointData& jd, const Vector3d& X, const Pose& pose, double t, const char* land) const;
  std::vector<Vector6d> body_loads(const spatial::Frame& frame) const;
  SpatialPoseSolution solve(const spatial::Frame& frame);
};

int SpatialElasticAssembly::Impl::add_interface(int body, const std::string& name, const std::string& face_set,
                                                const Vector3d& reference) {
  Interface iface;
  iface.body = body;
  iface.part = part_of_body[size_t(body)];
  iface.name = name;
  iface.face_set = face_set;
  iface.reference = reference;
  const int k = int(interfaces.size());
  if (iface.part >= 0) {
    PartData& part = *parts[size_t(iface.part)];
    iface.local = int(part.interfaces.size());
    try {
      part.couplings.push_back(std::make_unique<fem::DistributingCoupling>(part.supported.mesh, face_set));
    } catch (const Error& e) {
      fail("spatial elastic assembly: {}, {}: face set '{}': {}", part.label, name, face_set, e.what());
    }
    part.interfaces.push_back(k);
  }
  interfaces.push_back(std::move(iface));
  interfaces_of_body[size_t(body)].push_back(k);
  return k;
}

int SpatialElasticAssembly::Impl::attach(int body, const std::string& item, const Vector3d& point, const char* what) {
  if (ground(body)) return -1;
  const std::string name = fmt::format("{} '{}'", what, item);
  const int p = part_of_body[size_t(body)];
  if (p < 0) return add_interface(body, name, "", point);
  const PartData& part = *parts[size_t(p)];
  for (const loads::SpatialAttachment& a : part.load_definition.joints)
    if (a.name == item) return add_interface(body, name, a.face_set, point);
  fail("spatial elastic assembly: {} names no face set for {} (attachments.joints)", part.label, name);
}

SpatialElasticAssembly::Impl::Impl(const std::vector<SpatialPart>& given, const spatial::Model& model,
                                   SpatialAssemblyOptions o, const Log& l,
                                   const std::vector<fem::LinearStaticAnalysis*>& factorized)
    : log(l), options(std::move(o)), system(model), given_parts(given) {
  const spatial::Model& m = system.model();
  const size_t nb = m.bodies.size();
  part_of_body.assign(nb, -1);
  moving.assign(nb, -1);
  interfaces_of_body.assign(nb, {});
  for (size_t b = 0; b < nb; ++b)
    if (!m.bodies[b].fixed) moving[b] = moving_count++;
  length_scale = system.characteristic_length() > 0 ? system.characteristic_length() : 1.0;
  require(factorized.empty() || factorized.size() == given.size(),
          "spatial elastic assembly: {} factorizations lent for {} parts", factorized.size(), given.size());
  for (const SpatialPart& sp : given) {
    const std::string label = sp.label.empty() ? "part '" + sp.body() + "'" : sp.label;
    int body = -1;
    for (size_t b = 0; b < nb; ++b)
      if (m.bodies[b].name == sp.body()) body = int(b);
    require(body >= 0, "spatial elastic assembly: {}: the mechanism has no body '{}'", label, sp.body());
    require(!ground(body), "spatial elastic assembly: {}: a part of the ground (body '{}') is not modelled", label,
            sp.body());
    require(part_of_body[size_t(body)] < 0, "spatial elastic assembly: two parts of body '{}'", sp.body());
    auto part = std::make_unique<PartData>();
    part->body = sp.body();
    part->label = label;
    part->body_index = body;
    part->supported = spatial_supported_model(sp);
    if (!factorized.empty()) {
      part->lent = factorized[parts.size()];
      require(part->lent != nullptr && part->lent->is_factorized() &&
                  part->lent->model().mesh.node_count() == part->supported.mesh.node_count() &&
                  part->lent->model().supports.size() == part->supported.supports.size(),
              "spatial elastic assembly: {}: the factorization lent is not of the part with its 3-2-1 support", label);
    }
    // The part's own loads; its joints, drives and slides are the structure's.
    part->load_definition = sp.attachments;
    part->load_definition.model = &part->supported;
    loads::SpatialLinkDefinition own = part->load_definition;
    own.joints.clear();
    own.slides.clear();
    part->loads = std::make_unique<loads::SpatialLinkLoads>(own, m, std::numeric_limits<double>::infinity());
    part_of_body[size_t(body)] = int(parts.size());
    parts.push_back(std::move(part));
  }
  for (size_t j = 0; j < m.joints.size(); ++j) add_joint(int(j));
  for (size_t d = 0; d < m.motion_drives.size(); ++d) add_drive(int(d));
  for (const SpatialAssemblyPoint& p : options.points) add_point(p);
  for (size_t b = 0; b < nb; ++b)
    require(ground(int(b)) || !interfaces_of_body[b].empty(),
            "spatial elastic assembly: body '{}' is held by no joint or drive", m.bodies[b].name);
  Stopwatch clock;
  for (auto& part : parts) set_up_part(*part);
  setup_seconds = clock.seconds();
}

void SpatialElasticAssembly::Impl::add_joint(int j) {
  const spatial::Joint& joint = system.model().joints[size_t(j)];
  if (joint.type == spatial::JointType::Chain) {
    ChainData cd;
    cd.joint = j;
    cd.block = &system.block(joint.name);
    cd.body_i = cd.block->body_i;
    cd.body_j = cd.block->body_j;
    for (const ChainMember& member : options.chains)
      if (member.chain == joint.name) cd.ea = member.axial_stiffness_n;
    require(cd.ea > 0 && std::isfinite(cd.ea),
            "spatial elastic assembly: chain '{}' needs its axial stiffness EA > 0 (SpatialAssemblyOptions::chains)",
            joint.name);
    cd.if_i = attach(cd.body_i, joint.name, system.named_point(cd.body_i, joint.point_i), "joint");
    cd.if_j = attach(cd.body_j, joint.name, system.named_point(cd.body_j, joint.point_j), "joint");
    chains.push_back(cd);
    return;
  }
  JointData jd;
  jd.joint = j;
  jd.block = &system.block(joint.name);
  jd.body_i = jd.block->body_i;
  jd.body_j = jd.block->body_j;
  for (const auto& part : parts)
    for (const loads::SpatialSlideAttachment& s : part->load_definition.slides)
      if (s.joint == joint.name) {
        add_slide(jd, s);
        joints.push_back(std::move(jd));
        return;
      }
  jd.if_i = attach(jd.body_i, joint.name, system.named_point(jd.body_i, joint.point_i), "joint");
  jd.if_j = attach(jd.body_j, joint.name, system.named_point(jd.body_j, joint.point_j), "joint");
  joints.push_back(std::move(jd));
}

void SpatialElasticAssembly::Impl::add_slide(JointData& jd, const loads::SpatialSlideAttachment& slide) {
  const spatial::Joint& joint = system.model().joints[size_t(jd.joint)];
  require(joint.type == spatial::JointType::Prismatic,
          "spatial elastic assembly: slide '{}': the joint is not prismatic", joint.name);
  SlideData sd;
  sd.attachment = slide;
  if (!slide.drive.empty()) {
    const auto& drives_of_model = system.model().motion_drives;
    for (size_t d = 0; d < drives_of_model.size(); ++d)
      if (drives_of_model[d].name == slide.drive) sd.drive = int(d);
    require(sd.drive >= 0 && drives_of_model[size_t(sd.drive)].joint == joint.name &&
                drives_of_model[size_t(sd.drive)].coordinate == spatial::DriveCoordinate::Translation,
            "spatial elastic assembly: slide '{}': '{}' is not a motion drive of its translation", joint.name,
            slide.drive);
  }
  const Vector3d P_i = system.named_point(jd.body_i, joint.point_i);
  const double x[2] = {slide.front_m, slide.rear_m};
  const std::string* face[2] = {&slide.front_face_set, &slide.rear_face_set};
  const char* which[2] = {"front", "rear"};
  for (int L = 0; L < 2; ++L) {
    if (ground(jd.body_i)) continue;
    const std::string name = fmt::format("slide '{}' {} land", joint.name, which[L]);
    sd.land[L] = add_interface(jd.body_i, name, part_of_body[size_t(jd.body_i)] >= 0 ? *face[L] : "",
                               P_i + x[L] * jd.block->h_i);
  }
  const Vector3d P_j = system.named_point(jd.body_j, joint.point_j);
  if (part_of_body[size_t(jd.body_j)] >= 0) {
    require(!slide.stations.face_sets.empty(),
            "spatial elastic assembly: slide '{}': the slider's part has no stations on its slide face", joint.name);
    for (size_t s = 0; s < slide.stations.face_sets.size(); ++s)
      sd.stations.push_back(add_interface(jd.body_j, fmt::format("slide '{}' station {}", joint.name, s),
                                          slide.stations.face_sets[s], P_j + slide.stations.s_m[s] * jd.block->h_j));
  } else if (!ground(jd.body_j)) {
    sd.slider = add_interface(jd.body_j, fmt::format("slide '{}' slider", joint.name), "", P_j);
  }
  jd.slide = std::move(sd);
}

void SpatialElasticAssembly::Impl::add_drive(int d) {
  const spatial::MotionDrive& drive = system.model().motion_drives[size_t(d)];
  for (const JointData& jd : joints)
    if (jd.slide && jd.slide->drive == d) return;  // the slide's rows hold it
  DriveData dd;
  dd.drive = d;
  dd.block = &system.block(drive.name);
  dd.body_i = dd.block->body_i;
  dd.body_j = dd.block->body_j;
  const spatial::Joint& joint = joint_named(system.model(), drive.joint);
  dd.if_i = attach(dd.body_i, drive.name, system.named_point(dd.body_i, joint.point_i), "drive");
  dd.if_j = attach(dd.body_j, drive.name, system.named_point(dd.body_j, joint.point_j), "drive");
  drives.push_back(dd);
}

void SpatialElasticAssembly::Impl::add_point(const SpatialAssemblyPoint& p) {
  const std::string who = fmt::format("spatial elastic assembly: point '{}'", p.name);
  int body = -1;
  const auto& bodies = system.model().bodies;
  for (size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].name == p.body) body = int(b);
  require(body >= 0, "{}: the mechanism has no body '{}'", who, p.body);
  require(!ground(body), "{}: on the ground, which does not move", who);
  Vector3d at;
  try {
    at = system.named_point(body, p.point);
  } catch (const Error& e) {
    fail("{}: {}", who, e.what());
  }
  const bool elastic = part_of_body[size_t(body)] >= 0;
  require(!elastic || !p.face_set.empty(), "{}: on the part of body '{}' it needs the face set carrying it", who,
          p.body);
  PointData pd;
  pd.body = body;
  pd.iface = add_interface(body, fmt::format("point '{}'", p.name), elastic ? p.face_set : "", at);
  points.push_back(pd);
}

void SpatialElasticAssembly::Impl::set_up_part(PartData& part) {
  fem::FeModel& fe = part.supported;
  const fem::Index N = fe.mesh.node_count();
  log.info("spatial elastic assembly: part '{}': {} nodes, {} interfaces", part.body, N, part.interfaces.size());
  if (!part.lent) {
    part.analysis = std::make_unique<fem::LinearStaticAnalysis>(fe, log, options.solver);
    part.analysis->factorize();
  }
  fem::LinearStaticAnalysis& analysis = part.lent ? *part.lent : *part.analysis;
  const Eigen::Index m = Eigen::Index(part.interfaces.size());
  part.G = Eigen::MatrixXd::Zero(3 * N, 6 * m);
  for (Eigen::Index l = 0; l < m; ++l) {
    const Vector3d& X = interfaces[size_t(part.interfaces[size_t(l)])].reference;
    for (int c = 0; c < 3; ++c) {
      part.couplings[size_t(l)]->add(Vector3d::Unit(c), Vector3d::Zero(), X, part.G.col(6 * l + c));
      part.couplings[size_t(l)]->add(Vector3d::Zero(), Vector3d::Unit(c), X, part.G.col(6 * l + 3 + c));
    }
  }
  const Eigen::MatrixXd P = part.loads->pattern_forces();
  Eigen::MatrixXd B(3 * N, part.G.cols() + P.cols());
  B << part.G, P;
  const Eigen::MatrixXd Z = detail::solve_columns(analysis, B);
  part.ZG = Z.leftCols(part.G.cols());
  part.Zp = Z.rightCols(P.cols());
  part.F = part.G.transpose() * part.ZG;
  part.F = 0.5 * (part.F + part.F.transpose()).eval();
  part.GtZp = part.G.transpose() * part.Zp;
  part.Rp.resize(6, P.cols());
  for (Eigen::Index k = 0; k < P.cols(); ++k) {
    Vector3d force, moment;
    fem::resultant(fe.mesh, P.col(k), Vector3d::Zero(), force, moment);
    part.Rp.col(k) << force, moment;
  }
  if (options.recover_stress) {
    const fem::ElementMaterials materials = fem::element_materials(fe);
    part.SG = detail::nodal_stress_columns(fe.mesh, materials, part.ZG);
    part.Sp = detail::nodal_stress_columns(fe.mesh, materials, part.Zp);
  }
  // The factor is no longer needed: every pose is a product with these columns.
  part.analysis.reset();
  part.lent = nullptr;
}

SpatialElasticAssembly::Impl::Pose SpatialElasticAssembly::Impl::pose_of(const spatial::Frame& frame) const {
  const auto& bodies = system.model().bodies;
  require(frame.bodies.size() == bodies.size(),
          "spatial elastic assembly at t = {:.6g} s: the frame has {} bodies, the mechanism {}", frame.t,
          frame.bodies.size(), bodies.size());
  Pose pose;
  for (size_t b = 0; b < bodies.size(); ++b) {
    require(frame.bodies[b].name == bodies[b].name,
            "spatial elastic assembly at t = {:.6g} s: the frame is of another mechanism (body '{}')", frame.t,
            frame.bodies[b].name);
    pose.R.push_back(frame.bodies[b].rotation);
    pose.origin.push_back(frame.bodies[b].origin);
  }
  for (const Interface& iface : interfaces) {
    const Eigen::Matrix3d& R = pose.R[size_t(iface.body)];
    pose.arm.push_back(R * iface.reference);
    pose.P.push_back(pose.origin[size_t(iface.body)] + pose.arm.back());
  }
  return pose;
}

void SpatialElasticAssembly::Impl::add_side(Eigen::RowVectorXd& row, const Side& side,
                                            const Eigen::Matrix<double, 1, 6>& e, const Vector3d& X, const Pose& pose,
                                            double sign) const {
  for (const auto& [k, w] : side)
    if (k >= 0 && w != 0.0) row.segment<6>(6 * k) += sign * w * e * transfer(X - pose.P[size_t(k)]);
}

SpatialElasticAssembly::Impl::Side SpatialElasticAssembly::Impl::slider_side(const JointData& jd, const Vector3d& X,
                                                                             const Pose& pose, double t,
                                                                             const char* land) const {
  const SlideData& sd = *jd.slide;
  if (sd.stations.empty()) return {{sd.slider, 1.0}};
  const spatial::Joint& joint = system.model().joints[size_t(jd.joint)];
  const Vector3d local = pose.R[size_t(jd.body_j)].transpose() * (X - pose.origin[size_t(jd.body_j)]) -
                         system.named_point(jd.body_j, joint.point_j);
  const double s = jd.block->h_j.dot(local);
  const loads::StationBracket b = loads::bracket_station(
      sd.attachment.stations, s,
      fmt::format("spatial elastic assembly at t = {:.6g} s: slide '{}', the {} land (beyond the slider's stroke)", t,
                  joint.name, land));
  Side side{{sd.stations[size_t(b.a)], 1.0 - b.weight_b}};
  if (b.b != b.a) side.push_back({sd.stations[size_t(b.b)], b.weight_b});
  return side;
}

SpatialElasticAssembly::Impl::Rows SpatialElasticAssembly::Impl::rows_of(const spatial::Frame& frame,
                                                                         const Pose& pose) const {
  const Eigen::Index n = 6 * Eigen::Index(interfaces.size());
  Rows rows;
  auto unit = [](bool rotation, const Vector3d& direction) {
    Eigen::Matrix<double, 1, 6> e = Eigen::Matrix<double, 1, 6>::Zero();
    (rotation ? e.tail<3>() : e.head<3>()) = direction.transpose();
    return e;
  };
  auto add = [&](const Side& i, const Side& j, const Vector3d& X, bool rotation, const Vector3d& direction,
                 std::string owner) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    add_side(r, j, unit(rotation, direction), X, pose, 1.0);
    add_side(r, i, unit(rotation, direction), X, pose, -1.0);
    rows.C.push_back(std::move(r));
    rows.rotation.push_back(rotation);
    rows.owner.push_back(std::move(owner));
  };
  for (const JointData& jd : joints) {
    const spatial::Joint& joint = system.model().joints[size_t(jd.joint)];
    const Eigen::Matrix3d& Ri = pose.R[size_t(jd.body_i)];
    const Vector3d f = Ri * jd.block->f_i, g = Ri * jd.block->g_i, h = Ri * jd.block->h_i;
    if (jd.slide) {
      const SlideData& sd = *jd.slide;
      const Vector3d P_i = pose.origin[size_t(jd.body_i)] + Ri * system.named_point(jd.body_i, joint.point_i);
      const double x[2] = {sd.attachment.front_m, sd.attachment.rear_m};
      const char* which[2] = {"front", "rear"};
      for (int L = 0; L < 2; ++L) {
        const Vector3d X = P_i + x[L] * h;
        const Side guide{{sd.land[L], 1.0}};
        const Side slider = slider_side(jd, X, pose, frame.t, which[L]);
        add(guide, slider, X, false, f, fmt::format("slide '{}' {} land (f)", joint.name, which[L]));
        add(guide, slider, X, false, g, fmt::format("slide '{}' {} land (g)", joint.name, which[L]));
        if (L == 0) {
          // Along h only through the slide's drive: without one the slide is free.
          if (sd.drive >= 0)
            add(guide, slider, X, false, h, fmt::format("slide '{}' drive '{}'", joint.name, sd.attachment.drive));
          add(guide, slider, X, true, h, fmt::format("slide '{}' (rotation about h)", joint.name));
        }
      }
      continue;
    }
    const spatial::JointFacts& facts = spatial::joint_facts(joint.type);
    const Vector3d X = jd.if_j >= 0
                           ? pose.P[size_t(jd.if_j)]
                           : Vector3d(pose.origin[size_t(jd.body_j)] +
                                      pose.R[size_t(jd.body_j)] * system.named_point(jd.body_j, joint.point_j));
    const Side si{{jd.if_i, 1.0}}, sj{{jd.if_j, 1.0}};
    const Vector3d across[3] = {f, g, h};
    const char* axis_name[3] = {"f", "g", "h"};
    for (int c = 0; c < facts.forces; ++c)
      add(si, sj, X, false, across[c], fmt::format("joint '{}' (force along {})", joint.name, axis_name[c]));
    if (facts.moments == 1) {
      const Vector3d hj = pose.R[size_t(jd.body_j)] * jd.block->h_j;
      add(si, sj, X, true, h.cross(hj).normalized(), fmt::format("joint '{}' (moment about h_i x h_j)", joint.name));
    } else {
      for (int c = 0; c < facts.moments; ++c)
        add(si, sj, X, true, across[c], fmt::format("joint '{}' (moment about {})", joint.name, axis_name[c]));
    }
  }
  for (const ChainData& cd : chains) {
    const spatial::Joint& joint = system.model().joints[size_t(cd.joint)];
    const Eigen::Matrix3d& Ri = pose.R[size_t(cd.body_i)];
    const Vector3d f = Ri * cd.block->f_i, g = Ri * cd.block->g_i;
    const Vector3d hinge = pose.origin[size_t(cd.body_i)] + Ri * system.named_point(cd.body_i, joint.point_i);
    const Vector3d centre = pose.P[size_t(cd.if_j)];
    // In the chain's plane (f, g through the roller's centre).
    const Eigen::Vector2d hinge_2d((hinge - centre).dot(f), (hinge - centre).dot(g));
    require(hinge_2d.norm() > cd.block->radius_m,
            "spatial elastic assembly at t = {:.6g} s: chain '{}': the hinge lies within the roller", frame.t,
            joint.name);
    const mech::ChainTangent tangent =
        mech::chain_tangent(hinge_2d, Eigen::Vector2d::Zero(), cd.block->radius_m, cd.block->sigma);
    ChainResult cr;
    cr.chain = joint.name;
    cr.axial_stiffness_n = cd.ea;
    cr.free_length_m = tangent.free_length_m;
    cr.stiffness_n_per_m = cd.ea / tangent.free_length_m;
    cr.tangent_point_m = centre + tangent.tangent_point_m.x() * f + tangent.tangent_point_m.y() * g;
    cr.direction = (centre + hinge_2d.x() * f + hinge_2d.y() * g - cr.tangent_point_m).normalized();
    // elongation = n . (u_hinge - u_T), the hinge's and the tangent point's motions.
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    add_side(r, {{cd.if_j, 1.0}}, unit(false, cr.direction), cr.tangent_point_m, pose, -1.0);
    add_side(r, {{cd.if_i, 1.0}}, unit(false, cr.direction), hinge, pose, 1.0);
    rows.spring_g.push_back(std::move(r));
    rows.spring_k.push_back(cr.stiffness_n_per_m);
    rows.chain.push_back(cr);
  }
  for (const DriveData& dd : drives) {
    const spatial::MotionDrive& drive = system.model().motion_drives[size_t(dd.drive)];
    const Vector3d h = pose.R[size_t(dd.body_i)] * dd.block->h_i;
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    const bool rotation = drive.coordinate == spatial::DriveCoordinate::Rotation;
    if (rotation) {
      if (dd.if_j >= 0) r.segment<3>(6 * dd.if_j + 3) += h.transpose();
      if (dd.if_i >= 0) r.segment<3>(6 * dd.if_i + 3) -= h.transpose();
    } else {
      const spatial::Joint& joint = joint_named(system.model(), drive.joint);
      auto world = [&](int k, int body, const std::string& point) {
        return k >= 0 ? pose.P[size_t(k)]
                      : Vector3d(pose.origin[size_t(body)] + pose.R[size_t(body)] * system.named_point(body, point));
      };
      const Vector3d d = world(dd.if_j, dd.body_j, joint.point_j) - world(dd.if_i, dd.body_i, joint.point_i);
      if (dd.if_j >= 0) r.segment<3>(6 * dd.if_j) += h.transpose();
      if (dd.if_i >= 0) {
        r.segment<3>(6 * dd.if_i) -= h.transpose();
        r.segment<3>(6 * dd.if_i + 3) += h.cross(d).transpose();
      }
    }
    rows.drive_row.push_back(int(rows.C.size()));
    rows.C.push_back(std::move(r));
    rows.rotation.push_back(rotation);
    rows.owner.push_back(fmt::format("drive '{}'", drive.name));
  }
  return rows;
}

// Per moving body: its applied minus inertia loads at the frame (world axes,
// force and moment about the body's origin), which the multibody solution
// balances with the loads of its joints and drives: minus their sum.
std::vector<Vector6d> SpatialElasticAssembly::Impl::body_loads(const spatial::Frame& frame) const {
  std::vector<Vector6d> out(size_t(moving_count), Vector6d::Zero());
  auto add = [&](const spatial::Reaction& r) {
    int b = -1;
    for (size_t k = 0; k < frame.bodies.size(); ++k)
      if (frame.bodies[k].name == r.body) b = int(k);
    if (b < 0 || ground(b)) return;
    Vector6d& l = out[size_t(moving[size_t(b)])];
    l.head<3>() -= r.force_world;
    l.tail<3>() -= r.moment_world + (r.point_world - frame.bodies[size_t(b)].origin).cross(r.force_world);
  };
  for (const spatial::JointState& j : frame.joints) {
    add(j.on_i);
    add(j.on_j);
  }
  for (const spatial::DriveState& d : frame.drives) {
    add(d.on_i);
    add(d.on_j);
  }
  return out;
}

SpatialPoseSolution SpatialElasticAssembly::Impl::solve(const spatial::Frame& frame) {
  const Pose pose = pose_of(frame);
  const Rows rows = rows_of(frame, pose);
  const int M = int(interfaces.size()), B = moving_count, nc = int(rows.C.size());
  const int ou = 0, ol = 6 * M, oa = 12 * M, om = 12 * M + 6 * B, n = om + nc;
  const double Lr = length_scale;

  // The loads: per part its pattern coefficients, the interface
  // displacements d they cause and their resultant; per body the multibody
  // applied-minus-inertia loads (the check, and the rigid bodies' loads).
  const std::vector<Vector6d> from_multibody = body_loads(frame);
  std::vector<Eigen::VectorXd> coefficients(parts.size());
  std::vector<Vector6d> resultant = from_multibody;
  for (size_t p = 0; p < parts.size(); ++p) {
    PartData& part = *parts[p];
    coefficients[p] = part.loads->coefficients_at(frame).coefficients;
    const Vector6d r_body = part.Rp * coefficients[p];
    const Eigen::Matrix3d& R = pose.R[size_t(part.body_index)];
    Vector6d r_world;
    r_world << R * r_body.head<3>(), R * r_body.tail<3>();
    const Vector6d& expected = from_multibody[size_t(moving[size_t(part.body_index)])];
    const double size = std::max({expected.head<3>().norm(), expected.tail<3>().norm() / Lr, r_world.head<3>().norm(),
                                  r_world.tail<3>().norm() / Lr, 1e-300});
    const Vector6d diff = r_world - expected;
    const double mismatch = std::max(diff.head<3>().norm(), diff.tail<3>().norm() / Lr) / size;
    require(!(mismatch > options.load_check_tolerance),
            "spatial elastic assembly at t = {:.6g} s: {}: the resultant of its loads differs from its body's applied "
            "minus inertia loads by {:.3g} of their size (a load acting on the body that the part does not carry, "
            "e.g. a spring or a force drive, or mass properties that are not the mesh's)",
            frame.t, part.label, mismatch);
    resultant[size_t(moving[size_t(part.body_index)])] = r_world;
  }

  // Scales of the unknowns and equations (forces P, displacements U, length Lr).
  double P = 0.0;
  for (const Vector6d& r : resultant) P = std::max({P, r.head<3>().norm(), r.tail<3>().norm() / Lr});
  if (!(P > 0)) P = 1.0;
  double compliance = 0.0;
  for (const auto& part : parts)
    for (Eigen::Index k = 0; k < part->F.rows(); ++k)
      if (k % 6 < 3) compliance = std::max(compliance, part->F(k, k));
  for (const double k : rows.spring_k) compliance = std::max(compliance, 1.0 / k);
  const double U = compliance > 0 ? compliance * P : Lr;

  // Interfaces that no row ties and no point loads (a slider's stations away
  // from the lands in this pose) carry no load: lambda = 0; they are left out
  // of the system (cu, cl, ca, cm: its blocks over the active ones).
  std::vector<int> slot(size_t(M), -1), active;
  for (int k = 0; k < M; ++k) {
    bool used = false;
    for (const Eigen::RowVectorXd& r : rows.C) used = used || r.segment<6>(6 * k).cwiseAbs().maxCoeff() > 0.0;
    for (const Eigen::RowVectorXd& r : rows.spring_g) used = used || r.segment<6>(6 * k).cwiseAbs().maxCoeff() > 0.0;
    for (const PointData& pd : points) used = used || pd.iface == k;
    if (used) {
      slot[size_t(k)] = int(active.size());
      active.push_back(k);
    }
  }
  const int Ma = int(active.size());
  const int cu = 0, cl = 6 * Ma, ca = 12 * Ma, cm = 12 * Ma + 6 * B, nn = cm + nc;
  const int ncols = 1 + (options.unit_load_split ? 3 * int(points.size()) : 0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nn, nn);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nn, ncols);
  for (int a = 0; a < Ma; ++a) {
    const int k = active[size_t(a)];
    const Interface& iface = interfaces[size_t(k)];
    const int mb = moving[size_t(iface.body)];
    // (a) u_k - Q F Q^T lambda - T(arm) alpha = Q d
    A.block<6, 6>(cu + 6 * a, cu + 6 * a).setIdentity();
    A.block<6, 6>(cu + 6 * a, ca + 6 * mb) = -transfer(pose.arm[size_t(k)]);
    if (iface.part >= 0) {
      const PartData& part = *parts[size_t(iface.part)];
      const Matrix6d Q = rotate6(pose.R[size_t(iface.body)]);
      for (size_t l = 0; l < part.interfaces.size(); ++l)
        if (const int b = slot[size_t(part.interfaces[l])]; b >= 0)
          A.block<6, 6>(cu + 6 * a, cl + 6 * b) =
              -Q * part.F.block<6, 6>(6 * iface.local, 6 * Eigen::Index(l)) * Q.transpose();
      const Vector6d d = part.GtZp.middleRows<6>(6 * iface.local) * coefficients[size_t(iface.part)];
      rhs.block<6, 1>(cu + 6 * a, 0) = Q * d;
    }
    // (b) lambda_k - (C^T mu)_k = external load at k (the unit loads of the split)
    A.block<6, 6>(cl + 6 * a, cl + 6 * a).setIdentity();
    // (c) sum_k T(arm_k)^T lambda_k = -r_b
    A.block<6, 6>(ca + 6 * mb, cl + 6 * a) = transfer(pose.arm[size_t(k)]).transpose();
  }
  for (int b = 0; b < B; ++b) rhs.block<6, 1>(ca + 6 * b, 0) = -resultant[size_t(b)];
  for (int r = 0; r < nc; ++r)
    for (int a = 0; a < Ma; ++a) {
      const auto c = rows.C[size_t(r)].segment<6>(6 * active[size_t(a)]);
      A.block<6, 1>(cl + 6 * a, cm + r) = -c.transpose();
      A.block<1, 6>(cm + r, cu + 6 * a) = c;  // (d) C u = 0
    }
  // (b) with the springs: lambda + S u - C^T mu = external load, S = sum k g^T g
  for (size_t sp = 0; sp < rows.spring_g.size(); ++sp) {
    Eigen::RowVectorXd ga(6 * Ma);
    for (int a = 0; a < Ma; ++a) ga.segment<6>(6 * a) = rows.spring_g[sp].segment<6>(6 * active[size_t(a)]);
    A.block(cl, cu, 6 * Ma, 6 * Ma) += rows.spring_k[sp] * ga.transpose() * ga;
  }
  if (options.unit_load_split)
    for (size_t p = 0; p < points.size(); ++p)
      for (int c = 0; c < 3; ++c) rhs(cl + 6 * slot[size_t(points[p].iface)] + c, 1 + 3 * Eigen::Index(p) + c) = 1.0;

  Eigen::VectorXd var(nn), eq(nn);
  for (int k = 0; k < 6 * Ma; ++k) {
    const bool rot = k % 6 >= 3;
    var(cu + k) = eq(cu + k) = rot ? U / Lr : U;
    var(cl + k) = eq(cl + k) = rot ? P * Lr : P;
  }
  for (int k = 0; k < 6 * B; ++k) {
    const bool rot = k % 6 >= 3;
    var(ca + k) = rot ? U / Lr : U;
    eq(ca + k) = rot ? P * Lr : P;
  }
  for (int r = 0; r < nc; ++r) {
    var(cm + r) = rows.rotation[size_t(r)] ? P * Lr : P;
    eq(cm + r) = rows.rotation[size_t(r)] ? U / Lr : U;
  }
  Eigen::VectorXd Dr = eq.cwiseInverse(), Dc = var;
  Eigen::MatrixXd As = Dr.asDiagonal() * A * Dc.asDiagonal();
  detail::ruiz_equilibrate(As, Dr, Dc);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(As);
  lu.setThreshold(options.rank_tolerance);
  const int rank = int(lu.rank());
  if (rank < nn) {
    const Eigen::MatrixXd kernel = lu.kernel();
    std::vector<std::string> free;
    // The bodies whose rigid motion the kernel moves (scaled unknowns).
    for (Eigen::Index c = 0; c < kernel.cols(); ++c) {
      const double largest = kernel.col(c).cwiseAbs().maxCoeff();
      for (size_t b = 0; b < moving.size(); ++b)
        if (!ground(int(b)) && kernel.col(c).segment<6>(ca + 6 * moving[b]).cwiseAbs().maxCoeff() > 1e-3 * largest &&
            std::find(free.begin(), free.end(), body_name(int(b))) == free.end())
          free.push_back(body_name(int(b)));
    }
    std::string names;
    for (const std::string& b : free) names += (names.empty() ? "'" : ", '") + b + "'";
    fail(
        "spatial elastic assembly at t = {:.6g} s: the structure is a mechanism (rank {} of {}): nothing holds the "
        "motion of bod{} {} (a joint or drive missing, or a slide without its drive)",
        frame.t, rank, nn, free.size() == 1 ? "y" : "ies", names.empty() ? std::string("?") : names);
  }
  const Eigen::MatrixXd bs = Dr.asDiagonal() * rhs;
  const Eigen::MatrixXd y = lu.solve(bs);
  const Eigen::MatrixXd Xa = Dc.asDiagonal() * y;
  // Back to every interface (the inactive ones: no load, motion not needed).
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, ncols);
  for (int a = 0; a < Ma; ++a) {
    X.middleRows<6>(ou + 6 * active[size_t(a)]) = Xa.middleRows<6>(cu + 6 * a);
    X.middleRows<6>(ol + 6 * active[size_t(a)]) = Xa.middleRows<6>(cl + 6 * a);
  }
  X.middleRows(oa, 6 * B) = Xa.middleRows(ca, 6 * B);
  X.middleRows(om, nc) = Xa.middleRows(cm, nc);
  const Eigen::VectorXd x = X.col(0);

  SpatialPoseSolution out;
  out.t = frame.t;
  out.unknowns = nn;
  out.rank = rank;
  out.relative_residual =
      bs.col(0).norm() > 0 ? (As * y.col(0) - bs.col(0)).norm() / bs.col(0).norm() : (As * y.col(0)).norm();
  require(std::isfinite(out.relative_residual) && x.allFinite(),
          "spatial elastic assembly at t = {:.6g} s: the solution is not finite", frame.t);

  for (size_t b = 0; b < moving.size(); ++b) {
    if (ground(int(b))) continue;
    BodyMotion bm;
    bm.body = body_name(int(b));
    bm.elastic = part_of_body[b] >= 0;
    bm.translation_m = x.segment<3>(oa + 6 * moving[b]);
    bm.rotation_rad = x.segment<3>(oa + 6 * moving[b] + 3);
    out.bodies.push_back(bm);
  }

  // Fields of the parts: u = R (Z_G lambda_b + Z_p c) + rigid(alpha).
  for (size_t p = 0; p < parts.size(); ++p) {
    const PartData& part = *parts[p];
    const Eigen::Matrix3d& R = pose.R[size_t(part.body_index)];
    const Matrix6d Q = rotate6(R);
    // Only the interfaces tied in this pose carry load: their columns alone.
    Eigen::VectorXd u_body = part.Zp * coefficients[p];
    Eigen::VectorXd stress;
    if (options.recover_stress) stress = part.Sp * coefficients[p];
    for (size_t l = 0; l < part.interfaces.size(); ++l) {
      const int k = part.interfaces[l];
      if (slot[size_t(k)] < 0) continue;
      const Vector6d lambda = Q.transpose() * x.segment<6>(ol + 6 * k);
      u_body.noalias() += part.ZG.middleCols<6>(6 * Eigen::Index(l)) * lambda;
      if (options.recover_stress) stress.noalias() += part.SG.middleCols<6>(6 * Eigen::Index(l)) * lambda;
    }
    const fem::Mesh& mesh = part.supported.mesh;
    const fem::Index N = mesh.node_count();
    const Vector6d alpha = x.segment<6>(oa + 6 * moving[size_t(part.body_index)]);
    PartField field;
    field.body = part.body;
    field.displacement_m.resize(N, 3);
    for (fem::Index i = 0; i < N; ++i) {
      const Vector3d arm = R * mesh.nodes.row(i).transpose();
      const Vector3d u = R * u_body.segment<3>(3 * i) + alpha.head<3>() + alpha.tail<3>().cross(arm);
      field.displacement_m.row(i) = u.transpose();
      const double magnitude = u.norm();
      if (magnitude > field.max_displacement_m) {
        field.max_displacement_m = magnitude;
        field.max_displacement_node = i;
      }
    }
    if (options.recover_stress) {
      field.von_mises_pa.resize(N);
      for (fem::Index i = 0; i < N; ++i) field.von_mises_pa(i) = fem::von_mises(stress.segment<6>(6 * i));
    }
    if (field.max_displacement_m > out.max_displacement_m) {
      out.max_displacement_m = field.max_displacement_m;
      out.max_displacement_body = part.body;
    }
    out.parts.push_back(std::move(field));
  }

  // Joint loads: each side's interfaces' loads carried to its joint point;
  // the ground's side, minus the other's.
  auto side_load = [&](const std::vector<int>& on, const Vector3d& at, Vector3d& force, Vector3d& moment) {
    force.setZero();
    moment.setZero();
    for (const int k : on) {
      if (k < 0) continue;
      const Vector3d f = x.segment<3>(ol + 6 * k);
      force += f;
      moment += x.segment<3>(ol + 6 * k + 3) + (pose.P[size_t(k)] - at).cross(f);
    }
  };
  for (const JointData& jd : joints) {
    const spatial::Joint& joint = system.model().joints[size_t(jd.joint)];
    SpatialJointLoad jl;
    jl.joint = joint.name;
    jl.body_i = body_name(jd.body_i);
    jl.body_j = body_name(jd.body_j);
    jl.point_i_m =
        pose.origin[size_t(jd.body_i)] + pose.R[size_t(jd.body_i)] * system.named_point(jd.body_i, joint.point_i);
    jl.point_j_m =
        pose.origin[size_t(jd.body_j)] + pose.R[size_t(jd.body_j)] * system.named_point(jd.body_j, joint.point_j);
    std::vector<int> on_i{jd.if_i}, on_j{jd.if_j};
    if (jd.slide) {
      on_i = {jd.slide->land[0], jd.slide->land[1]};
      on_j = jd.slide->stations.empty() ? std::vector<int>{jd.slide->slider} : jd.slide->stations;
    }
    side_load(on_i, jl.point_i_m, jl.force_on_i_n, jl.moment_on_i_nm);
    side_load(on_j, jl.point_j_m, jl.force_on_j_n, jl.moment_on_j_nm);
    if (ground(jd.body_i)) {
      jl.force_on_i_n = -jl.force_on_j_n;
      jl.moment_on_i_nm = -(jl.moment_on_j_nm + (jl.point_j_m - jl.point_i_m).cross(jl.force_on_j_n));
    } else if (ground(jd.body_j)) {
      jl.force_on_j_n = -jl.force_on_i_n;
      jl.moment_on_j_nm = -(jl.moment_on_i_nm + (jl.point_i_m - jl.point_j_m).cross(jl.force_on_i_n));
    }
    out.joints.push_back(jl);
  }
  for (size_t sp = 0; sp < rows.chain.size(); ++sp) {
    ChainResult cr = rows.chain[sp];
    cr.elongation_m = rows.spring_g[sp].dot(X.col(0).segment(ou, 6 * M));
    cr.tension_n = cr.stiffness_n_per_m * cr.elongation_m;
    require(cr.tension_n > 0, "spatial elastic assembly at t = {:.6g} s: chain '{}' is slack (tension {:.6g} N)",
            frame.t, cr.chain, cr.tension_n);
    out.chains.push_back(cr);
  }
  for (size_t d = 0; d < drives.size(); ++d)
    out.drives.push_back({system.model().motion_drives[size_t(drives[d].drive)].name, x(om + rows.drive_row[d])});

  // Tracked points: displacement, rotation, compliance and the parts' shares
  // (unit-load method: lambda_v^T (F lambda + d) over each part's interfaces).
  for (size_t p = 0; p < points.size(); ++p) {
    const PointData& pd = points[p];
    PointResult pr;
    pr.name = options.points[p].name;
    pr.body = options.points[p].body;
    pr.position_m = pose.P[size_t(pd.iface)];
    pr.displacement_m = x.segment<3>(ou + 6 * pd.iface);
    pr.rotation_rad = x.segment<3>(ou + 6 * pd.iface + 3);
    pr.coupling_displacement_m = pr.displacement_m;
    if (options.unit_load_split) {
      for (int c = 0; c < 3; ++c)
        pr.compliance_m_per_n.col(c) = X.col(1 + 3 * Eigen::Index(p) + c).segment<3>(ou + 6 * pd.iface);
      for (size_t q = 0; q < parts.size(); ++q) {
        const PartData& part = *parts[q];
        const Matrix6d Q = rotate6(pose.R[size_t(part.body_index)]);
        const Eigen::Index m6 = 6 * Eigen::Index(part.interfaces.size());
        Eigen::VectorXd lambda(m6);
        Eigen::MatrixXd virtual_lambda(m6, 3);
        for (size_t l = 0; l < part.interfaces.size(); ++l) {
          const int k = part.interfaces[l];
          lambda.segment<6>(6 * Eigen::Index(l)) = Q.transpose() * x.segment<6>(ol + 6 * k);
          for (int c = 0; c < 3; ++c)
            virtual_lambda.block<6, 1>(6 * Eigen::Index(l), c) =
                Q.transpose() * X.col(1 + 3 * Eigen::Index(p) + c).segment<6>(ol + 6 * k);
        }
        const Eigen::VectorXd deformation = part.F * lambda + part.GtZp * coefficients[q];
        pr.contributions.push_back({"part." + part.body, virtual_lambda.transpose() * deformation});
      }
      // A chain: N_v N / k = k (g u_v)(g u).
      for (size_t sp = 0; sp < rows.chain.size(); ++sp) {
        const double real = rows.spring_g[sp].dot(X.col(0).segment(ou, 6 * M));
        Vector3d share;
        for (int c = 0; c < 3; ++c)
          share(c) =
              rows.spring_k[sp] * rows.spring_g[sp].dot(X.col(1 + 3 * Eigen::Index(p) + c).segment(ou, 6 * M)) * real;
        pr.contributions.push_back({"chain." + rows.chain[sp].chain, share});
      }
    }
    out.points.push_back(std::move(pr));
  }
  return out;
}

// ---------------------------------------------------------------------------

SpatialElasticAssembly::SpatialElasticAssembly(const std::vector<SpatialPart>& parts, const spatial::Model& model,
                                               SpatialAssemblyOptions options, const Log& log,
                                               const std::vector<fem::LinearStaticAnalysis*>& factorized)
    : impl_(std::make_unique<Impl>(parts, model, std::move(options), log, factorized)) {}
SpatialElasticAssembly::~SpatialElasticAssembly() = default;
SpatialElasticAssembly::SpatialElasticAssembly(SpatialElasticAssembly&&) noexcept = default;
SpatialElasticAssembly& SpatialElasticAssembly::operator=(SpatialElasticAssembly&&) noexcept = default;

SpatialPoseSolution SpatialElasticAssembly::solve(const spatial::Frame& frame) { return impl_->solve(frame); }

std::vector<SpatialPoseSolution> SpatialElasticAssembly::solve(const std::vector<spatial::Frame>& frames) {
  std::vector<SpatialPoseSolution> out;
  out.reserve(frames.size());
  for (const spatial::Frame& frame : frames) out.push_back(impl_->solve(frame));
  return out;
}

std::vector<SpatialInterfaceInfo> SpatialElasticAssembly::interfaces() const {
  std::vector<SpatialInterfaceInfo> out;
  for (const auto& iface : impl_->interfaces)
    out.push_back({impl_->body_name(iface.body), iface.name, iface.face_set, iface.reference});
  return out;
}

InterfaceStructure SpatialElasticAssembly::interface_structure(const spatial::Frame& frame) const {
  const Impl::Pose pose = impl_->pose_of(frame);
  const Impl::Rows rows = impl_->rows_of(frame, pose);
  InterfaceStructure out;
  out.body_rotation = pose.R;
  out.interface_arm_m = pose.arm;
  const Eigen::Index n = 6 * Eigen::Index(impl_->interfaces.size());
  out.constraints.resize(Eigen::Index(rows.C.size()), n);
  for (size_t r = 0; r < rows.C.size(); ++r) out.constraints.row(Eigen::Index(r)) = rows.C[r];
  out.constraint_owner = rows.owner;
  out.springs = Eigen::MatrixXd::Zero(n, n);
  for (size_t sp = 0; sp < rows.spring_g.size(); ++sp)
    out.springs.noalias() += rows.spring_k[sp] * rows.spring_g[sp].transpose() * rows.spring_g[sp];
  return out;
}

const std::vector<SpatialPart>& SpatialElasticAssembly::parts() const { return impl_->given_parts; }

const Eigen::MatrixXd& SpatialElasticAssembly::flexibility(const std::string& body) const {
  for (const auto& part : impl_->parts)
    if (part->body == body) return part->F;
  fail("spatial elastic assembly: body '{}' has no elastic part", body);
}

const fem::FeModel& SpatialElasticAssembly::supported_model(const std::string& body) const {
  for (const auto& part : impl_->parts)
    if (part->body == body) return part->supported;
  fail("spatial elastic assembly: body '{}' has no elastic part", body);
}

const Eigen::MatrixXd& SpatialElasticAssembly::interface_columns(const std::string& body) const {
  for (const auto& part : impl_->parts)
    if (part->body == body) return part->G;
  fail("spatial elastic assembly: body '{}' has no elastic part", body);
}

Eigen::VectorXd SpatialElasticAssembly::part_loads(const std::string& body, const spatial::Frame& frame) const {
  for (const auto& part : impl_->parts)
    if (part->body == body) return part->loads->loads_at(frame);
  fail("spatial elastic assembly: body '{}' has no elastic part", body);
}

std::vector<Vector6d> SpatialElasticAssembly::body_loads(const spatial::Frame& frame) const {
  return impl_->body_loads(frame);
}

double SpatialElasticAssembly::setup_seconds() const { return impl_->setup_seconds; }

namespace {
template <class T>
const T& named_in(const std::vector<T>& items, const std::string& name, std::string T::*key, const char* what) {
  for (const T& item : items)
    if (item.*key == name) return item;
  fail("spatial elastic assembly: the pose has no {} '{}'", what, name);
}
}  // namespace

const PartField& SpatialPoseSolution::part(const std::string& body) const& {
  return named_in(parts, body, &PartField::body, "part");
}
const SpatialJointLoad& SpatialPoseSolution::joint(const std::string& name) const& {
  return named_in(joints, name, &SpatialJointLoad::joint, "joint");
}
const PointResult& SpatialPoseSolution::point(const std::string& name) const& {
  return named_in(points, name, &PointResult::name, "point");
}

}  // namespace kinetofem::structure
