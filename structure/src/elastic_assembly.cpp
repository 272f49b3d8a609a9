#include "kinetofem/structure/elastic_assembly.hpp"

#include "kinetofem/structure/rigid_bore.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "condensation_tools.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/ranges.h>
#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/loads/iso_fit.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/solver/blas_threads.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/dense_product.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::structure {

namespace {

using detail::Matrix6d;
using detail::rotate6;
using detail::skew;
using detail::solve_columns;
using detail::transfer;
using Eigen::Vector2d;
using Eigen::Vector3d;

// Poses per block of ElasticAssembly::solve when every part's fields are
// formed over chunks of nodes (MotionFields): the chunks' copies of the
// pattern rows are shared by the block's poses.
constexpr size_t kChunkedPosesPerBlock = 256;

Eigen::Matrix3d rot_z(double theta) { return Eigen::AngleAxisd(theta, Vector3d::UnitZ()).toRotationMatrix(); }

Vector3d lift(const Vector2d& v, double z = 0.0) { return Vector3d(v.x(), v.y(), z); }

double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

const char* const kComponent[6] = {"x", "y", "z", "rx", "ry", "rz"};

}  // namespace

// ---------------------------------------------------------------------------

const char* name_of(BoreCoupling coupling) {
  return coupling == BoreCoupling::RigidBore ? "rigid_bore" : "distributing";
}

const PartField& PoseSolution::part(const std::string& name) const& {
  for (const auto& p : parts)
    if (p.body == name) return p;
  fail("elastic assembly: no part of body '{}'", name);
}
const JointLoad& PoseSolution::joint(const std::string& name) const& {
  for (const auto& j : joints)
    if (j.joint == name) return j;
  fail("elastic assembly: no joint '{}'", name);
}
const PointResult& PoseSolution::point(const std::string& name) const& {
  for (const auto& p : points)
    if (p.name == name) return p;
  fail("elastic assembly: no tracked point '{}'", name);
}
const ChainResult& PoseSolution::chain(const std::string& name) const& {
  for (const auto& c : chains)
    if (c.chain == name) return c;
  fail("elastic assembly: no chain '{}'", name);
}
const DriveResult& PoseSolution::drive(const std::string& name) const& {
  for (const auto& d : drives)
    if (d.drive == name) return d;
  fail("elastic assembly: no motion drive '{}'", name);
}
const TransmissionResult& PoseSolution::transmission(const std::string& name) const& {
  for (const auto& t : transmissions)
    if (t.transmission == name) return t;
  fail("elastic assembly: no transmission '{}'", name);
}
const PinResult& PoseSolution::pin(const std::string& joint) const& {
  for (const auto& p : pins)
    if (p.joint == joint) return p;
  fail("elastic assembly: no elastic pin at joint '{}'", joint);
}
const BodyMotion& PoseSolution::body(const std::string& name) const& {
  for (const auto& b : bodies)
    if (b.body == name) return b;
  fail("elastic assembly: no moving body '{}'", name);
}

// ---------------------------------------------------------------------------

struct ElasticAssembly::Impl {
  enum class Kind { Joint, Drive, Point };
  struct Interface {
    int body = -1, part = -1, local = -1;
    Kind kind = Kind::Joint;
    std::string name, face_set;
    Vector3d reference = Vector3d::Zero();  // body frame
  };
  struct PartData {
    std::string body, label;
    int body_index = -1;
    // The frame (a part of the ground): held on its foundation, so it has no
    // rigid motion alpha and no equilibrium rows (the foundation takes the
    // resultant); its interfaces move by G^T u of the held model alone.
    bool held = false;
    fem::FeModel supported;
    loads::LinkDefinition attachments;  // as given (joints, drives and all)
    std::unique_ptr<fem::LinearStaticAnalysis> own_analysis;
    fem::LinearStaticAnalysis* analysis = nullptr;  // own_analysis or one given (shared with the per-part stage)
    fem::LinearStaticAnalysis* given_analysis = nullptr;
    std::unique_ptr<RigidBoreCondensation> rigid;  // BoreCoupling::RigidBore: replaces G, Z_G, F
    std::unique_ptr<loads::LinkLoads> loads;
    std::vector<std::unique_ptr<fem::DistributingCoupling>> couplings;  // per local interface
    std::vector<int> interfaces;                                        // global indices, local order
    Eigen::MatrixXd G, ZG, F;                                           // 3N x 6m, 3N x 6m, 6m x 6m (body axes)
    // Unit-load superposition (AssemblyOptions::superpose_loads): the load
    // patterns P of `loads` solved once, Z_p = K_s^-1 P (3N x p), their
    // resultants (force; moment about the origin, body axes), and the nodal
    // stresses of Z_G's and Z_p's columns (6N x 6m, 6N x p), so a pose costs
    // products with its coefficients, not a solve and a stress recovery.
    bool superposed = false;
    bool set_up = false;  // set_up_part done
    Eigen::MatrixXd Zp, SG, Sp, GtZp;  // GtZp = G^T Z_p (6m x p)
    Eigen::MatrixXd stress_block;      // add_fields' 6N x poses buffer, reused
    Eigen::Matrix<double, 6, Eigen::Dynamic> Rp;
    // Pins in contact with its bores (Impl::contact_bores indices, interface
    // order) and their mP corners. With H = F_c - G X (F_c: the corners' unit
    // pressures as nodal forces; X, 6m x mP: their resultants on the bores'
    // couplings, so H p is self-equilibrated): HKH = H^T K_s^-1 H, HKG =
    // H^T K_s^-1 G, FcZp = F_c^T Z_p (superposed), FcT: F_c^T of columns.
    std::vector<int> contact_bores;
    Eigen::Index contact_corners = 0, first_contact_corner = 0;  // first: among all the assembly's corners
    Eigen::MatrixXd contact_resultants;  // X, 6m x mP (body axes, about each interface's reference)
    Eigen::MatrixXd HKH, HKG, FcZp;
  };
  // A bore of an elastic part that its joint's pin is in contact with.
  struct ContactBore {
    int iface = -1, part = -1, joint = -1;  // its coupling interface, part, model joint
    double clearance_m = 0.0;               // radial
    std::unique_ptr<fem::BoreContactSurface> surface;  // axis through the interface's reference, along z
    Eigen::Index first = 0;                 // first corner among its part's
    Eigen::Matrix<double, 6, Eigen::Dynamic> resultant;  // per corner: its unit pressure's resultant about the reference
  };
  struct JointData {
    int joint = -1;
    mech::JointType type = mech::JointType::Revolute;
    mech::AssemblyTie tie = mech::AssemblyTie::Rigid;  // the type's row in the joint table
    int held = 0;                                     // Rigid: components held (joint table)
    int body_i = -1, body_j = -1, if_i = -1, if_j = -1;
    double ea = 0.0, radius = 0.0, sigma = 1.0;  // chain
    Vector2d hinge = Vector2d::Zero();           // chain: hinge point in the ground's frame
    int pin = -1;                                // revolute with bores at different z: its elastic pin
    // Slide (prismatic): the axis and the line's point on body_i (body_i
    // frame). An elastic guide has no if_i: its stations (interfaces of the
    // windows of its face set, at station_s along the axis from the line's
    // point, m) take the slider where it sits.
    Vector2d axis = Vector2d::UnitX(), line_point = Vector2d::Zero();
    std::vector<int> stations;
    std::vector<double> station_s;
    double contact_length = 0.0;
  };
  // The elastic pin of a revolute joint (structure/pin_member.hpp). A side on
  // the rigid ground (no interface) is held at the joint point, z = 0.
  struct PinData {
    int joint = -1;
    PinSection section;
    Vector3d ground_end_i = Vector3d::Zero(), ground_end_j = Vector3d::Zero();  // the ground's frame
  };
  struct DriveData {
    int drive = -1, body_i = -1, body_j = -1, if_i = -1, if_j = -1;
    double k = kRigid;  // N m/rad (angle) or N/m (displacement)
    bool displacement = false;
    Vector2d axis = Vector2d::UnitX(), point_i = Vector2d::Zero(), point_j = Vector2d::Zero();  // displacement
  };
  // A transmission: the interfaces of its input's and output's two ends
  // (-1: the rigid ground), its ratio and member.
  struct TransmissionData {
    int transmission = -1;
    int in_i = -1, in_j = -1, out_i = -1, out_j = -1;
    double ratio = 1.0;
    TransmissionMember member;
  };
  struct PointData {
    int body = -1, iface = -1;
  };
  // The geometry of one pose.
  struct Pose {
    std::vector<Eigen::Matrix3d> R;  // per body
    std::vector<Vector3d> origin;    // per body, world
    std::vector<Vector3d> P, arm;    // per interface: reference point (world), offset from its body origin (world axes)
  };

  Log log;
  AssemblyOptions options;
  mech::MultibodyModel model;
  std::unique_ptr<mech::MultibodySystem> system;
  double length_scale = 1.0;
  std::vector<std::unique_ptr<PartData>> parts;
  std::vector<int> part_of_body;  // -1: rigid or ground
  std::vector<int> moving;        // per body: index among the moving bodies, -1 ground
  int moving_count = 0;
  std::vector<Interface> interfaces;
  std::vector<std::vector<int>> interfaces_of_body;
  std::vector<JointData> joints;
  std::vector<DriveData> drives;
  std::vector<TransmissionData> transmissions;
  std::vector<PinData> pins;
  std::vector<PointData> points;
  std::vector<ContactBore> contact_bores;
  Eigen::Index contact_corners = 0;  // all bores
  std::vector<char> contact_set;     // the last pose's, the next one's start
  AssemblyStatistics stats;

  Impl(const std::vector<Part>& given, const mech::MultibodyModel& m, AssemblyOptions o, const Log& l,
       const std::vector<fem::LinearStaticAnalysis*>& factorized, bool set_up_now);
  // Per body: no part yet, its index among the moving bodies (-1 ground), no
  // interfaces.
  void index_bodies();
  // Adds the elastic part of a moving body: its 3-2-1-supported model, the
  // factor lent for it (or none), its loads without the joints and the motion
  // drives (held by the structure).
  void add_part(const Part& part, fem::LinearStaticAnalysis* factor);
  // The face set that body's part names for joint (empty on a rigid body).
  std::string face_set_of_joint(int body, const std::string& joint) const;
  // The options' chains and drives must be the mechanism's, with valid
  // stiffnesses.
  void check_member_options() const;
  // Adds model joint j with its interfaces (a chain: its roller's only).
  void add_joint(size_t j);
  // A revolute joint whose bores sit at different z gets an elastic pin
  // (its diameter, material and the check that it fits its bores).
  void add_pin_if_offset(JointData& jd, const mech::Joint& joint, const std::string& who);
  // Every PinOption must name a joint that has an elastic pin.
  void check_pin_options() const;
  // Diameter of the bore that interface k's face set makes about its
  // reference point's axis (twice the mean in-plane distance of its nodes).
  double bore_diameter(int k) const;
  // A chain joint's spring data (EA, roller, hinge on the ground) and the
  // interface of its roller.
  void tie_chain(JointData& jd, const mech::Joint& joint, const std::string& who);
  // A prismatic joint's slider interface and its guide side: the joint point
  // of a rigid guide, or the stations of an elastic one.
  void tie_slide(JointData& jd, const mech::Joint& joint, const std::string& who);
  // The stations of an elastic guide: its face set cut into windows one
  // contact length long, each an interface.
  void add_guide_stations(JointData& jd, const mech::Joint& joint, const std::string& who);
  // Where the slider sits on an elastic guide in a pose: the two stations
  // that bracket it and the weight of the second; outside them: Error.
  struct Bracket {
    int a = -1, b = -1;
    double weight_b = 0.0;
  };
  Bracket slide_bracket(const JointData& jd, const mech::Frame& frame, const Pose& pose) const;
  // Every SlideOption must name a prismatic joint with an elastic guide.
  void check_slide_options() const;
  // Adds motion drive d with the interfaces of its two sides.
  void add_drive(size_t d);
  // The interface of a motion drive on body (-1 on the ground): at the
  // centroid of the face set its part names (an angle drive), or at `point`
  // with the face set's centroid z (a displacement drive).
  int add_drive_side(int body, const std::string& drive, const Vector2d& point, bool centroid_reference);
  // Adds transmission t with the interfaces of its four ends.
  void add_transmission(size_t t);
  // Every TransmissionMember must name a transmission, with a valid stiffness.
  void check_transmission_options() const;
  // ds_out - ratio ds_in by the interfaces' motion (6M, world).
  Eigen::RowVectorXd transmission_row(const TransmissionData& td) const;
  // Adds a tracked point with its interface.
  void add_point(const AssemblyPoint& tp);
  // The bores whose pins are in contact (the parts' joint attachments), after
  // every interface is added.
  void find_contact_bores();
  // A part's contact operators HKH, HKG, FcZp (its factor: m solves).
  void set_up_contact(PartData& part);
  // F_c^T U of a part's contact corners for displacement columns U (3N x k).
  Eigen::MatrixXd contact_normal_components(const PartData& part, const Eigen::MatrixXd& U) const;
  // F_c P: the nodal forces of a part's corner pressures (mP x k) as 3N x k.
  Eigen::MatrixXd contact_forces(const PartData& part, const Eigen::Ref<const Eigen::MatrixXd>& pressure) const;

  int body_index(const std::string& name, const std::string& who) const {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return int(b);
    fail("elastic assembly: {} names body '{}', which the mechanism '{}' lacks", who, name, model.name);
  }
  Vector2d named_point(int body, const std::string& point, const std::string& who) const {
    if (point == "origin") return Vector2d::Zero();
    const auto& pts = model.bodies[size_t(body)].points;
    const auto it = pts.find(point);
    require(it != pts.end(), "elastic assembly: {} names point '{}', which body '{}' lacks", who, point,
            model.bodies[size_t(body)].name);
    return it->second;
  }
  const std::string& body_name(int b) const { return model.bodies[size_t(b)].name; }
  bool ground(int b) const { return moving[size_t(b)] < 0; }
  // The ground without a frame part: fixed, no interfaces (its side of a
  // joint or drive is held in space).
  bool rigid_ground(int b) const { return ground(b) && part_of_body[size_t(b)] < 0; }

  // A new interface of `body`: on an elastic part the coupling of
  // `face_set`, reference (point, centroid z) or the centroid itself.
  int add_interface(int body, Kind kind, const std::string& name, const std::string& face_set, const Vector2d& point,
                    bool centroid_reference) {
    Interface iface;
    iface.body = body;
    iface.kind = kind;
    iface.name = name;
    iface.reference = lift(point);
    const int p = part_of_body[size_t(body)];
    if (p >= 0) {
      PartData& part = *parts[size_t(p)];
      iface.part = p;
      iface.local = int(part.couplings.size());
      iface.face_set = face_set;
      try {
        part.couplings.push_back(std::make_unique<fem::DistributingCoupling>(part.supported.mesh, face_set));
      } catch (const Error& e) {
        fail("{}: the {} '{}': {}", part.label,
             kind == Kind::Joint   ? "joint"
             : kind == Kind::Drive ? "drive"
                                   : "point",
             name, e.what());
      }
      const Vector3d c = part.couplings.back()->centroid();
      iface.reference = centroid_reference ? c : lift(point, c.z());
      part.interfaces.push_back(int(interfaces.size()));
    }
    interfaces_of_body[size_t(body)].push_back(int(interfaces.size()));
    interfaces.push_back(iface);
    return int(interfaces.size()) - 1;
  }

  // Resultant (world axes, moment about the body origin) of the applied
  // minus inertia loads of the multibody body, and its size.
  Vector6d multibody_resultant(const mech::Frame& frame, const std::vector<Vector3d>& applied, int b,
                               double& scale) const {
    const mech::EffectiveBody& eff = system->effective(b);
    const mech::BodyFrame& bf = frame.bodies[size_t(b)];
    const Vector2d inertia = eff.mass_kg * bf.com_acceleration;
    const Vector2d F = applied[size_t(b)].head<2>() - inertia;
    const double inertia_moment = eff.inertia_kgm2 * bf.q_ddot.z();
    const Vector2d arm = bf.com - bf.q.head<2>();
    const double M = applied[size_t(b)].z() - inertia_moment + cross2(arm, F);
    const double force_size = applied[size_t(b)].head<2>().norm() + inertia.norm();
    scale =
        std::max(force_size, (std::abs(applied[size_t(b)].z()) + std::abs(inertia_moment) + arm.norm() * force_size) /
                                 length_scale);
    Vector6d r = Vector6d::Zero();
    r.head<2>() = F;
    r(5) = M;
    return r;
  }

  Pose pose_of(const mech::Frame& frame) const {
    Pose pose;
    for (size_t b = 0; b < model.bodies.size(); ++b) {
      const Vector3d q = frame.bodies[b].q;
      pose.R.push_back(rot_z(q.z()));
      pose.origin.push_back(lift(q.head<2>()));
    }
    for (const Interface& i : interfaces) {
      pose.arm.push_back(pose.R[size_t(i.body)] * i.reference);
      pose.P.push_back(pose.origin[size_t(i.body)] + pose.arm.back());
    }
    return pose;
  }

  void check_frame(const mech::Frame& frame) const {
    require(frame.bodies.size() == model.bodies.size(),
            "elastic assembly at t = {:.6g} s: the frame has {} bodies, the mechanism '{}' {}", frame.t,
            frame.bodies.size(), model.name, model.bodies.size());
    require(frame.q.size() == system->n_coordinates() && frame.q_dot.size() == system->n_coordinates(),
            "elastic assembly at t = {:.6g} s: the frame has no solver coordinates of the mechanism '{}' (a frame of "
            "another model, or built by hand)",
            frame.t, model.name);
  }

