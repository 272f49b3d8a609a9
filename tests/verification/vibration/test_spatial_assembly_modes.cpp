// The natural frequencies of a spatial mechanism's elastic assembly per pose
// (vibration/spatial_assembly_modes.hpp).
//
// 1. A cantilevered bar (HEX20, 1 m x 50 mm x 30 mm, steel) on a rigid
//    prismatic joint to the ground with an oblique axis, held along it by a
//    rigid displacement drive: the root face's coupling is held in all six
//    components, so the first two modes are the cantilever's first bending in
//    the bar's thin direction (z) and in its deep one (y), told apart by the
//    tip's motion in the bar's axes.
//    a. vs the Timoshenko cantilever (shear and rotary inertia, Cowper's
//       kappa; verification/beam_vibration.hpp), 1 %, and Euler-Bernoulli
//       1.875^2 sqrt(E I / (rho A L^4)) / (2 pi), 2 %: the root is held
//       through a distributing coupling of its end face, which lets the face
//       warp (softer than a built-in end: the statics' tip compliance is
//       +0.17 % of Timoshenko's, tests/verification/structure/
//       test_spatial_assembly.cpp), and a solid bar has Poisson coupling a
//       beam lacks; Euler-Bernoulli also neglects shear and rotary inertia
//       (L/h = 20). Measured: -0.10 % and -0.11 % of Timoshenko, -0.17 % and
//       -0.31 % of Euler-Bernoulli.
//    b. The same model turned as a whole by a rotation (axis, base and pose):
//       the same frequencies, 1e-8 relative (the parts' reductions are in body
//       axes; only U(pose) and the constraints turn; measured 7e-10, the
//       parts' eigen solves' own scatter between two reductions).
// 2. The spatial two-link arm of tests/verification/structure/
//    test_spatial_assembly.cpp (a revolute about the vertical, a revolute
//    about link1's own y axis, both driven rigidly; a 3 kg payload with
//    rotary inertia on link2's end face) at two output times of its motion,
//    against a monolithic reference that reduces nothing (below): every
//    part's full stiffness and consistent mass in world axes, the payload's
//    6 x 6 mass (mass and rotary inertia) on its coupling's world motion, the
//    joints and drives as linear constraints on the couplings' motions
//    written independently of the assembly (as
//    tests/verification/structure/spatial_monolithic_reference.hpp does), and
//    shift-invert Lanczos (fem::solve_eigen, Spectra) on the constrained
//    operator (one sparse LU of [K - sigma M, C^T; C, 0]); its modes are
//    checked to satisfy the constraints (1e-9) and K phi - w^2 M phi to be a
//    constraint reaction (1e-8).
//    Craig-Bampton is exact only in the limit of all fixed-interface modes,
//    so eight modes are compared at three part-mode cutoffs: 300 Hz (below
//    both parts' first fixed-interface modes, 960 and 1664 Hz: constraint
//    modes and residual vectors only), the automatic rule (2 x f_8 of the
//    static reduction: 2 modes per part) and 10 kHz (11 and 9 modes). The
//    lowest four (33-161 Hz) lie far below the parts' fixed-interface modes
//    and equal the reference within 1e-6 at every cutoff (measured 2e-10,
//    the reference's own precision); modes 6-8 (420-845 Hz) show the
//    convergence: mode 8 +1.4e-5, +4e-9, +4e-12. No reduced frequency is
//    below the reference (Rayleigh-Ritz, up to 1e-9) and no mode's error
//    grows as the cutoff rises.
// 3. The reduced model's static response to the frame's loads (inertia,
//    weight, the payload's force and moment) at the tracked tip equals the
//    elastic assembly's own static solution (SpatialElasticAssembly::solve)
//    within 1e-8 relative at the 10 kHz cutoff (measured 6e-10): the
//    reduction's statics are exact for loads at the interfaces (constraint
//    modes) and the interfaces' inertia (residual vectors); a distributed
//    load such as the centripetal field only through the kept modes.
// 4. A rigid body (its 6 x 6 mass from the mesh's mass properties and its
//    point mass's rotary inertia) is the limit of a stiff part: the arm with
//    link2 rigid vs link2 100, 200 and 400 times stiffer than steel,
//    extrapolated to infinite stiffness, 1e-6 (below, at the test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "../../unit/structure/spatial_fixtures.hpp"
#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"
#include "kinetofem/verification/beam_vibration.hpp"
#include "kinetofem/vibration/spatial_assembly_modes.hpp"

