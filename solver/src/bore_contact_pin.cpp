#include "kinetofem/solver/bore_contact_pin.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/element_traits.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::fem {

namespace {

constexpr double kPi = std::numbers::pi;

// HEX20 node k at lattice offset (dx, dy, dz) in {0, 1, 2}^3 of its cell
// (mesh.hpp's numbering: corners, then mid-edge nodes 8..19).
constexpr int kHex20Offsets[20][3] = {
    {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2},  // corners
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0},                        // 8..13
    {2, 2, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2}, {2, 1, 2}, {1, 2, 2}};                       // 14..19

// Nodes of a structured mesh shared between its blocks: one node per
// position (rounded to 1e-9 of the size).
class NodeTable {
 public:
  explicit NodeTable(double size) : quantum_(1e-9 * size) {}
  Index at(const Eigen::Vector3d& x) {
    const std::array<long long, 3> key = {std::llround(x.x() / quantum_), std::llround(x.y() / quantum_),
                                          std::llround(x.z() / quantum_)};
    const auto [it, inserted] = index_.emplace(key, Index(points_.size()));
    if (inserted) points_.push_back(x);
    return it->second;
  }
  NodeCoordinates coordinates() const {
    NodeCoordinates out(Index(points_.size()), 3);
    for (size_t k = 0; k < points_.size(); ++k) out.row(Index(k)) = points_[k].transpose();
    return out;
  }

 private:
  double quantum_;
  std::map<std::array<long long, 3>, Index> index_;
  std::vector<Eigen::Vector3d> points_;
};

// The area weights of a face's quadrature split into s x s parts: points
// (xi, weight) on the reference face. A triangle's parts are mapped from the
// quadrilateral's 3 x 3 Gauss rule by the collapsed (Duffy) map, so both
// kinds integrate to degree 5 in each part.
std::vector<QuadraturePoint> subdivided_rule(FaceType type, int s) {
  const auto& square = quadrature(FaceType::Quad8);  // 3 x 3 on [-1, 1]^2
  std::vector<QuadraturePoint> out;
  const bool triangle = type == FaceType::Tri3 || type == FaceType::Tri6;
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < s; ++j) {
      if (!triangle) {
        for (const auto& q : square)
          out.push_back({Eigen::Vector3d(-1 + (2 * i + 1 + q.xi[0]) / s, -1 + (2 * j + 1 + q.xi[1]) / s, 0),
                         q.weight / double(s * s)});
        continue;
      }
      // Sub-triangles of the reference triangle: upright (i, j), (i+1, j),
      // (i, j+1) for i + j < s; inverted (i+1, j+1), (i, j+1), (i+1, j) for
      // i + j < s - 1; all of area 1 / (2 s^2).
      for (int flip = 0; flip < 2; ++flip) {
        if (i + j + flip >= s) continue;
        Eigen::Vector2d v0(i, j), v1(i + 1, j), v2(i, j + 1);
        if (flip) v0 = {i + 1, j + 1}, v1 = {i, j + 1}, v2 = {i + 1, j};
        v0 /= s, v1 /= s, v2 /= s;
        for (const auto& q : square) {
          const double a = 0.5 * (1 + q.xi[0]), b = 0.5 * (1 + q.xi[1]);
          const double u = a * (1 - b), v = b;  // on the unit triangle, Jacobian (1 - b) / 4 from [-1, 1]^2
          const Eigen::Vector2d p = v0 + u * (v1 - v0) + v * (v2 - v0);
          out.push_back({Eigen::Vector3d(p.x(), p.y(), 0), q.weight * 0.25 * (1 - b) / double(s * s)});
        }
      }
    }
  return out;
}

}  // namespace