  // Indeterminacy: the rigid-body equilibrium of every moving body (6 per
  // body, world axes, about its origin) against the joint loads that the
  // held components (rows of C) and spring members (g) can carry.
  Indeterminacy indeterminacy_of(const Pose& pose, const std::vector<Eigen::RowVectorXd>& rows,
                                 const std::vector<bool>& row_in_plane,
                                 const std::vector<Eigen::RowVectorXd>& spring_g) const {
    const int B = moving_count;
    auto column = [&](const Eigen::RowVectorXd& r) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(6 * B);
      for (size_t k = 0; k < interfaces.size(); ++k) {
        const int mb = moving[size_t(interfaces[k].body)];
        if (mb < 0) continue;  // the frame's side: a support, like the rigid ground's
        e.segment<6>(6 * mb) += transfer(pose.arm[k]).transpose() * r.segment<6>(6 * Eigen::Index(k)).transpose();
      }
      for (int i = 0; i < 6 * B; ++i)
        if (i % 6 >= 3) e(i) /= length_scale;  // moments as forces
      return e;
    };
    auto degree = [&](bool in_plane) {
      std::vector<Eigen::VectorXd> cols;
      for (size_t r = 0; r < rows.size(); ++r)
        if (row_in_plane[r] == in_plane) cols.push_back(column(rows[r]));
      if (in_plane)
        for (const auto& g : spring_g) cols.push_back(column(g));
      if (cols.empty()) return 0;
      Eigen::MatrixXd E(3 * B, Eigen::Index(cols.size()));
      const int pick[2][3] = {{2, 3, 4}, {0, 1, 5}};
      for (size_t c = 0; c < cols.size(); ++c) {
        for (int b = 0; b < B; ++b)
          for (int i = 0; i < 3; ++i) E(3 * b + i, Eigen::Index(c)) = cols[c](6 * b + pick[in_plane][i]);
        const double norm = E.col(Eigen::Index(c)).norm();
        if (norm > 0) E.col(Eigen::Index(c)) /= norm;
      }
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(E);
      qr.setThreshold(1e-9);
      return int(cols.size()) - int(qr.rank());
    };
    return {degree(true), degree(false)};
  }

  // Spring members (chains, compliant drives: elongation or twist = g u) and
  // the constraint rows C (6M columns) of a pose.
  struct ChainPose {
    double k = 0, b = 0;
    Vector3d T, n;
    Eigen::Matrix<double, 1, 6> g;  // elongation = g u_roller (+ g_hinge u_hinge)
    Eigen::Matrix<double, 1, 6> g_hinge = Eigen::Matrix<double, 1, 6>::Zero();  // hinge on a frame part
  };
  struct PoseMembers {
    Eigen::MatrixXd S;
    std::vector<Eigen::RowVectorXd> rows;
    std::vector<bool> row_rotation, row_in_plane;
    std::vector<std::string> row_owner;
    std::vector<Eigen::RowVectorXd> spring_g;
    std::vector<double> spring_k;
    std::vector<std::string> spring_name;
    std::vector<ChainPose> chain_pose;  // per joint (chains only)
    // Elastic pins: their members in the pose, and the load systems they
    // carry (the rigid tie's rows) for the indeterminacy count.
    struct PinPose {
      int pin = -1, if_i = -1, if_j = -1;
      PinMember member;
    };
    std::vector<PinPose> pin_pose;
    std::vector<Eigen::RowVectorXd> pin_rows;
    std::vector<bool> pin_row_in_plane;
    double max_compliance = 0.0;        // largest translational compliance of a spring member, m/N
  };
  PoseMembers members_of(const mech::Frame& frame, const Pose& pose) const;
  // A drive's coordinate change by the interfaces' motion u (6M, world): an
  // angle drive's twist rz_j - rz_i; a displacement drive's
  // ds = t . (u_j - u_i) + (t x d) . rot_i (t its axis in world, d = P_j -
  // P_i: the axis turns with body_i's side).
  Eigen::RowVectorXd drive_row(const DriveData& dd, const Pose& pose) const;
  const PartData& part_of(const std::string& body) const {
    for (const auto& p : parts)
      if (p->body == body) return *p;
    fail("elastic assembly: body '{}' has no elastic part", body);
  }

  // coefficients: per part, its load patterns' coefficients at the frame
  // (superposed parts; empty for the others).
  // What a pose leaves for its fields: per part, the interface loads
  // (body axes) and the rigid motion (body axes) of its solution.
  struct FieldInputs {
    std::vector<Eigen::VectorXd> lambda_body;
    std::vector<Vector3d> translation, rotation;
    std::vector<Eigen::VectorXd> contact_pressure;  // per part with pins in contact: its corners' (Pa)
  };
  // interface_load_displacement: per part G^T Z_f (6m, body axes);
  // contact_load_gap: per part with pins in contact, H^T Z_f (mP).
  PoseSolution solve_pose(const mech::Frame& frame, const std::vector<Eigen::VectorXd>& interface_load_displacement,
                          const std::vector<Eigen::VectorXd>& contact_load_gap,
                          const std::vector<Vector6d>& resultant_world, FieldInputs& field_inputs);
  // Unknowns of a pose system, in this order: interface displacements u (6M,
  // world axes), interface loads lambda (6M, world axes), rigid motions alpha
  // of the moving bodies (6B, about their origins), constraint multipliers mu
  // (one per constraint row); ou, ol, oa, om are where each block starts.
  struct PoseLayout {
    int M = 0, B = 0, nc = 0;
    int ou = 0, ol = 0, oa = 0, om = 0, n = 0;
  };
  // Reference sizes of a pose: P the largest load resultant (N; moments in
  // N m divided by length_scale), U = largest compliance * P (m).
  struct PoseScales {
    double P = 1.0, U = 0.0;
  };
  // The pose system A x = rhs in physical units (rows (a) to (d) below).
  struct PoseSystem {
    Eigen::MatrixXd A;
    Eigen::VectorXd rhs;
  };
  // The solved pose system: x = Dc y with (Dr A Dc) y = Dr rhs, and the LU
  // factor of Dr A Dc, kept for further right-hand sides (unit loads).
  struct PoseUnknowns {
    PoseLayout at;
    Eigen::FullPivLU<Eigen::MatrixXd> lu;
    Eigen::VectorXd Dr, Dc, x;
    int rank = 0;
    double residual = 0.0;
    // Pins in contact: x of the couplings (before the contact), and each
    // contact bore's pin motion delta in it (4 per bore: x, y, about x,
    // about y; body axes).
    Eigen::VectorXd x_coupling, pin_motion;
    // Per interface (6M, world): where the pin's end sits relative to it,
    // Delta delta at a bore in contact (empty without contact).
    Eigen::VectorXd release;
    // Displacement of interface k (world axes); zero for the ground (k < 0).
    Vector6d u_of(int k) const { return k >= 0 ? Vector6d(x.segment<6>(at.ou + 6 * k)) : Vector6d::Zero(); }
    // Load on interface k (world axes); zero for the ground (k < 0).
    Vector6d lambda_of(int k) const { return k >= 0 ? Vector6d(x.segment<6>(at.ol + 6 * k)) : Vector6d::Zero(); }
  };
  // Layout of the unknowns of a pose with these members.
  PoseLayout layout_of(const PoseMembers& members) const;
  // Scales of a pose: the largest translational compliance (parts, chains,
  // drives; m/N) and the largest load resultant of a moving body.
  PoseScales scales_of(const PoseMembers& members, const std::vector<Vector6d>& resultant_world) const;
  // Assembles A and rhs of a pose (world axes, physical units).
  PoseSystem assemble_pose_system(const Pose& pose, const PoseMembers& members, const PoseLayout& at,
                                  const std::vector<Eigen::VectorXd>& interface_load_displacement,
                                  const std::vector<Vector6d>& resultant_world) const;
  // Solves the pose system scaled to physical units (U, P, length_scale), then
  // Ruiz-equilibrated, by full-pivoting LU; a rank below n is an error naming
  // the free motion.
  PoseUnknowns solve_equilibrated(const mech::Frame& frame, const Pose& pose, const PoseMembers& members,
                                  const PoseLayout& at, const PoseScales& scales, const PoseSystem& system) const;
  // The rigid motion (world axes, about the origin) of every moving body.
  void add_body_motions(PoseSolution& out, const PoseUnknowns& solved) const;
  // The loads of every joint and the results of every chain; a chain that
  // would push (tension not above 1e-9 P) is an error.
  void add_joint_loads(PoseSolution& out, const mech::Frame& frame, const Pose& pose, const PoseMembers& members,
                       const PoseUnknowns& solved, double P) const;
  // Joint j's loads on both ends from the interface loads of a held joint;
  // the ground's side carries the reaction of the other.
  JointLoad held_joint_load(JointLoad jl, const JointData& jd, const Pose& pose, const PoseUnknowns& solved) const;
  // The twist and moment (angle) or stretch and force (displacement) of every drive.
  void add_drive_results(PoseSolution& out, const Pose& pose, const PoseUnknowns& solved) const;
  // The moment and twist of every transmission, a belt's span tensions; a
  // preloaded span that would go slack is an Error naming the time.
  void add_transmission_results(PoseSolution& out, const mech::Frame& frame, const PoseUnknowns& solved) const;
  // The end motions (u_i, theta_i, u_j, theta_j) of an elastic pin; a side
  // on the rigid ground: zero.
  static Vector12d pin_motion(const PoseMembers::PinPose& pp, const PoseUnknowns& solved) {
    Vector12d u;
    u << solved.u_of(pp.if_i), solved.u_of(pp.if_j);
    if (solved.release.size() > 0) {  // an end released in its bore (a pin in contact)
      if (pp.if_i >= 0) u.head<6>() += solved.release.segment<6>(6 * pp.if_i);
      if (pp.if_j >= 0) u.tail<6>() += solved.release.segment<6>(6 * pp.if_j);
    }
    return u;
  }
  // Every elastic pin's loads, stresses and deflection.
  void add_pin_results(PoseSolution& out, const PoseMembers& members, const PoseUnknowns& solved) const;
  // The tracked points' motion and, with unit_load_split, their compliance
  // and each part's and spring's share of their displacement.
  void add_point_results(PoseSolution& out, const Pose& pose, const PoseMembers& members,
                         const PoseUnknowns& solved) const;
  // Unit-load method for point pr at interface k: the factorized system with
  // a unit force at the point alone gives the virtual loads of every element
  // (interface loads lambda_v, spring forces k g u_v); their work on the real
  // solution is each element's contribution.
  void split_by_unit_loads(PointResult& pr, int k, const Pose& pose, const PoseMembers& members,
                           const PoseUnknowns& solved) const;
  // What the fields need (add_fields): per part its interface loads and rigid
  // motion in body axes.
  void collect_field_inputs(const Pose& pose, const PoseUnknowns& solved, FieldInputs& field_inputs) const;
  // The pins in contact of a solved pose (the couplings' solution `solved`,
  // whose x becomes the contact's): p, delta and the record in `out`.
  void solve_contact_pose(const mech::Frame& frame, const Pose& pose, const PoseMembers& members,
                          const std::vector<Eigen::VectorXd>& contact_load_gap, PoseUnknowns& solved,
                          PoseSolution& out, Eigen::VectorXd& pressure);
  // The parts' fields of a block of solved poses: u = Z_G lambda + Z_f +
  // rigid, von Mises from S_G lambda + S_p c (superposed) or recovered, as
  // block products over the poses (not one matrix-vector product per pose).
  // With `motion` (the block's first frame is frame `first` of the solve()
  // call): every pose folded into its envelopes, full fields only where
  // written; a part in_chunks by add_chunked_fields.
  void add_fields(std::vector<PoseSolution>& poses, const std::vector<mech::Frame>& frames,
                  const std::vector<FieldInputs>& inputs, const std::vector<Eigen::MatrixXd>& load_displacement,
                  const std::vector<Eigen::MatrixXd>& coefficients, MotionFields* motion, size_t first);
  // Whether a part's fields over a motion are formed over chunks of nodes:
  // its loads superposed, its stress from patterns (no pin in contact).
  bool in_chunks(const PartData& part, const MotionFields* motion) const {
    return motion && options.recover_stress && part.superposed && part.contact_bores.empty();
  }
  // One such part's fields of a block: per chunk of nodes (the chunks on the
  // cores), its rows of [Z_p Z_G; S_p S_G] times [c; lambda] in tiles that
  // stay in cache, then the rigid motion, world axes, magnitude and von
  // Mises stress of the chunk's nodes at once, folded into the envelope;
  // written poses' fields copied out.
  void add_chunked_fields(PartData& part, size_t p, std::vector<PoseSolution>& poses,
                          const std::vector<mech::Frame>& frames, const std::vector<FieldInputs>& inputs,
                          const Eigen::MatrixXd& lambda, const Eigen::MatrixXd& coefficients, MotionFields& motion,
                          size_t first);
  std::vector<PoseSolution> solve_frames(const std::vector<mech::Frame>& frames, MotionFields* motion);
  void set_up_load_patterns(PartData& part);
  void solve_interface_columns(PartData& part);
  void set_up_part(PartData& part);
  void require_set_up() const;
  [[noreturn]] void explain_rank_deficiency(const mech::Frame& frame, const Pose& pose, const Eigen::MatrixXd& kernel,
                                            const Eigen::VectorXd& unscale, int rank, int n,
                                            const std::vector<std::string>& row_owner) const;
};

namespace {

// A factorization lent by the caller must be of this very supported model.
void require_factor_of(const fem::FeModel& supported, const fem::LinearStaticAnalysis& factor, const std::string& label) {
  const fem::FeModel& theirs = factor.model();
  bool same = theirs.mesh.node_count() == supported.mesh.node_count() && theirs.supports.size() == supported.supports.size();
  for (size_t k = 0; same && k < theirs.supports.size(); ++k) same = theirs.supports[k].nodes == supported.supports[k].nodes;
  require(same, "{}: the factorization given is not of this part with its support (3-2-1, or a frame's foundation)",
          label);
}

}  // namespace

ElasticAssembly::Impl::Impl(const std::vector<Part>& given, const mech::MultibodyModel& m, AssemblyOptions o,
                            const Log& l, const std::vector<fem::LinearStaticAnalysis*>& factorized, bool set_up_now)
    : log(l), options(std::move(o)), model(m) {
  require(factorized.empty() || factorized.size() == given.size(),
          "elastic assembly: {} factorizations given for {} parts", factorized.size(), given.size());
  require(!options.keep_part_stress || options.recover_stress,
          "elastic assembly: keeping the parts' stress needs their stress recovered (recover_stress)");
  Stopwatch clock;
  system = std::make_unique<mech::MultibodySystem>(model);
  length_scale = model.characteristic_length_m > 0 ? model.characteristic_length_m : 1.0;
  index_bodies();
  for (const Part& part : given) add_part(part, factorized.empty() ? nullptr : factorized[parts.size()]);
  check_member_options();
  for (size_t j = 0; j < model.joints.size(); ++j) add_joint(j);
  check_pin_options();
  check_slide_options();
  for (size_t d = 0; d < model.motion_drives.size(); ++d) add_drive(d);
  check_transmission_options();
  for (size_t t = 0; t < model.transmissions.size(); ++t) add_transmission(t);
  for (const AssemblyPoint& tp : options.points) add_point(tp);
  find_contact_bores();
  for (const auto& part : parts)
    require(!part->held || !part->interfaces.empty(),
            "{}: no joint, chain or drive of the mechanism acts on the frame (body '{}'): name the frame's bores in "
            "the ground joints",
            part->label, part->body);

  stats.elastic_parts = int(parts.size());
  stats.rigid_bodies = moving_count - int(std::count_if(parts.begin(), parts.end(), [](const auto& p) { return !p->held; }));
  stats.interfaces = int(interfaces.size());
  stats.setup_seconds = clock.seconds();
  if (set_up_now)
    for (auto& part : parts) set_up_part(*part);
}

void ElasticAssembly::Impl::index_bodies() {
  const size_t nb = model.bodies.size();
  part_of_body.assign(nb, -1);
  moving.assign(nb, -1);
  interfaces_of_body.assign(nb, {});
  for (size_t b = 0; b < nb; ++b)
    if (!model.bodies[b].fixed) moving[b] = moving_count++;
}

void ElasticAssembly::Impl::add_part(const Part& part, fem::LinearStaticAnalysis* factor) {
  auto data = std::make_unique<PartData>();
  data->body = part.body();
  data->label = part.label.empty() ? fmt::format("part '{}'", part.body()) : part.label;
  data->body_index = body_index(part.body(), data->label);
  data->held = model.bodies[size_t(data->body_index)].fixed;
  require(data->held || part.held_face.empty(),
          "{}: held_face '{}' is for a part of the ground (a frame); body '{}' moves, and a moving part is held by no "
          "foundation",
          data->label, part.held_face, data->body);
  require(part_of_body[size_t(data->body_index)] < 0, "{}: body '{}' has two parts", data->label, data->body);
  part_of_body[size_t(data->body_index)] = int(parts.size());
  if (data->held) (void)foundation_support(part);  // a frame part needs its held_face: an Error naming it
  data->supported = supported_model(part);
  data->attachments = part.attachments;
  data->attachments.body = part.body();
  if (factor) {
    require_factor_of(data->supported, *factor, data->label);
    data->given_analysis = factor;
  }
  for (const auto& a : data->attachments.joints) {
    const auto it = std::find_if(model.joints.begin(), model.joints.end(),
                                 [&](const mech::Joint& j) { return j.name == a.joint; });
    require(it != model.joints.end(), "{}: the mechanism has no joint '{}'", data->label, a.joint);
    require(it->body_i == data->body || it->body_j == data->body,
            "{}: joint '{}' does not act on body '{}' (it joins '{}' and '{}')", data->label, a.joint, data->body,
            it->body_i, it->body_j);
  }
  loads::LinkDefinition own = data->attachments;
  own.model = &data->supported;
  own.joints.clear();
  std::erase_if(own.drives, [&](const loads::DriveAttachment& d) {
    return std::any_of(model.motion_drives.begin(), model.motion_drives.end(),
                       [&](const mech::MotionDrive& md) { return md.name == d.drive; });
  });
  own.transmissions.clear();  // a transmission's moments are internal here too
  // No equilibrium check in loads_at: without the joint reactions the loads
  // are not self-equilibrated; the resultant is checked against the
  // multibody body instead (solve).
  data->loads = std::make_unique<loads::LinkLoads>(own, model, std::numeric_limits<double>::infinity());
  parts.push_back(std::move(data));
}

std::string ElasticAssembly::Impl::face_set_of_joint(int body, const std::string& joint) const {
  const int p = part_of_body[size_t(body)];
  if (p < 0) return {};
  for (const auto& a : parts[size_t(p)]->attachments.joints)
    if (a.joint == joint) return a.face_set;
  fail("{}: joint '{}' acts on body '{}' but the part names no face set for it (LinkDefinition::joints)",
       parts[size_t(p)]->label, joint, body_name(body));
}