namespace kinetofem::vibration {
namespace {

namespace sp = mech::spatial;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using structure::SpatialPart;
using structure::test::BarSize;
using structure::test::kDeg;
using structure::test::give_mass_of;
using structure::test::slide_model;
using structure::test::spatial_arm;
using structure::test::spatial_bar;
using structure::test::SlideModel;
using structure::test::SpatialArm;

// --- 1. The cantilevered bar on an oblique prismatic joint ----------------

constexpr BarSize kCantilever{.length_m = 1.0, .height_m = 0.05, .thickness_m = 0.03, .cells = {40, 4, 2}};

// The bar along its body x from `base`, its body axes R; the slide's axis
// (world) is R's x axis. `turn` turns the whole model.
sp::Model sliding_cantilever(const Eigen::Matrix3d& turn, std::vector<SpatialPart>& parts) {
  const Vector3d axis = Vector3d(1.0, 0.7, 0.4).normalized();
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitX(), axis).toRotationMatrix() *
                            Eigen::AngleAxisd(25 * kDeg, Vector3d::UnitX()).toRotationMatrix();
  const Vector3d base(0.2, -0.1, 0.3);
  sp::Model model;
  model.name = "sliding cantilever";
  model.gravity.setZero();
  sp::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["base"] = turn * base;
  sp::Body arm;
  arm.name = "arm";
  arm.position = turn * base;
  sp::set_rotation(arm, turn * R);
  arm.points["tip"] = Vector3d(kCantilever.length_m, 0.0, 0.0);
  model.bodies = {ground, arm};
  model.joints = {sp::make_joint("slide", sp::JointType::Prismatic, "ground", "base", "arm", "origin", turn * axis,
                                 Vector3d::UnitX())};
  sp::MotionDrive push;
  push.name = "push";
  push.joint = "slide";
  push.coordinate = sp::DriveCoordinate::Translation;
  push.law = std::make_shared<mech::ConstantVelocityLaw>(0.0);
  model.motion_drives = {push};
  parts = {spatial_bar("arm", kCantilever, {{"slide", "x0"}, {"push", "x0"}})};
  give_mass_of(model, parts);
  return model;
}

struct CantileverModes {
  VectorXd frequency_hz;
  std::vector<Vector3d> tip_bar_axes;  // per mode: the tip's translation in the bar's axes
};

CantileverModes cantilever_modes(const Eigen::Matrix3d& turn) {
  std::vector<SpatialPart> parts;
  const sp::Model model = sliding_cantilever(turn, parts);
  const sp::Results run = sp::run_kinematics(sp::System(model), {0.0});
  structure::SpatialAssemblyOptions options;
  options.points = {{"tip", "arm", "tip", "x1"}};
  options.recover_stress = false;
  const structure::SpatialElasticAssembly assembly(parts, model, options);
  AssemblyModesOptions mo;
  mo.modes = 3;
  mo.part_mode_cutoff_hz = 3000.0;  // 100 x f_1: the reduction's error far below the beam models'
  const SpatialAssemblyModes modes(assembly, model, mo, run.frames);
  const sp::Frame& frame = run.frames[0];
  const PoseModes pose = modes.modes(frame);
  CantileverModes out;
  out.frequency_hz = pose.frequency_hz;
  const MatrixXd tip = modes.point_rows("tip", frame);
  for (int i = 0; i < mo.modes; ++i)
    out.tip_bar_axes.push_back(frame.bodies[1].rotation.transpose() * (tip * pose.shapes.col(i)));
  return out;
}

TEST(SpatialAssemblyModes, ACantileverOnAnObliquePrismaticJointBendsAsBeamTheorySays) {
  const CantileverModes c = cantilever_modes(Eigen::Matrix3d::Identity());
  const fem::IsotropicMaterial steel = structure::test::steel();
  const double nu = steel.poisson_ratio;
  auto beam = [&](double second_moment_m4) {
    return verification::TimoshenkoBeam{.length_m = kCantilever.length_m,
                                        .youngs_modulus_pa = steel.youngs_modulus_pa,
                                        .shear_modulus_pa = steel.youngs_modulus_pa / (2 * (1 + nu)),
                                        .density_kg_m3 = steel.density_kg_m3,
                                        .area_m2 = kCantilever.height_m * kCantilever.thickness_m,
                                        .second_moment_m4 = second_moment_m4,
                                        .shear_coefficient = verification::cowper_rectangle_shear_coefficient(nu)};
  };
  const double h = kCantilever.height_m, t = kCantilever.thickness_m;
  // Mode 1 bends in the thin direction (body z), mode 2 in the deep one (y).
  const verification::TimoshenkoBeam in_z = beam(h * t * t * t / 12), in_y = beam(t * h * h * h / 12);
  const int direction[2] = {2, 1};
  const verification::TimoshenkoBeam* beams[2] = {&in_z, &in_y};
  for (int i = 0; i < 2; ++i) {
    const Vector3d& tip = c.tip_bar_axes[size_t(i)];
    EXPECT_GT(std::abs(tip(direction[i])),
              100 * std::max(std::abs(tip((direction[i] + 1) % 3)), std::abs(tip((direction[i] + 2) % 3))))
        << "mode " << i + 1 << " does not bend in body "
        << "xyz"[direction[i]] << ": " << tip.transpose();
    const double f = c.frequency_hz(i);
    const double timoshenko =
        verification::timoshenko_frequencies_hz(*beams[i], verification::BeamEnds::ClampedFree, 1)[0];
    const double euler = verification::euler_bernoulli_frequency_hz(*beams[i], verification::BeamEnds::ClampedFree, 1);
    std::printf(
        "mode %d (bending in body %c): %.5f Hz; Timoshenko %.5f Hz (%+.3f %%), Euler-Bernoulli %.5f Hz "
        "(%+.3f %%)\n",
        i + 1, "xyz"[direction[i]], f, timoshenko, 100 * (f / timoshenko - 1), euler, 100 * (f / euler - 1));
    EXPECT_NEAR(f / timoshenko, 1.0, 0.01);  // Timoshenko cantilever, 1 % (header)
    EXPECT_NEAR(f / euler, 1.0, 0.02);       // Euler-Bernoulli, 2 % (header)
  }
  std::printf("mode 3: %.5f Hz\n", c.frequency_hz(2));

  // b. The model turned as a whole: the same frequencies.
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(70 * kDeg, Vector3d(0.3, -1.0, 0.5).normalized()) *
                                Eigen::AngleAxisd(-35 * kDeg, Vector3d::UnitZ()))
                                   .toRotationMatrix();
  const CantileverModes turned = cantilever_modes(turn);
  for (int i = 0; i < 3; ++i) {
    const double difference = turned.frequency_hz(i) / c.frequency_hz(i) - 1;
    std::printf("mode %d turned: %.10f Hz vs %.10f Hz (%+.1e)\n", i + 1, turned.frequency_hz(i), c.frequency_hz(i),
                difference);
    EXPECT_NEAR(difference, 0.0, 1e-8) << "mode " << i + 1;  // round-off of U(pose) and the null space
  }
}

