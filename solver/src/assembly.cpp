#include "kinetofem/solver/assembly.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>

#include <omp.h>

#include "element_kernels.hpp"
#include "face_integration.hpp"
#include "sparse_assembly.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

namespace {

using detail::NodeMatrix;
using detail::RuleTable;

// The first element failure met inside a parallel loop; exceptions must not
// cross an OpenMP region, so the loop records and the caller throws.
struct FirstFailure {
  std::mutex mutex;
  std::optional<Index> element;
  std::string message;
  void record(Index e, std::string text) {
    std::lock_guard lock(mutex);
    if (!element || e < *element) {
      element = e;
      message = std::move(text);
    }
  }
  void throw_if_any() const {
    if (element) throw Error(message);
  }
};

// Characteristic length cubed of an element (bounding-box diagonal^3), for a
// scale-free degeneracy test of det J.
template <int NPE>
double size_cubed(const NodeMatrix<NPE>& X) {
  const double diag = (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  return diag * diag * diag;
}

std::string jacobian_message(Index element, ElementType type, double det) {
  return fmt::format(
      "element {} ({}) is inverted or degenerate: Jacobian determinant {:.3e} is not positive",
      element, name_of(type), det);
}

// Node -> elements incidence (CSR over global element indices).
struct Incidence {
  std::vector<Index> offset, element;
};

Incidence node_incidence(const Mesh& mesh) {
  Incidence inc;
  inc.offset.assign(size_t(mesh.node_count() + 1), 0);
  for (const auto& block : mesh.blocks)
    for (Index node : block.connectivity) ++inc.offset[size_t(node + 1)];
  for (size_t i = 1; i < inc.offset.size(); ++i) inc.offset[i] += inc.offset[i - 1];
  inc.element.resize(size_t(inc.offset.back()));
  std::vector<Index> cursor(inc.offset.begin(), inc.offset.end() - 1);
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    const int n = nodes_per_element(block.type);
    for (Index e = 0; e < block.size(); ++e)
      for (int a = 0; a < n; ++a)
        inc.element[size_t(cursor[size_t(block.connectivity[size_t(e * n + a)])]++)] = first + e;
    first += block.size();
  }
  return inc;
}

// Global element index -> (block, local index).
std::pair<const ElementBlock*, Index> locate(const Mesh& mesh, Index global) {
  for (const auto& block : mesh.blocks) {
    if (global < block.size()) return {&block, global};
    global -= block.size();
  }
  return {nullptr, 0};
}

// Pattern of the upper triangle of K_ff from the connectivity.
void build_pattern(const Mesh& mesh, const DofMap& dofs, SymmetricUpperMatrix& K) {
  const Index nodes = mesh.node_count();
  const Incidence inc = node_incidence(mesh);
  // Neighbour nodes a <= b of every node b.
  std::vector<std::vector<Index>> lower_neighbours(static_cast<size_t>(nodes));
#pragma omp parallel for schedule(dynamic, 256)
  for (Index b = 0; b < nodes; ++b) {
    auto& list = lower_neighbours[size_t(b)];
    for (Index k = inc.offset[size_t(b)]; k < inc.offset[size_t(b + 1)]; ++k) {
      const auto [block, e] = locate(mesh, inc.element[size_t(k)]);
      for (Index a : block->element(e))
        if (a <= b) list.push_back(a);
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  const Index n_free = dofs.free_count();
  std::vector<std::int64_t> column_start(size_t(n_free + 1), 0);
  for (Index b = 0; b < nodes; ++b)
    for (int cb = 0; cb < 3; ++cb) {
      const Index col = dofs.equation(3 * b + cb);
      if (col < 0) continue;
      std::int64_t count = 0;
      for (Index a : lower_neighbours[size_t(b)])
        for (int ca = 0; ca < 3; ++ca) {
          const Index row = dofs.equation(3 * a + ca);
          if (row >= 0 && row <= col) ++count;
        }
      column_start[size_t(col + 1)] = count;
    }
  for (size_t i = 1; i < column_start.size(); ++i) column_start[i] += column_start[i - 1];

  K.resize(n_free, n_free);
  K.resizeNonZeros(column_start.back());
  std::copy(column_start.begin(), column_start.end(), K.outerIndexPtr());
  auto* rows = K.innerIndexPtr();
#pragma omp parallel for schedule(dynamic, 256)
  for (Index b = 0; b < nodes; ++b)
    for (int cb = 0; cb < 3; ++cb) {
      const Index col = dofs.equation(3 * b + cb);
      if (col < 0) continue;
      std::int64_t pos = column_start[size_t(col)];
      for (Index a : lower_neighbours[size_t(b)])
        for (int ca = 0; ca < 3; ++ca) {
          const Index row = dofs.equation(3 * a + ca);
          if (row >= 0 && row <= col) rows[pos++] = row;
        }
    }
  std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
}

// Lame constants (lambda, mu) of each material of the elements, by material index.
std::vector<std::pair<double, double>> lame_of(const ElementMaterials& materials) {
  std::vector<std::pair<double, double>> out;
  for (const IsotropicMaterial& m : materials.materials()) {
    double lambda, mu;
    detail::lame(m.youngs_modulus_pa, m.poisson_ratio, lambda, mu);
    out.emplace_back(lambda, mu);
  }
  return out;
}

inline void atomic_add(double& target, double value) {
#pragma omp atomic
  target += value;
}

}  // namespace

void detail::build_upper_pattern(const Mesh& mesh, const DofMap& dofs,
                                 SymmetricUpperMatrix& matrix) {
  build_pattern(mesh, dofs, matrix);
}

void check_element_jacobians(const Mesh& mesh) {
  FirstFailure failure;
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const RuleTable<NPE> gauss(block.type, quadrature(block.type));
      std::vector<QuadraturePoint> corner_points;
      const Eigen::MatrixXd ref = reference_nodes(block.type);
      for (int a = 0; a < corner_nodes(block.type); ++a)
        corner_points.push_back({ref.row(a).transpose(), 1.0});
      const RuleTable<NPE> corners(block.type, corner_points);
#pragma omp parallel for schedule(static)
      for (Index e = 0; e < block.size(); ++e) {
        const auto X = detail::element_coordinates<NPE>(mesh, block.element(e));
        const double tol = 1e-12 * size_cubed<NPE>(X);
        Eigen::Matrix<double, NPE, 3> G;
        for (const auto* table : {&gauss, &corners})
          for (size_t q = 0; q < table->size(); ++q) {
            const double det = detail::physical_gradients<NPE>(X, table->dN[q], G);
            if (!(det > tol)) {
              failure.record(first + e, jacobian_message(first + e, block.type, det));
              break;
            }
          }
      }
    });
    first += block.size();
  }
  failure.throw_if_any();
}