void ElasticAssembly::Impl::check_member_options() const {
  for (const auto& c : options.chains) {
    const auto it = std::find_if(model.joints.begin(), model.joints.end(), [&](const mech::Joint& j) {
      return j.name == c.chain && mech::joint_facts(j.type).assembly_tie == mech::AssemblyTie::ChainSpring;
    });
    require(it != model.joints.end(), "elastic assembly: options name chain '{}', which the mechanism '{}' lacks",
            c.chain, model.name);
  }
  for (const auto& d : options.drives) {
    const auto it = std::find_if(model.motion_drives.begin(), model.motion_drives.end(),
                                 [&](const mech::MotionDrive& md) { return md.name == d.drive; });
    require(it != model.motion_drives.end(),
            "elastic assembly: options name motion drive '{}', which the mechanism '{}' lacks", d.drive, model.name);
    require(d.torsional_stiffness_nm_per_rad >= 0 && !std::isnan(d.torsional_stiffness_nm_per_rad),
            "elastic assembly: drive '{}': torsional stiffness {} N m/rad must be >= 0 (kRigid: held rigidly)", d.drive,
            d.torsional_stiffness_nm_per_rad);
    require(d.axial_stiffness_n_per_m >= 0 && !std::isnan(d.axial_stiffness_n_per_m),
            "elastic assembly: drive '{}': axial stiffness {} N/m must be >= 0 (kRigid: held rigidly)", d.drive,
            d.axial_stiffness_n_per_m);
    const bool angle = it->coordinate.type == mech::CoordinateType::Angle;
    require(angle ? std::isinf(d.axial_stiffness_n_per_m) : std::isinf(d.torsional_stiffness_nm_per_rad),
            "elastic assembly: drive '{}' drives {}: it has {} stiffness, not {}", d.drive,
            angle ? "an angle" : "a displacement", angle ? "a torsional" : "an axial",
            angle ? "an axial one (N/m)" : "a torsional one (N m/rad)");
  }
}

void ElasticAssembly::Impl::add_joint(size_t j) {
  const mech::Joint& joint = model.joints[j];
  JointData jd;
  jd.joint = int(j);
  jd.type = joint.type;
  const std::string who = fmt::format("joint '{}'", joint.name);
  jd.body_i = body_index(joint.body_i, who);
  jd.body_j = body_index(joint.body_j, who);
  jd.tie = mech::joint_facts(joint.type).assembly_tie;
  jd.held = mech::joint_facts(joint.type).assembly_held;
  require(jd.tie != mech::AssemblyTie::None,
          "elastic assembly: joint '{}' is {}, which the elastic assembly does not model", joint.name,
          mech::joint_facts(joint.type).name);
  if (jd.tie == mech::AssemblyTie::ChainSpring) {
    tie_chain(jd, joint, who);
  } else if (jd.tie == mech::AssemblyTie::Slide) {
    tie_slide(jd, joint, who);
  } else {
    // A side on the ground is held in space, or on the frame's bore when the
    // ground has a part.
    if (!rigid_ground(jd.body_i))
      jd.if_i = add_interface(jd.body_i, Kind::Joint, joint.name, face_set_of_joint(jd.body_i, joint.name),
                              named_point(jd.body_i, joint.point_i, who), false);
    if (!rigid_ground(jd.body_j))
      jd.if_j = add_interface(jd.body_j, Kind::Joint, joint.name, face_set_of_joint(jd.body_j, joint.name),
                              named_point(jd.body_j, joint.point_j, who), false);
    if (joint.type == mech::JointType::Revolute) add_pin_if_offset(jd, joint, who);
  }
  joints.push_back(jd);
}

double ElasticAssembly::Impl::bore_diameter(int k) const {
  const Interface& iface = interfaces[size_t(k)];
  const PartData& part = *parts[size_t(iface.part)];
  const fem::DistributingCoupling& coupling = *part.couplings[size_t(iface.local)];
  double sum = 0.0;
  for (const fem::Index n : coupling.nodes())
    sum += (part.supported.mesh.nodes.row(n).head<2>().transpose() - iface.reference.head<2>()).norm();
  return 2.0 * sum / double(std::max<size_t>(coupling.nodes().size(), 1));
}

void ElasticAssembly::Impl::add_pin_if_offset(JointData& jd, const mech::Joint& joint, const std::string& who) {
  // The rigid ground's side is the joint point in the mechanism's plane.
  const double zi = jd.if_i >= 0 ? interfaces[size_t(jd.if_i)].reference.z() : 0.0;
  const double zj = jd.if_j >= 0 ? interfaces[size_t(jd.if_j)].reference.z() : 0.0;
  const bool offset = std::abs(zj - zi) > options.pin_offset_tolerance * length_scale;
  const auto option = std::find_if(options.pins.begin(), options.pins.end(),
                                   [&](const PinOption& o) { return o.joint == joint.name; });
  if (!offset && option == options.pins.end()) return;
  PinData pd;
  pd.joint = jd.joint;
  std::vector<std::pair<int, double>> bores;  // elastic sides: interface, bore diameter
  for (const int k : {jd.if_i, jd.if_j})
    if (k >= 0 && interfaces[size_t(k)].part >= 0) bores.push_back({k, bore_diameter(k)});
  auto require_fits = [&](double diameter) {
    for (const auto& [k, bore] : bores)
      require(diameter <= bore * (1.0 + 1e-6),
              "elastic assembly: {}: the pin's diameter {:.3f} mm is larger than the bore it passes through on body "
              "'{}' (face set '{}', {:.3f} mm)",
              who, diameter / units::kMm, body_name(interfaces[size_t(k)].body), interfaces[size_t(k)].face_set,
              bore / units::kMm);
  };
  if (!offset) {
    // A pin through bores in one plane (a clevis about its lug, say) bends
    // nothing the rigid tie leaves out: the joint stays the rigid tie, and a
    // given diameter only has to fit its bores.
    require_fits(option->diameter_m);
    log.info("elastic assembly: {}: its bores sit at the same z (within {:.3g} mm): the pin is the rigid tie, not an "
             "elastic member; its [[pin]] diameter is only checked against the bores",
             who, options.pin_offset_tolerance * length_scale / units::kMm);
    return;
  }
  const PartData* joined = bores.empty() ? nullptr : parts[size_t(interfaces[size_t(bores.front().first)].part)].get();
  if (option != options.pins.end() && option->diameter_m > 0) {
    pd.section.diameter_m = option->diameter_m;
  } else {
    require(!bores.empty(),
            "elastic assembly: {}: its bores are {:.3f} mm apart in z, so its pin is an elastic member, but neither "
            "side is a part with a bore to measure: give the pin's diameter ([[pin]] diameter_mm)",
            who, std::abs(zj - zi) / units::kMm);
    pd.section.diameter_m = std::min_element(bores.begin(), bores.end(), [](const auto& a, const auto& b) {
                              return a.second < b.second;
                            })->second;
  }
  const fem::IsotropicMaterial material = joined ? joined->supported.material : fem::IsotropicMaterial{};
  require(joined || (option != options.pins.end() && option->youngs_modulus_pa),
          "elastic assembly: {}: its pin is an elastic member between bodies without parts: give its Young's modulus "
          "([[pin]] youngs_modulus_mpa)",
          who);
  pd.section.youngs_modulus_pa =
      option != options.pins.end() && option->youngs_modulus_pa ? *option->youngs_modulus_pa : material.youngs_modulus_pa;
  pd.section.poisson_ratio =
      option != options.pins.end() && option->poisson_ratio ? *option->poisson_ratio : material.poisson_ratio;
  pd.section.validate(fmt::format("elastic assembly: the pin of {}", who));
  require_fits(pd.section.diameter_m);
  const Vector2d point_i = named_point(jd.body_i, joint.point_i, who), point_j = named_point(jd.body_j, joint.point_j, who);
  pd.ground_end_i = lift(point_i);
  pd.ground_end_j = lift(point_j);
  jd.pin = int(pins.size());
  pins.push_back(pd);
}

void ElasticAssembly::Impl::check_pin_options() const {
  for (const PinOption& o : options.pins) {
    const auto joint = std::find_if(model.joints.begin(), model.joints.end(),
                                    [&](const mech::Joint& j) { return j.name == o.joint; });
    require(joint != model.joints.end() && joint->type == mech::JointType::Revolute,
            "elastic assembly: a pin is given for joint '{}', which is not a revolute joint of the mechanism '{}'",
            o.joint, model.name);
    require(o.diameter_m >= 0 && std::isfinite(o.diameter_m),
            "elastic assembly: the pin of joint '{}': diameter {} m must be positive (0: the smaller bore's)", o.joint,
            o.diameter_m);
  }
}

void ElasticAssembly::Impl::tie_chain(JointData& jd, const mech::Joint& joint, const std::string& who) {
  require(ground(jd.body_i),
          "elastic assembly: chain '{}' is hinged to body '{}'; the elastic assembly needs the hinge (body_i) on the "
          "ground",
          joint.name, joint.body_i);
  require(!ground(jd.body_j), "elastic assembly: chain '{}' wraps a roller on the ground", joint.name);
  const auto it = std::find_if(options.chains.begin(), options.chains.end(),
                               [&](const ChainMember& c) { return c.chain == joint.name; });
  require(it != options.chains.end(),
          "elastic assembly: chain '{}' has no axial stiffness (AssemblyOptions::chains: EA in N)", joint.name);
  require(it->axial_stiffness_n > 0 && std::isfinite(it->axial_stiffness_n),
          "elastic assembly: chain '{}': axial stiffness EA = {} N must be positive and finite", joint.name,
          it->axial_stiffness_n);
  jd.ea = it->axial_stiffness_n;
  jd.radius = joint.radius_m;
  jd.sigma = joint.wrap_ccw ? 1.0 : -1.0;
  jd.hinge = named_point(jd.body_i, joint.point_i, who);
  // A hinge on a face of the frame (a ground part naming a face set for the
  // chain) moves with that face; otherwise it is held in space.
  const int frame = part_of_body[size_t(jd.body_i)];
  if (frame >= 0)
    for (const auto& a : parts[size_t(frame)]->attachments.joints)
      if (a.joint == joint.name)
        jd.if_i = add_interface(jd.body_i, Kind::Joint, joint.name, a.face_set, jd.hinge, false);
  jd.if_j = add_interface(jd.body_j, Kind::Joint, joint.name, face_set_of_joint(jd.body_j, joint.name),
                          named_point(jd.body_j, joint.point_j, who), false);
}

void ElasticAssembly::Impl::add_drive(size_t d) {
  const mech::MotionDrive& drive = model.motion_drives[d];
  DriveData dd;
  dd.drive = int(d);
  const std::string who = fmt::format("drive '{}'", drive.name);
  dd.body_i = body_index(drive.coordinate.body_i, who);
  dd.body_j = body_index(drive.coordinate.body_j, who);
  dd.displacement = drive.coordinate.type == mech::CoordinateType::Displacement;
  for (const auto& h : options.drives)
    if (h.drive == drive.name) dd.k = dd.displacement ? h.axial_stiffness_n_per_m : h.torsional_stiffness_nm_per_rad;
  if (dd.displacement) {
    const double length = drive.coordinate.axis_i.norm();
    require(length > 0 && std::isfinite(length), "elastic assembly: {}: its axis has zero length", who);
    dd.axis = drive.coordinate.axis_i / length;
    dd.point_i = named_point(dd.body_i, drive.coordinate.point_i, who);
    dd.point_j = named_point(dd.body_j, drive.coordinate.point_j, who);
  }
  dd.if_i = add_drive_side(dd.body_i, drive.name, dd.point_i, !dd.displacement);
  dd.if_j = add_drive_side(dd.body_j, drive.name, dd.point_j, !dd.displacement);
  drives.push_back(dd);
}

void ElasticAssembly::Impl::check_transmission_options() const {
  for (const TransmissionMember& o : options.transmissions) {
    require(std::any_of(model.transmissions.begin(), model.transmissions.end(),
                        [&](const mech::Transmission& t) { return t.name == o.transmission; }),
            "elastic assembly: options name transmission '{}', which the mechanism '{}' lacks", o.transmission,
            model.name);
    require(o.torsional_stiffness_nm_per_rad >= 0 && !std::isnan(o.torsional_stiffness_nm_per_rad),
            "elastic assembly: transmission '{}': torsional stiffness {} N m/rad must be >= 0 (kRigid: held rigidly)",
            o.transmission, o.torsional_stiffness_nm_per_rad);
    require(o.radius_m >= 0 && std::isfinite(o.radius_m) && o.preload_n >= 0 && std::isfinite(o.preload_n),
            "elastic assembly: transmission '{}': radius {} m and preload {} N must be >= 0 and finite", o.transmission,
            o.radius_m, o.preload_n);
  }
}

void ElasticAssembly::Impl::add_transmission(size_t t) {
  const mech::Transmission& tr = model.transmissions[t];
  const std::string who = fmt::format("transmission '{}'", tr.name);
  TransmissionData td;
  td.transmission = int(t);
  td.ratio = tr.ratio;
  td.member.transmission = tr.name;
  for (const TransmissionMember& o : options.transmissions)
    if (o.transmission == tr.name) td.member = o;
  // An end on the rigid ground is held; on a part, the face set its
  // attachment for that side names (at its centroid, like a drive's).
  auto end = [&](const std::string& body_name, loads::TransmissionSide side) {
    const int body = body_index(body_name, who);
    if (rigid_ground(body)) return -1;
    std::string face_set;
    const int p = part_of_body[size_t(body)];
    if (p >= 0) {
      for (const auto& a : parts[size_t(p)]->attachments.transmissions)
        if (a.transmission == tr.name && a.side == side) face_set = a.face_set;
      require(!face_set.empty(),
              "{}: {} acts on body '{}' through its {} but the part names no face set for it "
              "(LinkDefinition::transmissions)",
              parts[size_t(p)]->label, who, body_name, side == loads::TransmissionSide::Input ? "input" : "output");
    }
    return add_interface(body, Kind::Drive, tr.name, face_set, Vector2d::Zero(), true);
  };
  td.in_i = end(tr.input.body_i, loads::TransmissionSide::Input);
  td.in_j = end(tr.input.body_j, loads::TransmissionSide::Input);
  td.out_i = end(tr.output.body_i, loads::TransmissionSide::Output);
  td.out_j = end(tr.output.body_j, loads::TransmissionSide::Output);
  transmissions.push_back(td);
}

Eigen::RowVectorXd ElasticAssembly::Impl::transmission_row(const TransmissionData& td) const {
  Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(6 * Eigen::Index(interfaces.size()));
  auto add = [&](int k, double w) {
    if (k >= 0) g(6 * k + 5) += w;
  };
  add(td.out_j, 1.0);
  add(td.out_i, -1.0);
  add(td.in_j, -td.ratio);
  add(td.in_i, td.ratio);
  return g;
}

void ElasticAssembly::Impl::add_transmission_results(PoseSolution& out, const mech::Frame& frame,
                                                     const PoseUnknowns& solved) const {
  for (const TransmissionData& td : transmissions) {
    const TransmissionMember& m = td.member;
    TransmissionResult tr;
    tr.transmission = m.transmission;
    tr.rigid = std::isinf(m.torsional_stiffness_nm_per_rad);
    tr.stiffness_nm_per_rad = m.torsional_stiffness_nm_per_rad;
    const Eigen::RowVectorXd g = transmission_row(td);
    for (Eigen::Index k = 0; k < g.size() / 6; ++k) tr.twist_rad += g(6 * k + 5) * solved.u_of(int(k))(5);
    // Its interfaces carry g^T times the output moment.
    tr.moment_output_nm = td.out_j >= 0   ? solved.lambda_of(td.out_j)(5)
                          : td.out_i >= 0 ? -solved.lambda_of(td.out_i)(5)
                          : td.in_j >= 0  ? -solved.lambda_of(td.in_j)(5) / td.ratio
                                          : solved.lambda_of(td.in_i)(5) / td.ratio;
    if (m.radius_m > 0) {
      tr.has_spans = true;
      const double pull = tr.moment_output_nm / m.radius_m;
      if (m.preload_n > 0) {
        tr.span_tension_n[0] = m.preload_n + 0.5 * pull;
        tr.span_tension_n[1] = m.preload_n - 0.5 * pull;
        for (int span = 0; span < 2; ++span)
          require(tr.span_tension_n[span] > 0,
                  "elastic assembly at t = {:.6g} s: transmission '{}': span {} goes slack (tension {:.6g} N: the "
                  "preload {:.6g} N {} half the pull {:.6g} N): raise the preload, or give none (one span carries)",
                  frame.t, m.transmission, span + 1, tr.span_tension_n[span], m.preload_n, span == 0 ? "plus" : "less",
                  std::abs(pull));
      } else {
        tr.span_tension_n[0] = std::max(pull, 0.0);
        tr.span_tension_n[1] = std::max(-pull, 0.0);
      }
    }
    out.transmissions.push_back(tr);
  }
}

void ElasticAssembly::Impl::tie_slide(JointData& jd, const mech::Joint& joint, const std::string& who) {
  const double length = joint.axis_i.norm();
  require(length > 0 && std::isfinite(length), "elastic assembly: {}: its axis has zero length", who);
  jd.axis = joint.axis_i / length;
  jd.line_point = named_point(jd.body_i, joint.point_i, who);
  require(!rigid_ground(jd.body_j), "elastic assembly: {}: its slider (body_j '{}') is the ground", who, joint.body_j);
  jd.if_j = add_interface(jd.body_j, Kind::Joint, joint.name, face_set_of_joint(jd.body_j, joint.name),
                          named_point(jd.body_j, joint.point_j, who), false);
  if (rigid_ground(jd.body_i)) return;
  if (part_of_body[size_t(jd.body_i)] < 0) {  // a rigid guide: the joint point on its line
    jd.if_i = add_interface(jd.body_i, Kind::Joint, joint.name, "", jd.line_point, false);
    return;
  }
  add_guide_stations(jd, joint, who);
}