// --- 2. The spatial two-link arm vs a monolithic reference ----------------

// The monolithic reference (header, 2): the lowest `count` frequencies, Hz.
VectorXd monolithic_frequencies(const std::vector<SpatialPart>& parts, const sp::Model& model, const sp::Frame& frame,
                                int count) {
  using SpMat = Eigen::SparseMatrix<double>;
  using Triplet = Eigen::Triplet<double>;
  const sp::System system(model);
  const size_t np = parts.size();
  std::vector<Index> offset(np + 1, 0);
  for (size_t p = 0; p < np; ++p) offset[p + 1] = offset[p] + 3 * parts[p].model.mesh.node_count();
  const Index ndof = offset[np];
  auto part_of = [&](int body) {
    for (size_t p = 0; p < np; ++p)
      if (parts[p].body() == model.bodies[size_t(body)].name) return int(p);
    return -1;
  };
  std::vector<Eigen::Matrix3d> R(np);
  for (size_t p = 0; p < np; ++p) R[p] = frame.bodies[size_t(system.body_index(parts[p].body()))].rotation;

  // The world motion (translation, rotation) of the coupling of `face_set`
  // on part p with its reference at X (body frame): 6 x ndof.
  auto coupling_rows = [&](size_t p, const std::string& face_set, const Vector3d& X) {
    const fem::Mesh& mesh = parts[p].model.mesh;
    const fem::DistributingCoupling coupling(mesh, face_set);
    MatrixXd G = MatrixXd::Zero(3 * mesh.node_count(), 6);
    for (int c = 0; c < 3; ++c) {
      coupling.add(Vector3d::Unit(c), Vector3d::Zero(), X, G.col(c));
      coupling.add(Vector3d::Zero(), Vector3d::Unit(c), X, G.col(3 + c));
    }
    MatrixXd rows = MatrixXd::Zero(6, ndof);
    for (fem::Index i = 0; i < mesh.node_count(); ++i) {
      const Eigen::Matrix<double, 6, 3> g = G.middleRows<3>(3 * i).transpose();
      rows.block<3, 3>(0, offset[p] + 3 * i) = R[p] * g.topRows<3>() * R[p].transpose();
      rows.block<3, 3>(3, offset[p] + 3 * i) = R[p] * g.bottomRows<3>() * R[p].transpose();
    }
    return rows;
  };
  auto face_of = [&](size_t p, const std::string& item) {
    for (const loads::SpatialAttachment& a : parts[p].attachments.joints)
      if (a.name == item) return a.face_set;
    fail("monolithic reference: no face set for '{}'", item);
  };

  // K and M of every part in world axes (no support), the payloads' 6 x 6
  // masses on their couplings' world motions.
  std::vector<Triplet> kt, mt;
  double diagonal = 0.0;
  MatrixXd point_mass_rows(0, ndof);
  MatrixXd point_mass_6(0, 0);
  for (size_t p = 0; p < np; ++p) {
    const fem::FeModel& fe = parts[p].model;
    const fem::Index N = fe.mesh.node_count();
    const fem::DofMap dofs(N, {});
    const SpMat K(SpMat(fem::assemble_stiffness(fe.mesh, fe.material, dofs).free_free).selfadjointView<Eigen::Upper>());
    const SpMat M(SpMat(fem::assemble_mass(fe.mesh, fe.material, dofs)).selfadjointView<Eigen::Upper>());
    std::vector<Triplet> qt;
    for (fem::Index i = 0; i < N; ++i)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) qt.emplace_back(3 * i + a, 3 * i + b, R[p](a, b));
    SpMat Q(3 * N, 3 * N);
    Q.setFromTriplets(qt.begin(), qt.end());
    const SpMat Kw = Q * K * SpMat(Q.transpose()), Mw = Q * M * SpMat(Q.transpose());
    for (int k = 0; k < Kw.outerSize(); ++k)
      for (SpMat::InnerIterator it(Kw, k); it; ++it)
        kt.emplace_back(offset[p] + it.row(), offset[p] + it.col(), it.value());
    for (int k = 0; k < Mw.outerSize(); ++k)
      for (SpMat::InnerIterator it(Mw, k); it; ++it)
        mt.emplace_back(offset[p] + it.row(), offset[p] + it.col(), it.value());
    diagonal = std::max(diagonal, K.diagonal().cwiseAbs().maxCoeff());
    const sp::Body& body = model.bodies[size_t(system.body_index(parts[p].body()))];
    for (const loads::SpatialAttachment& a : parts[p].attachments.point_masses)
      for (const sp::PointMass& pm : body.point_masses) {
        if (pm.name != a.name) continue;
        const MatrixXd rows = coupling_rows(p, a.face_set, pm.position_body);
        Eigen::Matrix<double, 6, 6> m6 = Eigen::Matrix<double, 6, 6>::Zero();
        m6.topLeftCorner<3, 3>() = pm.mass_kg * Eigen::Matrix3d::Identity();
        m6.bottomRightCorner<3, 3>() = R[p] * pm.inertia_kgm2 * R[p].transpose();
        const MatrixXd added = rows.transpose() * m6 * rows;
        for (Index c = 0; c < ndof; ++c)
          for (Index r = 0; r < ndof; ++r)
            if (added(r, c) != 0.0) mt.emplace_back(r, c, added(r, c));
      }
  }
  SpMat K(ndof, ndof), M(ndof, ndof);
  K.setFromTriplets(kt.begin(), kt.end());
  M.setFromTriplets(mt.begin(), mt.end());

  // The joints (held in the components their reaction carries) and drives.
  auto transfer = [](const Vector3d& d) {
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
    Eigen::Matrix3d S;
    S << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
    T.block<3, 3>(0, 3) = -S;
    return T;
  };
  auto world_point = [&](int body, const std::string& point) {
    return Vector3d(frame.bodies[size_t(body)].origin +
                    frame.bodies[size_t(body)].rotation * system.named_point(body, point));
  };
  std::vector<Eigen::RowVectorXd> C;
  for (const sp::Joint& j : model.joints) {
    const sp::ConstraintBlock& block = system.block(j.name);
    const int pi = part_of(block.body_i), pj = part_of(block.body_j);
    const Vector3d Xi = world_point(block.body_i, j.point_i), Xj = world_point(block.body_j, j.point_j);
    MatrixXd vi = MatrixXd::Zero(6, ndof), vj = MatrixXd::Zero(6, ndof);
    if (pi >= 0)
      vi = transfer(Xj - Xi) *
           coupling_rows(size_t(pi), face_of(size_t(pi), j.name), system.named_point(block.body_i, j.point_i));
    if (pj >= 0)
      vj = coupling_rows(size_t(pj), face_of(size_t(pj), j.name), system.named_point(block.body_j, j.point_j));
    const Eigen::Matrix3d& Ri = frame.bodies[size_t(block.body_i)].rotation;
    const Vector3d axes[3] = {Ri * block.f_i, Ri * block.g_i, Ri * block.h_i};
    const sp::JointFacts& facts = sp::joint_facts(j.type);
    for (int c = 0; c < facts.forces; ++c) C.push_back(axes[c].transpose() * (vj - vi).topRows<3>());
    if (facts.moments == 1) {
      const Vector3d hj = frame.bodies[size_t(block.body_j)].rotation * block.h_j;
      C.push_back(axes[2].cross(hj).normalized().transpose() * (vj - vi).bottomRows<3>());
    } else {
      for (int c = 0; c < facts.moments; ++c) C.push_back(axes[c].transpose() * (vj - vi).bottomRows<3>());
    }
  }
  for (const sp::MotionDrive& d : model.motion_drives) {
    const sp::ConstraintBlock& block = system.block(d.name);
    const sp::Joint& j = model.joints[size_t(system.block(d.joint).source)];
    const int pi = part_of(block.body_i), pj = part_of(block.body_j);
    MatrixXd vi = MatrixXd::Zero(6, ndof), vj = MatrixXd::Zero(6, ndof);
    if (pi >= 0)
      vi = coupling_rows(size_t(pi), face_of(size_t(pi), d.name), system.named_point(block.body_i, j.point_i));
    if (pj >= 0)
      vj = coupling_rows(size_t(pj), face_of(size_t(pj), d.name), system.named_point(block.body_j, j.point_j));
    const Vector3d h = frame.bodies[size_t(block.body_i)].rotation * block.h_i;
    if (d.coordinate == sp::DriveCoordinate::Rotation) {
      C.push_back(h.transpose() * (vj - vi).bottomRows<3>());
    } else {
      const Vector3d dist = world_point(block.body_j, j.point_j) - world_point(block.body_i, j.point_i);
      C.push_back(h.transpose() * (vj - vi).topRows<3>() + h.cross(dist).transpose() * vi.bottomRows<3>());
    }
  }

  // Shift-invert on the constrained space: y = (K - sigma M)^-1 b with C y = 0
  // from one sparse LU of [K - sigma M, s C^T; s C, 0] (s balances the rows).
  const double sigma = -std::pow(2 * std::numbers::pi * 1.0, 2);  // below every eigenvalue: K - sigma M > 0 on C y = 0
  const Index nc = Index(C.size()), n = ndof + nc;
  std::vector<Triplet> at;
  const SpMat shifted = K - sigma * M;
  for (int k = 0; k < shifted.outerSize(); ++k)
    for (SpMat::InnerIterator it(shifted, k); it; ++it) at.emplace_back(it.row(), it.col(), it.value());
  for (Index r = 0; r < nc; ++r)
    for (Index a = 0; a < ndof; ++a)
      if (C[size_t(r)](a) != 0.0) {
        at.emplace_back(ndof + r, a, diagonal * C[size_t(r)](a));
        at.emplace_back(a, ndof + r, diagonal * C[size_t(r)](a));
      }
  SpMat A(n, n);
  A.setFromTriplets(at.begin(), at.end());
  A.makeCompressed();
  Eigen::SparseLU<SpMat> lu;
  lu.compute(A);
  EXPECT_EQ(lu.info(), Eigen::Success) << lu.lastErrorMessage();
  fem::EigenOperators ops;
  ops.size = ndof;
  ops.shift_rad2_s2 = sigma;
  ops.shift_inverse = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) {
    VectorXd rhs = VectorXd::Zero(n);
    rhs.head(ndof) = x;
    VectorXd z = lu.solve(rhs);
    z += lu.solve(VectorXd(rhs - A * z));  // one refinement step
    y = z.head(ndof);
  };
  ops.mass = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) { y = M * x; };
  ops.stiffness = [&](const Eigen::Ref<const VectorXd>& x, Eigen::Ref<VectorXd> y) { y = K * x; };
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  VectorXd start(ndof);
  for (Index i = 0; i < ndof; ++i) start(i) = uniform(random);
  ops.start.resize(ndof);
  ops.shift_inverse(start, ops.start);  // in the constrained space
  fem::EigenOptions eo;
  eo.modes = count;
  eo.tolerance = 1e-12;
  eo.label = "monolithic spatial arm";
  const fem::EigenSolution solution = fem::solve_eigen(ops, eo);
  // The modes satisfy the constraints, and K phi - w^2 M phi is a
  // constraint reaction (in the range of C^T) to the solver's tolerance.
  MatrixXd Ct(ndof, nc);
  for (Index r = 0; r < nc; ++r) Ct.col(r) = C[size_t(r)].transpose();
  const Eigen::LDLT<MatrixXd> gram(Ct.transpose() * Ct);
  double drift = 0.0, residual = 0.0;
  for (Index i = 0; i < count; ++i) {
    const VectorXd phi = solution.modes.col(i), Kphi = K * phi, Mphi = M * phi;
    const double w2 = solution.omega2_rad2_s2(i);
    const VectorXd r = Kphi - w2 * Mphi;
    const VectorXd free_part = r - Ct * gram.solve(Ct.transpose() * r);
    drift = std::max(drift, (Ct.transpose() * phi).cwiseAbs().maxCoeff() / phi.cwiseAbs().maxCoeff());
    residual = std::max(residual, free_part.norm() / (Kphi.norm() + w2 * Mphi.norm()));
  }
  EXPECT_LT(drift, 1e-9);
  EXPECT_LT(residual, 1e-8);
  std::printf(
      "  monolithic reference: %lld DoFs, %lld constraints, %lld solves, constraint drift %.1e, residual off "
      "the reactions %.1e\n",
      (long long)ndof, (long long)nc, solution.statistics.operator_applications, drift, residual);
  return solution.frequency_hz;
}

