// `kinetofem verify`: the FEM core and the load transfer against exact
// solutions — patch tests of the four element types on distorted meshes
// built here, a bar in uniaxial tension and an accelerated link (meshed by
// Gmsh from meshes/geometry/verification/), the Lamé thick cylinder on a
// structured HEX20 quarter annulus built here, and CHOLMOD against Eigen's
// SimplicialLDLT.
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/SparseCholesky>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::app {

namespace {

namespace fem = kinetofem::fem;
using fem::ElementType;
using fem::Index;
using Key = std::array<int, 3>;  // node position on the doubled grid
constexpr double kPi = std::numbers::pi;

std::filesystem::path verification_geometry(const std::string& name) {
  return std::filesystem::path(KINETOFEM_GEOMETRY_DIR) / "verification" / name;
}

// A structured mesh of n[0] x n[1] x n[2] cells in grid coordinates
// (i, j, k) in [0, n]. Corner nodes sit at integer grid points, mid-edge
// nodes at the midpoint (in grid coordinates) of their edge; a node is keyed
// by twice its grid coordinates, so a key component 0 or 2 n marks the
// boundary. Hexahedra in Gmsh order; tetrahedra by the Kuhn split of each
// cell into six along its diagonal 0-6 (conforming between cells, all with
// positive volume). `position` maps grid coordinates to space (m);
// straight_edges puts mid-edge nodes at the middle of their chord instead.
class GridMesh {
 public:
  using Position = std::function<Eigen::Vector3d(const Eigen::Vector3d& grid)>;

  GridMesh(Key n, ElementType type, Position position, bool straight_edges)
      : n_(n), type_(type), position_(std::move(position)), straight_(straight_edges) {
    static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    static constexpr int kHexEdges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                             {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
    static constexpr int kKuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                        {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
    static constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    const bool quadratic = type == ElementType::Tet10 || type == ElementType::Hex20;
    const bool hex = type == ElementType::Hex8 || type == ElementType::Hex20;
    fem::ElementBlock block;
    block.type = type;
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) {
          Key corner[8];
          for (int c = 0; c < 8; ++c)
            corner[c] = {i + kCorner[c][0], j + kCorner[c][1], k + kCorner[c][2]};
          auto add = [&](const int* local, int n_corners, const int (*edges)[2], int n_edges) {
            for (int c = 0; c < n_corners; ++c) block.connectivity.push_back(corner_node(corner[local[c]]));
            if (quadratic)
              for (int e = 0; e < n_edges; ++e)
                block.connectivity.push_back(mid_node(corner[local[edges[e][0]]], corner[local[edges[e][1]]]));
          };
          if (hex) {
            static constexpr int kAll[8] = {0, 1, 2, 3, 4, 5, 6, 7};
            add(kAll, 8, kHexEdges, 12);
          } else {
            for (const auto& tet : kKuhn) add(tet, 4, kTetEdges, 6);
          }
        }
    mesh_.nodes.resize(Index(positions_.size()), 3);
    for (std::size_t a = 0; a < positions_.size(); ++a) mesh_.nodes.row(Index(a)) = positions_[a].transpose();
    mesh_.blocks.push_back(std::move(block));
  }

  const fem::Mesh& mesh() const { return mesh_; }
  fem::Mesh& mesh() { return mesh_; }
  const Key& key(Index node) const { return keys_[std::size_t(node)]; }
  Key doubled_extent() const { return {2 * n_[0], 2 * n_[1], 2 * n_[2]}; }

  // Nodes whose key satisfies `on`.
  std::vector<Index> nodes_where(const std::function<bool(const Key&)>& on) const {
    std::vector<Index> out;
    for (std::size_t a = 0; a < keys_.size(); ++a)
      if (on(keys_[a])) out.push_back(Index(a));
    return out;
  }
  // Element faces all of whose nodes satisfy `on` (outward normals).
  std::vector<fem::FaceBlock> faces_where(const std::function<bool(const Key&)>& on) const {
    fem::FaceBlock faces;
    faces.type = fem::face_type_of(type_);
    const auto& block = mesh_.blocks.front();
    for (Index e = 0; e < block.size(); ++e)
      for (int f = 0; f < fem::faces_per_element(type_); ++f) {
        const auto local = fem::element_face_nodes(type_, f);
        bool all = true;
        for (int l : local) all = all && on(key(block.element(e)[std::size_t(l)]));
        if (!all) continue;
        for (int l : local) faces.connectivity.push_back(block.element(e)[std::size_t(l)]);
      }
    return {faces};
  }

 private:
  Index node(const Key& key, const Eigen::Vector3d& x) {
    auto [it, inserted] = index_.try_emplace(key, Index(positions_.size()));
    if (inserted) {
      positions_.push_back(x);
      keys_.push_back(key);
    }
    return it->second;
  }
  Index corner_node(const Key& g) {
    return node({2 * g[0], 2 * g[1], 2 * g[2]}, position_(Eigen::Vector3d(g[0], g[1], g[2])));
  }
  Index mid_node(const Key& a, const Key& b) {
    const Eigen::Vector3d ga(a[0], a[1], a[2]), gb(b[0], b[1], b[2]);
    const Eigen::Vector3d x = straight_ ? Eigen::Vector3d(0.5 * (position_(ga) + position_(gb)))
                                        : position_(0.5 * (ga + gb));
    return node({a[0] + b[0], a[1] + b[1], a[2] + b[2]}, x);
  }

  Key n_;
  ElementType type_;
  Position position_;
  bool straight_;
  std::map<Key, Index> index_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<Key> keys_;
  fem::Mesh mesh_;
};

bool on_boundary(const Key& k, const Key& extent) {
  for (int d = 0; d < 3; ++d)
    if (k[d] == 0 || k[d] == extent[d]) return true;
  return false;
}

// Voigt strain (xx, yy, zz, xy, yz, zx; engineering shear) of u = A x + b.
fem::Vector6d voigt_strain(const Eigen::Matrix3d& A) {
  fem::Vector6d e;
  e << A(0, 0), A(1, 1), A(2, 2), A(0, 1) + A(1, 0), A(1, 2) + A(2, 1), A(2, 0) + A(0, 2);
  return e;
}

std::vector<CheckRow> patch_test(ElementType type) {
  // Box 1.0 x 0.8 x 0.6 m, 3 x 3 x 3 cells, every corner node moved at random
  // by up to 12 % of a cell in each direction (seeded: the same mesh on every
  // run), straight edges.
  const Eigen::Vector3d size(1.0, 0.8, 0.6);
  const Key n{3, 3, 3};
  auto position = [&](const Eigen::Vector3d& g) {
    std::mt19937 rng(std::uint32_t(1000003 * g[0] + 1009 * g[1] + g[2] + 7));
    std::uniform_real_distribution<double> shift(-0.12, 0.12);
    Eigen::Vector3d x;
    for (int d = 0; d < 3; ++d) x[d] = (g[d] + shift(rng)) * size[d] / n[d];
    return x;
  };
  const GridMesh grid(n, type, position, true);
  fem::FeModel model;
  model.mesh = grid.mesh();
  fem::check_element_jacobians(model.mesh);
  Eigen::Matrix3d A;
  A << 1.0e-3, -0.4e-3, 0.7e-3, 0.3e-3, -0.6e-3, 0.2e-3, -0.5e-3, 0.9e-3, 0.8e-3;
  const Eigen::Vector3d b(2e-4, -1e-4, 3e-4);
  auto exact = [&](Index node) -> Eigen::Vector3d { return A * model.mesh.nodes.row(node).transpose() + b; };
  const Key extent = grid.doubled_extent();
  for (Index node : grid.nodes_where([&](const Key& k) { return on_boundary(k, extent); }))
    model.supports.push_back({"boundary", {node}, {true, true, true}, exact(node)});
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const fem::DisplacementField u = analysis.solve({fem::LoadCase{}}).at(0);
  double u_error = 0.0, scale = 0.0;
  int interior = 0;
  for (Index node = 0; node < model.mesh.node_count(); ++node) {
    scale = std::max(scale, exact(node).norm());
    if (on_boundary(grid.key(node), extent)) continue;
    ++interior;
    u_error = std::max(u_error, (u.row(node).transpose() - exact(node)).norm());
  }
  require(interior > 0, "patch test mesh has no interior node");
  const fem::Vector6d sigma = model.material.elasticity_matrix() * voigt_strain(A);
  const auto gauss = fem::gauss_point_stress(model.mesh, model.material, u);
  double s_error = 0.0;
  for (Index p = 0; p < gauss.stress_pa.rows(); ++p)
    s_error = std::max(s_error, (gauss.stress_pa.row(p).transpose() - sigma).norm());
  const std::string name = fem::name_of(type);
  // A linear field lies in every element's span: reproduced to round-off
  // (systems of condition ~1e4-1e6): 1e-10 relative.
  const char* why = "exact in the element's span: round-off, 1e-10";
  return {compare_absolute("patch test " + name + ", distorted, interior u", "u = A x + b", "1", 0.0,
                           u_error / scale, 1e-10, why),
          compare_absolute("patch test " + name + ", distorted, Gauss-point stress", "sigma = D eps(A)", "1", 0.0,
                           s_error / sigma.norm(), 1e-10, why)};
}

std::vector<CheckRow> patch_tests(const CheckContext&) {
  std::vector<CheckRow> rows;
  for (ElementType type : {ElementType::Tet4, ElementType::Tet10, ElementType::Hex8, ElementType::Hex20})
    for (auto& row : patch_test(type)) rows.push_back(std::move(row));
  return rows;
}

std::vector<CheckRow> bar_tension(const CheckContext&) {
  // tests/data/cases/bar_tension: bar 100 x 20 x 20 mm, x0 face held in x,
  // origin in x, y, z, corner (0, 20, 0) mm in z (statically determinate),
  // 10 kN on the x1 face. Exact: sigma_xx = F/A = 25 MPa,
  // u = sigma/E (x, -nu y, -nu z), linear: TET10 reproduces it exactly.
  meshes::MeshOptions options;
  options.element_size_m = 0.01;
  options.order = 2;
  fem::FeModel model;
  model.mesh = meshes::mesh_geometry(verification_geometry("bar.geo"), options);
  model.material = fem::IsotropicMaterial{"steel", 200e9, 0.3, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  model.supports = {{"x0", model.mesh.node_set("x0"), {true, false, false}, zero},
                    {"origin", model.mesh.node_set("origin"), {true, true, true}, zero},
                    {"corner_y", model.mesh.node_set("corner_y"), {false, false, true}, zero}};
  const double force = 10e3, area = 0.02 * 0.02, length = 0.1, E = 200e9, nu = 0.3;
  const double sigma = force / area;
  fem::LoadCase load;
  load.tractions = {{"x1", Eigen::Vector3d(sigma, 0, 0)}};
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const fem::DisplacementField u = analysis.solve({load}).at(0);
  double u_error = 0.0, u_end = 0.0;
  for (Index n = 0; n < model.mesh.node_count(); ++n) {
    const Eigen::Vector3d x = model.mesh.nodes.row(n).transpose();
    const Eigen::Vector3d exact = sigma / E * Eigen::Vector3d(x[0], -nu * x[1], -nu * x[2]);
    u_error = std::max(u_error, (u.row(n).transpose() - exact).norm());
    u_end = std::max(u_end, u(n, 0));
  }
  const auto gauss = fem::gauss_point_stress(model.mesh, model.material, u);
  double s_max = 0.0;
  for (Index p = 0; p < gauss.stress_pa.rows(); ++p) s_max = std::max(s_max, gauss.stress_pa(p, 0));
  const double u_exact = force * length / (E * area);
  // Linear exact field, straight-sided TET10: round-off; 1e-9 relative leaves
  // room for the solver's residual check (1e-8 bound, ~1e-14 measured).
  const char* why = "linear field, straight TET10: round-off, 1e-9";
  return {compare_relative("bar in tension: end displacement u_x(L)", "u = F L / (E A)", "mm", u_exact * 1e3,
                           u_end * 1e3, 1e-9, why),
          compare_absolute("bar in tension: max nodal |u - u_exact| / u(L)", "u = sigma/E (x, -nu y, -nu z)", "1", 0.0,
                           u_error / u_exact, 1e-9, why),
          compare_relative("bar in tension: max Gauss-point sigma_xx", "sigma = F / A", "MPa", sigma * 1e-6,
                           s_max * 1e-6, 1e-9, why)};
}

// Quarter annulus a <= r <= b, 0 <= theta <= 90 deg, 0 <= z <= 20 mm,
// HEX20 with mid-edge nodes on the arcs; radial element sizes grow
// geometrically by 2x from bore to rim (the stress gradient is at the bore).
struct LameModel {
  fem::FeModel model;
  std::vector<Index> bore;
  fem::LoadCase load;
};

LameModel lame_model(double a, double b, double p) {
  const int nr = 6, nt = 12;
  std::vector<double> radius{a};
  const double q = std::pow(2.0, 1.0 / (nr - 1));
  double h = (b - a) * (q - 1) / (std::pow(q, nr) - 1);
  for (int i = 0; i < nr; ++i, h *= q) radius.push_back(radius.back() + h);
  radius.back() = b;
  auto position = [&](const Eigen::Vector3d& g) {
    const int i = std::min(int(std::floor(g[0])), nr - 1);
    const double r = radius[std::size_t(i)] + (g[0] - i) * (radius[std::size_t(i) + 1] - radius[std::size_t(i)]);
    const double t = 0.5 * kPi * g[1] / nt;
    return Eigen::Vector3d(r * std::cos(t), r * std::sin(t), 0.02 * g[2]);
  };
  const GridMesh grid({nr, nt, 1}, ElementType::Hex20, position, false);
  LameModel m;
  m.model.mesh = grid.mesh();
  const Key ext = grid.doubled_extent();
  m.bore = grid.nodes_where([](const Key& k) { return k[0] == 0; });
  m.model.mesh.face_sets["bore"] = grid.faces_where([](const Key& k) { return k[0] == 0; });
  m.model.mesh.node_sets["bore"] = m.bore;
  m.model.material = fem::IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  // Symmetry u_y = 0 on theta = 0, u_x = 0 on theta = 90 deg; plane strain u_z = 0.
  m.model.supports = {
      {"theta = 0", grid.nodes_where([](const Key& k) { return k[1] == 0; }), {false, true, false}, zero},
      {"theta = 90", grid.nodes_where([&](const Key& k) { return k[1] == ext[1]; }), {true, false, false}, zero},
      {"z ends", grid.nodes_where([&](const Key& k) { return k[2] == 0 || k[2] == ext[2]; }), {false, false, true},
       zero}};
  m.model.mesh.validate();
  m.load.pressures = {{"bore", p}};
  return m;
}

std::vector<CheckRow> lame_cylinder(const CheckContext&) {
  const double a = 0.1, b = 0.2, p = 100e6;
  const LameModel m = lame_model(a, b, p);
  const double E = m.model.material.youngs_modulus_pa, nu = m.model.material.poisson_ratio;
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(m.model, log);
  const fem::DisplacementField u = analysis.solve({m.load}).at(0);
  const fem::NodalStress stress = fem::recover_nodal_stress(m.model.mesh, m.model.material, u);
  // Lamé, plane strain: u_r(a) = (1 + nu) p a ((1 - 2 nu) a^2 + b^2) / (E (b^2 - a^2)),
  // sigma_tt(a) = p (a^2 + b^2) / (b^2 - a^2).
  const double u_bore = (1 + nu) * p * a * ((1 - 2 * nu) * a * a + b * b) / (E * (b * b - a * a));
  const double hoop_bore = p * (a * a + b * b) / (b * b - a * a);
  double worst_u = u_bore, worst_hoop = hoop_bore;  // the bore value farthest from the exact one
  for (Index n : m.bore) {
    const Eigen::Vector3d x = m.model.mesh.nodes.row(n).transpose();
    const Eigen::Vector3d e_r = Eigen::Vector3d(x[0], x[1], 0.0).normalized();
    const Eigen::Vector3d e_t(-e_r[1], e_r[0], 0.0);
    const double u_r = u.row(n).dot(e_r);
    const auto s = stress.stress_pa.row(n);
    Eigen::Matrix3d sigma;
    sigma << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const double hoop = e_t.dot(sigma * e_t);
    if (std::abs(u_r - u_bore) > std::abs(worst_u - u_bore)) worst_u = u_r;
    if (std::abs(hoop - hoop_bore) > std::abs(worst_hoop - hoop_bore)) worst_hoop = hoop;
  }
  // 1 % at every bore node (discretisation of 6 x 12 HEX20: ~1e-5 and ~6e-3).
  const char* why = "discretisation, 6 x 12 HEX20: 1 %, worst bore node";
  return {compare_relative("Lamé cylinder, p = 100 MPa: u_r at the bore", "Lamé, plane strain", "mm", u_bore * 1e3,
                           worst_u * 1e3, 0.01, why),
          compare_relative("Lamé cylinder: hoop stress at the bore (nodal)", "Lamé, sigma_tt(a)", "MPa",
                           hoop_bore * 1e-6, worst_hoop * 1e-6, 0.01, why)};
}

std::vector<CheckRow> cholmod_vs_ldlt(const CheckContext&) {
  const LameModel m = lame_model(0.1, 0.2, 100e6);
  const fem::DofMap dofs(m.model.mesh.node_count(), m.model.supports);
  const fem::AssembledStiffness K = fem::assemble_stiffness(m.model.mesh, m.model.material, dofs);
  const Eigen::MatrixXd f = fem::assemble_external_forces(m.model.mesh, m.model.material, {m.load});
  Eigen::VectorXd rhs(dofs.free_count());
  for (Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) >= 0) rhs[dofs.equation(d)] = f(d, 0);
  rhs -= K.prescribed_coupling_force;
  fem::CholmodSolver cholmod;
  cholmod.analyze(K.free_free);
  cholmod.factorize(K.free_free);
  const Eigen::VectorXd x_cholmod = cholmod.solve(rhs);
  Eigen::SimplicialLDLT<fem::SymmetricUpperMatrix, Eigen::Upper> ldlt(K.free_free);
  require(ldlt.info() == Eigen::Success, "Eigen SimplicialLDLT failed on the Lamé stiffness");
  const Eigen::VectorXd x_eigen = ldlt.solve(rhs);
  // Two direct factorizations of the same SPD system: round-off, 1e-10.
  return {compare_absolute("CHOLMOD vs Eigen SimplicialLDLT, Lamé system", "same K u = f, independent solver", "1",
                           0.0, (x_cholmod - x_eigen).norm() / x_eigen.norm(), 1e-10, "round-off, 1e-10 relative")};
}

std::vector<CheckRow> accelerated_link(const CheckContext&) {
  // tests/verification/loads: the link (640 x 40 x 20 mm, pins 600 mm apart)
  // translating with a = 100 m/s^2 along y, its d'Alembert body force balanced
  // by the two pin reactions m a / 2 (distributing couplings on the bores), is
  // a simply supported beam under q = rho A a with overhangs e = 20 mm:
  //   M_mid = R L / 2 - q (L/2 + e)^2 / 2, R = q (L + 2e) / 2, sigma = M_mid (h/2) / I.
  meshes::MeshOptions options;
  options.element_size_m = 0.006;
  options.order = 2;
  fem::FeModel model;
  model.mesh = meshes::mesh_geometry(verification_geometry("beam_link.geo"), options);
  const double a = 100.0, rho = model.material.density_kg_m3;
  const double L = 0.6, e = 0.02, h = 0.04, t = 0.02;
  const double q = rho * h * t * a;
  const double M_mid = 0.5 * q * (L + 2 * e) * L / 2 - q * (L / 2 + e) * (L / 2 + e) / 2;
  const double sigma_beam = M_mid * (h / 2) / (t * h * h * h / 12.0);
  std::vector<Index> all(std::size_t(model.mesh.node_count()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = Index(i);
  model.supports = fem::three_two_one_support(model.mesh, all);
  const fem::RigidBodyMotionLoads inertia(model.mesh, model.material);
  Eigen::VectorXd f = inertia.forces(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, a, 0), Eigen::Vector3d::Zero(),
                                     Eigen::Vector3d::Zero());
  const Eigen::Vector3d reaction(0, 0.5 * inertia.mass_kg() * a, 0);
  fem::DistributingCoupling(model.mesh, "bore_1").add(reaction, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), f);
  fem::DistributingCoupling(model.mesh, "bore_2").add(reaction, Eigen::Vector3d::Zero(), Eigen::Vector3d(L, 0, 0), f);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve_forces(f);
  const fem::NodalStress s = fem::recover_nodal_stress(model.mesh, model.material, u.at(0));
  double top = 0, bottom = 0;
  int n_top = 0, n_bottom = 0;
  for (Index i = 0; i < model.mesh.node_count(); ++i) {
    const auto x = model.mesh.nodes.row(i);
    if (std::abs(x[0] - 0.5 * L) > 0.004) continue;
    if (std::abs(x[1] - 0.5 * h) < 1e-9) top += s.stress_pa(i, 0), ++n_top;
    if (std::abs(x[1] + 0.5 * h) < 1e-9) bottom += s.stress_pa(i, 0), ++n_bottom;
  }
  require(n_top > 0 && n_bottom > 0, "no mid-span nodes on the link's extreme fibres");
  // The body force points along -y, the pins push +y: the +y fibre is in
  // compression. Beam theory vs elasticity at L/h = 15: ~0.1 %; 2 % (issue 4).
  const char* why = "beam theory at L/h = 15: 2 % (issue 4)";
  return {compare_relative("accelerated link: mid-span sigma_xx, +y fibre", "simply supported beam, M c / I", "MPa",
                           -sigma_beam * 1e-6, top / n_top * 1e-6, 0.02, why),
          compare_relative("accelerated link: mid-span sigma_xx, -y fibre", "simply supported beam, M c / I", "MPa",
                           sigma_beam * 1e-6, bottom / n_bottom * 1e-6, 0.02, why)};
}

}  // namespace

std::vector<Check> fem_checks() {
  return {
      {"fem.patch_tests", "FEM", true, patch_tests},
      {"fem.bar_tension", "FEM", true, bar_tension},
      {"fem.lame_cylinder", "FEM", true, lame_cylinder},
      {"fem.cholmod_vs_ldlt", "FEM", true, cholmod_vs_ldlt},
      {"loads.accelerated_link", "load transfer", true, accelerated_link},
  };
}

}  // namespace kinetofem::app
