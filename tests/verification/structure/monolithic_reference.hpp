#pragma once
// The monolithic reference of the elastic assembly (verification test 1):
// every part's FULL stiffness (no support) in world axes in one sparse
// system, the joints imposed as linear constraints on the couplings'
// reference motions (the RBE3 definition v_k = G_k^T u, rotated to world
// axes) by Lagrange multipliers, solved directly (Eigen SparseLU on the
// augmented system [K + S, C^T; C, 0]). Nothing of the condensed method is
// reused: no 3-2-1 support, no flexibility, no rigid modes, no dense system;
// what is shared is the model's definition (meshes, couplings, loads).
//
// Joints handled: revolute (5 held components, rigid pin between the two
// reference points), prismatic between two parts (the slider's coupling at
// its joint point tied in the slide's axes n, z, rx, ry, rz to the guide's
// window: the faces of the guide's face set whose nodes lie within half the
// contact length of the slider's position, which must be a station of the
// assembly's, so that no interpolation enters), angle motion drives (rigid,
// or a torsional spring k (theta_j - theta_i)^2 / 2), displacement drives
// (rigid, or an axial spring: ds = t . (v_j - v_i) + (t x d) . rot_i).
// Ground: zero motion.
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/dof_map.hpp"

namespace kinetofem::structure::test {

struct MonolithicResult {
  std::vector<fem::DisplacementField> displacement;  // per part (given order), world axes
  double relative_residual = 0.0;
};

inline MonolithicResult solve_monolithic(const std::vector<pipeline::Part>& parts, const mech::MultibodyModel& model,
                                         const mech::Frame& frame,
                                         const std::map<std::string, double>& drive_stiffness = {},
                                         const std::map<std::string, double>& slide_contact_length = {}) {
  using SpMat = Eigen::SparseMatrix<double>;
  using Triplet = Eigen::Triplet<double>;
  const size_t np = parts.size();
  std::vector<Eigen::Index> offset(np + 1, 0);
  for (size_t p = 0; p < np; ++p) offset[p + 1] = offset[p] + 3 * parts[p].model.mesh.node_count();
  const Eigen::Index ndof = offset[np];
  auto body_of = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return int(b);
    fail("no body {}", name);
  };
  auto part_of = [&](const std::string& body) {
    for (size_t p = 0; p < np; ++p)
      if (parts[p].body() == body) return int(p);
    return -1;
  };
  std::vector<Eigen::Matrix3d> R(np);
  std::vector<Eigen::Vector3d> origin(np);
  for (size_t p = 0; p < np; ++p) {
    const Eigen::Vector3d q = frame.bodies[size_t(body_of(parts[p].body()))].q;
    R[p] = Eigen::AngleAxisd(q.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    origin[p] = Eigen::Vector3d(q.x(), q.y(), 0.0);
  }

  // K (world) and f (world).
  std::vector<Triplet> kt;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(ndof);
  double diagonal = 0.0;
  for (size_t p = 0; p < np; ++p) {
    const fem::FeModel& fe = parts[p].model;
    const fem::Index N = fe.mesh.node_count();
    const fem::DofMap dofs(N, {});
    const fem::AssembledStiffness K = fem::assemble_stiffness(fe.mesh, fe.material, dofs);
    const SpMat upper(K.free_free);
    SpMat full = SpMat(upper.selfadjointView<Eigen::Upper>());
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
    loads::LinkDefinition def = parts[p].attachments;
    def.model = &fe;
    def.joints.clear();
    std::erase_if(def.drives, [&](const loads::DriveAttachment& d) {
      for (const auto& md : model.motion_drives)
        if (md.name == d.drive) return true;
      return false;
    });
    const loads::LinkLoads link_loads(def, model, std::numeric_limits<double>::infinity());
    const Eigen::VectorXd fb = link_loads.loads_at(frame).forces;
    for (fem::Index i = 0; i < N; ++i) f.segment<3>(offset[p] + 3 * i) = R[p] * fb.segment<3>(3 * i);
  }

  // Reference motion (world) of a coupling: 6 x ndof rows, and its point.
  struct Ref {
    Eigen::MatrixXd rows;  // 6 x ndof (dense: small models)
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
  };
  auto coupling_ref = [&](int p, const std::string& face_set, const Eigen::Vector2d& point, bool centroid,
                          const fem::Mesh* window = nullptr) {
    const fem::Mesh& mesh = parts[size_t(p)].model.mesh;
    const fem::DistributingCoupling coupling(window ? *window : mesh, face_set);
    const Eigen::Vector3d X =
        centroid ? coupling.centroid() : Eigen::Vector3d(point.x(), point.y(), coupling.centroid().z());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(3 * mesh.node_count(), 6);
    for (int c = 0; c < 3; ++c) {
      coupling.add(Eigen::Vector3d::Unit(c), Eigen::Vector3d::Zero(), X, G.col(c));
      coupling.add(Eigen::Vector3d::Zero(), Eigen::Vector3d::Unit(c), X, G.col(3 + c));
    }
    // v_body = G^T u_body, u_body = R^T u_world per node; v_world = blockdiag(R, R) v_body.
    Ref ref;
    ref.rows = Eigen::MatrixXd::Zero(6, ndof);
    for (fem::Index i = 0; i < mesh.node_count(); ++i) {
      const Eigen::Matrix<double, 6, 3> g = G.middleRows<3>(3 * i).transpose();
      Eigen::Matrix<double, 6, 3> gw;
      gw.topRows<3>() = R[size_t(p)] * g.topRows<3>() * R[size_t(p)].transpose();
      gw.bottomRows<3>() = R[size_t(p)] * g.bottomRows<3>() * R[size_t(p)].transpose();
      ref.rows.middleCols<3>(offset[size_t(p)] + 3 * i) = gw;
    }
    ref.point = origin[size_t(p)] + R[size_t(p)] * X;
    return ref;
  };
  auto face_of_joint = [&](int p, const std::string& joint) {
    for (const auto& a : parts[size_t(p)].attachments.joints)
      if (a.joint == joint) return a.face_set;
    fail("no face set for {}", joint);
  };
  auto face_of_drive = [&](int p, const std::string& drive) {
    for (const auto& a : parts[size_t(p)].attachments.drives)
      if (a.drive == drive) return a.face_set;
    fail("no face set for {}", drive);
  };
  auto point_of = [&](const std::string& body, const std::string& point) -> Eigen::Vector2d {
    if (point == "origin") return Eigen::Vector2d::Zero();
    return model.bodies[size_t(body_of(body))].points.at(point);
  };

  auto transfer = [](const Eigen::Vector3d& d) {  // carries (translation, rotation) at a point to one d away
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
    Eigen::Matrix3d S;
    S << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
    T.block<3, 3>(0, 3) = -S;
    return T;
  };
  std::vector<Eigen::RowVectorXd> C;
  for (const mech::Joint& j : model.joints) {
    if (j.type == mech::JointType::Prismatic) {
      const int pi = part_of(j.body_i), pj = part_of(j.body_j);
      require(pi >= 0 && pj >= 0, "monolithic reference: a prismatic joint between two parts only");
      const Eigen::Vector2d axis = j.axis_i.normalized(), line = point_of(j.body_i, j.point_i);
      const Ref rj = coupling_ref(pj, face_of_joint(pj, j.name), point_of(j.body_j, j.point_j), false);
      // The slider's position along the guide, and the guide's window there.
      const Eigen::Vector3d local = R[size_t(pi)].transpose() * (rj.point - origin[size_t(pi)]);
      const double s = (local.head<2>() - line).dot(axis), c = slide_contact_length.at(j.name);
      fem::Mesh window = parts[size_t(pi)].model.mesh;
      std::vector<fem::FaceBlock> faces;
      for (const fem::FaceBlock& block : window.face_set(face_of_joint(pi, j.name))) {
        fem::FaceBlock kept{block.type, {}};
        for (fem::Index f = 0; f < block.size(); ++f) {
          bool inside = true;
          for (const fem::Index n : block.face(f))
            inside = inside && std::abs((window.nodes.row(n).head<2>().transpose() - line).dot(axis) - s) <= 0.5 * c * (1 + 1e-9);
          if (inside) kept.connectivity.insert(kept.connectivity.end(), block.face(f).begin(), block.face(f).end());
        }
        if (kept.size() > 0) faces.push_back(kept);
      }
      window.face_sets["window"] = faces;
      const Ref ri = coupling_ref(pi, "window", line + s * axis, false, &window);
      const Eigen::Vector3d t = R[size_t(pi)] * Eigen::Vector3d(axis.x(), axis.y(), 0.0);
      const Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(t);
      const Eigen::Matrix<double, 6, 6> T = transfer(rj.point - ri.point);
      for (int r = 0; r < 5; ++r) {
        Eigen::Matrix<double, 1, 6> e = Eigen::Matrix<double, 1, 6>::Zero();
        if (r == 0) e.head<3>() = n.transpose();
        if (r == 1) e.head<3>() = Eigen::Vector3d::UnitZ().transpose();
        if (r >= 2) e(3 + (r - 2)) = 1.0;
        C.push_back(e * rj.rows - e * T * ri.rows);
      }
      continue;
    }
    require(j.type == mech::JointType::Revolute, "monolithic reference: revolute and prismatic joints only");
    const int pi = part_of(j.body_i), pj = part_of(j.body_j);
    Ref ri, rj;
    if (pi >= 0) ri = coupling_ref(pi, face_of_joint(pi, j.name), point_of(j.body_i, j.point_i), false);
    if (pj >= 0) rj = coupling_ref(pj, face_of_joint(pj, j.name), point_of(j.body_j, j.point_j), false);
    Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Identity();
    if (pi >= 0 && pj >= 0) {
      const Eigen::Vector3d d = rj.point - ri.point;
      Eigen::Matrix3d S;
      S << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
      T.block<3, 3>(0, 3) = -S;
    }
    for (int c = 0; c < 5; ++c) {
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(ndof);
      if (pj >= 0) row += rj.rows.row(c);
      if (pi >= 0) row -= T.row(c) * ri.rows;
      C.push_back(row);
    }
  }
  std::vector<Triplet> st;  // drive springs
  for (const mech::MotionDrive& d : model.motion_drives) {
    const int pi = part_of(d.coordinate.body_i), pj = part_of(d.coordinate.body_j);
    Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(ndof);
    if (d.coordinate.type == mech::CoordinateType::Displacement) {
      require(pi >= 0 && pj >= 0, "monolithic reference: a displacement drive between two parts only");
      const Ref vi = coupling_ref(pi, face_of_drive(pi, d.name), point_of(d.coordinate.body_i, d.coordinate.point_i), false);
      const Ref vj = coupling_ref(pj, face_of_drive(pj, d.name), point_of(d.coordinate.body_j, d.coordinate.point_j), false);
      const Eigen::Vector2d axis = d.coordinate.axis_i.normalized();
      const Eigen::Vector3d t = R[size_t(pi)] * Eigen::Vector3d(axis.x(), axis.y(), 0.0);
      g = t.transpose() * (vj.rows.topRows<3>() - vi.rows.topRows<3>()) +
          t.cross(vj.point - vi.point).transpose() * vi.rows.bottomRows<3>();
    } else {
      if (pj >= 0) g += coupling_ref(pj, face_of_drive(pj, d.name), Eigen::Vector2d::Zero(), true).rows.row(5);
      if (pi >= 0) g -= coupling_ref(pi, face_of_drive(pi, d.name), Eigen::Vector2d::Zero(), true).rows.row(5);
    }
    const auto it = drive_stiffness.find(d.name);
    if (it == drive_stiffness.end()) {
      C.push_back(g);
    } else {
      for (Eigen::Index a = 0; a < ndof; ++a)
        if (g(a) != 0.0)
          for (Eigen::Index b = 0; b < ndof; ++b)
            if (g(b) != 0.0) st.emplace_back(a, b, it->second * g(a) * g(b));
    }
  }
  const Eigen::Index nc = Eigen::Index(C.size()), n = ndof + nc;
  const double s = diagonal;  // balances the constraint rows against K
  std::vector<Triplet> at = kt;
  at.insert(at.end(), st.begin(), st.end());
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
  for (int refine = 0; refine < 3; ++refine) x += lu.solve(Eigen::VectorXd(rhs - A * x));  // iterative refinement
  MonolithicResult out;
  out.relative_residual = (A * x - rhs).norm() / rhs.norm();
  for (size_t p = 0; p < np; ++p) {
    const fem::Index N = parts[p].model.mesh.node_count();
    out.displacement.push_back(Eigen::Map<const fem::DisplacementField>(x.data() + offset[p], N, 3));
  }
  return out;
}

}  // namespace kinetofem::structure::test