TEST(SpatialAssemblyModes, ASpatialArmConvergesToTheMonolithicAssemblyAsTheCutoffRises) {
  const SpatialArm arm = spatial_arm();
  const sp::Results run = sp::run_kinematics(sp::System(arm.model), {0.3, 0.6});
  structure::SpatialAssemblyOptions options;
  options.points = {{"tip", "link2", "tip", "x1"}};
  options.recover_stress = false;
  structure::SpatialElasticAssembly assembly(arm.parts, arm.model, options);
  constexpr int kCompared = 4;  // held to 1e-6 at every cutoff
  constexpr int kModes = 8;     // modes 5-8 reach the parts' fixed-interface range: the convergence shows there
  std::vector<VectorXd> reference;
  for (const sp::Frame& frame : run.frames)
    reference.push_back(monolithic_frequencies(arm.parts, arm.model, frame, kModes));

  struct Rule {
    const char* name;
    double cutoff_hz;
  };
  const Rule rules[] = {{"given 300 Hz (no fixed-interface mode: constraint modes and residual vectors only)", 300.0},
                        {"automatic (2 x f_8 of the static reduction)", 0.0},
                        {"given 10 kHz", 1e4}};
  std::vector<VectorXd> error_of_rule;  // per rule: |error| per mode, worst over the poses
  for (const Rule& rule : rules) {
    AssemblyModesOptions mo;
    mo.modes = kModes;
    mo.part_mode_cutoff_hz = rule.cutoff_hz;
    const SpatialAssemblyModes modes(assembly, arm.model, mo, run.frames);
    std::printf("cutoff %s = %.5g Hz: part modes kept", rule.name, modes.cutoff_hz());
    for (const PartReduction& r : modes.reductions())
      std::printf(" %s %lld (+%lld residual vectors, first dropped %.5g Hz)", r.body.c_str(), (long long)r.modes,
                  (long long)r.residual, r.first_dropped_hz);
    std::printf("\n");
    VectorXd worst = VectorXd::Zero(kModes);
    double highest = 0.0;
    for (size_t f = 0; f < run.frames.size(); ++f) {
      const PoseModes pose = modes.modes(run.frames[f]);
      highest = std::max(highest, pose.frequency_hz(kModes - 1));
      for (int i = 0; i < kModes; ++i) {
        const double error = pose.frequency_hz(i) / reference[f](i) - 1;
        std::printf("  t = %.1f s mode %d: reduced %.8f Hz, monolithic %.8f Hz (%+.2e)\n", run.frames[f].t, i + 1,
                    pose.frequency_hz(i), reference[f](i), error);
        EXPECT_GT(error, -1e-9) << "mode " << i + 1;  // Rayleigh-Ritz: never below the full model (its tolerance)
        if (i < kCompared) {
          EXPECT_LT(error, 1e-6) << "mode " << i + 1 << " at t = " << run.frames[f].t;
        }
        worst(i) = std::max(worst(i), std::abs(error));
      }
    }
    std::printf("  %s\n", modes.check_rule(highest).c_str());
    if (rule.cutoff_hz != 300.0) {
      EXPECT_NE(modes.check_rule(highest).find("holds"), std::string::npos);
    }
    if (!error_of_rule.empty())
      for (int i = 0; i < kModes; ++i) {
        // Converging: no mode's error grows as the cutoff rises (slack: the reference's precision).
        EXPECT_LE(worst(i), error_of_rule.back()(i) + 1e-9) << "mode " << i + 1 << ", cutoff " << rule.name;
      }
    error_of_rule.push_back(worst);
  }
  EXPECT_LT(error_of_rule.back().maxCoeff(), 1e-6);  // 10 kHz: all eight equal the monolithic model
}

