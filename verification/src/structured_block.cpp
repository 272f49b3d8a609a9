#include "kinetofem/verification/structured_block.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "kinetofem/core/error.hpp"

namespace kinetofem::verification {
namespace {

using fem::ElementType;
using fem::FaceType;
using fem::Index;
using Lattice = std::array<int, 3>;

bool is_quadratic(ElementType type) {
  return fem::element_facts(type).nodes > fem::element_facts(type).corners;
}

// Parameter values of the lattice points along one direction: cell ends by a
// geometric series of sizes, mid points (quadratic lattices) the mean of the
// ends.
std::vector<double> lattice_parameters(int cells, double ratio, int resolution) {
  std::vector<double> ends(size_t(cells) + 1, 0.0);
  const double q = cells > 1 ? std::pow(ratio, 1.0 / double(cells - 1)) : 1.0;
  double size = 1.0;
  for (int k = 0; k < cells; ++k) {
    ends[size_t(k) + 1] = ends[size_t(k)] + size;
    size *= q;
  }
  for (double& s : ends) s /= ends.back();
  ends.back() = 1.0;
  if (resolution == 1) return ends;
  std::vector<double> points(size_t(2 * cells) + 1);
  for (int k = 0; k <= cells; ++k) points[size_t(2 * k)] = ends[size_t(k)];
  for (int k = 0; k < cells; ++k)
    points[size_t(2 * k) + 1] = 0.5 * (ends[size_t(k)] + ends[size_t(k) + 1]);
  return points;
}

// Cell corners in Gmsh HEX8 order, as (0/1) offsets along u, v, w.
constexpr int hex_corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
constexpr int hex_edge[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                 {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
constexpr int tet_edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};

Lattice midpoint(const Lattice& a, const Lattice& b) {
  return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
}

// The six Kuhn tetrahedra of the unit cell, corners as (0/1) offsets, each
// ordered with a positive volume in parameter space.
std::vector<std::array<Lattice, 4>> kuhn_tetrahedra() {
  std::vector<std::array<Lattice, 4>> tets;
  std::array<int, 3> perm = {0, 1, 2};
  do {
    Lattice v1 = {0, 0, 0};
    v1[size_t(perm[0])] = 1;
    Lattice v2 = v1;
    v2[size_t(perm[1])] = 1;
    std::array<Lattice, 4> tet = {Lattice{0, 0, 0}, v1, v2, Lattice{1, 1, 1}};
    Eigen::Matrix3d edges;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) edges(c, k) = tet[size_t(k) + 1][size_t(c)];
    if (edges.determinant() < 0) std::swap(tet[1], tet[2]);
    tets.push_back(tet);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return tets;
}

}  // namespace

fem::Mesh structured_block_mesh(const StructuredBlock& block) {
  require(bool(block.mapping), "structured block: no mapping given");
  for (int d = 0; d < 3; ++d) {
    require(block.divisions[size_t(d)] >= 1, "structured block: divisions[{}] = {} must be >= 1",
            d, block.divisions[size_t(d)]);
    require(block.grading_ratio[size_t(d)] > 0 && std::isfinite(block.grading_ratio[size_t(d)]),
            "structured block: grading_ratio[{}] = {} must be positive", d,
            block.grading_ratio[size_t(d)]);
  }
  require(block.random_perturbation >= 0 && block.random_perturbation < 0.5,
          "structured block: random_perturbation = {} outside [0, 0.5)",
          block.random_perturbation);
  require(block.mid_node_perturbation >= 0 && block.mid_node_perturbation < 0.5,
          "structured block: mid_node_perturbation = {} outside [0, 0.5)",
          block.mid_node_perturbation);

  const int r = is_quadratic(block.type) ? 2 : 1;
  std::array<std::vector<double>, 3> param;
  Lattice size;
  for (size_t d = 0; d < 3; ++d) {
    param[d] = lattice_parameters(block.divisions[d], block.grading_ratio[d], r);
    size[d] = int(param[d].size());
  }
  auto lattice_index = [&](const Lattice& p) {
    return (Index(p[2]) * size[1] + p[1]) * size[0] + p[0];
  };
  const Index lattice_count = Index(size[0]) * size[1] * size[2];

  // Connectivity in lattice indices first; nodes are numbered afterwards so
  // that only used lattice points become nodes.
  fem::Mesh mesh;
  fem::ElementBlock elements;
  elements.type = block.type;
  const auto tets = kuhn_tetrahedra();
  const bool hex = fem::corner_nodes(block.type) == 8;
  for (int k = 0; k < block.divisions[2]; ++k)
    for (int j = 0; j < block.divisions[1]; ++j)
      for (int i = 0; i < block.divisions[0]; ++i) {
        const Lattice base = {r * i, r * j, r * k};
        auto at = [&](const Lattice& offset) {
          return Lattice{base[0] + r * offset[0], base[1] + r * offset[1], base[2] + r * offset[2]};
        };
        if (hex) {
          std::array<Lattice, 8> c;
          for (int n = 0; n < 8; ++n)
            c[size_t(n)] = at({hex_corner[n][0], hex_corner[n][1], hex_corner[n][2]});
          for (const auto& p : c) elements.connectivity.push_back(lattice_index(p));
          if (r == 2)
            for (const auto& e : hex_edge)
              elements.connectivity.push_back(
                  lattice_index(midpoint(c[size_t(e[0])], c[size_t(e[1])])));
        } else {
          for (const auto& tet : tets) {
            std::array<Lattice, 4> c;
            for (size_t n = 0; n < 4; ++n) c[n] = at(tet[n]);
            for (const auto& p : c) elements.connectivity.push_back(lattice_index(p));
            if (r == 2)
              for (const auto& e : tet_edge)
                elements.connectivity.push_back(
                    lattice_index(midpoint(c[size_t(e[0])], c[size_t(e[1])])));
          }
        }
      }

  // Boundary faces on the six parameter faces. For the face normal to
  // direction d, (d1, d2) = (d+1, d+2) mod 3 span it with e_d1 x e_d2 = e_d;
  // corners counter-clockwise in (d1, d2) give +e_d, reversed give -e_d.
  const fem::FaceType face_type = fem::face_type_of(block.type);
  std::array<fem::FaceBlock, 6> faces;
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      auto& face_block = faces[size_t(2 * d + side)];
      face_block.type = face_type;
      const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
      for (int b = 0; b < block.divisions[size_t(d2)]; ++b)
        for (int a = 0; a < block.divisions[size_t(d1)]; ++a) {
          auto corner = [&](int da, int db) {
            Lattice p{};
            p[size_t(d)] = side * (size[size_t(d)] - 1);
            p[size_t(d1)] = r * (a + da);
            p[size_t(d2)] = r * (b + db);
            return p;
          };
          std::vector<std::vector<Lattice>> polygons;
          if (hex)
            polygons.push_back({corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)});
          else  // the Kuhn diagonal of a face joins its (0,0) and (1,1) corners
            polygons = {{corner(0, 0), corner(1, 0), corner(1, 1)},
                        {corner(0, 0), corner(1, 1), corner(0, 1)}};
          for (auto& poly : polygons) {
            if (side == 0) std::reverse(poly.begin() + 1, poly.end());
            for (const auto& p : poly) face_block.connectivity.push_back(lattice_index(p));
            if (r == 2)
              for (size_t n = 0; n < poly.size(); ++n)
                face_block.connectivity.push_back(
                    lattice_index(midpoint(poly[n], poly[(n + 1) % poly.size()])));
          }
        }
    }

