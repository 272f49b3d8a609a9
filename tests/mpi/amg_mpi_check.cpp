// Distributed AMG-PCG solve under `mpirun -n N` (ctest label `mpi`): every
// rank assembles the same TET10 cantilever, owns a contiguous block of nodes
// of the hypre ParCSR system, and gets the full solution back; each rank
// compares it with its own CHOLMOD solution. Exit status 0 when every rank
// agrees within 1e-6 of the largest displacement (the criterion of
// tests/verification/solver/amg_solver_test.cpp) and the run used more than
// one rank.
#include <cstdio>
#include <exception>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/amg_solver.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/testing/box_mesh.hpp"

using namespace kinetofem;
using namespace kinetofem::fem;

int main() {
  try {
    const int rank = mpi_world_rank(), size = mpi_world_size();
    FeModel model;
    testing::BoxMeshOptions box;
    box.length_m = Eigen::Vector3d(1.6, 0.2, 0.2);
    box.divisions = {16, 4, 4};
    box.type = ElementType::Tet10;
    box.random_perturbation = 0.2;
    box.seed = 7;
    model.mesh = testing::box_mesh(box);
    model.material = IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
    model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true},
                       Eigen::Vector3d::Zero()}};
    LoadCase shear, twist;
    shear.tractions = {{"x1", Eigen::Vector3d(0, -2e6, 0)}};
    twist.tractions = {{"y1", Eigen::Vector3d(0, 0, 1e5)}, {"x1", Eigen::Vector3d(5e6, 0, -1e6)}};
    const DofMap dofs(model.mesh.node_count(), model.supports);
    const AssembledStiffness K = assemble_stiffness(model.mesh, model.material, dofs);
    const Eigen::MatrixXd f = assemble_external_forces(model.mesh, model.material, {shear, twist});
    Eigen::MatrixXd rhs(dofs.free_count(), f.cols());
    for (Index d = 0; d < dofs.dof_count(); ++d)
      if (dofs.equation(d) >= 0) rhs.row(dofs.equation(d)) = f.row(d);

    const Log log;
    const Log quiet = Log::quiet();
    AmgOptions options;
    options.distributed = true;
    AmgSolver amg(options, rank == 0 ? &log : &quiet);
    amg.setup(K.free_free, model.mesh.nodes, dofs);
    const Eigen::MatrixXd x_amg = amg.solve(rhs);

    CholmodSolver cholmod;
    cholmod.analyze(K.free_free);
    cholmod.factorize(K.free_free);
    const Eigen::MatrixXd x_direct = cholmod.solve(rhs);
    bool ok = size > 1 && amg.statistics().ranks == size;
    for (Index k = 0; k < rhs.cols(); ++k) {
      const double difference = (x_amg.col(k) - x_direct.col(k)).cwiseAbs().maxCoeff() /
                                x_direct.col(k).cwiseAbs().maxCoeff();
      ok = ok && difference < 1e-6;
      std::printf("rank %d of %d: load case %lld, %d PCG iterations, max|u_amg - u_chol| / "
                  "max|u_chol| = %.2e\n",
                  rank, size, static_cast<long long>(k), amg.statistics().iterations[size_t(k)],
                  difference);
    }
    if (size < 2) std::printf("rank %d: run under mpirun -n 2 or more\n", rank);
    return ok ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "amg_mpi_check: %s\n", error.what());
    return 2;
  }
}
