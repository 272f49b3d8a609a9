#include "kinetofem/verification/direct_solvers.hpp"

#include <Eigen/SparseCholesky>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"

namespace kinetofem::verification {

DirectSolverComparison compare_cholmod_with_ldlt(const fem::FeModel& model, const fem::LoadCase& load) {
  const fem::DofMap dofs(model.mesh.node_count(), model.supports);
  const fem::AssembledStiffness K = fem::assemble_stiffness(model.mesh, model.material, dofs);
  const Eigen::MatrixXd f = fem::assemble_external_forces(model.mesh, model.material, {load});
  Eigen::VectorXd rhs(dofs.free_count());
  for (fem::Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) >= 0) rhs[dofs.equation(d)] = f(d, 0);
  rhs -= K.prescribed_coupling_force;

  fem::CholmodSolver cholmod;
  cholmod.analyze(K.free_free);
  cholmod.factorize(K.free_free);
  const Eigen::VectorXd x_cholmod = cholmod.solve(rhs);
  Eigen::SimplicialLDLT<fem::SymmetricUpperMatrix, Eigen::Upper> ldlt(K.free_free);
  require(ldlt.info() == Eigen::Success, "Eigen SimplicialLDLT failed on the stiffness matrix");
  const Eigen::VectorXd x_eigen = ldlt.solve(rhs);

  DirectSolverComparison comparison;
  comparison.relative_difference = (x_cholmod - x_eigen).norm() / x_eigen.norm();
  const Eigen::VectorXd Kx = K.free_free.selfadjointView<Eigen::Upper>() * x_cholmod;
  comparison.relative_residual = (Kx - rhs).norm() / rhs.norm();
  comparison.factor_nonzeros = cholmod.statistics().factor_nonzeros;
  comparison.matrix_nonzeros = double(K.free_free.nonZeros());
  return comparison;
}

}  // namespace kinetofem::verification