AssembledStiffness assemble_stiffness(const Mesh& mesh, const ElementMaterials& materials,
                                      const DofMap& dofs) {
  materials.validate();
  require(dofs.dof_count() == 3 * mesh.node_count(), "DoF map has {} DoFs, mesh needs {}",
          dofs.dof_count(), 3 * mesh.node_count());
  AssembledStiffness out;
  build_pattern(mesh, dofs, out.free_free);
  out.prescribed_coupling_force = Eigen::VectorXd::Zero(dofs.free_count());
  const Eigen::VectorXd& prescribed = dofs.prescribed_values();
  const std::vector<std::pair<double, double>> lame = lame_of(materials);

  FirstFailure failure;
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const detail::StiffnessRules<NPE> rules(block.type);
#pragma omp parallel
      {
        Eigen::Matrix<double, 3 * NPE, 3 * NPE> Ke;
        std::array<Index, 3 * NPE> eq;
        std::array<Index, 3 * NPE> dof;
#pragma omp for schedule(dynamic, 64)
        for (Index e = 0; e < block.size(); ++e) {
          const auto nodes = block.element(e);
          const auto X = detail::element_coordinates<NPE>(mesh, nodes);
          const auto [lambda, mu] = lame[size_t(materials.index_of(first + e))];
          const double min_det =
              detail::element_stiffness<NPE>(X, rules.for_element(X), lambda, mu, Ke);
          if (!(min_det > 1e-12 * size_cubed<NPE>(X))) {
            failure.record(first + e, jacobian_message(first + e, block.type, min_det));
            continue;
          }
          bool has_prescribed_value = false;
          for (int a = 0; a < NPE; ++a)
            for (int c = 0; c < 3; ++c) {
              dof[size_t(3 * a + c)] = 3 * nodes[size_t(a)] + c;
              eq[size_t(3 * a + c)] = dofs.equation(3 * nodes[size_t(a)] + c);
              if (eq[size_t(3 * a + c)] < 0 && prescribed[3 * nodes[size_t(a)] + c] != 0.0)
                has_prescribed_value = true;
            }
          detail::scatter_upper<3 * NPE>(eq, Ke, out.free_free);
          if (has_prescribed_value) {
            for (int p = 0; p < 3 * NPE; ++p) {
              if (eq[size_t(p)] < 0) continue;
              double sum = 0.0;
              for (int q = 0; q < 3 * NPE; ++q)
                if (eq[size_t(q)] < 0) sum += Ke(p, q) * prescribed[dof[size_t(q)]];
              atomic_add(out.prescribed_coupling_force[eq[size_t(p)]], sum);
            }
          }
        }
      }
    });
    first += block.size();
  }
  failure.throw_if_any();
  return out;
}