// --- 3. The reduced statics equal the assembly's ----------------------------

TEST(SpatialAssemblyModes, TheReducedStaticsOfTheSpatialArmEqualTheAssemblys) {
  const SpatialArm arm = spatial_arm();
  const sp::Results run = sp::run_kinematics(sp::System(arm.model), {0.0, 0.3, 0.6});
  structure::SpatialAssemblyOptions options;
  options.points = {{"tip", "link2", "tip", "x1"}};
  options.recover_stress = false;
  structure::SpatialElasticAssembly assembly(arm.parts, arm.model, options);
  AssemblyModesOptions mo;
  mo.modes = 4;
  mo.part_mode_cutoff_hz = 1e4;
  const SpatialAssemblyModes modes(assembly, arm.model, mo, run.frames);
  for (const sp::Frame& frame : run.frames) {
    const structure::SpatialPoseSolution pose = assembly.solve(frame);
    const Vector3d expected = pose.point("tip").displacement_m;
    const Vector3d reduced = modes.point_rows("tip", frame) * modes.static_response(frame, modes.load(frame));
    const double mismatch = (reduced - expected).norm() / expected.norm();
    std::printf("t = %.1f s: tip %.6e m (assembly) vs %.6e m (reduced model), mismatch %.2e\n", frame.t,
                expected.norm(), reduced.norm(), mismatch);
    EXPECT_LT(mismatch, 1e-8) << "t = " << frame.t;  // header, 3
  }
}