  // Number the used lattice points.
  std::vector<Index> node_of(size_t(lattice_count), -1);
  for (Index p : elements.connectivity) node_of[size_t(p)] = 0;
  Index node_count = 0;
  for (auto& n : node_of)
    if (n == 0) n = node_count++;

  // Random shifts in parameter space. A point moves only along the
  // directions in which it is off the boundary, so boundary nodes slide
  // within their faces and edges. Cell corners move by up to f times the
  // local cell size. The other points of a quadratic lattice are midpoints of
  // element edges (cell edges, and the Kuhn diagonals from a face's or cell's
  // lowest corner to its highest): they take the mean shift of the edge's two
  // ends, so edges stay straight, plus an own shift of up to g times half the
  // cell size, which curves them. Every lattice point draws, used or not, so
  // the sequence does not depend on the element type's node subset.
  std::vector<Eigen::Vector3d> shift(size_t(lattice_count), Eigen::Vector3d::Zero());
  if (block.random_perturbation > 0 || block.mid_node_perturbation > 0) {
    std::mt19937_64 random(block.seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int k = 0; k < size[2]; ++k)
      for (int j = 0; j < size[1]; ++j)
        for (int i = 0; i < size[0]; ++i) {
          const Lattice p = {i, j, k};
          const bool corner = p[0] % r == 0 && p[1] % r == 0 && p[2] % r == 0;
          auto& s = shift[size_t(lattice_index(p))];
          for (size_t d = 0; d < 3; ++d) {
            const double draw = uniform(random);
            if (p[d] == 0 || p[d] == size[d] - 1) continue;
            const int step = (p[d] % r == 0) ? r : 1;
            const size_t at = size_t(p[d]);
            const double spacing = std::min(param[d][at] - param[d][at - size_t(step)],
                                            param[d][at + size_t(step)] - param[d][at]);
            s[Eigen::Index(d)] =
                (corner ? block.random_perturbation : block.mid_node_perturbation) * spacing * draw;
          }
        }
    if (r == 2) {
      const std::vector<Eigen::Vector3d> own = shift;
      for (int k = 0; k < size[2]; ++k)
        for (int j = 0; j < size[1]; ++j)
          for (int i = 0; i < size[0]; ++i) {
            const Lattice p = {i, j, k};
            const Lattice o = {p[0] % 2, p[1] % 2, p[2] % 2};
            if (o[0] + o[1] + o[2] == 0) continue;
            const Lattice lo = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
            const Lattice hi = {p[0] + o[0], p[1] + o[1], p[2] + o[2]};
            shift[size_t(lattice_index(p))] = 0.5 * (own[size_t(lattice_index(lo))] +
                                                     own[size_t(lattice_index(hi))]) +
                                              own[size_t(lattice_index(p))];
          }
    }
  }
  mesh.nodes.resize(node_count, 3);
  for (int k = 0; k < size[2]; ++k)
    for (int j = 0; j < size[1]; ++j)
      for (int i = 0; i < size[0]; ++i) {
        const Lattice p = {i, j, k};
        const Index node = node_of[size_t(lattice_index(p))];
        if (node < 0) continue;
        Eigen::Vector3d uvw;
        for (size_t d = 0; d < 3; ++d) uvw[Eigen::Index(d)] = param[d][size_t(p[d])];
        uvw += shift[size_t(lattice_index(p))];
        mesh.nodes.row(node) = block.mapping(uvw).transpose();
      }

  for (Index& p : elements.connectivity) p = node_of[size_t(p)];
  std::vector<Index> boundary;
  for (size_t f = 0; f < 6; ++f) {
    for (Index& p : faces[f].connectivity) p = node_of[size_t(p)];
    auto nodes = fem::nodes_of_faces({faces[f]});
    boundary.insert(boundary.end(), nodes.begin(), nodes.end());
    auto& set = mesh.node_sets[block.face_names[f]];
    set.insert(set.end(), nodes.begin(), nodes.end());
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    mesh.face_sets[block.face_names[f]].push_back(std::move(faces[f]));
  }
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  mesh.node_sets["boundary"] = std::move(boundary);
  mesh.blocks.push_back(std::move(elements));
  return mesh;
}

}  // namespace kinetofem::verification