namespace {

// Outward-normal sign of a boundary face: +1 if its node order gives the
// outward normal of the adjacent element, -1 if it points inwards. Gmsh's
// surface elements follow the surface's parametrisation, not the volume.
double face_orientation(const Mesh& mesh, const Incidence& inc, std::span<const Index> face,
                        int corners, const Eigen::Vector3d& normal, const Eigen::Vector3d& centre) {
  const Index n0 = face[0];
  for (Index k = inc.offset[size_t(n0)]; k < inc.offset[size_t(n0 + 1)]; ++k) {
    const auto [block, e] = locate(mesh, inc.element[size_t(k)]);
    const auto nodes = block->element(e);
    bool contains_all = true;
    for (int c = 1; c < corners && contains_all; ++c)
      contains_all = std::find(nodes.begin(), nodes.end(), face[size_t(c)]) != nodes.end();
    if (!contains_all) continue;
    Eigen::Vector3d element_centre = Eigen::Vector3d::Zero();
    const int nc = corner_nodes(block->type);
    for (int a = 0; a < nc; ++a) element_centre += mesh.nodes.row(nodes[size_t(a)]).transpose();
    element_centre /= nc;
    return (element_centre - centre).dot(normal) > 0.0 ? -1.0 : 1.0;
  }
  fail("face with nodes {}, {}, {} is not a face of any element of the mesh", face[0], face[1],
       face[2]);
}

// Integrates N_a * (traction or -p n) over the faces of a face set into F(:, column).
void add_face_loads(const Mesh& mesh, const Incidence* inc, const std::vector<FaceBlock>& faces,
                    const Eigen::Vector3d& traction, double pressure, Eigen::MatrixXd& F,
                    Index column) {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const auto& block : faces) {
    const int n = nodes_per_face(block.type);
    const auto& rule = quadrature(block.type);
    for (Index f = 0; f < block.size(); ++f) {
      const auto nodes = block.face(f);
      Eigen::MatrixXd X(n, 3);
      for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(nodes[size_t(a)]);
      double sign = 1.0;
      if (pressure != 0.0) {
        shape_functions(block.type, rule[0].xi, N, dN);
        const Eigen::Vector3d t1 = X.transpose() * dN.col(0), t2 = X.transpose() * dN.col(1);
        const int corners = face_facts(block.type).corners;
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (int a = 0; a < corners; ++a) centre += X.row(a).transpose() / corners;
        sign = face_orientation(mesh, *inc, nodes, corners, t1.cross(t2), centre);
      }
      for (const auto& qp : rule) {
        shape_functions(block.type, qp.xi, N, dN);
        const Eigen::Vector3d t1 = X.transpose() * dN.col(0), t2 = X.transpose() * dN.col(1);
        const Eigen::Vector3d area_normal = t1.cross(t2);  // |n| = dA / (dxi deta)
        const Eigen::Vector3d load =
            traction * area_normal.norm() - pressure * sign * area_normal;
        for (int a = 0; a < n; ++a)
          F.block<3, 1>(3 * nodes[size_t(a)], column) += qp.weight * N[a] * load;
      }
    }
  }
}

}  // namespace