void ElasticAssembly::Impl::add_guide_stations(JointData& jd, const mech::Joint& joint, const std::string& who) {
  PartData& guide = *parts[size_t(part_of_body[size_t(jd.body_i)])];
  const std::string face_set = face_set_of_joint(jd.body_i, joint.name);
  const auto option = std::find_if(options.slides.begin(), options.slides.end(),
                                   [&](const SlideOption& o) { return o.joint == joint.name; });
  double contact = option != options.slides.end() ? option->contact_length_m : 0.0;
  if (!(contact > 0)) {
    // The slider's own bearing: its face set's extent along the axis (the
    // axis turned into the slider's frame by the joint's relative angle).
    const int slider = part_of_body[size_t(jd.body_j)];
    require(slider >= 0,
            "elastic assembly: {}: its guide (body '{}') is elastic and its slider (body '{}') has no part to measure "
            "the bearing on: give the contact length ([[slide]] contact_length_mm)",
            who, joint.body_i, joint.body_j);
    const double relative = joint.reference.value_or(model.bodies[size_t(jd.body_j)].pose.z() -
                                                     model.bodies[size_t(jd.body_i)].pose.z());
    const Vector2d axis_j = Eigen::Rotation2Dd(-relative) * jd.axis;
    const PartData& part = *parts[size_t(slider)];
    const std::vector<fem::Index> on_slider =
        fem::nodes_of_faces(part.supported.mesh.face_set(face_set_of_joint(jd.body_j, joint.name)));
    double a = std::numeric_limits<double>::infinity(), b = -a;
    for (const fem::Index n : on_slider) {
      const double x = part.supported.mesh.nodes.row(n).head<2>().dot(axis_j);
      a = std::min(a, x), b = std::max(b, x);
    }
    contact = b - a;
    require(contact > 0, "elastic assembly: {}: the slider's face set has no extent along the axis", who);
  }
  require(std::isfinite(contact), "elastic assembly: {}: contact length {} m is not finite", who, contact);
  jd.contact_length = contact;
  const double spacing = option != options.slides.end() && option->station_spacing_m > 0 ? option->station_spacing_m
                                                                                         : 0.25 * contact;
  // The windows of the guide's face set, one contact length long (the axis
  // and its line point in the plane: z of the mesh does not enter).
  loads::SlideStations stations;
  try {
    stations =
        loads::add_slide_stations(guide.supported.mesh, face_set, Vector3d(jd.line_point.x(), jd.line_point.y(), 0),
                                  Vector3d(jd.axis.x(), jd.axis.y(), 0), contact, spacing, "@");
  } catch (const Error& e) {
    fail("elastic assembly: {}: the guide, {}: {}", who, guide.label, e.what());
  }
  for (size_t k = 0; k < stations.s_m.size(); ++k) {
    const double s = stations.s_m[k];
    jd.stations.push_back(
        add_interface(jd.body_i, Kind::Joint, joint.name, stations.face_sets[k], jd.line_point + s * jd.axis, false));
    jd.station_s.push_back(s);
  }
}

ElasticAssembly::Impl::Bracket ElasticAssembly::Impl::slide_bracket(const JointData& jd, const mech::Frame& frame,
                                                                   const Pose& pose) const {
  const Vector3d local = pose.R[size_t(jd.body_i)].transpose() * (pose.P[size_t(jd.if_j)] - pose.origin[size_t(jd.body_i)]);
  const double s = (local.head<2>() - jd.line_point).dot(jd.axis);
  const double slack = 1e-9 * jd.contact_length;
  const std::vector<double>& at = jd.station_s;
  const mech::Joint& joint = model.joints[size_t(jd.joint)];
  require(s >= at.front() - slack && s <= at.back() + slack,
          "elastic assembly at t = {:.6g} s: joint '{}': the slider sits at {:.3f} mm along its guide (body '{}'), "
          "beyond the guide: its {:.3f} mm contact length fits between {:.3f} and {:.3f} mm",
          frame.t, joint.name, s / units::kMm, joint.body_i, jd.contact_length / units::kMm,
          (at.front() - 0.5 * jd.contact_length) / units::kMm, (at.back() + 0.5 * jd.contact_length) / units::kMm);
  Bracket bracket;
  if (at.size() == 1) {
    bracket.a = bracket.b = jd.stations.front();
    return bracket;
  }
  const size_t k = std::min<size_t>(size_t(std::upper_bound(at.begin(), at.end(), s) - at.begin()), at.size() - 1);
  const size_t a = k == 0 ? 0 : k - 1;
  bracket.a = jd.stations[a];
  bracket.b = jd.stations[a + 1];
  bracket.weight_b = std::clamp((s - at[a]) / (at[a + 1] - at[a]), 0.0, 1.0);
  return bracket;
}

void ElasticAssembly::Impl::check_slide_options() const {
  for (const SlideOption& o : options.slides) {
    const auto joint = std::find_if(joints.begin(), joints.end(),
                                    [&](const JointData& jd) { return model.joints[size_t(jd.joint)].name == o.joint; });
    require(joint != joints.end() && joint->tie == mech::AssemblyTie::Slide,
            "elastic assembly: a slide option is given for joint '{}', which is not a prismatic joint of the mechanism "
            "'{}'",
            o.joint, model.name);
    require(!joint->stations.empty(),
            "elastic assembly: a slide option is given for joint '{}', whose guide (body '{}') is rigid: the contact "
            "length only spreads the slider's load on an elastic guide",
            o.joint, body_name(joint->body_i));
    require(o.contact_length_m >= 0 && std::isfinite(o.contact_length_m) && o.station_spacing_m >= 0 &&
                std::isfinite(o.station_spacing_m),
            "elastic assembly: the slide option of joint '{}': contact length {} m and station spacing {} m must be "
            ">= 0 and finite",
            o.joint, o.contact_length_m, o.station_spacing_m);
  }
}

int ElasticAssembly::Impl::add_drive_side(int body, const std::string& drive, const Vector2d& point,
                                          bool centroid_reference) {
  if (rigid_ground(body)) return -1;
  std::string face_set;
  const int p = part_of_body[size_t(body)];
  if (p >= 0) {
    for (const auto& a : parts[size_t(p)]->attachments.drives)
      if (a.drive == drive) face_set = a.face_set;
    require(!face_set.empty(),
            "{}: motion drive '{}' acts on body '{}' but the part names no face set for it "
            "(LinkDefinition::drives)",
            parts[size_t(p)]->label, drive, body_name(body));
  }
  return add_interface(body, Kind::Drive, drive, face_set, point, centroid_reference);
}

void ElasticAssembly::Impl::add_point(const AssemblyPoint& tp) {
  PointData pd;
  const std::string who = fmt::format("tracked point '{}'", tp.name);
  pd.body = body_index(tp.body, who);
  require(!ground(pd.body), "elastic assembly: tracked point '{}' is on the ground, which does not move", tp.name);
  const int p = part_of_body[size_t(pd.body)];
  require(p < 0 || !tp.face_set.empty(), "elastic assembly: tracked point '{}' on part '{}' needs a face set",
          tp.name, tp.body);
  pd.iface = add_interface(pd.body, Kind::Point, tp.name, tp.face_set, named_point(pd.body, tp.point, who), false);
  points.push_back(pd);
}

// The part's factorization (lent by the caller, or made and owned here), its
// interface columns G, Z_G = K_s^-1 G and flexibility G^T Z_G.
void ElasticAssembly::Impl::solve_interface_columns(PartData& part) {
  fem::FeModel& fe = part.supported;
  const fem::Index dofs = 3 * fe.mesh.node_count();
  log.detail("elastic assembly: part '{}': {} nodes, {} interfaces", part.body, fe.mesh.node_count(),
           part.interfaces.size());
  if (part.given_analysis) {
    part.analysis = part.given_analysis;
    require(part.analysis->is_factorized(), "{}: the factorization lent to the elastic assembly is not factorized",
            part.label);
  } else {
    part.own_analysis = std::make_unique<fem::LinearStaticAnalysis>(fe, log, options.solver);
    part.analysis = part.own_analysis.get();
    part.analysis->factorize();  // a no-op unless the solver options defer it
  }
  const Eigen::Index m = Eigen::Index(part.interfaces.size());
  if (options.coupling == BoreCoupling::RigidBore) {
    std::vector<RigidBoreInterface> bores;
    for (const int g : part.interfaces) bores.push_back({interfaces[size_t(g)].face_set, interfaces[size_t(g)].reference});
    try {
      part.rigid = std::make_unique<RigidBoreCondensation>(*part.analysis, fe.mesh, bores, log);
    } catch (const Error& e) {
      fail("{}: rigid-bore couplings: {}", part.label, e.what());
    }
    part.G = part.rigid->loads();
    part.ZG = part.rigid->load_displacement();
    part.F = part.rigid->flexibility();
    part.F = 0.5 * (part.F + part.F.transpose()).eval();
    stats.part_dofs += long(dofs);
    stats.interface_columns += long(part.rigid->statistics().setup_solves);
    if (!part.given_analysis) stats.factorize_seconds += part.analysis->solver_statistics().factorize_seconds;
    return;
  }
  part.G = Eigen::MatrixXd::Zero(dofs, 6 * m);
  for (Eigen::Index l = 0; l < m; ++l) {
    const Vector3d& X = interfaces[size_t(part.interfaces[size_t(l)])].reference;
    for (int c = 0; c < 3; ++c) {
      part.couplings[size_t(l)]->add(Vector3d::Unit(c), Vector3d::Zero(), X, part.G.col(6 * l + c));
      part.couplings[size_t(l)]->add(Vector3d::Zero(), Vector3d::Unit(c), X, part.G.col(6 * l + 3 + c));
    }
  }
  part.ZG = solve_columns(*part.analysis, part.G);
  part.F = part.G.transpose() * part.ZG;
  part.F = 0.5 * (part.F + part.F.transpose()).eval();
  stats.part_dofs += long(dofs);
  stats.interface_columns += long(6 * m);
  if (!part.given_analysis) stats.factorize_seconds += part.analysis->solver_statistics().factorize_seconds;
}

// Per part: interface columns, Z_G, flexibility, the load patterns. A lent
// factor is the lender's to free (solves_with_factor says whether the poses
// still need it).
void ElasticAssembly::Impl::set_up_part(PartData& data) {
  require(!data.set_up, "elastic assembly: {} is set up already", data.label);
  Stopwatch clock;
  solve_interface_columns(data);
  if (options.superpose_loads && data.loads->superposable()) set_up_load_patterns(data);
  set_up_contact(data);
  data.set_up = true;
  stats.setup_seconds += clock.seconds();
}

// ---------------------------------------------------------------------------
// Pins in contact (docs/contact.md, "In the elastic assembly").

void ElasticAssembly::Impl::find_contact_bores() {
  for (size_t p = 0; p < parts.size(); ++p) {
    PartData& part = *parts[p];
    const fem::Mesh& mesh = part.supported.mesh;
    for (const int k : part.interfaces) {
      const Interface& iface = interfaces[size_t(k)];
      if (iface.kind != Kind::Joint) continue;
      const auto attachment = std::find_if(part.attachments.joints.begin(), part.attachments.joints.end(),
                                           [&](const loads::JointAttachment& a) { return a.joint == iface.name; });
      if (attachment == part.attachments.joints.end() || attachment->distribution != loads::BoreLoad::Contact) continue;
      const auto joint = std::find_if(model.joints.begin(), model.joints.end(),
                                      [&](const mech::Joint& j) { return j.name == iface.name; });
      require(mech::joint_facts(joint->type).out_of_plane_pin,
              "{}: joint '{}': contact needs a revolute (pin) joint, not {}", part.label, iface.name,
              mech::joint_facts(joint->type).name);
      require(options.coupling == BoreCoupling::Distributing,
              "{}: joint '{}': a pin in contact needs the distributing couplings (rigid_bore presses every pin into "
              "its bore)",
              part.label, iface.name);
      require(std::isfinite(attachment->clearance_m) && attachment->clearance_m >= 0,
              "{}: joint '{}': the pin's clearance {} m is negative (an interference fit is not supported)", part.label,
              iface.name, attachment->clearance_m);
      require(!attachment->pin_material,
              "{}: joint '{}': an elastic pin in contact is modelled in the per-part analysis only; the elastic "
              "assembly's pins in contact are rigid in their bores",
              part.label, iface.name);
      ContactBore bore;
      bore.iface = k;
      bore.part = int(p);
      bore.joint = int(joint - model.joints.begin());
      try {
        // The normals radial from the bore's own axis (through its coupling's
        // centroid, as in the per-link analysis), not from the joint point
        // (the mesh's bore may sit a round-off off it); the resultants and
        // the pin's motion are about the interface's reference.
        bore.surface = std::make_unique<fem::BoreContactSurface>(
            mesh, iface.face_set, part.couplings[size_t(iface.local)]->centroid(), Vector3d::UnitZ());
        bore.clearance_m =
            loads::radial_clearance(attachment->clearance_m, attachment->fit, 2.0 * bore.surface->radius_m());
      } catch (const Error& e) {
        fail("{}: joint '{}' on face set '{}': {}", part.label, iface.name, iface.face_set, e.what());
      }
      if (part.held)
        for (const fem::DisplacementSupport& held : part.supported.supports)
          for (const fem::Index n : bore.surface->nodes())
            require(std::find(held.nodes.begin(), held.nodes.end(), n) == held.nodes.end(),
                    "{}: the bore of joint '{}' (face set '{}') shares node {} with its {}: a pin in contact needs a "
                    "bore free to move",
                    part.label, iface.name, iface.face_set, n, held.label);
      // Each corner's unit pressure as a resultant about the reference.
      const fem::BoreContactSurface& surface = *bore.surface;
      bore.resultant = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, surface.size());
      for (size_t a = 0; a < surface.nodes().size(); ++a) {
        const Vector3d n = surface.normals().row(Eigen::Index(a)).transpose();
        const Vector3d arm = mesh.nodes.row(surface.nodes()[a]).transpose() - iface.reference;
        for (Eigen::Index c = 0; c < surface.size(); ++c) {
          const double w = surface.force_map()(Eigen::Index(a), c);
          bore.resultant.col(c).head<3>() += w * n;
          bore.resultant.col(c).tail<3>() += w * arm.cross(n);
        }
      }
      bore.first = part.contact_corners;
      part.contact_corners += surface.size();
      part.contact_bores.push_back(int(contact_bores.size()));
      contact_bores.push_back(std::move(bore));
    }
    part.first_contact_corner = contact_corners;
    contact_corners += part.contact_corners;
  }
  stats.contact_corners = int(contact_corners);
}

Eigen::MatrixXd ElasticAssembly::Impl::contact_normal_components(const PartData& part, const Eigen::MatrixXd& U) const {
  Eigen::MatrixXd out(part.contact_corners, U.cols());
  for (const int b : part.contact_bores) {
    const ContactBore& bore = contact_bores[size_t(b)];
    out.middleRows(bore.first, bore.surface->size()) = bore.surface->weighted_normal_components(U);
  }
  return out;
}

Eigen::MatrixXd ElasticAssembly::Impl::contact_forces(const PartData& part,
                                                      const Eigen::Ref<const Eigen::MatrixXd>& pressure) const {
  Eigen::MatrixXd forces = Eigen::MatrixXd::Zero(3 * part.supported.mesh.node_count(), pressure.cols());
  for (const int b : part.contact_bores) {
    const ContactBore& bore = contact_bores[size_t(b)];
    bore.surface->add_forces(pressure.middleRows(bore.first, bore.surface->size()), forces);
  }
  return forces;
}

void ElasticAssembly::Impl::set_up_contact(PartData& part) {
  if (part.contact_bores.empty()) return;
  Stopwatch clock;
  const Eigen::Index mP = part.contact_corners;
  part.contact_resultants = Eigen::MatrixXd::Zero(part.G.cols(), mP);
  for (const int b : part.contact_bores) {
    const ContactBore& bore = contact_bores[size_t(b)];
    part.contact_resultants.block(6 * interfaces[size_t(bore.iface)].local, bore.first, 6, bore.surface->size()) =
        bore.resultant;
  }
  // F_c^T K_s^-1 F_c in blocks of 64 corners (3N x 64 at a time in memory).
  Eigen::MatrixXd FKF(mP, mP);
  for (Eigen::Index first = 0; first < mP; first += 64) {
    const Eigen::Index k = std::min<Eigen::Index>(64, mP - first);
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(mP, k);
    for (Eigen::Index i = 0; i < k; ++i) unit(first + i, i) = 1.0;
    FKF.middleCols(first, k) = contact_normal_components(part, solve_columns(*part.analysis, contact_forces(part, unit)));
  }
  const Eigen::MatrixXd FZG = contact_normal_components(part, part.ZG);  // F_c^T K_s^-1 G
  const Eigen::MatrixXd& X = part.contact_resultants;
  part.HKG = FZG - X.transpose() * part.F;
  part.HKH = FKF - FZG * X - X.transpose() * FZG.transpose() + X.transpose() * part.F * X;
  part.HKH = 0.5 * (part.HKH + part.HKH.transpose()).eval();
  if (part.superposed) part.FcZp = contact_normal_components(part, part.Zp);
  const double seconds = clock.seconds();
  stats.contact_setup_seconds += seconds;
  stats.interface_columns += long(mP);
  log.detail("elastic assembly: {}: {} contact corners on {} bores, condensed in {:.2f} s", part.label, mP,
             part.contact_bores.size(), seconds);
}