// --- 4. A rigid body is the limit of a stiff part ----------------------------

// The arm with link2 rigid (no part: its mesh's mass, centre of mass and
// inertia tensor with the payload's mass and rotary inertia, one 6 x 6 on its
// origin) against link2 as a part k = 100, 200 and 400 times stiffer than
// steel (its consistent mass, the payload on its coupling). The stiff link's
// compliance is in series with the rest, so f(k) = f_rigid + a / k + b / k^2
// + O(1 / k^3): the difference halves as k doubles (measured -4.6e-4 at k =
// 100 on mode 1, -5.2e-3 on mode 4), and the Richardson extrapolation of the
// three to 1 / k = 0 equals the rigid link's frequency within 1e-6 relative
// (the O(1 / k^3) term; measured 1e-9 to 8e-8. Much stiffer parts are not
// usable: the eigen solve's round-off grows like k, about 1e-6 at k = 1e4).
TEST(SpatialAssemblyModes, ARigidLinkWithItsPayloadIsTheLimitOfAStiffPart) {
  SpatialArm rigid = spatial_arm();  // link2 keeps its mesh's mass properties and its payload
  rigid.parts.pop_back();
  const sp::Results run = sp::run_kinematics(sp::System(rigid.model), {0.3, 0.6});
  auto frequencies = [&](const SpatialArm& arm) {  // per frame
    structure::SpatialAssemblyOptions options;
    options.recover_stress = false;
    const structure::SpatialElasticAssembly assembly(arm.parts, arm.model, options);
    AssemblyModesOptions mo;
    mo.modes = 4;
    const SpatialAssemblyModes modes(assembly, arm.model, mo, run.frames);
    std::vector<VectorXd> out;
    for (const sp::Frame& frame : run.frames) out.push_back(modes.modes(frame).frequency_hz);
    return out;
  };
  auto stiff = [](double factor) {
    SpatialArm arm = spatial_arm();
    arm.parts[1].model.material = structure::test::steel(factor);
    return arm;
  };
  const std::vector<VectorXd> rigid_hz = frequencies(rigid), hz_100 = frequencies(stiff(100.0)),
                              hz_200 = frequencies(stiff(200.0)), hz_400 = frequencies(stiff(400.0));
  for (size_t f = 0; f < run.frames.size(); ++f) {
    const sp::Frame& frame = run.frames[f];
    const VectorXd &f_rigid = rigid_hz[f], &f_100 = hz_100[f], &f_200 = hz_200[f], &f_400 = hz_400[f];
    for (int i = 0; i < 4; ++i) {
      const double first_100 = 2 * f_200(i) - f_100(i), first_200 = 2 * f_400(i) - f_200(i);
      const double limit = (4 * first_200 - first_100) / 3;
      const double d_100 = f_100(i) / f_rigid(i) - 1, d_200 = f_200(i) / f_rigid(i) - 1;
      const double difference = limit / f_rigid(i) - 1;
      std::printf(
          "t = %.1f s mode %d: link2 rigid %.8f Hz; stiff part k = 100 %+.2e, k = 200 %+.2e, extrapolated "
          "%+.2e\n",
          frame.t, i + 1, f_rigid(i), d_100, d_200, difference);
      EXPECT_NEAR(d_100 / d_200, 2.0, 0.05) << "mode " << i + 1;  // first order in 1 / k
      EXPECT_NEAR(difference, 0.0, 1e-6) << "mode " << i + 1 << " at t = " << frame.t;
    }
  }
}