Eigen::MatrixXd assemble_external_forces(const Mesh& mesh, const ElementMaterials& materials,
                                         const std::vector<LoadCase>& load_cases) {
  const Index n_dof = 3 * mesh.node_count();
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(n_dof, Index(load_cases.size()));
  std::optional<Incidence> incidence;
  bool any_body_load = false;
  for (size_t k = 0; k < load_cases.size(); ++k) {
    const LoadCase& load = load_cases[k];
    for (const auto& nf : load.nodal_forces) {
      require(nf.node >= 0 && nf.node < mesh.node_count(),
              "load case '{}': nodal force on node {} (mesh has {} nodes)", load.name, nf.node,
              mesh.node_count());
      require(nf.force_n.allFinite(), "load case '{}': nodal force on node {} is not finite",
              load.name, nf.node);
      F.block<3, 1>(3 * nf.node, Index(k)) += nf.force_n;
    }
    for (const auto& t : load.tractions) {
      require(t.traction_pa.allFinite(), "load case '{}': traction on '{}' is not finite",
              load.name, t.face_set);
      add_face_loads(mesh, nullptr, mesh.face_set(t.face_set), t.traction_pa, 0.0, F, Index(k));
    }
    for (const auto& p : load.pressures) {
      require(std::isfinite(p.pressure_pa), "load case '{}': pressure on '{}' is not finite",
              load.name, p.face_set);
      if (!incidence) incidence = node_incidence(mesh);
      add_face_loads(mesh, &*incidence, mesh.face_set(p.face_set), Eigen::Vector3d::Zero(),
                     p.pressure_pa, F, Index(k));
    }
    require(load.gravity_m_s2.allFinite(), "load case '{}': gravity is not finite", load.name);
    if (load.body_force || load.acceleration || !load.gravity_m_s2.isZero()) any_body_load = true;
  }
  if (!any_body_load) return F;

  // Body loads: f_a = int N_a (rho (g + a(x)) + b(x)) dV, all load cases per
  // element, rho the element's density.
  const Index cases = Index(load_cases.size());
  FirstFailure failure;
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const RuleTable<NPE> rule(block.type, load_quadrature(block.type));
#pragma omp parallel
      {
        Eigen::Matrix<double, NPE, 3> G;
        Eigen::Matrix<double, 3 * NPE, Eigen::Dynamic> fe(3 * NPE, cases);
#pragma omp for schedule(dynamic, 256)
        for (Index e = 0; e < block.size(); ++e) {
          const auto nodes = block.element(e);
          const auto X = detail::element_coordinates<NPE>(mesh, nodes);
          const double rho = materials.of(first + e).density_kg_m3;
          fe.setZero();
          for (size_t q = 0; q < rule.size(); ++q) {
            const double det = detail::physical_gradients<NPE>(X, rule.dN[q], G);
            const double w = rule.weight[q] * det;
            const Eigen::Vector3d x = X.transpose() * rule.N[q];
            for (Index k = 0; k < cases; ++k) {
              const LoadCase& load = load_cases[size_t(k)];
              Eigen::Vector3d b = rho * load.gravity_m_s2;
              if (load.body_force) b += load.body_force(x);
              if (load.acceleration) b += rho * load.acceleration(x);
              if (!b.allFinite()) {
                failure.record(first + e, fmt::format("load case '{}': body force is not finite at "
                                              "({:.6g}, {:.6g}, {:.6g}) m",
                                              load.name, x[0], x[1], x[2]));
                continue;
              }
              for (int a = 0; a < NPE; ++a)
                fe.template block<3, 1>(3 * a, k) += w * rule.N[q][a] * b;
            }
          }
          for (Index k = 0; k < cases; ++k)
            for (int a = 0; a < NPE; ++a)
              for (int c = 0; c < 3; ++c)
                atomic_add(F(3 * nodes[size_t(a)] + c, k), fe(3 * a + c, k));
        }
      }
    });
    first += block.size();
  }
  failure.throw_if_any();
  return F;
}

