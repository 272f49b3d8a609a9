#pragma once
// The monolithic reference of the spatial elastic assembly: every part's FULL
// stiffness (no support) turned into world axes by its body's rotation in one
// sparse system, the joints and drives imposed as linear constraints on the
// couplings' reference motions (the RBE3 definition v = G^T u, turned into
// world axes) by Lagrange multipliers, solved directly (Eigen SparseLU on
// [K, C^T; C, 0] with iterative refinement). Nothing of the condensed method
// is reused (no 3-2-1 support, flexibility, rigid modes or dense pose
// system); what is shared is the model's definition: meshes, face sets,
// joint points, and the parts' own loads (loads::SpatialLinkLoads without
// joints, drives and slides).
//
// Joints handled: every type but the chain and slides, as plain ties held in
// the components of joint_facts (the reaction's); motion drives rigid. Every
// body must carry a part (no rigid bodies); the ground does not move.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/structure/spatial_part.hpp"

namespace kinetofem::structure::test {

struct SpatialMonolithicResult {
  std::vector<fem::DisplacementField> displacement;  // per part (given order), world axes
  double relative_residual = 0.0;
};

inline SpatialMonolithicResult solve_spatial_monolithic(const std::vector<SpatialPart>& parts,
                                                        const mech::spatial::Model& model,
                                                        const mech::spatial::Frame& frame) {
  namespace sp = mech::spatial;
  using SpMat = Eigen::SparseMatrix<double>;
  using Triplet = Eigen::Triplet<double>;
  const sp::System system(model);
  const size_t np = parts.size();
  std::vector<Eigen::Index> offset(np + 1, 0);
  for (size_t p = 0; p < np; ++p) offset[p + 1] = offset[p] + 3 * parts[p].model.mesh.node_count();
  const Eigen::Index ndof = offset[np];
  auto part_of = [&](int body) {
    for (size_t p = 0; p < np; ++p)
      if (parts[p].body() == model.bodies[size_t(body)].name) return int(p);
    return -1;
  };
  std::vector<Eigen::Matrix3d> R(np);
  std::vector<Eigen::Vector3d> origin(np);
  for (size_t p = 0; p < np; ++p) {
    const int b = system.body_index(parts[p].body());
    R[p] = frame.bodies[size_t(b)].rotation;
    origin[p] = frame.bodies[size_t(b)].origin;
  }

  std::vector<Triplet> kt;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(ndof);
  double diagonal = 0.0;
  for (size_t p = 0; p < np; ++p) {
    const fem::FeModel& fe = parts[p].model;
    const fem::Index N = fe.mesh.node_count();
    const fem::DofMap dofs(N, {});
    const fem::AssembledStiffness K = fem::assemble_stiffness(fe.mesh, fe.material, dofs);
    const SpMat upper(K.free_free);
    const SpMat full = SpMat(upper.selfadjointView<Eigen::Upper>());
    std::vector<Triplet> qt;
    for (fem::Index i = 0; i < N; ++i)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) qt.emplace_back(3 * i + a, 3 * i + b, R[p](a, b));
    SpMat Q(3 * N, 3 * N);
    Q.setFromTriplets(qt.begin(), qt.end());
    const SpMat Kw = Q * full * SpMat(Q.transpose());
    for (int k = 0; k < Kw.outerSize(); ++k)
      for (SpMat::InnerIterator it(Kw, k); it; ++it)
        kt.emplace_back(offset[p] + it.row(), offset[p] + it.col(), it.value());
    diagonal = std::max(diagonal, full.diagonal().cwiseAbs().maxCoeff());
    loads::SpatialLinkDefinition own = parts[p].attachments;
    own.model = &fe;
    own.joints.clear();
    own.slides.clear();
    const loads::SpatialLinkLoads link_loads(own, model, std::numeric_limits<double>::infinity());
    const Eigen::VectorXd fb = link_loads.loads_at(frame);
    for (fem::Index i = 0; i < N; ++i) f.segment<3>(offset[p] + 3 * i) = R[p] * fb.segment<3>(3 * i);
  }