void ElasticAssembly::Impl::solve_contact_pose(const mech::Frame& frame, const Pose& pose, const PoseMembers& members,
                                               const std::vector<Eigen::VectorXd>& contact_load_gap,
                                               PoseUnknowns& solved, PoseSolution& out, Eigen::VectorXd& pressure) {
  Stopwatch clock;
  const PoseLayout& at = solved.at;
  const Eigen::Index m = contact_corners, nq = 4 * Eigen::Index(contact_bores.size()), n = at.n;
  // The components the pin carries across its axis: x, y, about x, about y.
  Eigen::Matrix<double, 6, 4> across = Eigen::Matrix<double, 6, 4>::Zero();
  across(0, 0) = across(1, 1) = across(3, 2) = across(4, 3) = 1.0;
  // Unit corner pressures: their self-equilibrated part H p moves every
  // interface l of their part by (G^T K^-1 H)_l p (rows (a)).
  Eigen::MatrixXd rhs_p = Eigen::MatrixXd::Zero(n, m);
  for (const auto& part : parts) {
    if (part->contact_bores.empty()) continue;
    const Matrix6d Q = rotate6(pose.R[size_t(part->body_index)]);
    for (size_t l = 0; l < part->interfaces.size(); ++l)
      rhs_p.block(at.ou + 6 * part->interfaces[l], part->first_contact_corner, 6, part->contact_corners) =
          Q * part->HKG.middleCols(6 * Eigen::Index(l), 6).transpose();
  }
  // Unit pin motions delta in a bore: the joint's tie rows and its elastic
  // pin act at the pin's end, u_k + Delta delta (rows (b) and (d)).
  Eigen::MatrixXd rhs_d = Eigen::MatrixXd::Zero(n, nq);
  std::vector<Eigen::Matrix<double, 6, 4>> Delta(contact_bores.size());
  for (size_t b = 0; b < contact_bores.size(); ++b) {
    const int k = contact_bores[b].iface;
    Delta[b] = rotate6(pose.R[size_t(interfaces[size_t(k)].body)]) * across;
    rhs_d.block(at.ol, 4 * Eigen::Index(b), 6 * at.M, 4) -= members.S.middleCols(6 * k, 6) * Delta[b];
    for (int r = 0; r < at.nc; ++r)
      rhs_d.block(at.om + r, 4 * Eigen::Index(b), 1, 4) -= members.rows[size_t(r)].segment(6 * k, 6) * Delta[b];
  }
  auto solve_scaled = [&](const Eigen::MatrixXd& rhs) -> Eigen::MatrixXd {
    return solved.Dc.asDiagonal() * solved.lu.solve(solved.Dr.asDiagonal() * rhs);
  };
  const Eigen::MatrixXd Xp = solve_scaled(rhs_p), Xd = solve_scaled(rhs_d);
  const Eigen::VectorXd x0 = solved.x;
  // What the contact sees of solution columns: the gaps through their parts'
  // interface loads (H^T K^-1 G lambda_body), and each bore's coupling load
  // across the axis (body axes).
  auto gap_of = [&](const Eigen::Ref<const Eigen::MatrixXd>& X) {
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero(m, X.cols());
    for (const auto& part : parts) {
      if (part->contact_bores.empty()) continue;
      const Matrix6d Q = rotate6(pose.R[size_t(part->body_index)]);
      Eigen::MatrixXd lambda_body(6 * Eigen::Index(part->interfaces.size()), X.cols());
      for (size_t l = 0; l < part->interfaces.size(); ++l)
        lambda_body.middleRows(6 * Eigen::Index(l), 6) = Q.transpose() * X.middleRows(at.ol + 6 * part->interfaces[l], 6);
      g.middleRows(part->first_contact_corner, part->contact_corners) = part->HKG * lambda_body;
    }
    return g;
  };
  auto load_of = [&](const Eigen::Ref<const Eigen::MatrixXd>& X) {
    Eigen::MatrixXd L(nq, X.cols());
    for (size_t b = 0; b < contact_bores.size(); ++b)
      L.middleRows(4 * Eigen::Index(b), 4) = Delta[b].transpose() * X.middleRows(at.ol + 6 * contact_bores[b].iface, 6);
    return L;
  };
  Eigen::VectorXd gap = gap_of(x0);
  Eigen::MatrixXd A = gap_of(Xp), E_gap = -gap_of(Xd), E_force = -load_of(Xp).transpose();
  Eigen::MatrixXd C = -load_of(Xd);
  const Eigen::VectorXd r = load_of(x0);
  for (const auto& part : parts)
    if (!part->contact_bores.empty()) {
      const Eigen::Index first = part->first_contact_corner, mP = part->contact_corners;
      A.block(first, first, mP, mP) += part->HKH;
      gap.segment(first, mP) += contact_load_gap[size_t(&part - &parts.front())];
    }
  for (size_t b = 0; b < contact_bores.size(); ++b) {
    const ContactBore& bore = contact_bores[b];
    const Eigen::Index first = parts[size_t(bore.part)]->first_contact_corner + bore.first, mb = bore.surface->size();
    gap.segment(first, mb) += bore.clearance_m * bore.surface->corner_area_m2();
    const Eigen::MatrixXd pin_map = (across.transpose() * bore.resultant).transpose();  // mb x 4: the pin's motion as weighted gaps
    E_gap.block(first, 4 * Eigen::Index(b), mb, 4) += pin_map;
    E_force.block(first, 4 * Eigen::Index(b), mb, 4) += pin_map;
  }
  // Maxwell-Betti: a unit pressure's load on the released pin is the gap a
  // unit pin motion opens there; the compliance and C are symmetric. A
  // mismatch beyond round-off is a defect of the model, not of the input.
  const double E_size = std::max(E_force.cwiseAbs().maxCoeff(), 1e-300);
  out.contact.reciprocity_error =
      std::max((E_gap - E_force).cwiseAbs().maxCoeff() / E_size,
               (A - A.transpose()).cwiseAbs().maxCoeff() / std::max(A.cwiseAbs().maxCoeff(), 1e-300));
  require(out.contact.reciprocity_error <= 1e-6,
          "elastic assembly at t = {:.6g} s: the pins' contact responses are not reciprocal ({:.1e}): an internal "
          "inconsistency, please report it",
          frame.t, out.contact.reciprocity_error);
  A = 0.5 * (A + A.transpose()).eval();
  const Eigen::MatrixXd E = 0.5 * (E_gap + E_force);
  // C, the structure's stiffness against the pins' motions, is positive
  // semi-definite; a statically determinate structure has none (round-off).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (C + C.transpose()));
  C = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  if (contact_set.size() != size_t(m)) contact_set.clear();
  fem::ContactSolution solution;
  try {
    solution = fem::solve_contact(A, gap, E, C, r, contact_set, options.contact);
  } catch (const Error& e) {
    std::vector<std::string> names;
    for (const ContactBore& bore : contact_bores) names.push_back(model.joints[size_t(bore.joint)].name);
    fail("elastic assembly at t = {:.6g} s: the pins in contact (joints {}): {}", frame.t, fmt::join(names, ", "),
         e.what());
  }
  contact_set = solution.in_contact;
  pressure = solution.pressure;
  solved.pin_motion = solution.pin_motion;
  solved.x_coupling = x0;
  solved.x = x0 + Xp * pressure + Xd * solution.pin_motion;
  solved.release = Eigen::VectorXd::Zero(6 * at.M);
  for (size_t b = 0; b < contact_bores.size(); ++b)
    solved.release.segment<6>(6 * contact_bores[b].iface) =
        Delta[b] * solution.pin_motion.segment<4>(4 * Eigen::Index(b));

  out.contact.corners = int(m);
  out.contact.in_contact = int(std::count(contact_set.begin(), contact_set.end(), char(1)));
  out.contact.active_set_steps = solution.active_set_steps;
  out.contact.interior_point = solution.interior_point_steps > 0;
  out.contact.resultant_error = solution.resultant_error;
  for (size_t b = 0; b < contact_bores.size(); ++b) {
    const ContactBore& bore = contact_bores[b];
    const PartData& part = *parts[size_t(bore.part)];
    const Eigen::Index first = part.first_contact_corner + bore.first, mb = bore.surface->size();
    BoreContactResult result;
    result.joint = model.joints[size_t(bore.joint)].name;
    result.body = part.body;
    result.face_set = bore.surface->face_set();
    result.clearance_m = bore.clearance_m;
    result.pressure_pa = pressure.segment(first, mb);
    result.state = fem::contact_state(*bore.surface, result.pressure_pa);
    result.pin_motion = solution.pin_motion.segment<4>(4 * Eigen::Index(b));
    // The mean overlap at a corner (weighted gap over its area).
    out.contact.worst_penetration_m =
        std::max(out.contact.worst_penetration_m,
                 (-solution.gap.segment(first, mb).cwiseQuotient(bore.surface->corner_area_m2())).maxCoeff());
    out.contacts.push_back(std::move(result));
  }
  out.contact.worst_penetration_m = std::max(0.0, out.contact.worst_penetration_m);
  stats.contact_seconds += clock.seconds();
  stats.contact_interior_point_poses += out.contact.interior_point ? 1 : 0;
  stats.most_contact_active_set_steps = std::max(stats.most_contact_active_set_steps, solution.active_set_steps);
}

// ---------------------------------------------------------------------------

void ElasticAssembly::Impl::add_fields(std::vector<PoseSolution>& poses, const std::vector<mech::Frame>& frames,
                                       const std::vector<FieldInputs>& inputs,
                                       const std::vector<Eigen::MatrixXd>& load_displacement,
                                       const std::vector<Eigen::MatrixXd>& coefficients, MotionFields* motion,
                                       size_t first) {
  Stopwatch clock;
  const Eigen::Index count = Eigen::Index(poses.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    PartData& part = *parts[p];
    const fem::Mesh& mesh = part.supported.mesh;
    const fem::Index N = mesh.node_count();
    Eigen::MatrixXd lambda(part.ZG.cols(), count);
    for (Eigen::Index f = 0; f < count; ++f) lambda.col(f) = inputs[size_t(f)].lambda_body[p];
    if (in_chunks(part, motion)) {
      add_chunked_fields(part, p, poses, frames, inputs, lambda, coefficients[p], *motion, first);
      continue;
    }
    Eigen::MatrixXd elastic = load_displacement[p];
    fem::blas_product(part.ZG, lambda, elastic, 1.0);
    const bool contact = !part.contact_bores.empty();
    if (contact) {  // + K_s^-1 F_c p, one block solve (lambda already has - X p)
      Eigen::MatrixXd pressure(part.contact_corners, count);
      for (Eigen::Index f = 0; f < count; ++f) pressure.col(f) = inputs[size_t(f)].contact_pressure[p];
      elastic += solve_columns(*part.analysis, contact_forces(part, pressure));
    }
    // Kept between blocks: a fresh block of this size is mapped anew and
    // costs more in page faults than the products.
    Eigen::MatrixXd& stress = part.stress_block;
    // A part with pins in contact: its stress recovered pose by pose (the
    // contact pressure has no fixed patterns).
    const bool stress_from_patterns = options.recover_stress && part.superposed && !contact;
    if (stress_from_patterns) {
      if (stress.rows() != part.SG.rows() || stress.cols() < count) stress.resize(part.SG.rows(), count);
      fem::blas_product(part.SG, lambda, stress.leftCols(count));
      fem::blas_product(part.Sp, coefficients[p], stress.leftCols(count), 1.0);
    }
    for (Eigen::Index f = 0; f < count; ++f) {
      const Eigen::Matrix3d R = rot_z(frames[size_t(f)].bodies[size_t(part.body_index)].q.z());
      const Vector3d& t = inputs[size_t(f)].translation[p];
      const Vector3d& w = inputs[size_t(f)].rotation[p];
      PartField field;
      field.body = part.body;
      field.displacement_m.resize(N, 3);
      if (stress_from_patterns) field.von_mises_pa.resize(N);
      const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> sv(
          stress_from_patterns ? stress.col(f).data() : nullptr, 6, stress_from_patterns ? N : 0);
#pragma omp parallel for schedule(static)
      for (fem::Index i = 0; i < N; ++i) {
        const Vector3d X = mesh.nodes.row(i).transpose();
        const Vector3d ub = elastic.col(f).segment<3>(3 * i) + t + w.cross(X);
        field.displacement_m.row(i) = (R * ub).transpose();
        if (stress_from_patterns) field.von_mises_pa[i] = fem::von_mises(sv.col(i));
      }
      field.max_displacement_m = field.displacement_m.rowwise().norm().maxCoeff(&field.max_displacement_node);
      if (options.recover_stress && !stress_from_patterns) {
        const fem::DisplacementField ue = Eigen::Map<const fem::DisplacementField>(elastic.col(f).data(), N, 3);
        fem::NodalStress recovered = fem::recover_nodal_stress(mesh, fem::element_materials(part.supported), ue);
        field.von_mises_pa = std::move(recovered.von_mises_pa);
        if (options.keep_part_stress)
          field.stress_pa = Eigen::Map<const Eigen::VectorXd>(recovered.stress_pa.data(), recovered.stress_pa.size());
      }
      if (field.von_mises_pa.size() > 0) field.max_von_mises_pa = field.von_mises_pa.maxCoeff();
      if (options.keep_part_stress && stress_from_patterns) {
        field.stress_coefficients.resize(lambda.rows() + coefficients[p].rows());
        field.stress_coefficients << lambda.col(f), coefficients[p].col(f);
      }
      if (motion) {  // the envelope from the full fields; kept where written
        PartEnvelope& e = motion->envelopes[p];
        const int step = int(motion->first_step + first + size_t(f));
        const Eigen::VectorXd magnitude = field.displacement_m.rowwise().norm();
        for (Eigen::Index i = 0; i < N; ++i)
          if (magnitude(i) > e.max_displacement_m(i))
            e.max_displacement_m(i) = magnitude(i), e.displacement_step(i) = step;
        for (Eigen::Index i = 0; i < e.max_von_mises_pa.size(); ++i)
          if (field.von_mises_pa(i) > e.max_von_mises_pa(i))
            e.max_von_mises_pa(i) = field.von_mises_pa(i), e.von_mises_step(i) = step;
        if (!motion->write.empty() && !motion->write[first + size_t(f)]) {
          field.displacement_m.resize(0, 3);
          field.von_mises_pa.resize(0);
        }
      }
      PoseSolution& out = poses[size_t(f)];
      if (field.max_displacement_m > out.max_displacement_m || out.max_displacement_body.empty()) {
        out.max_displacement_m = field.max_displacement_m;
        out.max_displacement_body = field.body;
      }
      out.parts.push_back(std::move(field));
    }
  }
  stats.recovery_seconds += clock.seconds();
}

namespace {

// Nodes per chunk and poses per tile of add_chunked_fields: a chunk's
// pattern rows (9 x 1024 x the patterns and interface columns, 3 to 6 MB) and
// its tile (9 x 1024 x 128, 9.4 MB) stay in the last-level cache.
constexpr Eigen::Index kChunkNodes = 1024, kTilePoses = 128;

// Rows c, c + stride, ... of a node-major field matrix's chunk (nodes i0 ..
// i0 + n - 1, `stride` components a node) as n contiguous rows.
void copy_component_rows(const Eigen::MatrixXd& field, int stride, int c, Eigen::Index i0, Eigen::Index n,
                         Eigen::Ref<Eigen::MatrixXd> out) {
  using Strided = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
  out = Strided(field.data() + stride * i0 + c, n, field.cols(),
                Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(field.rows(), stride));
}

// A chunk's largest displacement magnitude (its node) and von Mises stress in one pose.
struct ChunkPeak {
  double displacement_m = -1.0, von_mises_pa = -1.0;
  Eigen::Index node = 0;
};

}  // namespace

void ElasticAssembly::Impl::add_chunked_fields(PartData& part, size_t p, std::vector<PoseSolution>& poses,
                                               const std::vector<mech::Frame>& frames,
                                               const std::vector<FieldInputs>& inputs, const Eigen::MatrixXd& lambda,
                                               const Eigen::MatrixXd& coefficients, MotionFields& motion,
                                               size_t first) {
  const fem::Mesh& mesh = part.supported.mesh;
  const fem::Index N = mesh.node_count();
  const Eigen::Index count = lambda.cols(), chunk = std::max<Eigen::Index>(1, std::min(kChunkNodes, N));
  const Eigen::Index mg = lambda.rows(), mp = coefficients.rows(), K = mp + mg;
  const Eigen::Index chunks = (N + chunk - 1) / chunk, tile = std::min(kTilePoses, count);
  PartEnvelope& env = motion.envelopes[p];
  const size_t poses_here = size_t(count);
  std::vector<Eigen::Matrix3d> R(poses_here);
  std::vector<PartField> fields(poses_here);
  std::vector<char> write(poses_here);
  for (Eigen::Index f = 0; f < count; ++f) {
    R[size_t(f)] = rot_z(frames[size_t(f)].bodies[size_t(part.body_index)].q.z());
    PartField& field = fields[size_t(f)];
    field.body = part.body;
    write[size_t(f)] = motion.write.empty() || motion.write[first + size_t(f)];
    if (write[size_t(f)]) {
      field.displacement_m.resize(N, 3);
      field.von_mises_pa.resize(N);
    }
  }
  // The coefficients of the stacked pattern columns [Z_p Z_G; S_p S_G].
  Eigen::MatrixXd C(K, count);
  C.topRows(mp) = coefficients;
  C.bottomRows(mg) = lambda;
  std::vector<ChunkPeak> peaks(size_t(chunks * count));  // chunk-major
  // The chunks on the cores, each with its own one-thread products: a team
  // of threads between multi-threaded BLAS calls spins against the BLAS's
  // own threads. A chunk's nodes are its own in the envelope and the fields.
  fem::BlasThreadLimit one_thread_each(1);
#pragma omp parallel
  {
    // The chunk's rows component-major (its n x rows, then its n y rows,
    // ..., then its six stress components), so that the tile's components
    // are contiguous and the arithmetic below vectorizes; copied once a
    // block of poses, a small share of the products.
    Eigen::MatrixXd A(9 * chunk, K), T(9 * chunk, tile);
    Eigen::ArrayXd X(chunk), Y(chunk), Z(chunk), bx(chunk), by(chunk), bz(chunk), wx(chunk), wy(chunk), wz(chunk),
        magnitude(chunk), vm(chunk);
#pragma omp for schedule(dynamic)
    for (Eigen::Index ci = 0; ci < chunks; ++ci) {
      const Eigen::Index i0 = ci * chunk, n = std::min(chunk, N - i0);
      for (int c = 0; c < 3; ++c) {
        copy_component_rows(part.Zp, 3, c, i0, n, A.block(c * n, 0, n, mp));
        copy_component_rows(part.ZG, 3, c, i0, n, A.block(c * n, mp, n, mg));
      }
      for (int c = 0; c < 6; ++c) {
        copy_component_rows(part.Sp, 6, c, i0, n, A.block((3 + c) * n, 0, n, mp));
        copy_component_rows(part.SG, 6, c, i0, n, A.block((3 + c) * n, mp, n, mg));
      }
      X.head(n) = mesh.nodes.col(0).segment(i0, n).array();
      Y.head(n) = mesh.nodes.col(1).segment(i0, n).array();
      Z.head(n) = mesh.nodes.col(2).segment(i0, n).array();
      for (Eigen::Index f0 = 0; f0 < count; f0 += tile) {
        const Eigen::Index fn = std::min(tile, count - f0);
        auto Tt = T.topLeftCorner(9 * n, fn);
        fem::blas_product(A.topRows(9 * n), C.middleCols(f0, fn), Tt);
        for (Eigen::Index f = f0; f < f0 + fn; ++f) {
          const Vector3d& t = inputs[size_t(f)].translation[p];
          const Vector3d& w = inputs[size_t(f)].rotation[p];
          const Eigen::Matrix3d& Rf = R[size_t(f)];
          const auto uc = [&](int c) { return Tt.col(f - f0).segment(c * n, n).array(); };
          const auto sc = [&](int c) { return Tt.col(f - f0).segment((3 + c) * n, n).array(); };
          // Body axes: elastic + t + w x X; then world axes.
          bx.head(n) = (uc(0) + t.x()) + (w.y() * Z.head(n) - w.z() * Y.head(n));
          by.head(n) = (uc(1) + t.y()) + (w.z() * X.head(n) - w.x() * Z.head(n));
          bz.head(n) = (uc(2) + t.z()) + (w.x() * Y.head(n) - w.y() * X.head(n));
          wx.head(n) = Rf(0, 0) * bx.head(n) + Rf(0, 1) * by.head(n) + Rf(0, 2) * bz.head(n);
          wy.head(n) = Rf(1, 0) * bx.head(n) + Rf(1, 1) * by.head(n) + Rf(1, 2) * bz.head(n);
          wz.head(n) = Rf(2, 0) * bx.head(n) + Rf(2, 1) * by.head(n) + Rf(2, 2) * bz.head(n);
          magnitude.head(n) = (wx.head(n).square() + wy.head(n).square() + wz.head(n).square()).sqrt();
          // fem::von_mises, on the chunk's nodes at once.
          vm.head(n) = (0.5 * ((sc(0) - sc(1)).square() + (sc(1) - sc(2)).square() + (sc(2) - sc(0)).square()) +
                        3.0 * (sc(3).square() + sc(4).square() + sc(5).square()))
                           .sqrt();
          const int step = int(motion.first_step + first + size_t(f));
          for (Eigen::Index j = 0; j < n; ++j) {
            const Eigen::Index i = i0 + j;
            if (magnitude[j] > env.max_displacement_m[i])
              env.max_displacement_m[i] = magnitude[j], env.displacement_step[i] = step;
            if (vm[j] > env.max_von_mises_pa[i]) env.max_von_mises_pa[i] = vm[j], env.von_mises_step[i] = step;
          }
          ChunkPeak& peak = peaks[size_t(ci * count + f)];
          peak.displacement_m = magnitude.head(n).maxCoeff(&peak.node);
          peak.node += i0;
          peak.von_mises_pa = vm.head(n).maxCoeff();
          if (write[size_t(f)]) {
            PartField& field = fields[size_t(f)];
            field.displacement_m.col(0).segment(i0, n) = wx.head(n).matrix();
            field.displacement_m.col(1).segment(i0, n) = wy.head(n).matrix();
            field.displacement_m.col(2).segment(i0, n) = wz.head(n).matrix();
            field.von_mises_pa.segment(i0, n) = vm.head(n).matrix();
          }
        }
      }
    }
  }
  for (Eigen::Index f = 0; f < count; ++f) {
    PartField& field = fields[size_t(f)];
    // The pose's largest values, chunks in node order (the first node on ties).
    field.max_displacement_m = field.max_von_mises_pa = -1.0;
    for (Eigen::Index ci = 0; ci < chunks; ++ci) {
      const ChunkPeak& peak = peaks[size_t(ci * count + f)];
      if (peak.displacement_m > field.max_displacement_m)
        field.max_displacement_m = peak.displacement_m, field.max_displacement_node = peak.node;
      field.max_von_mises_pa = std::max(field.max_von_mises_pa, peak.von_mises_pa);
    }
    if (options.keep_part_stress) {
      field.stress_coefficients.resize(mg + mp);
      field.stress_coefficients << lambda.col(f), coefficients.col(f);
    }
    PoseSolution& out = poses[size_t(f)];
    if (field.max_displacement_m > out.max_displacement_m || out.max_displacement_body.empty()) {
      out.max_displacement_m = field.max_displacement_m;
      out.max_displacement_body = field.body;
    }
    out.parts.push_back(std::move(field));
  }
}