Eigen::VectorXd internal_forces(const Mesh& mesh, const ElementMaterials& materials,
                                const DisplacementField& displacement) {
  require(displacement.rows() == mesh.node_count(), "displacement has {} rows, mesh {} nodes",
          displacement.rows(), mesh.node_count());
  Eigen::VectorXd R = Eigen::VectorXd::Zero(3 * mesh.node_count());
  const std::vector<std::pair<double, double>> lame = lame_of(materials);
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const detail::StiffnessRules<NPE> rules(block.type);
#pragma omp parallel
      {
        Eigen::Matrix<double, 3 * NPE, 3 * NPE> Ke;
        Eigen::Matrix<double, 3 * NPE, 1> ue;
#pragma omp for schedule(dynamic, 256)
        for (Index e = 0; e < block.size(); ++e) {
          const auto nodes = block.element(e);
          const auto X = detail::element_coordinates<NPE>(mesh, nodes);
          const auto [lambda, mu] = lame[size_t(materials.index_of(first + e))];
          detail::element_stiffness<NPE>(X, rules.for_element(X), lambda, mu, Ke);
          for (int a = 0; a < NPE; ++a) ue.template segment<3>(3 * a) = displacement.row(nodes[size_t(a)]).transpose();
          const Eigen::Matrix<double, 3 * NPE, 1> fe = Ke * ue;
          for (int a = 0; a < NPE; ++a)
            for (int c = 0; c < 3; ++c) atomic_add(R[3 * nodes[size_t(a)] + c], fe[3 * a + c]);
        }
      }
    });
    first += block.size();
  }
  return R;
}

Eigen::VectorXd internal_forces_at(const Mesh& mesh, const ElementMaterials& materials,
                                   const DisplacementField& displacement,
                                   const std::vector<Index>& nodes) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(3 * Index(nodes.size()));
  const std::vector<std::pair<double, double>> lame = lame_of(materials);
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const detail::StiffnessRules<NPE> rules(block.type);
      Eigen::Matrix<double, 3 * NPE, 3 * NPE> Ke;
      Eigen::Matrix<double, 3 * NPE, 1> ue;
      for (Index e = 0; e < block.size(); ++e) {
        const auto element = block.element(e);
        bool touches = false;
        for (Index node : element)
          touches = touches || std::find(nodes.begin(), nodes.end(), node) != nodes.end();
        if (!touches) continue;
        const auto X = detail::element_coordinates<NPE>(mesh, element);
        const auto [lambda, mu] = lame[size_t(materials.index_of(first + e))];
        detail::element_stiffness<NPE>(X, rules.for_element(X), lambda, mu, Ke);
        for (int a = 0; a < NPE; ++a)
          ue.template segment<3>(3 * a) = displacement.row(element[size_t(a)]).transpose();
        const Eigen::Matrix<double, 3 * NPE, 1> fe = Ke * ue;
        for (int a = 0; a < NPE; ++a)
          for (size_t k = 0; k < nodes.size(); ++k)
            if (element[size_t(a)] == nodes[k]) out.segment<3>(3 * Index(k)) += fe.template segment<3>(3 * a);
      }
    });
    first += block.size();
  }
  return out;
}

double surface_area(const Mesh& mesh, const std::vector<FaceBlock>& faces) {
  double area = 0.0;
  detail::for_each_face_point(mesh, faces, [&](auto&&, const Eigen::VectorXd&, const Eigen::Vector3d&,
                                               double dA) { area += dA; });
  return area;
}

double mesh_volume(const Mesh& mesh) {
  double volume = 0.0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const RuleTable<NPE> rule(block.type, load_quadrature(block.type));  // exact for curved TET10 det J
      double sum = 0.0;
#pragma omp parallel for reduction(+ : sum) schedule(static)
      for (Index e = 0; e < block.size(); ++e) {
        const auto X = detail::element_coordinates<NPE>(mesh, block.element(e));
        Eigen::Matrix<double, NPE, 3> G;
        for (size_t q = 0; q < rule.size(); ++q)
          sum += rule.weight[q] * detail::physical_gradients<NPE>(X, rule.dN[q], G);
      }
      volume += sum;
    });
  }
  return volume;
}

}  // namespace kinetofem::fem