Mesh pin_mesh(double radius_m, double span_m, int circumferential, int radial, int axial) {
  require(std::isfinite(radius_m) && radius_m > 0 && std::isfinite(span_m) && span_m > 0,
          "pin mesh: radius {} m and span {} m must be positive", radius_m, span_m);
  require(circumferential >= 8 && circumferential % 4 == 0 && radial >= 1 && axial >= 1,
          "pin mesh: {} elements around (a multiple of 4, at least 8), {} across the curved blocks and {} along the "
          "span (at least 1 each)",
          circumferential, radial, axial);
  const int k = circumferential / 4;  // elements per side of the core, per quarter of the circle
  const double half_side = 0.4 * radius_m;
  NodeTable table(std::max(radius_m, span_m));
  ElementBlock hexes{ElementType::Hex20, {}};
  // A block: its lattice point (I, J) (double resolution, 0 .. 2 cells) at
  // height level L; the cell's first lattice axis, its second and z are
  // right-handed.
  auto add_block = [&](int cells_1, int cells_2, auto&& point) {
    for (int i = 0; i < cells_1; ++i)
      for (int j = 0; j < cells_2; ++j)
        for (int l = 0; l < axial; ++l)
          for (int a = 0; a < 20; ++a) {
            const auto& o = kHex20Offsets[a];
            const Eigen::Vector2d xy = point(2 * i + o[0], 2 * j + o[1]);
            const double z = span_m * double(2 * l + o[2]) / double(2 * axial);
            hexes.connectivity.push_back(table.at({xy.x(), xy.y(), z}));
          }
  };
  // The core: a square of k x k cells.
  add_block(k, k, [&](int I, int J) {
    return Eigen::Vector2d(half_side * (double(I) / k - 1), half_side * (double(J) / k - 1));
  });
  // Four curved blocks, the first on the +x side (the circle from -45 to 45
  // degrees), the others turned by 90 degrees each: lattice axis 1 from the
  // core's side out to the circle, axis 2 along the side.
  for (int q = 0; q < 4; ++q) {
    const Eigen::Rotation2Dd turn(q * kPi / 2);
    add_block(radial, k, [&](int I, int J) {
      const double t = double(I) / (2 * radial), u = double(J) / (2 * k);
      const Eigen::Vector2d side(half_side, half_side * (2 * u - 1));
      const double phi = -kPi / 4 + u * kPi / 2;
      const Eigen::Vector2d circle(radius_m * std::cos(phi), radius_m * std::sin(phi));
      return Eigen::Vector2d(turn * ((1 - t) * side + t * circle));
    });
  }
  Mesh mesh;
  mesh.nodes = table.coordinates();
  // The lateral surface: element faces whose eight nodes lie on the circle.
  FaceBlock surface{FaceType::Quad8, {}};
  for (Index e = 0; e < hexes.size(); ++e) {
    const auto nodes = hexes.element(e);
    for (int f = 0; f < faces_per_element(ElementType::Hex20); ++f) {
      const std::vector<int> local = element_face_nodes(ElementType::Hex20, f);
      bool on_circle = true;
      for (const int a : local)
        on_circle = on_circle &&
                    std::abs(mesh.nodes.row(nodes[size_t(a)]).head<2>().norm() - radius_m) < 1e-9 * radius_m;
      if (on_circle)
        for (const int a : local) surface.connectivity.push_back(nodes[size_t(a)]);
    }
  }
  mesh.blocks.push_back(std::move(hexes));
  mesh.face_sets["surface"] = {std::move(surface)};
  mesh.validate();
  return mesh;
}