void ElasticAssembly::Impl::set_up_load_patterns(PartData& part) {
  const fem::Mesh& mesh = part.supported.mesh;
  const Eigen::MatrixXd P = part.loads->pattern_forces();
  part.Rp.resize(6, P.cols());
  for (Eigen::Index k = 0; k < P.cols(); ++k) {
    Vector3d force, moment;
    fem::resultant(mesh, P.col(k), Vector3d::Zero(), force, moment);
    part.Rp.col(k) << force, moment;
  }
  part.Zp = solve_columns(*part.analysis, P);
  if (part.rigid) part.Zp += part.rigid->correction(part.Zp);
  part.GtZp = part.G.transpose() * part.Zp;
  if (options.recover_stress) {
    const fem::ElementMaterials materials = fem::element_materials(part.supported);
    part.SG = detail::nodal_stress_columns(mesh, materials, part.ZG);
    part.Sp = detail::nodal_stress_columns(mesh, materials, part.Zp);
  }
  part.superposed = true;
}

ElasticAssembly::Impl::PoseMembers ElasticAssembly::Impl::members_of(const mech::Frame& frame,
                                                                    const Pose& pose) const {
  const int M = int(interfaces.size());
  const double Lr = length_scale;
  PoseMembers out;
  out.S = Eigen::MatrixXd::Zero(6 * M, 6 * M);
  Eigen::MatrixXd& S = out.S;
  auto& rows = out.rows;
  auto& row_rotation = out.row_rotation;
  auto& row_in_plane = out.row_in_plane;
  auto& row_owner = out.row_owner;
  auto add_row = [&](const Eigen::RowVectorXd& r, int component, const std::string& owner) {
    rows.push_back(r);
    row_rotation.push_back(component >= 3);
    row_in_plane.push_back(component == 0 || component == 1 || component == 5);
    row_owner.push_back(owner);
  };
  auto& spring_g = out.spring_g;
  auto& spring_k = out.spring_k;
  auto& spring_name = out.spring_name;
  auto& chain_pose = out.chain_pose;
  chain_pose.resize(joints.size());
  double& max_compliance = out.max_compliance;
  for (size_t j = 0; j < joints.size(); ++j) {
    const JointData& jd = joints[j];
    const mech::Joint& joint = model.joints[size_t(jd.joint)];
    if (jd.tie == mech::AssemblyTie::ChainSpring) {
      const Vector2d hinge =
          pose.origin[size_t(jd.body_i)].head<2>() + pose.R[size_t(jd.body_i)].topLeftCorner<2, 2>() * jd.hinge;
      const Vector3d& A = pose.P[size_t(jd.if_j)];
      const mech::ChainTangent tangent = mech::chain_tangent(hinge, A.head<2>(), jd.radius, jd.sigma);
      ChainPose& cp = chain_pose[j];
      cp.b = tangent.free_length_m;
      require(cp.b > 0 && std::isfinite(cp.b), "elastic assembly at t = {:.6g} s: chain '{}' has no free length",
              frame.t, joint.name);
      cp.k = jd.ea / cp.b;
      cp.T = lift(tangent.tangent_point_m, A.z());
      cp.n = (lift(hinge, A.z()) - cp.T).normalized();
      Eigen::Matrix<double, 3, 6> Bm;
      Bm << Eigen::Matrix3d::Identity(), -skew(cp.T - A);
      cp.g = -cp.n.transpose() * Bm;  // elongation = n . (u_hinge - u_T), u_hinge = 0 on the rigid ground
      spring_g.push_back(Eigen::RowVectorXd::Zero(6 * M));
      spring_g.back().segment<6>(6 * jd.if_j) = cp.g;
      if (jd.if_i >= 0) {  // the hinge on a face of the frame: u_hinge is that interface's motion at the hinge
        Eigen::Matrix<double, 3, 6> Bh;
        Bh << Eigen::Matrix3d::Identity(), -skew(lift(hinge, A.z()) - pose.P[size_t(jd.if_i)]);
        cp.g_hinge = cp.n.transpose() * Bh;
        spring_g.back().segment<6>(6 * jd.if_i) = cp.g_hinge;
      }
      S += cp.k * spring_g.back().transpose() * spring_g.back();
      max_compliance = std::max(max_compliance, 1.0 / cp.k);
      spring_k.push_back(cp.k);
      spring_name.push_back("chain." + joint.name);
      continue;
    }
    if (jd.tie == mech::AssemblyTie::Slide) {
      // Rows in the slide's axes: across it in the plane (n), along z, the
      // three rotations; the slider's motion at its point minus the guide's
      // carried rigidly to that point (an elastic guide: its two bracketing
      // stations, weighted).
      const Vector3d t = pose.R[size_t(jd.body_i)] * lift(jd.axis);
      const Vector3d n = Vector3d::UnitZ().cross(t);
      std::vector<std::pair<int, double>> guide;  // interfaces and weights
      if (!jd.stations.empty()) {
        const Bracket bracket = slide_bracket(jd, frame, pose);
        guide.push_back({bracket.a, 1.0 - bracket.weight_b});
        if (bracket.b != bracket.a) guide.push_back({bracket.b, bracket.weight_b});
      } else if (jd.if_i >= 0) {
        guide.push_back({jd.if_i, 1.0});
      }
      const std::pair<int, Vector3d> held[5] = {{0, n}, {2, Vector3d::UnitZ()}, {3, Vector3d::UnitX()},
                                                {4, Vector3d::UnitY()}, {5, Vector3d::UnitZ()}};
      const char* across[5] = {"across the slide", "z", "rx", "ry", "rz"};
      for (int c = 0; c < 5; ++c) {
        Eigen::Matrix<double, 1, 6> e = Eigen::Matrix<double, 1, 6>::Zero();
        if (held[c].first < 3)
          e.head<3>() = held[c].second.transpose();
        else
          e.tail<3>() = held[c].second.transpose();
        Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(6 * M);
        r.segment<6>(6 * jd.if_j) += e;
        for (const auto& [k, w] : guide)
          if (w != 0.0) r.segment<6>(6 * k) -= w * e * transfer(pose.P[size_t(jd.if_j)] - pose.P[size_t(k)]);
        add_row(r, held[c].first, fmt::format("joint '{}' ({})", joint.name, across[c]));
      }
      continue;
    }
    const int held = jd.held;
    Matrix6d T = Matrix6d::Identity();
    if (jd.if_i >= 0 && jd.if_j >= 0) T = transfer(pose.P[size_t(jd.if_j)] - pose.P[size_t(jd.if_i)]);
    for (int c = 0; c < held; ++c) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(6 * M);
      if (jd.if_j >= 0) r(6 * jd.if_j + c) += 1.0;
      if (jd.if_i >= 0) r.segment<6>(6 * jd.if_i) -= T.row(c);
      if (jd.pin >= 0) {  // an elastic pin carries the same load systems as the rigid tie, through its stiffness
        out.pin_rows.push_back(r);
        out.pin_row_in_plane.push_back(c == 0 || c == 1 || c == 5);
      } else {
        add_row(r, c, fmt::format("joint '{}' ({})", joint.name, kComponent[c]));
      }
    }
    if (jd.pin >= 0) {
      const PinData& pd = pins[size_t(jd.pin)];
      auto end = [&](int k, int body, const Vector3d& on_ground) {
        return k >= 0 ? pose.P[size_t(k)] : Vector3d(pose.origin[size_t(body)] + pose.R[size_t(body)] * on_ground);
      };
      PoseMembers::PinPose pp{jd.pin, jd.if_i, jd.if_j,
                              PinMember(end(jd.if_i, jd.body_i, pd.ground_end_i), end(jd.if_j, jd.body_j, pd.ground_end_j),
                                        pd.section, fmt::format("elastic assembly: the pin of joint '{}'", joint.name))};
      const Matrix12d& K = pp.member.stiffness();
      const int at[2] = {jd.if_i, jd.if_j};
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          if (at[a] >= 0 && at[b] >= 0) S.block<6, 6>(6 * at[a], 6 * at[b]) += K.block<6, 6>(6 * a, 6 * b);
      for (int c = 0; c < 3; ++c)
        if (K(6 + c, 6 + c) > 0) max_compliance = std::max(max_compliance, 1.0 / K(6 + c, 6 + c));
      out.pin_pose.push_back(std::move(pp));
    }
  }
  for (const DriveData& dd : drives) {
    const std::string& name = model.motion_drives[size_t(dd.drive)].name;
    const Eigen::RowVectorXd g = drive_row(dd, pose);
    if (std::isinf(dd.k)) {
      add_row(g, dd.displacement ? 0 : 5, fmt::format("drive '{}'", name));
    } else {
      S += dd.k * g.transpose() * g;
      if (dd.k > 0) max_compliance = std::max(max_compliance, dd.displacement ? 1.0 / dd.k : Lr * Lr / dd.k);
      spring_g.push_back(g);
      spring_k.push_back(dd.k);
      spring_name.push_back("drive." + name);
    }
  }
  for (const TransmissionData& td : transmissions) {
    const std::string& name = model.transmissions[size_t(td.transmission)].name;
    const Eigen::RowVectorXd g = transmission_row(td);
    const double k = td.member.torsional_stiffness_nm_per_rad;
    if (std::isinf(k)) {
      add_row(g, 5, fmt::format("transmission '{}'", name));
    } else {
      S += k * g.transpose() * g;
      if (k > 0) max_compliance = std::max(max_compliance, Lr * Lr / k);
      spring_g.push_back(g);
      spring_k.push_back(k);
      spring_name.push_back("transmission." + name);
    }
  }
  return out;
}

Eigen::RowVectorXd ElasticAssembly::Impl::drive_row(const DriveData& dd, const Pose& pose) const {
  Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(6 * Eigen::Index(interfaces.size()));
  if (!dd.displacement) {
    if (dd.if_j >= 0) g(6 * dd.if_j + 5) += 1.0;
    if (dd.if_i >= 0) g(6 * dd.if_i + 5) -= 1.0;
    return g;
  }
  auto world = [&](int k, int body, const Vector2d& point) {
    return k >= 0 ? pose.P[size_t(k)] : Vector3d(pose.origin[size_t(body)] + pose.R[size_t(body)] * lift(point));
  };
  const Vector3d t = pose.R[size_t(dd.body_i)] * lift(dd.axis);
  const Vector3d d = world(dd.if_j, dd.body_j, dd.point_j) - world(dd.if_i, dd.body_i, dd.point_i);
  if (dd.if_j >= 0) g.segment<3>(6 * dd.if_j) += t.transpose();
  if (dd.if_i >= 0) {
    g.segment<3>(6 * dd.if_i) -= t.transpose();
    g.segment<3>(6 * dd.if_i + 3) += t.cross(d).transpose();
  }
  return g;
}


ElasticAssembly::Impl::PoseLayout ElasticAssembly::Impl::layout_of(const PoseMembers& members) const {
  PoseLayout at;
  at.M = int(interfaces.size());
  at.B = moving_count;
  at.nc = int(members.rows.size());
  at.ou = 0;
  at.ol = 6 * at.M;
  at.oa = 12 * at.M;
  at.om = 12 * at.M + 6 * at.B;
  at.n = at.om + at.nc;
  return at;
}

ElasticAssembly::Impl::PoseScales ElasticAssembly::Impl::scales_of(
    const PoseMembers& members, const std::vector<Vector6d>& resultant_world) const {
  const double Lr = length_scale;
  double max_compliance = members.max_compliance;
  for (const auto& part : parts)
    for (Eigen::Index k = 0; k < part->F.rows(); ++k)
      if (k % 6 < 3) max_compliance = std::max(max_compliance, part->F(k, k));
  double P = 0.0;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (!ground(int(b))) {
      const Vector6d& r = resultant_world[size_t(moving[b])];
      P = std::max({P, r.head<3>().norm(), r.tail<3>().norm() / Lr});
    }
  if (!(P > 0)) P = 1.0;
  if (!(max_compliance > 0)) max_compliance = Lr / P;
  PoseScales scales;
  scales.P = P;
  scales.U = max_compliance * P;
  return scales;
}

ElasticAssembly::Impl::PoseSystem ElasticAssembly::Impl::assemble_pose_system(
    const Pose& pose, const PoseMembers& members, const PoseLayout& at,
    const std::vector<Eigen::VectorXd>& interface_load_displacement,
    const std::vector<Vector6d>& resultant_world) const {
  const int M = at.M, nc = at.nc, n = at.n;
  const int ou = at.ou, ol = at.ol, oa = at.oa, om = at.om;
  PoseSystem system;
  system.A = Eigen::MatrixXd::Zero(n, n);
  system.rhs = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd& A = system.A;
  Eigen::VectorXd& rhs = system.rhs;
  for (int k = 0; k < M; ++k) {
    const Interface& iface = interfaces[size_t(k)];
    const int mb = moving[size_t(iface.body)];
    // (a) u_k - sum_l F_kl lambda_l - R_k alpha = d_k; on the frame (mb < 0)
    // no alpha: its foundation holds it
    A.block<6, 6>(ou + 6 * k, ou + 6 * k).setIdentity();
    if (mb >= 0) A.block<6, 6>(ou + 6 * k, oa + 6 * mb) = -transfer(pose.arm[size_t(k)]);
    if (iface.part >= 0) {
      const PartData& part = *parts[size_t(iface.part)];
      const Matrix6d Q = rotate6(pose.R[size_t(iface.body)]);
      for (size_t l = 0; l < part.interfaces.size(); ++l) {
        const Matrix6d Fkl = part.F.block<6, 6>(6 * iface.local, 6 * Eigen::Index(l));
        A.block<6, 6>(ou + 6 * k, ol + 6 * part.interfaces[l]) = -Q * Fkl * Q.transpose();
      }
      const Vector6d d = interface_load_displacement[size_t(iface.part)].segment<6>(6 * iface.local);
      rhs.segment<6>(ou + 6 * k) = Q * d;
    }
    // (b) lambda_k - (C^T mu)_k + (S u)_k = 0
    A.block<6, 6>(ol + 6 * k, ol + 6 * k).setIdentity();
    // (c) sum_k R_k^T lambda_k = -r_b; none for the frame (the foundation
    // takes its resultant)
    if (mb >= 0) A.block<6, 6>(oa + 6 * mb, ol + 6 * k) = transfer(pose.arm[size_t(k)]).transpose();
  }
  A.block(ol, ou, 6 * M, 6 * M) = members.S;
  for (int r = 0; r < nc; ++r) {
    A.block(ol, om + r, 6 * M, 1) = -members.rows[size_t(r)].transpose();
    A.block(om + r, ou, 1, 6 * M) = members.rows[size_t(r)];  // (d) C u = 0
  }
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (!ground(int(b))) rhs.segment<6>(oa + 6 * moving[b]) = -resultant_world[size_t(moving[b])];
  return system;
}

