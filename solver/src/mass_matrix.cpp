#include "kinetofem/solver/mass_matrix.hpp"

#include <optional>
#include <string>

#include "element_kernels.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "sparse_assembly.hpp"

namespace kinetofem::fem {

SymmetricUpperMatrix assemble_mass(const Mesh& mesh, const ElementMaterials& materials,
                                   const DofMap& dofs) {
  materials.validate();
  require(dofs.dof_count() == 3 * mesh.node_count(), "DoF map has {} DoFs, mesh needs {}",
          dofs.dof_count(), 3 * mesh.node_count());
  SymmetricUpperMatrix M;
  detail::build_upper_pattern(mesh, dofs, M);
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    // The first failing element of the block (exceptions must not cross the
    // OpenMP region).
    std::optional<std::pair<Index, double>> failure;
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const detail::RuleTable<NPE> rule(block.type, mass_quadrature(block.type));
#pragma omp parallel
      {
        Eigen::Matrix<double, NPE, 3> G;
        Eigen::Matrix<double, NPE, NPE> scalar_mass;
        Eigen::Matrix<double, 3 * NPE, 3 * NPE> Me;
        std::array<Index, 3 * NPE> eq;
#pragma omp for schedule(dynamic, 64)
        for (Index e = 0; e < block.size(); ++e) {
          const auto nodes = block.element(e);
          const auto X = detail::element_coordinates<NPE>(mesh, nodes);
          const double rho = materials.of(first + e).density_kg_m3;
          scalar_mass.setZero();
          double min_det = std::numeric_limits<double>::infinity();
          for (size_t q = 0; q < rule.size(); ++q) {
            const double det = detail::physical_gradients<NPE>(X, rule.dN[q], G);
            min_det = std::min(min_det, det);
            scalar_mass.noalias() += (rule.weight[q] * det * rho) * rule.N[q] * rule.N[q].transpose();
          }
          if (!(min_det > 0.0)) {
#pragma omp critical(kinetofem_mass_failure)
            if (!failure || e < failure->first) failure = std::make_pair(e, min_det);
            continue;
          }
          Me.setZero();
          for (int b = 0; b < NPE; ++b)
            for (int a = 0; a < NPE; ++a)
              for (int c = 0; c < 3; ++c) Me(3 * a + c, 3 * b + c) = scalar_mass(a, b);
          for (int a = 0; a < NPE; ++a)
            for (int c = 0; c < 3; ++c) eq[size_t(3 * a + c)] = dofs.equation(3 * nodes[size_t(a)] + c);
          detail::scatter_upper<3 * NPE>(eq, Me, M);
        }
      }
    });
    if (failure)
      fail("mass matrix: element {} ({}) is inverted or degenerate: Jacobian determinant {:.3e} "
           "is not positive",
           first + failure->first, name_of(block.type), failure->second);
    first += block.size();
  }
  return M;
}

Eigen::VectorXd rigid_body_field(const Mesh& mesh, const Eigen::Vector3d& translation,
                                 const Eigen::Vector3d& rotation) {
  Eigen::VectorXd v(3 * mesh.node_count());
  for (Index n = 0; n < mesh.node_count(); ++n)
    v.segment<3>(3 * n) = translation + rotation.cross(Eigen::Vector3d(mesh.nodes.row(n).transpose()));
  return v;
}

}  // namespace kinetofem::fem
