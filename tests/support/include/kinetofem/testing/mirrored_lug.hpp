#pragma once
// A lug (a plate with a bore) whose mesh is exactly mirror-symmetric about
// the plane y = 0 through the bore's axis, and one pose of a rigid round pin
// in frictionless contact with its bore (fem::solve_contact on the lug's
// condensed compliance), for the contact checks that need a symmetric mesh
// or the same mesh in another code (CalculiX).
//
// Geometry (m, the lug's frame): the bore of radius R about the z axis
// through the origin, the lug 0 <= z <= t thick; a round head of radius Ro
// about the bore on the side x < 0, a straight shank |y| <= Ro out to x = L,
// the end face x = L clamped (its nodes held in x, y and z: a support that
// is symmetric too, and far from the bore).
//
//          y
//          ^      ___________________________
//         Ro   .-'                           |
//            /      .-.                      |  clamped
//           |      ( + )  -> x               |  end face x = L
//            \      '-'                      |
//        -Ro   '-.___________________________|
//
// Mesh: two structured blocks (verification::StructuredBlock), each a ring
// from the bore (u = 0) to the outline (u = 1) over half the turn (v), t
// thick (w); the lower one is the upper's mirror image (its mapping is the
// upper's with y -> -y and, so that the elements keep a positive volume,
// z -> t - z), and the nodes on y = 0 are merged. The nodes of the lower
// half are then set to the exact mirror images of their upper partners, so
// the mesh is mirror-symmetric to the last bit (mirror_map gives each node's
// image). The pin's own mesh for CalculiX (mirrored_pin_mesh) is a tube of
// the bore's radius with the same node angles and layers, made the same way.
//
// Face sets: "bore" (r = R), "outline" (the outer boundary), "clamp" (its
// part on x = L), "z0", "z1"; node sets of the same names.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/verification/structured_block.hpp"