ElasticAssembly::Impl::PoseUnknowns ElasticAssembly::Impl::solve_equilibrated(const mech::Frame& frame,
                                                                              const Pose& pose,
                                                                              const PoseMembers& members,
                                                                              const PoseLayout& at,
                                                                              const PoseScales& scales,
                                                                              const PoseSystem& system) const {
  const int M = at.M, B = at.B, nc = at.nc, n = at.n;
  const int ou = at.ou, ol = at.ol, oa = at.oa, om = at.om;
  const double Lr = length_scale, P = scales.P, U = scales.U;
  Eigen::VectorXd var(n), eq(n);
  for (int k = 0; k < 6 * M; ++k) {
    const bool rot = k % 6 >= 3;
    var(ou + k) = rot ? U / Lr : U;
    var(ol + k) = rot ? P * Lr : P;
    eq(ou + k) = rot ? U / Lr : U;
    eq(ol + k) = rot ? P * Lr : P;
  }
  for (int k = 0; k < 6 * B; ++k) {
    const bool rot = k % 6 >= 3;
    var(oa + k) = rot ? U / Lr : U;
    eq(oa + k) = rot ? P * Lr : P;
  }
  for (int r = 0; r < nc; ++r) {
    var(om + r) = members.row_rotation[size_t(r)] ? P * Lr : P;
    eq(om + r) = members.row_rotation[size_t(r)] ? U / Lr : U;
  }
  PoseUnknowns solved;
  solved.at = at;
  Eigen::MatrixXd As = eq.cwiseInverse().asDiagonal() * system.A * var.asDiagonal();
  solved.Dr = eq.cwiseInverse();
  solved.Dc = var;
  detail::ruiz_equilibrate(As, solved.Dr, solved.Dc);
  const Eigen::VectorXd bs = solved.Dr.cwiseProduct(system.rhs);
  solved.lu.compute(As);
  solved.lu.setThreshold(options.rank_tolerance);
  solved.rank = int(solved.lu.rank());
  if (solved.rank < n)
    explain_rank_deficiency(frame, pose, solved.lu.kernel(), solved.Dc, solved.rank, n, members.row_owner);
  const Eigen::VectorXd y = solved.lu.solve(bs);
  solved.residual = bs.norm() > 0 ? (As * y - bs).norm() / bs.norm() : (As * y).norm();
  solved.x = solved.Dc.cwiseProduct(y);
  return solved;
}

void ElasticAssembly::Impl::add_body_motions(PoseSolution& out, const PoseUnknowns& solved) const {
  const int oa = solved.at.oa;
  const Eigen::VectorXd& x = solved.x;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (ground(int(b))) continue;
    BodyMotion bm;
    bm.body = body_name(int(b));
    bm.elastic = part_of_body[b] >= 0;
    bm.translation_m = x.segment<3>(oa + 6 * moving[b]);
    bm.rotation_rad = x.segment<3>(oa + 6 * moving[b] + 3);
    out.bodies.push_back(bm);
  }
}

void ElasticAssembly::Impl::add_joint_loads(PoseSolution& out, const mech::Frame& frame, const Pose& pose,
                                            const PoseMembers& members, const PoseUnknowns& solved,
                                            double P) const {
  for (size_t j = 0; j < joints.size(); ++j) {
    const JointData& jd = joints[j];
    const mech::Joint& joint = model.joints[size_t(jd.joint)];
    JointLoad jl;
    jl.joint = joint.name;
    jl.type = joint.type;
    jl.body_i = joint.body_i;
    jl.body_j = joint.body_j;
    if (jd.tie == mech::AssemblyTie::ChainSpring) {
      const ChainPose& cp = members.chain_pose[j];
      ChainResult cr;
      cr.chain = joint.name;
      cr.axial_stiffness_n = jd.ea;
      cr.free_length_m = cp.b;
      cr.stiffness_n_per_m = cp.k;
      cr.elongation_m = cp.g.dot(solved.u_of(jd.if_j)) + cp.g_hinge.dot(solved.u_of(jd.if_i));
      cr.tension_n = cp.k * cr.elongation_m;
      cr.tangent_point_m = cp.T;
      cr.direction = cp.n;
      if (!(cr.tension_n > 1e-9 * P))
        fail(
            "elastic assembly at t = {:.6g} s: chain '{}' would have to push (tension {:.6g} N): it is slack in this "
            "pose, and a tension-only member cannot hold it",
            frame.t, joint.name, cr.tension_n);
      out.chains.push_back(cr);
      const Vector6d lj = solved.lambda_of(jd.if_j);
      jl.point_j_m = pose.P[size_t(jd.if_j)];
      jl.force_on_j_n = lj.head<3>();
      jl.moment_on_j_nm = lj.tail<3>();
      jl.point_i_m = cp.T + cp.b * cp.n;  // the hinge
      jl.force_on_i_n = -cr.tension_n * cp.n;
      out.joints.push_back(jl);
      continue;
    }
    if (jd.pin >= 0) {  // what the elastic pin applies at its two ends
      const PoseMembers::PinPose& pp = members.pin_pose[size_t(jd.pin)];
      const PinLoads loads = pp.member.loads(pin_motion(pp, solved));
      jl.point_i_m = pp.member.end_i();
      jl.point_j_m = pp.member.end_j();
      jl.force_on_i_n = loads.force_on_i_n;
      jl.moment_on_i_nm = loads.moment_on_i_nm;
      jl.force_on_j_n = loads.force_on_j_n;
      jl.moment_on_j_nm = loads.moment_on_j_nm;
      out.joints.push_back(jl);
      continue;
    }
    out.joints.push_back(held_joint_load(jl, jd, pose, solved));
  }
}

void ElasticAssembly::Impl::add_pin_results(PoseSolution& out, const PoseMembers& members,
                                            const PoseUnknowns& solved) const {
  for (const PoseMembers::PinPose& pp : members.pin_pose) {
    const mech::Joint& joint = model.joints[size_t(pins[size_t(pp.pin)].joint)];
    PinResult pr;
    pr.joint = joint.name;
    pr.body_i = joint.body_i;
    pr.body_j = joint.body_j;
    pr.end_i_m = pp.member.end_i();
    pr.end_j_m = pp.member.end_j();
    pr.diameter_m = pp.member.section().diameter_m;
    pr.length_m = pp.member.length_m();
    pr.loads = pp.member.loads(pin_motion(pp, solved));
    out.pins.push_back(pr);
  }
}

JointLoad ElasticAssembly::Impl::held_joint_load(JointLoad jl, const JointData& jd, const Pose& pose,
                                                 const PoseUnknowns& solved) const {
  const Vector6d li = solved.lambda_of(jd.if_i), lj = solved.lambda_of(jd.if_j);
  if (jd.if_i >= 0) {
    jl.point_i_m = pose.P[size_t(jd.if_i)];
    jl.force_on_i_n = li.head<3>();
    jl.moment_on_i_nm = li.tail<3>();
  }
  if (jd.if_j >= 0) {
    jl.point_j_m = pose.P[size_t(jd.if_j)];
    jl.force_on_j_n = lj.head<3>();
    jl.moment_on_j_nm = lj.tail<3>();
  }
  if (jd.if_i < 0) {  // the ground's side: the reaction of the other
    jl.point_i_m = jl.point_j_m;
    jl.force_on_i_n = -jl.force_on_j_n;
    jl.moment_on_i_nm = -jl.moment_on_j_nm;
  }
  if (jd.if_j < 0) {
    jl.point_j_m = jl.point_i_m;
    jl.force_on_j_n = -jl.force_on_i_n;
    jl.moment_on_j_nm = -jl.moment_on_i_nm;
  }
  return jl;
}

void ElasticAssembly::Impl::add_drive_results(PoseSolution& out, const Pose& pose, const PoseUnknowns& solved) const {
  for (const DriveData& dd : drives) {
    DriveResult dr;
    dr.drive = model.motion_drives[size_t(dd.drive)].name;
    dr.rigid = std::isinf(dd.k);
    if (dd.displacement) {
      // Its interfaces carry only the drive's force along the axis (and, on
      // body_i's side, the moment of the axis turning): their loads are g^T
      // times the force.
      const Eigen::RowVectorXd g = drive_row(dd, pose);
      Eigen::VectorXd u(g.size());
      for (Eigen::Index k = 0; k < g.size() / 6; ++k) u.segment<6>(6 * k) = solved.u_of(int(k));
      dr.displacement = true;
      dr.stiffness_n_per_m = dd.k;
      dr.stretch_m = g.dot(u);
      const Vector3d t = pose.R[size_t(dd.body_i)] * lift(dd.axis);
      dr.force_on_j_n = dd.if_j >= 0 ? t.dot(solved.lambda_of(dd.if_j).head<3>()) : -t.dot(solved.lambda_of(dd.if_i).head<3>());
    } else {
      dr.stiffness_nm_per_rad = dd.k;
      dr.twist_rad = solved.u_of(dd.if_j)(5) - solved.u_of(dd.if_i)(5);
      dr.moment_on_j_nm = dd.if_j >= 0 ? solved.lambda_of(dd.if_j)(5) : -solved.lambda_of(dd.if_i)(5);
    }
    out.drives.push_back(dr);
  }
}

void ElasticAssembly::Impl::add_point_results(PoseSolution& out, const Pose& pose, const PoseMembers& members,
                                              const PoseUnknowns& solved) const {
  for (size_t p = 0; p < points.size(); ++p) {
    PointResult pr;
    pr.name = options.points[p].name;
    pr.body = options.points[p].body;
    const int k = points[p].iface;
    pr.position_m = pose.P[size_t(k)];
    const Vector6d u = solved.u_of(k);
    pr.displacement_m = u.head<3>();
    pr.rotation_rad = u.tail<3>();
    pr.coupling_displacement_m =
        solved.x_coupling.size() > 0 ? Vector3d(solved.x_coupling.segment<3>(solved.at.ou + 6 * k)) : pr.displacement_m;
    if (options.unit_load_split) split_by_unit_loads(pr, k, pose, members, solved);
    out.points.push_back(pr);
  }
}

void ElasticAssembly::Impl::split_by_unit_loads(PointResult& pr, int k, const Pose& pose, const PoseMembers& members,
                                                const PoseUnknowns& solved) const {
  const int M = solved.at.M, n = solved.at.n, ou = solved.at.ou, ol = solved.at.ol, oa = solved.at.oa;
  const Eigen::VectorXd& x = solved.x;
  const auto& spring_g = members.spring_g;
  const auto& spring_k = members.spring_k;
  auto deformation_of = [&](int l) -> Vector6d {  // u_l - R_l alpha = F lambda + d (world)
    const int mb = moving[size_t(interfaces[size_t(l)].body)];
    if (mb < 0) return solved.u_of(l);  // the frame: no rigid motion
    return solved.u_of(l) - transfer(pose.arm[size_t(l)]) * x.segment<6>(oa + 6 * mb);
  };
  for (const auto& part : parts) pr.contributions.push_back({"part." + part->body, Vector3d::Zero()});
  for (const auto& name : members.spring_name) pr.contributions.push_back({name, Vector3d::Zero()});
  const size_t first_pin = pr.contributions.size();
  for (const auto& pp : members.pin_pose)
    pr.contributions.push_back({"pin." + model.joints[size_t(pins[size_t(pp.pin)].joint)].name, Vector3d::Zero()});
  // A pin in contact: the virtual tie load at its bore on the pin's motion
  // there (the release; one entry per joint).
  std::vector<size_t> play_of_bore;
  for (const ContactBore& bore : contact_bores) {
    const std::string name = "play." + model.joints[size_t(bore.joint)].name;
    auto it = std::find_if(pr.contributions.begin(), pr.contributions.end(),
                           [&](const PointContribution& c) { return c.name == name; });
    if (it == pr.contributions.end()) {
      pr.contributions.push_back({name, Vector3d::Zero()});
      it = pr.contributions.end() - 1;
    }
    play_of_bore.push_back(size_t(it - pr.contributions.begin()));
  }
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(n);
    unit(ol + 6 * k + c) = 1.0;  // (b): lambda_k = e_c, the point's load on its body
    const Eigen::VectorXd xv = solved.Dc.cwiseProduct(solved.lu.solve(solved.Dr.cwiseProduct(unit)));
    pr.compliance_m_per_n.col(c) = xv.segment<3>(ou + 6 * k);
    for (size_t q = 0; q < parts.size(); ++q)
      for (const int l : parts[q]->interfaces)
        pr.contributions[q].displacement_m(c) += xv.segment<6>(ol + 6 * l).dot(deformation_of(l));
    for (size_t sm = 0; sm < spring_g.size(); ++sm) {
      const double virtual_force = spring_k[sm] * spring_g[sm].dot(xv.segment(ou, 6 * M));
      pr.contributions[parts.size() + sm].displacement_m(c) = virtual_force * spring_g[sm].dot(x.segment(ou, 6 * M));
    }
    // An elastic pin: the work of its virtual end loads on its real end motions.
    PoseUnknowns virtual_solution;
    virtual_solution.at = solved.at;
    virtual_solution.x = xv;
    for (size_t q = 0; q < members.pin_pose.size(); ++q) {
      const auto& pp = members.pin_pose[q];
      pr.contributions[first_pin + q].displacement_m(c) =
          pin_motion(pp, virtual_solution).dot(pp.member.stiffness() * pin_motion(pp, solved));
    }
    for (size_t b = 0; b < contact_bores.size(); ++b) {
      const int l = contact_bores[b].iface;
      pr.contributions[play_of_bore[b]].displacement_m(c) +=
          xv.segment<6>(ol + 6 * l).dot(solved.release.segment<6>(6 * l));
    }
  }
}

void ElasticAssembly::Impl::collect_field_inputs(const Pose& pose, const PoseUnknowns& solved,
                                                 FieldInputs& field_inputs) const {
  const int oa = solved.at.oa;
  const Eigen::VectorXd& x = solved.x;
  field_inputs.lambda_body.resize(parts.size());
  field_inputs.translation.resize(parts.size());
  field_inputs.rotation.resize(parts.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    const PartData& part = *parts[p];
    const int b = part.body_index;
    const Eigen::Matrix3d& R = pose.R[size_t(b)];
    const Matrix6d Q = rotate6(R);
    Eigen::VectorXd lambda_body(6 * Eigen::Index(part.interfaces.size()));
    for (size_t l = 0; l < part.interfaces.size(); ++l)
      lambda_body.segment<6>(6 * Eigen::Index(l)) = Q.transpose() * solved.lambda_of(part.interfaces[l]);
    field_inputs.lambda_body[p] = std::move(lambda_body);
    if (part.held) {  // the frame moves only by its deformation
      field_inputs.translation[p] = field_inputs.rotation[p] = Vector3d::Zero();
      continue;
    }
    field_inputs.translation[p] = R.transpose() * x.segment<3>(oa + 6 * moving[size_t(b)]);
    field_inputs.rotation[p] = R.transpose() * x.segment<3>(oa + 6 * moving[size_t(b)] + 3);
  }
}

PoseSolution ElasticAssembly::Impl::solve_pose(const mech::Frame& frame,
                                               const std::vector<Eigen::VectorXd>& interface_load_displacement,
                                               const std::vector<Eigen::VectorXd>& contact_load_gap,
                                               const std::vector<Vector6d>& resultant_world, FieldInputs& field_inputs) {
  Stopwatch clock;
  const Pose pose = pose_of(frame);
  // Springs S (chains, compliant drives) and constraint rows C (6M columns).
  const PoseMembers members = members_of(frame, pose);
  const PoseLayout at = layout_of(members);
  const PoseScales scales = scales_of(members, resultant_world);
  PoseUnknowns solved = solve_equilibrated(
      frame, pose, members, at, scales,
      assemble_pose_system(pose, members, at, interface_load_displacement, resultant_world));
  stats.system_seconds += clock.seconds();
  clock.restart();

  PoseSolution out;
  Eigen::VectorXd pressure;
  if (!contact_bores.empty()) solve_contact_pose(frame, pose, members, contact_load_gap, solved, out, pressure);
  out.t = frame.t;
  out.unknowns = at.n;
  out.rank = solved.rank;
  out.relative_residual = solved.residual;
  add_body_motions(out, solved);
  add_joint_loads(out, frame, pose, members, solved, scales.P);
  add_drive_results(out, pose, solved);
  add_transmission_results(out, frame, solved);
  add_pin_results(out, members, solved);
  {
    // Elastic pins carry the load systems of the rigid tie they replace.
    std::vector<Eigen::RowVectorXd> rows = members.rows;
    std::vector<bool> in_plane = members.row_in_plane;
    rows.insert(rows.end(), members.pin_rows.begin(), members.pin_rows.end());
    in_plane.insert(in_plane.end(), members.pin_row_in_plane.begin(), members.pin_row_in_plane.end());
    out.indeterminacy = indeterminacy_of(pose, rows, in_plane, members.spring_g);
  }
  add_point_results(out, pose, members, solved);
  collect_field_inputs(pose, solved, field_inputs);
  // A part with pins in contact is loaded by G lambda + H p = G (lambda - X p) + F_c p.
  field_inputs.contact_pressure.resize(parts.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    const PartData& part = *parts[p];
    if (part.contact_bores.empty()) continue;
    field_inputs.contact_pressure[p] = pressure.segment(part.first_contact_corner, part.contact_corners);
    field_inputs.lambda_body[p] -= part.contact_resultants * field_inputs.contact_pressure[p];
  }
  stats.recovery_seconds += clock.seconds();
  return out;
}