  // The world motion (translation, rotation) of the coupling of `item`'s face
  // set on part p with its reference at X (body frame): 6 x ndof rows.
  auto coupling_rows = [&](int p, const std::string& item, const Eigen::Vector3d& X) {
    std::string face_set;
    for (const loads::SpatialAttachment& a : parts[size_t(p)].attachments.joints)
      if (a.name == item) face_set = a.face_set;
    require(!face_set.empty(), "monolithic reference: no face set for '{}'", item);
    const fem::Mesh& mesh = parts[size_t(p)].model.mesh;
    const fem::DistributingCoupling coupling(mesh, face_set);
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3 * mesh.node_count(), 6);
    for (int c = 0; c < 3; ++c) {
      coupling.add(Eigen::Vector3d::Unit(c), Eigen::Vector3d::Zero(), X, G.col(c));
      coupling.add(Eigen::Vector3d::Zero(), Eigen::Vector3d::Unit(c), X, G.col(3 + c));
    }
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(6, ndof);
    for (fem::Index i = 0; i < mesh.node_count(); ++i) {
      const Eigen::Matrix<double, 6, 3> g = G.middleRows<3>(3 * i).transpose();
      rows.block<3, 3>(0, offset[size_t(p)] + 3 * i) = R[size_t(p)] * g.topRows<3>() * R[size_t(p)].transpose();
      rows.block<3, 3>(3, offset[size_t(p)] + 3 * i) = R[size_t(p)] * g.bottomRows<3>() * R[size_t(p)].transpose();
    }
    return rows;
  };
  auto transfer = [](const Eigen::Vector3d& d) {
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
    Eigen::Matrix3d S;
    S << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
    T.block<3, 3>(0, 3) = -S;
    return T;
  };
  auto world_point = [&](int body, const std::string& point) {
    return Eigen::Vector3d(frame.bodies[size_t(body)].origin +
                           frame.bodies[size_t(body)].rotation * system.named_point(body, point));
  };

  std::vector<Eigen::RowVectorXd> C;
  for (const sp::Joint& j : model.joints) {
    const sp::ConstraintBlock& block = system.block(j.name);
    const int pi = part_of(block.body_i), pj = part_of(block.body_j);
    const Eigen::Vector3d Xi = world_point(block.body_i, j.point_i), Xj = world_point(block.body_j, j.point_j);
    Eigen::MatrixXd vi = Eigen::MatrixXd::Zero(6, ndof), vj = Eigen::MatrixXd::Zero(6, ndof);
    if (pi >= 0) vi = transfer(Xj - Xi) * coupling_rows(pi, j.name, system.named_point(block.body_i, j.point_i));
    if (pj >= 0) vj = coupling_rows(pj, j.name, system.named_point(block.body_j, j.point_j));
    const Eigen::Matrix3d& Ri = frame.bodies[size_t(block.body_i)].rotation;
    const Eigen::Vector3d axes[3] = {Ri * block.f_i, Ri * block.g_i, Ri * block.h_i};
    const sp::JointFacts& facts = sp::joint_facts(j.type);
    for (int c = 0; c < facts.forces; ++c) C.push_back(axes[c].transpose() * (vj - vi).topRows<3>());
    if (facts.moments == 1) {
      const Eigen::Vector3d hj = frame.bodies[size_t(block.body_j)].rotation * block.h_j;
      C.push_back(axes[2].cross(hj).normalized().transpose() * (vj - vi).bottomRows<3>());
    } else {
      for (int c = 0; c < facts.moments; ++c) C.push_back(axes[c].transpose() * (vj - vi).bottomRows<3>());
    }
  }
  for (const sp::MotionDrive& d : model.motion_drives) {
    const sp::ConstraintBlock& block = system.block(d.name);
    const sp::Joint& j = model.joints[size_t(system.block(d.joint).source)];
    const int pi = part_of(block.body_i), pj = part_of(block.body_j);
    const Eigen::Vector3d Pi = system.named_point(block.body_i, j.point_i),
                          Pj = system.named_point(block.body_j, j.point_j);
    Eigen::MatrixXd vi = Eigen::MatrixXd::Zero(6, ndof), vj = Eigen::MatrixXd::Zero(6, ndof);
    if (pi >= 0) vi = coupling_rows(pi, d.name, Pi);
    if (pj >= 0) vj = coupling_rows(pj, d.name, Pj);
    const Eigen::Vector3d h = frame.bodies[size_t(block.body_i)].rotation * block.h_i;
    if (d.coordinate == sp::DriveCoordinate::Rotation) {
      C.push_back(h.transpose() * (vj - vi).bottomRows<3>());
    } else {
      const Eigen::Vector3d dist = world_point(block.body_j, j.point_j) - world_point(block.body_i, j.point_i);
      C.push_back(h.transpose() * (vj - vi).topRows<3>() + h.cross(dist).transpose() * vi.bottomRows<3>());
    }
  }

  const Eigen::Index nc = Eigen::Index(C.size()), n = ndof + nc;
  const double s = diagonal;  // balances the constraint rows against K
  std::vector<Triplet> at = kt;
  for (Eigen::Index r = 0; r < nc; ++r)
    for (Eigen::Index a = 0; a < ndof; ++a)
      if (C[size_t(r)](a) != 0.0) {
        at.emplace_back(ndof + r, a, s * C[size_t(r)](a));
        at.emplace_back(a, ndof + r, s * C[size_t(r)](a));
      }
  SpMat A(n, n);
  A.setFromTriplets(at.begin(), at.end());
  A.makeCompressed();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  rhs.head(ndof) = f;
  Eigen::SparseLU<SpMat> lu;
  lu.compute(A);
  require(lu.info() == Eigen::Success, "monolithic reference: SparseLU failed: {}", lu.lastErrorMessage());
  Eigen::VectorXd x = lu.solve(rhs);
  for (int refine = 0; refine < 3; ++refine) x += lu.solve(Eigen::VectorXd(rhs - A * x));
  SpatialMonolithicResult out;
  out.relative_residual = (A * x - rhs).norm() / rhs.norm();
  for (size_t p = 0; p < np; ++p) {
    const fem::Index N = parts[p].model.mesh.node_count();
    out.displacement.push_back(Eigen::Map<const fem::DisplacementField>(x.data() + offset[p], N, 3));
  }
  return out;
}

}  // namespace kinetofem::structure::test