namespace kinetofem::testing {

struct MirroredLugOptions {
  double bore_radius_m = 0.015;  // R
  double head_radius_m = 0.030;  // Ro, also the shank's half width
  double length_m = 0.090;       // L, bore axis to the clamped end face
  double thickness_m = 0.020;    // t
  int half_turn_divisions = 24;  // cells along the bore over 180 deg (corner spacing 180 deg / this)
  int end_face_divisions = 3;    // of those, the cells whose rays reach the end face x = L (per half)
  int radial_divisions = 8;
  int thickness_divisions = 4;   // a power of two keeps z -> t - z exact in the parameters
  double radial_grading = 4.0;   // outermost / bore-side cell size
  fem::ElementType type = fem::ElementType::Hex20;
};

namespace detail {

using Key = std::tuple<long long, long long, long long>;
inline Key key_of(const Eigen::Vector3d& x, double tolerance_m) {
  return {std::llround(x[0] / tolerance_m), std::llround(x[1] / tolerance_m), std::llround(x[2] / tolerance_m)};
}

// The meshes `parts` (one element type) as one mesh, nodes closer than
// tolerance_m merged (the first one kept), sets of the same name united.
inline fem::Mesh merge_coincident_nodes(const std::vector<fem::Mesh>& parts, double tolerance_m) {
  fem::Mesh out;
  std::map<Key, fem::Index> seen;
  std::vector<Eigen::Vector3d> nodes;
  fem::Index element_offset = 0;
  for (const fem::Mesh& part : parts) {
    std::vector<fem::Index> to(size_t(part.node_count()));
    for (fem::Index n = 0; n < part.node_count(); ++n) {
      const Eigen::Vector3d x = part.nodes.row(n).transpose();
      const auto [it, added] = seen.emplace(key_of(x, tolerance_m), fem::Index(nodes.size()));
      if (added) nodes.push_back(x);
      to[size_t(n)] = it->second;
    }
    for (const fem::ElementBlock& block : part.blocks) {
      if (out.blocks.empty()) out.blocks.push_back({block.type, {}});
      require(out.blocks.front().type == block.type, "merge: one element type expected");
      for (const fem::Index n : block.connectivity) out.blocks.front().connectivity.push_back(to[size_t(n)]);
    }
    for (const auto& [name, faces] : part.face_sets)
      for (const fem::FaceBlock& f : faces) {
        auto& target = out.face_sets[name];
        if (target.empty()) target.push_back({f.type, {}});
        for (const fem::Index n : f.connectivity) target.front().connectivity.push_back(to[size_t(n)]);
      }
    for (const auto& [name, set] : part.node_sets) {
      auto& target = out.node_sets[name];
      for (const fem::Index n : set) target.push_back(to[size_t(n)]);
      std::sort(target.begin(), target.end());
      target.erase(std::unique(target.begin(), target.end()), target.end());
    }
    for (const auto& [name, set] : part.element_sets)
      for (const fem::Index e : set) out.element_sets[name].push_back(e + element_offset);
    element_offset += part.element_count();
  }
  out.nodes.resize(fem::Index(nodes.size()), 3);
  for (size_t n = 0; n < nodes.size(); ++n) out.nodes.row(fem::Index(n)) = nodes[n].transpose();
  return out;
}

// A ring of the turn's upper half (0 <= theta <= pi) from the circle of
// radius `inner` (u = 0) to outline(v) (u = 1), and its mirror image; merged
// and made exactly symmetric.
inline fem::Mesh mirrored_ring(double inner_radius_m, const std::function<Eigen::Vector2d(double v)>& outline,
                               const MirroredLugOptions& o, int radial_divisions, double radial_grading) {
  constexpr double kPi = std::numbers::pi;
  const double t = o.thickness_m;
  auto upper = [=](const Eigen::Vector3d& uvw) -> Eigen::Vector3d {
    const double theta = kPi * uvw[1];
    const Eigen::Vector2d hole(inner_radius_m * std::cos(theta), inner_radius_m * std::sin(theta));
    const Eigen::Vector2d p = hole + uvw[0] * (outline(uvw[1]) - hole);
    return {p[0], p[1], t * uvw[2]};
  };
  verification::StructuredBlock block;
  block.divisions = {radial_divisions, o.half_turn_divisions, o.thickness_divisions};
  block.type = o.type;
  block.grading_ratio = {radial_grading, 1.0, 1.0};
  block.face_names = {"bore", "outline", "v0", "v1", "z0", "z1"};
  block.mapping = upper;
  const fem::Mesh top = verification::structured_block_mesh(block);
  block.mapping = [=](const Eigen::Vector3d& uvw) -> Eigen::Vector3d {
    const Eigen::Vector3d p = upper({uvw[0], uvw[1], 1.0 - uvw[2]});
    return {p[0], -p[1], p[2]};
  };
  block.face_names = {"bore", "outline", "v0", "v1", "z1", "z0"};
  const fem::Mesh bottom = verification::structured_block_mesh(block);
  const double tolerance = 1e-9 * o.head_radius_m;
  fem::Mesh mesh = merge_coincident_nodes({top, bottom}, tolerance);
  // The plane's nodes exactly on it (sin(pi) is 1.2e-16, not 0), the lower
  // half's the exact images of the upper half's.
  std::map<Key, fem::Index> upper_nodes;
  for (fem::Index n = 0; n < mesh.node_count(); ++n) {
    if (std::abs(mesh.nodes(n, 1)) < tolerance) mesh.nodes(n, 1) = 0.0;
    if (mesh.nodes(n, 1) > 0.0) upper_nodes.emplace(key_of(mesh.nodes.row(n).transpose(), tolerance), n);
  }
  for (fem::Index n = 0; n < mesh.node_count(); ++n) {
    if (mesh.nodes(n, 1) >= 0.0) continue;
    Eigen::Vector3d image = mesh.nodes.row(n).transpose();
    image[1] = -image[1];
    const auto it = upper_nodes.find(key_of(image, tolerance));
    require(it != upper_nodes.end(), "mirrored ring: node {} has no mirror image", n);
    mesh.nodes.row(n) = mesh.nodes.row(it->second);
    mesh.nodes(n, 1) = -mesh.nodes(it->second, 1);
  }
  mesh.node_sets.erase("v0");
  mesh.node_sets.erase("v1");
  mesh.face_sets.erase("v0");
  mesh.face_sets.erase("v1");
  mesh.validate();
  return mesh;
}

}  // namespace detail

// The lug of the header.
inline fem::Mesh mirrored_lug_mesh(const MirroredLugOptions& o = {}) {
  require(o.head_radius_m > o.bore_radius_m && o.length_m > o.head_radius_m, "mirrored lug: need R < Ro < L");
  require(o.end_face_divisions >= 1 && 2 * o.end_face_divisions < o.half_turn_divisions && o.half_turn_divisions % 2 == 0,
          "mirrored lug: need an even number of cells per half turn, more than twice those on the end face");
  constexpr double kPi = std::numbers::pi;
  const double Ro = o.head_radius_m, L = o.length_m;
  const int n = o.half_turn_divisions, n_end = o.end_face_divisions, n_head = n / 2, n_top = n - n_end - n_head;
  // The outline over the upper half, by cells of v: the end face x = L
  // (y from 0 to Ro), the shank's edge y = Ro (x from L to 0), the head's arc
  // (90 to 180 deg). Each piece spans whole cells, so its corners are nodes.
  auto outline = [=](double v) -> Eigen::Vector2d {
    const double s = v * n;
    if (s <= n_end) return {L, Ro * s / n_end};
    if (s <= n_end + n_top) return {L * (1.0 - (s - n_end) / n_top), Ro};
    const double theta = kPi * v;
    return {Ro * std::cos(theta), Ro * std::sin(theta)};
  };
  fem::Mesh mesh = detail::mirrored_ring(o.bore_radius_m, outline, o, o.radial_divisions, o.radial_grading);
  // The clamped end face: the outline's faces on x = L.
  fem::FaceBlock clamp{mesh.face_sets.at("outline").front().type, {}};
  const fem::FaceBlock& outer = mesh.face_sets.at("outline").front();
  for (fem::Index f = 0; f < outer.size(); ++f) {
    const auto face = outer.face(f);
    if (std::all_of(face.begin(), face.end(), [&](fem::Index a) { return std::abs(mesh.nodes(a, 0) - L) < 1e-12 * L; }))
      clamp.connectivity.insert(clamp.connectivity.end(), face.begin(), face.end());
  }
  mesh.node_sets["clamp"] = fem::nodes_of_faces({clamp});
  mesh.face_sets["clamp"] = {std::move(clamp)};
  return mesh;
}

// A tube from radius inner_radius_m to the lug's bore radius, the lug's
// thickness, with the bore's node angles and layers: the pin's surface
// coincides with the bore's, node for node (face set "outline").
inline fem::Mesh mirrored_pin_mesh(const MirroredLugOptions& o, double inner_radius_m, int radial_divisions) {
  const double R = o.bore_radius_m;
  auto outline = [=](double v) -> Eigen::Vector2d {
    const double theta = std::numbers::pi * v;
    return {R * std::cos(theta), R * std::sin(theta)};
  };
  return detail::mirrored_ring(inner_radius_m, outline, o, radial_divisions, 1.0);
}

// Each node's mirror image under y -> -y (itself on the plane). Throws Error
// when a node has no exact image.
inline std::vector<fem::Index> mirror_map(const fem::Mesh& mesh) {
  std::map<std::array<double, 3>, fem::Index> at;
  for (fem::Index n = 0; n < mesh.node_count(); ++n) at[{mesh.nodes(n, 0), mesh.nodes(n, 1), mesh.nodes(n, 2)}] = n;
  std::vector<fem::Index> image(size_t(mesh.node_count()));
  for (fem::Index n = 0; n < mesh.node_count(); ++n) {
    const auto it = at.find({mesh.nodes(n, 0), -mesh.nodes(n, 1), mesh.nodes(n, 2)});
    require(it != at.end(), "node {} has no exact mirror image", n);
    image[size_t(n)] = it->second;
  }
  return image;
}

// A steel lug of the header, its end face clamped.
inline fem::FeModel clamped_lug_model(const MirroredLugOptions& o = {}) {
  fem::FeModel model;
  model.mesh = mirrored_lug_mesh(o);
  model.material.name = "steel";
  model.material.youngs_modulus_pa = 210e9;
  model.material.poisson_ratio = 0.3;
  model.material.density_kg_m3 = 7850.0;
  model.supports.push_back({"clamp", model.mesh.node_set("clamp")});
  return model;
}

// One pose of the pin: the pressures, the pin's motion and the lug's field.
struct LugContactPose {
  fem::ContactSolution contact;
  fem::BoreContactState state;
  Eigen::Vector4d carried = Eigen::Vector4d::Zero();  // (F.e_1, F.e_2, M.e_1, M.e_2) the contact carries
  fem::DisplacementField displacement;                // m
};

// A rigid round pin in the bore of a factorized lug (its axis the z axis at
// mid-thickness): the lug's condensed compliance made once (one solve per
// bore corner), then any pin force (the force on the lug, N, in the x-y
// plane, through the mid-thickness: no tilting moment) and radial clearance.
class LugPinContact {
 public:
  LugPinContact(const fem::FeModel& model, const Log& log)
      : analysis_(model, log),
        bore_(model.mesh, "bore", {0.0, 0.0, 0.5 * bore_length(model.mesh)}, Eigen::Vector3d::UnitZ()) {
    const Eigen::Index m = bore_.size();
    const Eigen::Index dofs = 3 * model.mesh.node_count();
    Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(dofs, m);
    bore_.add_forces(Eigen::MatrixXd::Identity(m, m), unit);
    const std::vector<fem::DisplacementField> u = analysis_.solve_forces(unit);
    Eigen::MatrixXd W(dofs, m);
    for (Eigen::Index k = 0; k < m; ++k) W.col(k) = Eigen::Map<const Eigen::VectorXd>(u[size_t(k)].data(), dofs);
    compliance_ = bore_.weighted_normal_components(W);
    compliance_ = 0.5 * (compliance_ + compliance_.transpose()).eval();
  }