void ElasticAssembly::Impl::explain_rank_deficiency(const mech::Frame& frame, const Pose& pose,
                                                    const Eigen::MatrixXd& kernel, const Eigen::VectorXd& unscale,
                                                    int rank, int n, const std::vector<std::string>& row_owner) const {
  const int M = int(interfaces.size()), B = moving_count;
  const int ou = 0, ol = 6 * M, oa = 12 * M, om = 12 * M + 6 * B;
  const double Lr = length_scale;
  std::vector<std::string> free_things, stressed;
  auto note = [](std::vector<std::string>& list, const std::string& s) {
    if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
  };
  for (Eigen::Index c = 0; c < kernel.cols(); ++c) {
    const Eigen::VectorXd y = kernel.col(c).normalized();
    const double motion = std::max(y.segment(ou, 6 * M).norm(), y.segment(oa, 6 * B).norm());
    const double force = std::max(y.segment(ol, 6 * M).norm(), y.segment(om, n - om).norm());
    const Eigen::VectorXd x = unscale.cwiseProduct(y);
    if (motion >= 1e-3 * force) {
      // A mechanism: which free rotation moves?
      auto rz = [&](int k) { return k >= 0 ? x(ou + 6 * k + 5) : 0.0; };
      std::vector<std::pair<double, std::string>> candidates;
      for (const JointData& jd : joints) {
        if (jd.tie != mech::AssemblyTie::Rigid || jd.held == 6) continue;  // no free rotation about z
        const mech::Joint& joint = model.joints[size_t(jd.joint)];
        // A force drive (a motor torque) across the joint is a load, not a
        // support: name it, since it is what the user thought held the joint.
        std::string torque_only;
        for (const mech::ForceDrive& fd : model.force_drives) {
          const mech::RelativeCoordinate& fc = fd.coordinate;
          if (fc.type == mech::CoordinateType::Angle &&
              ((fc.body_i == joint.body_i && fc.body_j == joint.body_j) ||
               (fc.body_i == joint.body_j && fc.body_j == joint.body_i)))
            torque_only += fmt::format("; force drive '{}' applies a torque there but holds no angle", fd.name);
        }
        candidates.push_back({std::abs(rz(jd.if_j) - rz(jd.if_i)) * Lr,
                              fmt::format("the rotation about z at joint '{}' (between '{}' and '{}'{})", joint.name,
                                          joint.body_i, joint.body_j, torque_only)});
      }
      auto translation = [&](int k) { return k >= 0 ? Vector3d(x.segment<3>(ou + 6 * k)) : Vector3d::Zero(); };
      for (const JointData& jd : joints) {
        if (jd.tie != mech::AssemblyTie::Slide) continue;  // the slide: free unless a drive holds it
        const Vector3d t = pose.R[size_t(jd.body_i)] * lift(jd.axis);
        const int guide = !jd.stations.empty() ? jd.stations.front() : jd.if_i;
        const mech::Joint& joint = model.joints[size_t(jd.joint)];
        candidates.push_back({std::abs(t.dot(translation(jd.if_j) - translation(guide))),
                              fmt::format("the slide along the axis of prismatic joint '{}' (between '{}' and '{}'; "
                                          "no displacement drive holds it)",
                                          joint.name, joint.body_i, joint.body_j)});
      }
      for (const DriveData& dd : drives)
        if (dd.k == 0.0)
          candidates.push_back(
              {dd.displacement ? std::abs(drive_row(dd, pose).dot(x.segment(ou, 6 * M)))
                               : std::abs(rz(dd.if_j) - rz(dd.if_i)) * Lr,
               fmt::format("drive '{}' (zero {} stiffness)", model.motion_drives[size_t(dd.drive)].name,
                           dd.displacement ? "axial" : "torsional")});
      double body_motion = 0.0;
      std::string body_named;
      for (size_t b = 0; b < model.bodies.size(); ++b) {
        if (ground(int(b))) continue;
        const double m = x.segment<3>(oa + 6 * moving[b]).norm() + Lr * x.segment<3>(oa + 6 * moving[b] + 3).norm();
        if (m > body_motion) body_motion = m, body_named = body_name(int(b));
      }
      double best = 0.0;
      for (const auto& cand : candidates) best = std::max(best, cand.first);
      if (best > 1e-6 * body_motion) {
        for (const auto& cand : candidates)
          if (cand.first > 1e-3 * best) note(free_things, cand.second);
      } else {
        note(free_things, fmt::format("body '{}' (no joint holds it)", body_named));
      }
    } else {
      for (int r = 0; r < n - om; ++r)
        if (std::abs(y(om + r)) > 1e-3 * y.segment(om, n - om).cwiseAbs().maxCoeff()) {
          std::string owner = row_owner[size_t(r)];
          owner = owner.substr(0, owner.find(" ("));
          note(stressed, owner);
        }
    }
  }
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (size_t i = 0; i < v.size(); ++i) s += (i ? "; " : "") + v[i];
    return s;
  };
  if (!free_things.empty())
    fail(
        "elastic assembly at t = {:.6g} s: the structure is a mechanism (rank {} of {} unknowns): nothing holds {}; "
        "hold it by a motion drive (rigid or with a stiffness), a chain or another joint",
        frame.t, rank, n, join(free_things));
  fail(
      "elastic assembly at t = {:.6g} s: the joint loads cannot be determined (rank {} of {} unknowns): {} form a "
      "statically indeterminate loop of rigid bodies; give one of them an elastic part",
      frame.t, rank, n, join(stressed));
}

// ---------------------------------------------------------------------------

ElasticAssembly::ElasticAssembly(const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                 AssemblyOptions options, const Log& log,
                                 const std::vector<fem::LinearStaticAnalysis*>& factorized)
    : impl_(std::make_unique<Impl>(parts, model, std::move(options), log, factorized, true)) {}

ElasticAssembly::ElasticAssembly(const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                 AssemblyOptions options, const Log& log, PartsLentOneByOne)
    : impl_(std::make_unique<Impl>(parts, model, std::move(options), log, std::vector<fem::LinearStaticAnalysis*>{},
                                   false)) {}
ElasticAssembly::~ElasticAssembly() = default;
ElasticAssembly::ElasticAssembly(ElasticAssembly&&) noexcept = default;
ElasticAssembly& ElasticAssembly::operator=(ElasticAssembly&&) noexcept = default;

PoseSolution ElasticAssembly::solve(const mech::Frame& frame) {
  return std::move(solve(std::vector<mech::Frame>{frame}).front());
}

std::vector<PoseSolution> ElasticAssembly::solve(const std::vector<mech::Frame>& frames) {
  return impl_->solve_frames(frames, nullptr);
}

std::vector<PoseSolution> ElasticAssembly::solve(const std::vector<mech::Frame>& frames, MotionFields& fields) {
  require(fields.write.empty() || fields.write.size() == frames.size(), "elastic assembly: {} write flags for {} poses",
          fields.write.size(), frames.size());
  return impl_->solve_frames(frames, &fields);
}

std::vector<PoseSolution> ElasticAssembly::Impl::solve_frames(const std::vector<mech::Frame>& frames,
                                                              MotionFields* motion) {
  Impl& im = *this;
  require(!frames.empty(), "elastic assembly: no poses to solve");
  im.require_set_up();
  if (motion && motion->envelopes.size() != im.parts.size()) {
    motion->envelopes.assign(im.parts.size(), PartEnvelope{});
    for (size_t p = 0; p < im.parts.size(); ++p) {
      PartEnvelope& e = motion->envelopes[p];
      const fem::Index N = im.parts[p]->supported.mesh.node_count();
      const fem::Index V = im.options.recover_stress ? N : 0;
      e.body = im.parts[p]->body;
      e.max_displacement_m = Eigen::VectorXd::Constant(N, -1.0);
      e.displacement_step = Eigen::VectorXi::Zero(N);
      e.max_von_mises_pa = Eigen::VectorXd::Constant(V, -1.0);
      e.von_mises_step = Eigen::VectorXi::Zero(V);
    }
  }
  std::vector<PoseSolution> out;
  out.reserve(frames.size());
  // Poses per block: a block's load fields (3N each) of the parts not done
  // in chunks are in memory at once; parts done in chunks have none, and
  // longer blocks share their chunks' copies among more poses.
  const bool all_in_chunks = std::all_of(im.parts.begin(), im.parts.end(), [&](const std::unique_ptr<PartData>& part) {
    return im.in_chunks(*part, motion);
  });
  const size_t block = all_in_chunks ? kChunkedPosesPerBlock : 32;
  for (size_t first = 0; first < frames.size(); first += block) {
    const size_t count = std::min(block, frames.size() - first);
    Stopwatch clock;
    // Resultants of every moving body (world, about its origin): the
    // multibody model's for the rigid bodies and for the checks.
    std::vector<std::vector<Vector6d>> resultants(count, std::vector<Vector6d>(size_t(im.moving_count)));
    std::vector<std::vector<double>> scales(count, std::vector<double>(size_t(im.moving_count)));
    for (size_t f = 0; f < count; ++f) {
      const mech::Frame& frame = frames[first + f];
      im.check_frame(frame);
      const std::vector<Vector3d> applied = im.system->applied_loads(frame.q, frame.q_dot, frame.t);
      for (size_t b = 0; b < im.model.bodies.size(); ++b)
        if (!im.ground(int(b)))
          resultants[f][size_t(im.moving[b])] =
              im.multibody_resultant(frame, applied, int(b), scales[f][size_t(im.moving[b])]);
    }
    // Each part's loads for the block, one block solve.
    std::vector<Eigen::MatrixXd> load_displacement(im.parts.size());
    std::vector<std::vector<Eigen::VectorXd>> coefficients(count, std::vector<Eigen::VectorXd>(im.parts.size()));
    for (size_t p = 0; p < im.parts.size(); ++p) {
      Impl::PartData& part = *im.parts[p];
      const fem::Mesh& mesh = part.supported.mesh;
      const int mb = im.moving[size_t(part.body_index)];
      Eigen::MatrixXd Fl(part.superposed ? part.Zp.cols() : 3 * mesh.node_count(), Eigen::Index(count));
      for (size_t f = 0; f < count; ++f) {
        const mech::Frame& frame = frames[first + f];
        Vector3d force, moment;
        if (part.superposed) {
          Fl.col(Eigen::Index(f)) = coefficients[f][p] = part.loads->coefficients_at(frame).coefficients;
          const Vector6d r = part.Rp * Fl.col(Eigen::Index(f));
          force = r.head<3>();
          moment = r.tail<3>();
        } else {
          Fl.col(Eigen::Index(f)) = part.loads->loads_at(frame).forces;
          fem::resultant(mesh, Fl.col(Eigen::Index(f)), Vector3d::Zero(), force, moment);
        }
        // The frame (a part of the ground) has no multibody body to check
        // against: the ground carries no mass properties and no equations of
        // motion in the dynamics, and its foundation takes whatever resultant
        // its own weight and loads have.
        if (mb < 0) continue;
        const Eigen::Matrix3d R = rot_z(frame.bodies[size_t(part.body_index)].q.z());
        Vector6d r;
        r << R * force, R * moment;
        const Vector6d& mb_r = resultants[f][size_t(mb)];
        const double scale = std::max(scales[f][size_t(mb)], 1e-300);
        const double mismatch =
            std::max((r.head<2>() - mb_r.head<2>()).norm(), std::abs(r(5) - mb_r(5)) / im.length_scale) / scale;
        if (!(mismatch <= im.options.load_check_tolerance) && !std::isinf(im.options.load_check_tolerance))
          fail(
              "{} at t = {:.6g} s: its loads without the joint reactions (resultant {:.6g}, {:.6g} N, {:.6g} N m) "
              "differ "
              "from its multibody body's applied minus inertia loads ({:.6g}, {:.6g} N, {:.6g} N m) by {:.2e} of their "
              "size (tolerance {:.0e}): a load attachment is missing from the part, or the body's mass properties are "
              "not the mesh's (pipeline::apply_mass_properties)",
              part.label, frame.t, r(0), r(1), r(5), mb_r(0), mb_r(1), mb_r(5), mismatch,
              im.options.load_check_tolerance);
        resultants[f][size_t(mb)] = r;  // the part's own (with its out-of-plane components)
      }
      im.stats.loads_seconds += clock.seconds();
      clock.restart();
      if (im.in_chunks(part, motion)) {
        // Z_p c is formed chunk by chunk with the fields (add_chunked_fields).
      } else if (part.superposed) {
        load_displacement[p].resize(part.Zp.rows(), Fl.cols());
        fem::blas_product(part.Zp, Fl, load_displacement[p]);  // Fl: the coefficients
      } else {
        load_displacement[p] = solve_columns(*part.analysis, Fl);
        if (part.rigid) load_displacement[p] += part.rigid->correction(load_displacement[p]);
      }
      im.stats.load_solve_seconds += clock.seconds();
      clock.restart();
    }
    im.stats.loads_seconds += clock.seconds();  // the rigid bodies' resultants (no parts: all of it)
    std::vector<PoseSolution> block_poses;
    std::vector<Impl::FieldInputs> inputs(count);
    // d = G^T Z_f per part for the block (from the patterns: G^T Z_p c).
    std::vector<Eigen::MatrixXd> interface_load_displacement(im.parts.size());
    for (size_t p = 0; p < im.parts.size(); ++p) {
      const Impl::PartData& part = *im.parts[p];
      if (part.superposed) {
        interface_load_displacement[p].resize(part.GtZp.rows(), Eigen::Index(count));
        for (size_t f = 0; f < count; ++f)
          interface_load_displacement[p].col(Eigen::Index(f)) = part.GtZp * coefficients[f][p];
      } else {
        interface_load_displacement[p].noalias() = part.G.transpose() * load_displacement[p];
      }
    }
    // H^T Z_f per part with pins in contact: F_c^T Z_f - X^T G^T Z_f.
    std::vector<Eigen::MatrixXd> contact_load_gap(im.parts.size());
    for (size_t p = 0; p < im.parts.size(); ++p) {
      const Impl::PartData& part = *im.parts[p];
      if (part.contact_bores.empty()) continue;
      if (part.superposed) {
        contact_load_gap[p].resize(part.contact_corners, Eigen::Index(count));
        for (size_t f = 0; f < count; ++f) contact_load_gap[p].col(Eigen::Index(f)) = part.FcZp * coefficients[f][p];
      } else {
        contact_load_gap[p] = im.contact_normal_components(part, load_displacement[p]);
      }
      contact_load_gap[p] -= part.contact_resultants.transpose() * interface_load_displacement[p];
    }
    for (size_t f = 0; f < count; ++f) {
      std::vector<Eigen::VectorXd> d(im.parts.size()), h(im.parts.size());
      for (size_t p = 0; p < im.parts.size(); ++p) {
        d[p] = interface_load_displacement[p].col(Eigen::Index(f));
        if (!im.parts[p]->contact_bores.empty()) h[p] = contact_load_gap[p].col(Eigen::Index(f));
      }
      block_poses.push_back(im.solve_pose(frames[first + f], d, h, resultants[f], inputs[f]));
      ++im.stats.poses;
    }
    std::vector<Eigen::MatrixXd> block_coefficients(im.parts.size());
    for (size_t p = 0; p < im.parts.size(); ++p)
      if (im.parts[p]->superposed) {
        block_coefficients[p].resize(im.parts[p]->Zp.cols(), Eigen::Index(count));
        for (size_t f = 0; f < count; ++f) block_coefficients[p].col(Eigen::Index(f)) = coefficients[f][p];
      }
    const std::vector<mech::Frame> block_frames(frames.begin() + long(first), frames.begin() + long(first + count));
    im.add_fields(block_poses, block_frames, inputs, load_displacement, block_coefficients, motion, first);
    for (auto& pose : block_poses) out.push_back(std::move(pose));
  }
  im.stats.unknowns = out.back().unknowns;
  return out;
}

std::vector<InterfaceInfo> ElasticAssembly::interfaces() const {
  std::vector<InterfaceInfo> out;
  for (const auto& i : impl_->interfaces) {
    InterfaceInfo info;
    info.body = impl_->body_name(i.body);
    info.kind = i.kind == Impl::Kind::Joint ? "joint" : i.kind == Impl::Kind::Drive ? "drive" : "point";
    info.name = i.name;
    info.face_set = i.face_set;
    info.reference_body_m = i.reference;
    info.elastic = i.part >= 0;
    out.push_back(info);
  }
  return out;
}

InterfaceStructure ElasticAssembly::interface_structure(const mech::Frame& frame) const {
  const Impl& im = *impl_;
  im.check_frame(frame);
  const Impl::Pose pose = im.pose_of(frame);
  const Impl::PoseMembers members = im.members_of(frame, pose);
  InterfaceStructure out;
  out.body_rotation = pose.R;
  out.interface_arm_m = pose.arm;
  out.constraints.resize(Eigen::Index(members.rows.size()), 6 * Eigen::Index(im.interfaces.size()));
  for (size_t r = 0; r < members.rows.size(); ++r) out.constraints.row(Eigen::Index(r)) = members.rows[r];
  out.constraint_owner = members.row_owner;
  out.springs = members.S;
  return out;
}

void ElasticAssembly::Impl::require_set_up() const {
  for (const auto& p : parts)
    require(p->set_up, "elastic assembly: {} is not set up yet (call set_up_part with its factor)",
            p->label);
}

void ElasticAssembly::set_up_part(const std::string& body, fem::LinearStaticAnalysis& factor) {
  for (auto& p : impl_->parts)
    if (p->body == body) {
      require_factor_of(p->supported, factor, p->label);
      p->given_analysis = &factor;
      return impl_->set_up_part(*p);
    }
  fail("elastic assembly: body '{}' has no elastic part", body);
}

bool ElasticAssembly::solves_with_factor(const std::string& body) const {
  const Impl::PartData& part = impl_->part_of(body);
  return !part.superposed || !part.contact_bores.empty();
}

const fem::BoreContactSurface& ElasticAssembly::contact_surface(const std::string& body, const std::string& joint) const {
  for (const auto& bore : impl_->contact_bores)
    if (impl_->parts[size_t(bore.part)]->body == body && impl_->model.joints[size_t(bore.joint)].name == joint)
      return *bore.surface;
  fail("elastic assembly: body '{}' has no bore in contact with the pin of joint '{}'", body, joint);
}

bool ElasticAssembly::is_set_up() const {
  return std::all_of(impl_->parts.begin(), impl_->parts.end(), [](const auto& p) { return p->set_up; });
}

const Eigen::MatrixXd& ElasticAssembly::interface_columns(const std::string& body) const {
  impl_->require_set_up();
  const Impl::PartData& part = impl_->part_of(body);
  require(!part.rigid,
          "{}: the interface columns of rigid-bore couplings are not the couplings' motion; the modes of the "
          "assembly need assembly.coupling = \"distributing\"",
          part.label);
  return part.G;
}

fem::LinearStaticAnalysis& ElasticAssembly::supported_analysis(const std::string& body) const {
  impl_->require_set_up();
  return *impl_->part_of(body).analysis;
}

const loads::LinkLoads& ElasticAssembly::part_loads(const std::string& body) const {
  return *impl_->part_of(body).loads;
}

std::vector<Vector6d> ElasticAssembly::body_loads(const mech::Frame& frame) const {
  const Impl& im = *impl_;
  im.check_frame(frame);
  const std::vector<Vector3d> applied = im.system->applied_loads(frame.q, frame.q_dot, frame.t);
  std::vector<Vector6d> out;
  for (size_t b = 0; b < im.model.bodies.size(); ++b)
    if (!im.ground(int(b))) {
      double scale = 0.0;
      out.push_back(im.multibody_resultant(frame, applied, int(b), scale));
    }
  return out;
}

Eigen::MatrixXd ElasticAssembly::flexibility(const std::string& body) const {
  impl_->require_set_up();
  for (const auto& p : impl_->parts)
    if (p->body == body) return p->F;
  fail("elastic assembly: body '{}' has no elastic part", body);
}

Eigen::MatrixXd ElasticAssembly::stress_patterns(const std::string& body) const {
  impl_->require_set_up();
  for (const auto& p : impl_->parts)
    if (p->body == body) {
      require(p->superposed && impl_->options.recover_stress && p->contact_bores.empty(),
              "elastic assembly: part '{}' has no stress patterns (its loads are not superposed, its stress is not "
              "recovered, or a pin is in contact with it)",
              body);
      Eigen::MatrixXd out(p->SG.rows(), p->SG.cols() + p->Sp.cols());
      out << p->SG, p->Sp;
      return out;
    }
  fail("elastic assembly: body '{}' has no elastic part", body);
}

const AssemblyStatistics& ElasticAssembly::statistics() const { return impl_->stats; }

}  // namespace kinetofem::structure