ElasticPin::ElasticPin(const Mesh& part_mesh, const BoreContactSurface& bore, const IsotropicMaterial& material,
                       double clearance_m, const Log& log, const ElasticPinOptions& options) {
  Stopwatch clock;
  material.validate();
  const std::string& name = bore.face_set();
  radius_ = bore.radius_m() - clearance_m;
  require(std::isfinite(clearance_m) && clearance_m >= 0 && radius_ > 0,
          "elastic pin in bore '{}': the clearance {} m leaves no pin in a bore of radius {} m", name, clearance_m,
          bore.radius_m());
  require(options.quadrature_subdivisions >= 1, "elastic pin in bore '{}': quadrature subdivisions {} < 1", name,
          options.quadrature_subdivisions);

  // The bore's own frame: e_1, e_2 across the axis, z along it from the
  // bore's first node.
  const Eigen::Vector3d c = bore.axis_point(), a = bore.axis(), e1 = bore.e1(), e2 = bore.e2();
  double z0 = std::numeric_limits<double>::infinity(), z1 = -z0;
  for (const Index n : bore.nodes()) {
    const double z = (part_mesh.nodes.row(n).transpose() - c).dot(a);
    z0 = std::min(z0, z), z1 = std::max(z1, z);
  }
  span_ = z1 - z0;
  require(span_ > 0, "elastic pin in bore '{}': the bore has no extent along its axis", name);
  const double h = std::sqrt(bore.corner_area_m2().sum() / double(bore.size()));
  circumferential_ = options.circumferential_elements > 0
                         ? options.circumferential_elements
                         : std::max(16, 4 * int(std::ceil(2 * kPi * radius_ / (4 * h))));
  const int radial = options.radial_elements > 0 ? options.radial_elements : std::max(2, circumferential_ / 16);
  const int axial = options.axial_elements > 0 ? options.axial_elements : std::max(1, int(std::ceil(span_ / h)));

  // The pin, in the bore's frame (x along e_1, y along e_2, z from z0).
  FeModel pin;
  pin.mesh = pin_mesh(radius_, span_, circumferential_, radial, axial);
  pin.material = material;
  if (!(pin.material.density_kg_m3 > 0)) pin.material.density_kg_m3 = 1.0;  // only weights the balance
  std::vector<Index> all(size_t(pin.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = Index(i);
  pin.supports = three_two_one_support(pin.mesh, all);
  nodes_ = pin.mesh.node_count();

  // The pin's lateral faces by angle and height (the O-grid's circle starts at -45 degrees).
  const auto& surface = pin.mesh.face_set("surface").front();
  const double dtheta = 2 * kPi / circumferential_, dz = span_ / axial;
  std::vector<Index> face_at(size_t(circumferential_ * axial), -1);
  std::vector<Index> surface_row(size_t(nodes_), -1);
  std::vector<Index> surface_nodes;
  for (Index f = 0; f < surface.size(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) centre += 0.25 * pin.mesh.nodes.row(surface.face(f)[size_t(k)]).transpose();
    const double angle = std::atan2(centre.y(), centre.x());
    const int j = int(std::floor(std::remainder(angle + kPi / 4, 2 * kPi) / dtheta + circumferential_)) %
                  circumferential_;
    const int l = std::clamp(int(std::floor(centre.z() / dz)), 0, axial - 1);
    face_at[size_t(j * axial + l)] = f;
    for (const Index n : surface.face(f))
      if (surface_row[size_t(n)] < 0) {
        surface_row[size_t(n)] = Index(surface_nodes.size());
        surface_nodes.push_back(n);
      }
  }
  require(std::find(face_at.begin(), face_at.end(), -1) == face_at.end(),
          "elastic pin in bore '{}': the pin's surface faces do not tile the cylinder", name);

  // Q: the bore's corner functions integrated against the pin's surface
  // shape functions at the same angle and height, on the bore's faces.
  const Index m = bore.size();
  std::vector<Index> corner_column(size_t(part_mesh.node_count()), -1);
  for (Index k = 0; k < m; ++k) corner_column[size_t(bore.corner_nodes()[size_t(k)])] = k;
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(Index(surface_nodes.size()), m);
  Eigen::VectorXd N, L, Np;
  Eigen::MatrixXd dN, dL, dNp;
  Eigen::Matrix<double, 8, 3> pin_face;
  for (const auto& block : part_mesh.face_set(name)) {
    const int n = nodes_per_face(block.type), corners = face_facts(block.type).corners;
    const FaceType linear = corners == 3 ? FaceType::Tri3 : FaceType::Quad4;
    const auto rule = subdivided_rule(block.type, options.quadrature_subdivisions);
    Eigen::MatrixXd X(n, 3);
    for (Index f = 0; f < block.size(); ++f) {
      const auto nodes = block.face(f);
      for (int k = 0; k < n; ++k) X.row(k) = part_mesh.nodes.row(nodes[size_t(k)]);
      for (const auto& qp : rule) {
        shape_functions(block.type, qp.xi, N, dN);
        shape_functions(linear, qp.xi, L, dL);
        const Eigen::Vector3d x = X.transpose() * N;
        const Eigen::Vector3d t1 = X.transpose() * dN.col(0), t2 = X.transpose() * dN.col(1);
        const double dA = qp.weight * t1.cross(t2).norm();
        const Eigen::Vector3d d = x - c;
        const double theta = std::atan2(d.dot(e2), d.dot(e1)), z = d.dot(a) - z0;
        const int j = int(std::floor(std::remainder(theta + kPi / 4, 2 * kPi) / dtheta + circumferential_)) %
                      circumferential_;
        const int l = std::clamp(int(std::floor(z / dz)), 0, axial - 1);
        const auto pin_nodes = surface.face(face_at[size_t(j * axial + l)]);
        for (int k = 0; k < 8; ++k) pin_face.row(k) = pin.mesh.nodes.row(pin_nodes[size_t(k)]);
        // The pin face's point at (theta, z): Newton on its reference
        // coordinates, from the centre (2 to 3 steps: the face is a
        // quadratic image of a (theta, z) rectangle).
        Eigen::Vector3d s = Eigen::Vector3d::Zero();
        for (int step = 0; step < 20; ++step) {
          shape_functions(FaceType::Quad8, s, Np, dNp);
          const Eigen::Vector3d p = pin_face.transpose() * Np;
          const Eigen::Matrix<double, 3, 2> dp = pin_face.transpose() * dNp;
          const double r2 = p.head<2>().squaredNorm();
          const Eigen::Vector2d residual(std::remainder(std::atan2(p.y(), p.x()) - theta, 2 * kPi), p.z() - z);
          Eigen::Matrix2d J;
          J.row(0) = (p.x() * dp.row(1) - p.y() * dp.row(0)) / r2;
          J.row(1) = dp.row(2);
          const Eigen::Vector2d step_s = -J.partialPivLu().solve(residual);
          s.head<2>() += step_s;
          if (step_s.norm() < 1e-13) break;
        }
        require(s.head<2>().cwiseAbs().maxCoeff() < 1 + 1e-6,
                "elastic pin in bore '{}': a point of the bore at {:.6g} rad, z = {:.6g} m is not on the pin's "
                "face there (reference coordinates {}, {})",
                name, theta, z, s.x(), s.y());
        shape_functions(FaceType::Quad8, s, Np, dNp);
        for (int k = 0; k < 8; ++k)
          for (int cc = 0; cc < corners; ++cc)
            Q(surface_row[size_t(pin_nodes[size_t(k)])], corner_column[size_t(nodes[size_t(cc)])]) +=
                Np[k] * L[cc] * dA;
      }
    }
  }
  // Q's quadrature error: against the pin's own area weights, scaled from
  // the pin's radius to the bore's (the same angle and height band).
  {
    Eigen::VectorXd weights = Eigen::VectorXd::Zero(Q.rows());
    Eigen::VectorXd Nf;
    Eigen::MatrixXd dNf;
    Eigen::MatrixXd Xp(8, 3);
    for (Index f = 0; f < surface.size(); ++f) {
      for (int k = 0; k < 8; ++k) Xp.row(k) = pin.mesh.nodes.row(surface.face(f)[size_t(k)]);
      for (const auto& qp : quadrature(FaceType::Quad8)) {
        shape_functions(FaceType::Quad8, qp.xi, Nf, dNf);
        const Eigen::Vector3d t1 = Xp.transpose() * dNf.col(0), t2 = Xp.transpose() * dNf.col(1);
        const double dA = qp.weight * t1.cross(t2).norm();
        for (int k = 0; k < 8; ++k) weights[surface_row[size_t(surface.face(f)[size_t(k)])]] += Nf[k] * dA;
      }
    }
    mapping_error_ = (Q.rowwise().sum() - weights * (bore.radius_m() / radius_)).cwiseAbs().sum() /
                     bore.corner_area_m2().sum();
  }

  // F = N Q: the pin surface's nodal forces of unit corner pressures
  // pushing outwards (the pin gets -F p).
  const Index dofs = 3 * nodes_;
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(dofs, m);
  for (size_t r = 0; r < surface_nodes.size(); ++r) {
    const Index node = surface_nodes[r];
    const Eigen::Vector3d normal(pin.mesh.nodes(node, 0), pin.mesh.nodes(node, 1), 0.0);
    for (int i = 0; i < 3; ++i) F.row(3 * node + i) = normal.normalized()[i] * Q.row(Index(r));
  }
  // The rigid modes R and their body forces W = M R (uniform density).
  Eigen::MatrixXd R(dofs, 6);
  std::vector<LoadCase> rigid(6);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d unit = Eigen::Vector3d::Unit(i);
    R.col(i) = rigid_body_field(pin.mesh, unit, Eigen::Vector3d::Zero());
    R.col(3 + i) = rigid_body_field(pin.mesh, Eigen::Vector3d::Zero(), unit);
    rigid[size_t(i)].acceleration = [unit](const Eigen::Vector3d&) { return unit; };
    rigid[size_t(3 + i)].acceleration = [unit](const Eigen::Vector3d& x) { return Eigen::Vector3d(unit.cross(x)); };
  }
  const Eigen::MatrixXd W = assemble_external_forces(pin.mesh, element_materials(pin), rigid);
  const Eigen::LDLT<Eigen::MatrixXd> RtW((R.transpose() * W).eval());

  const Log quiet = Log::quiet();
  LinearStaticAnalysis analysis(pin, quiet);
  compliance_.resize(m, m);
  const Index block = 64;
  for (Index first = 0; first < m; first += block) {
    const Index count = std::min(block, m - first);
    // Pi (-F): the pressure on the pin balanced by its rigid accelerations.
    Eigen::MatrixXd load = -F.middleCols(first, count);
    load -= W * RtW.solve(R.transpose() * load);
    const std::vector<DisplacementField> u = analysis.solve_forces(load);
    Eigen::MatrixXd U(dofs, count);
    for (Index k = 0; k < count; ++k) U.col(k) = Eigen::Map<const Eigen::VectorXd>(u[size_t(k)].data(), dofs);
    U -= R * RtW.solve(W.transpose() * U);  // Pi^T: the deformation without rigid motion
    compliance_.middleCols(first, count).noalias() = -F.transpose() * U;
  }
  // Exactly symmetric: evaluated apart (A = (A + A^T) / 2 in place would read entries it has written).
  compliance_ = (0.5 * (compliance_ + compliance_.transpose())).eval();
  seconds_ = clock.seconds();
  log.detail("  elastic pin in bore '{}': radius {:.4g} mm, span {:.4g} mm, {} nodes ({} around); {} corner "
             "pressures in {:.2f} s; mortar map's area error {:.2e}",
             name, 1e3 * radius_, 1e3 * span_, nodes_, circumferential_, m, seconds_, mapping_error_);
}

}  // namespace kinetofem::fem