  LugContactPose solve(const Eigen::Vector3d& force_n, double clearance_m, const std::vector<char>& start = {},
                       bool with_field = true) {
    LugContactPose pose;
    pose.carried = bore_.carried(force_n, Eigen::Vector3d::Zero());
    pose.contact = fem::solve_contact(compliance_, clearance_m * bore_.corner_area_m2(), bore_.rigid_pin_map(),
                                      pose.carried, start);
    pose.state = fem::contact_state(bore_, pose.contact.pressure);
    if (with_field) {
      Eigen::MatrixXd f = Eigen::MatrixXd::Zero(3 * analysis_.model().mesh.node_count(), 1);
      bore_.add_forces(pose.contact.pressure, f);
      pose.displacement = analysis_.solve_forces(f).front();
    }
    return pose;
  }

  const fem::BoreContactSurface& bore() const { return bore_; }
  const fem::LinearStaticAnalysis& analysis() const { return analysis_; }

 private:
  static double bore_length(const fem::Mesh& mesh) {
    double z = 0.0;
    for (const fem::Index n : fem::nodes_of_faces(mesh.face_set("bore"))) z = std::max(z, mesh.nodes(n, 2));
    return z;
  }
  fem::LinearStaticAnalysis analysis_;
  fem::BoreContactSurface bore_;
  Eigen::MatrixXd compliance_;
};

}  // namespace kinetofem::testing