// The SPEC §1 lever-chain manipulator with box parts lifted into the spatial
// core (the chain a tension member of EA 2e6 N): the spatial modes equal the
// planar AssemblyModes (the same structure; the planar rigid bodies' assumed
// out-of-plane inertia does not enter: both links are parts, the gripper and
// casting are point masses without rotary inertia in both), the same fixed
// part-mode cutoff: 1e-8 relative on the lowest six (round-off of two dense
// eigen solves on different bases; the reductions are identical).
TEST(SpatialAssemblyModes, ThePlanarLeverChainLiftedHasThePlanarFrequencies) {
  const mech::ManipulatorDefinition def = structure::test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = structure::test::lever_chain_parts(def, structure::test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const std::vector<double> times = {0.6, 1.4};
  const mech::Results planar_run = mech::run_kinematics(mech::MultibodySystem(model), times);
  const sp::Model lifted = sp::from_planar(model);
  const sp::Results spatial_run = sp::run_kinematics(sp::System(lifted), times);
  structure::AssemblyOptions planar_options;
  planar_options.chains = {{"chain", 2e6}};
  structure::ElasticAssembly planar(parts, model, planar_options);
  std::vector<structure::SpatialPart> spatial_parts;
  for (const pipeline::Part& part : parts) spatial_parts.push_back(structure::spatial_part_of(part));
  structure::SpatialAssemblyOptions options;
  options.chains = planar_options.chains;
  const structure::SpatialElasticAssembly spatial(spatial_parts, lifted, options);
  AssemblyModesOptions modes_options;
  modes_options.modes = 6;
  modes_options.part_mode_cutoff_hz = 5000.0;
  const AssemblyModes planar_modes(planar, parts, model, modes_options, planar_run.frames, Log::quiet());
  const SpatialAssemblyModes spatial_modes(spatial, lifted, modes_options, spatial_run.frames);
  for (size_t k = 0; k < times.size(); ++k) {
    const PoseModes p = planar_modes.modes(planar_run.frames[k]);
    const PoseModes s = spatial_modes.modes(spatial_run.frames[k]);
    const double worst = ((s.frequency_hz - p.frequency_hz).cwiseQuotient(p.frequency_hz)).cwiseAbs().maxCoeff();
    std::printf("t = %.2f s: planar %.4f %.4f %.4f ... Hz, spatial vs planar %.2e\n", times[k], p.frequency_hz(0),
                p.frequency_hz(1), p.frequency_hz(2), worst);
    EXPECT_GT(p.frequency_hz(0), 1.0);  // the chain holds the arm
    EXPECT_LT(worst, 1e-8);
  }
}

}  // namespace
}  // namespace kinetofem::vibration
