#include "kinetofem/solver/amg_solver.hpp"

#include <mpi.h>

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
// Internal header, only to read the number of levels and the size of each
// level's operator (the operator complexity) after set-up.
#include <_hypre_parcsr_ls.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>

#include <Eigen/Geometry>

#include "kinetofem/solver/pcg_progress.hpp"

namespace kinetofem::fem {

namespace {

// MPI and hypre are process-wide libraries: they are initialised once, on the
// first AmgSolver of a program that has not initialised MPI itself, and
// finalised at exit (the call_once flag is the only state this file keeps
// beyond an AmgSolver, and it mirrors MPI's own).
void finalize_at_exit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) {
    HYPRE_Finalize();
    MPI_Finalize();
  }
}

void ensure_mpi_and_hypre() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      HYPRE_Init();
      std::atexit(finalize_at_exit);
    } else {
      HYPRE_Init();
    }
  });
}

void check_hypre(HYPRE_Int code, const char* function) {
  if (code == 0) return;
  char description[256] = {};
  HYPRE_DescribeError(code, description);
  HYPRE_ClearAllErrors();
  fail("hypre {} failed: {} (error code {})", function, description, int(code));
}

// Row block [first, last) of whole nodes owned by `rank` of `size`.
std::pair<Index, Index> node_block(Index nodes, int rank, int size) {
  const Index base = nodes / size, extra = nodes % size;
  const Index first = rank * base + std::min<Index>(rank, extra);
  return {first, first + base + (rank < extra ? 1 : 0)};
}

}  // namespace

int AmgStatistics::max_iterations() const {
  return iterations.empty() ? 0 : *std::max_element(iterations.begin(), iterations.end());
}

double AmgStatistics::max_relative_residual() const {
  return relative_residuals.empty()
             ? 0.0
             : *std::max_element(relative_residuals.begin(), relative_residuals.end());
}

Eigen::MatrixXd rigid_body_modes(const NodeCoordinates& nodes) {
  const Index n = nodes.rows();
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(3 * n, 6);
  const Eigen::RowVector3d centroid =
      n > 0 ? Eigen::RowVector3d(nodes.colwise().mean()) : Eigen::RowVector3d::Zero();
  for (Index i = 0; i < n; ++i) {
    const Eigen::Vector3d r = (nodes.row(i) - centroid).transpose();
    for (int c = 0; c < 3; ++c) modes(3 * i + c, c) = 1.0;
    // u = e_k x r for the rotation about axis k.
    for (int k = 0; k < 3; ++k)
      modes.block<3, 1>(3 * i, 3 + k) = Eigen::Vector3d::Unit(k).cross(r);
  }
  return modes;
}

int mpi_world_rank() {
  ensure_mpi_and_hypre();
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int mpi_world_size() {
  ensure_mpi_and_hypre();
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

struct AmgSolver::Impl {
  MPI_Comm comm = MPI_COMM_SELF;
  int rank = 0, size = 1;
  HYPRE_IJMatrix A_ij = nullptr;
  HYPRE_ParCSRMatrix A = nullptr;
  HYPRE_IJVector b_ij = nullptr, x_ij = nullptr;
  HYPRE_ParVector b = nullptr, x = nullptr;
  // PCG work vectors: residual r, search direction p, s = A p or C r.
  HYPRE_IJVector r_ij = nullptr, p_ij = nullptr, s_ij = nullptr;
  HYPRE_ParVector r = nullptr, p = nullptr, s = nullptr;
  std::vector<HYPRE_IJVector> mode_ij;
  std::vector<HYPRE_ParVector> modes;
  HYPRE_Solver amg = nullptr;

  const SymmetricUpperMatrix* matrix = nullptr;
  std::vector<Index> equation;  // of each DoF (-1: prescribed)
  Index first_row = 0, last_row = 0;   // owned rows (DoFs) [first, last)
  std::vector<int> rows_of_rank, first_row_of_rank;  // for the gather

  ~Impl() { release(); }

  void release() {
    if (amg) HYPRE_BoomerAMGDestroy(amg);
    amg = nullptr;
    for (auto& v : mode_ij) HYPRE_IJVectorDestroy(v);
    mode_ij.clear();
    modes.clear();
    for (HYPRE_IJVector* v : {&b_ij, &x_ij, &r_ij, &p_ij, &s_ij}) {
      if (*v) HYPRE_IJVectorDestroy(*v);
      *v = nullptr;
    }
    if (A_ij) HYPRE_IJMatrixDestroy(A_ij);
    A_ij = nullptr;
    A = nullptr;
    b = x = r = p = s = nullptr;
  }

  // A vector of the owned rows, zero, and its ParVector.
  HYPRE_ParVector make_zero_vector(HYPRE_IJVector& v, const Eigen::VectorXd& zero) const {
    v = make_vector();
    set_vector(v, zero.data());
    void* object = nullptr;
    check_hypre(HYPRE_IJVectorGetObject(v, &object), "HYPRE_IJVectorGetObject");
    return static_cast<HYPRE_ParVector>(object);
  }

  struct PcgResult {
    int iterations = 0;
    double relative_residual = 0.0;   // sqrt((r, C r) / (b, C b)) when PCG stopped
    bool converged = false;
    const char* breakdown = nullptr;  // why PCG stopped early, if it did
  };
  PcgResult pcg(double tolerance, int max_iterations, PcgProgress* progress) const;

  HYPRE_IJVector make_vector() const {
    HYPRE_IJVector v = nullptr;
    check_hypre(HYPRE_IJVectorCreate(comm, HYPRE_BigInt(first_row), HYPRE_BigInt(last_row - 1), &v),
                "HYPRE_IJVectorCreate");
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    check_hypre(HYPRE_IJVectorInitialize(v), "HYPRE_IJVectorInitialize");
    return v;
  }

  // Sets the owned entries of `v` from a full DoF vector and assembles it.
  void set_vector(HYPRE_IJVector v, const double* full) const {
    const Index n = last_row - first_row;
    std::vector<HYPRE_BigInt> rows(static_cast<size_t>(n));
    std::iota(rows.begin(), rows.end(), HYPRE_BigInt(first_row));
    check_hypre(HYPRE_IJVectorSetValues(v, HYPRE_Int(n), rows.data(), full + first_row),
                "HYPRE_IJVectorSetValues");
    check_hypre(HYPRE_IJVectorAssemble(v), "HYPRE_IJVectorAssemble");
  }
};

AmgSolver::AmgSolver(AmgOptions options, const Log* log)
    : impl_(std::make_unique<Impl>()), options_(options), log_(log) {
  require(options_.relative_tolerance > 0 && options_.relative_tolerance < 1,
          "AMG relative tolerance {} is not in (0, 1)", options_.relative_tolerance);
  require(options_.max_iterations > 0, "AMG max iterations {} is not positive",
          options_.max_iterations);
  require(!std::isnan(options_.progress_interval_s), "AMG progress interval is NaN");
  require(options_.strong_threshold > 0 && options_.strong_threshold < 1,
          "AMG strong threshold {} is not in (0, 1)", options_.strong_threshold);
  ensure_mpi_and_hypre();
  impl_->comm = options_.distributed ? MPI_COMM_WORLD : MPI_COMM_SELF;
  MPI_Comm_rank(impl_->comm, &impl_->rank);
  MPI_Comm_size(impl_->comm, &impl_->size);
}

AmgSolver::~AmgSolver() = default;

void AmgSolver::setup(const SymmetricUpperMatrix& K, const NodeCoordinates& nodes,
                      const DofMap& dofs) {
  Stopwatch clock;
  Impl& m = *impl_;
  m.release();
  require(K.rows() == K.cols() && K.rows() == dofs.free_count(),
          "AMG: K_ff is {} x {}, the DoF map has {} free equations", K.rows(), K.cols(),
          dofs.free_count());
  require(K.isCompressed(), "AMG: K_ff must be in compressed storage");
  require(nodes.rows() * 3 == dofs.dof_count(), "AMG: {} nodes, the DoF map has {} DoFs",
          nodes.rows(), dofs.dof_count());
  const Index n_dof = dofs.dof_count();
  require(n_dof < Index(std::numeric_limits<HYPRE_BigInt>::max()),
          "AMG: {} DoFs exceed hypre's index range", n_dof);
  m.matrix = &K;
  m.equation = dofs.equations();
  std::vector<Index> dof_of_equation(size_t(K.rows()));
  for (Index d = 0; d < n_dof; ++d)
    if (m.equation[size_t(d)] >= 0) dof_of_equation[size_t(m.equation[size_t(d)])] = d;

  const auto [first_node, last_node] = node_block(nodes.rows(), m.rank, m.size);
  m.first_row = 3 * first_node;
  m.last_row = 3 * last_node;
  m.rows_of_rank.assign(size_t(m.size), 0);
  m.first_row_of_rank.assign(size_t(m.size), 0);
  for (int r = 0; r < m.size; ++r) {
    const auto [a, b] = node_block(nodes.rows(), r, m.size);
    m.first_row_of_rank[size_t(r)] = int(3 * a);
    m.rows_of_rank[size_t(r)] = int(3 * (b - a));
  }
  const Index first = m.first_row, last = m.last_row, local_rows = last - first;
  auto owned = [&](Index dof) { return dof >= first && dof < last; };

  // Pass 1: nonzeros of each owned row of the full symmetric matrix, split
  // into the owned column block (diag) and the rest (offd), so that hypre
  // allocates once and each row is handed over whole.
  std::vector<HYPRE_Int> diag_sizes(static_cast<size_t>(local_rows), 0), offd_sizes(size_t(local_rows), 0);
  double diagonal_sum = 0.0;
  const Index* outer = K.outerIndexPtr();
  const Index* inner = K.innerIndexPtr();
  const double* value = K.valuePtr();
  for (Index j = 0; j < K.cols(); ++j) {
    const Index dj = dof_of_equation[size_t(j)];
    for (Index p = outer[j]; p < outer[j + 1]; ++p) {
      const Index i = inner[p], di = dof_of_equation[size_t(i)];
      if (owned(di)) (owned(dj) ? diag_sizes : offd_sizes)[size_t(di - first)]++;
      if (i != j && owned(dj)) (owned(di) ? diag_sizes : offd_sizes)[size_t(dj - first)]++;
      if (i == j) diagonal_sum += value[p];
    }
  }
  // Prescribed DoFs: a decoupled row d u = 0 with d of the size of K's diagonal.
  const double decoupled_diagonal = diagonal_sum / double(std::max<Index>(1, K.rows()));
  for (Index d = first; d < last; ++d)
    if (m.equation[size_t(d)] < 0) diag_sizes[size_t(d - first)] = 1;

  check_hypre(HYPRE_IJMatrixCreate(m.comm, HYPRE_BigInt(first), HYPRE_BigInt(last - 1),
                                   HYPRE_BigInt(first), HYPRE_BigInt(last - 1), &m.A_ij),
              "HYPRE_IJMatrixCreate");
  HYPRE_IJMatrixSetObjectType(m.A_ij, HYPRE_PARCSR);
  check_hypre(HYPRE_IJMatrixSetDiagOffdSizes(m.A_ij, diag_sizes.data(), offd_sizes.data()),
              "HYPRE_IJMatrixSetDiagOffdSizes");
  check_hypre(HYPRE_IJMatrixInitialize(m.A_ij), "HYPRE_IJMatrixInitialize");

  // Pass 2, by chunks of owned rows (bounded scratch memory): gather each
  // chunk's full rows in CSR form and hand them to hypre.
  std::vector<Index> row_size(static_cast<size_t>(local_rows));
  for (Index r = 0; r < local_rows; ++r)
    row_size[size_t(r)] = Index(diag_sizes[size_t(r)]) + offd_sizes[size_t(r)];
  const Index chunk_entries = 16'000'000;  // ~200 MB of scratch
  std::int64_t local_nonzeros = 0;
  for (Index r0 = 0; r0 < local_rows;) {
    Index r1 = r0, entries = 0;
    while (r1 < local_rows && (r1 == r0 || entries + row_size[size_t(r1)] <= chunk_entries))
      entries += row_size[size_t(r1++)];
    const Index lo = first + r0, hi = first + r1;  // DoF range of the chunk
    std::vector<Index> start(static_cast<size_t>(r1 - r0 + 1), 0);
    for (Index r = r0; r < r1; ++r) start[size_t(r - r0 + 1)] = start[size_t(r - r0)] + row_size[size_t(r)];
    std::vector<Index> fill(start.begin(), start.end() - 1);
    std::vector<HYPRE_BigInt> columns(static_cast<size_t>(entries));
    std::vector<double> values(static_cast<size_t>(entries));
    auto put = [&](Index row_dof, Index col_dof, double v) {
      const Index at = fill[size_t(row_dof - lo)]++;
      columns[size_t(at)] = HYPRE_BigInt(col_dof);
      values[size_t(at)] = v;
    };
    for (Index j = 0; j < K.cols(); ++j) {
      const Index dj = dof_of_equation[size_t(j)];
      const bool column_in_chunk = dj >= lo && dj < hi;
      for (Index p = outer[j]; p < outer[j + 1]; ++p) {
        const Index i = inner[p], di = dof_of_equation[size_t(i)];
        if (di >= lo && di < hi) put(di, dj, value[p]);
        if (i != j && column_in_chunk) put(dj, di, value[p]);
      }
    }
    for (Index d = lo; d < hi; ++d)
      if (m.equation[size_t(d)] < 0) put(d, d, decoupled_diagonal);
    std::vector<HYPRE_Int> ncols(static_cast<size_t>(r1 - r0));
    std::vector<HYPRE_BigInt> rows(static_cast<size_t>(r1 - r0));
    for (Index r = r0; r < r1; ++r) {
      ncols[size_t(r - r0)] = HYPRE_Int(row_size[size_t(r)]);
      rows[size_t(r - r0)] = HYPRE_BigInt(first + r);
    }
    check_hypre(HYPRE_IJMatrixSetValues(m.A_ij, HYPRE_Int(r1 - r0), ncols.data(), rows.data(),
                                        columns.data(), values.data()),
                "HYPRE_IJMatrixSetValues");
    local_nonzeros += entries;
    r0 = r1;
  }
  check_hypre(HYPRE_IJMatrixAssemble(m.A_ij), "HYPRE_IJMatrixAssemble");
  void* object = nullptr;
  check_hypre(HYPRE_IJMatrixGetObject(m.A_ij, &object), "HYPRE_IJMatrixGetObject");
  m.A = static_cast<HYPRE_ParCSRMatrix>(object);

  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n_dof);
  m.b = m.make_zero_vector(m.b_ij, zero);
  m.x = m.make_zero_vector(m.x_ij, zero);
  m.r = m.make_zero_vector(m.r_ij, zero);
  m.p = m.make_zero_vector(m.p_ij, zero);
  m.s = m.make_zero_vector(m.s_ij, zero);

  // BoomerAMG for 3D elasticity (see the header): systems AMG with nodal
  // coarsening, interpolation augmented by the rotations.
  check_hypre(HYPRE_BoomerAMGCreate(&m.amg), "HYPRE_BoomerAMGCreate");
  HYPRE_BoomerAMGSetPrintLevel(m.amg, options_.hypre_print_level >= 1 ? 1 : 0);
  HYPRE_BoomerAMGSetMaxIter(m.amg, 1);  // one V-cycle per preconditioner application
  HYPRE_BoomerAMGSetTol(m.amg, 0.0);
  HYPRE_BoomerAMGSetMaxLevels(m.amg, options_.max_levels);
  HYPRE_BoomerAMGSetCoarsenType(m.amg, 10);  // HMIS
  HYPRE_BoomerAMGSetInterpType(m.amg, 6);    // extended+i
  HYPRE_BoomerAMGSetPMaxElmts(m.amg, 4);
  HYPRE_BoomerAMGSetAggNumLevels(m.amg, 0);  // no aggressive coarsening: robust for systems
  HYPRE_BoomerAMGSetRelaxType(m.amg, 8);     // l1-scaled symmetric Gauss-Seidel (SPD for PCG)
  HYPRE_BoomerAMGSetNumSweeps(m.amg, 1);
  HYPRE_BoomerAMGSetStrongThreshold(m.amg, options_.strong_threshold);
  HYPRE_BoomerAMGSetNumFunctions(m.amg, 3);
  HYPRE_BoomerAMGSetNodal(m.amg, 4);  // row-sum norm of the 3 x 3 nodal blocks
  HYPRE_BoomerAMGSetNodalDiag(m.amg, 1);
  if (options_.rigid_body_modes) {
    const Eigen::MatrixXd all_modes = rigid_body_modes(nodes);
    for (int k = 3; k < 6; ++k) {  // the rotations (translations: see the header)
      Eigen::VectorXd mode = all_modes.col(k);
      HYPRE_IJVector v = m.make_vector();
      m.set_vector(v, mode.data());
      m.mode_ij.push_back(v);
      HYPRE_IJVectorGetObject(v, &object);
      m.modes.push_back(static_cast<HYPRE_ParVector>(object));
    }
    HYPRE_BoomerAMGSetInterpVecVariant(m.amg, 2);  // GM variant 2
    HYPRE_BoomerAMGSetInterpVecQMax(m.amg, 4);
    HYPRE_BoomerAMGSetSmoothInterpVectors(m.amg, 1);
    HYPRE_BoomerAMGSetInterpVectors(m.amg, HYPRE_Int(m.modes.size()), m.modes.data());
  }

  HYPRE_Int setup_code = HYPRE_BoomerAMGSetup(m.amg, m.A, m.b, m.x);
  if (setup_code != 0 && options_.rigid_body_modes && (setup_code & HYPRE_ERROR_ARG) &&
      hypre_ParAMGDataNumLevels(static_cast<hypre_ParAMGData*>(static_cast<void*>(m.amg))) > 1) {
    // hypre 2.26 leaves an argument-error flag from inside the GM
    // interpolation on some meshes although the hierarchy is complete; the
    // solve is still judged by PCG's convergence and the residual check.
    if (log_ && m.rank == 0)
      log_->info("  AMG set-up: hypre flagged an argument error in the rigid-body-mode "
                 "interpolation (code {}); hierarchy complete, continuing",
                 int(setup_code));
    HYPRE_ClearAllErrors();
    setup_code = 0;
  }
  check_hypre(setup_code, "HYPRE_BoomerAMGSetup");

  // Hierarchy summary.
  auto* amg_data = static_cast<hypre_ParAMGData*>(static_cast<void*>(m.amg));
  stats_ = AmgStatistics{};
  stats_.levels = hypre_ParAMGDataNumLevels(amg_data);
  double level_nonzeros = 0.0, fine_nonzeros = 0.0;
  for (int l = 0; l < stats_.levels; ++l) {
    hypre_ParCSRMatrix* Al = hypre_ParAMGDataAArray(amg_data)[l];
    hypre_ParCSRMatrixSetDNumNonzeros(Al);
    const double nnz = hypre_ParCSRMatrixDNumNonzeros(Al);
    if (l == 0) fine_nonzeros = nnz;
    level_nonzeros += nnz;
  }
  stats_.operator_complexity = fine_nonzeros > 0 ? level_nonzeros / fine_nonzeros : 0.0;
  stats_.equations = K.rows();
  stats_.system_rows = n_dof;
  std::int64_t all_nonzeros = local_nonzeros;
  MPI_Allreduce(&local_nonzeros, &all_nonzeros, 1, MPI_INT64_T, MPI_SUM, m.comm);
  stats_.matrix_nonzeros = all_nonzeros;
  stats_.ranks = m.size;
  stats_.setup_seconds = clock.seconds();
  if (log_ && m.rank == 0)
    log_->info("  AMG set-up (hypre BoomerAMG, nodal systems AMG{}, {} rank{}): {} equations "
               "({} rows with supports), nnz {}, {} levels, operator complexity {:.2f}, {:.2f} s",
               m.modes.empty() ? "" : " + 3 rigid-body rotations", m.size, m.size == 1 ? "" : "s",
               stats_.equations, stats_.system_rows, stats_.matrix_nonzeros, stats_.levels,
               stats_.operator_complexity, stats_.setup_seconds);
}

// Preconditioned conjugate gradients from x = 0, step by step as hypre's
// hypre_PCGSolve (krylov/pcg.c) with the options the hypre driver had here
// (TwoNorm 0, RecomputeResidual 1, no absolute, residual-change or
// convergence-factor test), so the iterates and the iteration count are
// those of HYPRE_ParCSRPCGSolve; our own loop only so that progress can be
// reported between iterations. C is one BoomerAMG V-cycle from zero.
//   gamma_0 = (r_0, C r_0), r_0 = b;  p = C r_0
//   per iteration i: s = A p, alpha = gamma / (s, p), x += alpha p,
//     r -= alpha s, gamma = (r, C r); stop when gamma < tol^2 (b, C b),
//     confirmed with the recomputed r = b - A x (then gamma and C r are
//     those of the true residual, also when the check fails and PCG goes
//     on); p = C r + (gamma / gamma_old) p.
// A zero (s, p), or a step length or gamma that is not a positive normal
// number, stops PCG unconverged (hypre's breakdown tests, skip_break 0).
AmgSolver::Impl::PcgResult AmgSolver::Impl::pcg(double tolerance, int max_iterations,
                                                PcgProgress* progress) const {
  auto matvec = [&](double alpha, HYPRE_ParVector in, double beta, HYPRE_ParVector out) {
    check_hypre(HYPRE_ParCSRMatrixMatvec(alpha, A, in, beta, out), "HYPRE_ParCSRMatrixMatvec");
  };
  auto dot = [](HYPRE_ParVector u, HYPRE_ParVector v) {  // over all ranks of the communicator
    HYPRE_Real product = 0.0;
    check_hypre(HYPRE_ParVectorInnerProd(u, v, &product), "HYPRE_ParVectorInnerProd");
    return double(product);
  };
  auto axpy = [](double alpha, HYPRE_ParVector u, HYPRE_ParVector v) {  // v += alpha u
    check_hypre(HYPRE_ParVectorAxpy(alpha, u, v), "HYPRE_ParVectorAxpy");
  };
  auto copy = [](HYPRE_ParVector from, HYPRE_ParVector to) {
    check_hypre(HYPRE_ParVectorCopy(from, to), "HYPRE_ParVectorCopy");
  };
  auto precondition = [&](HYPRE_ParVector in, HYPRE_ParVector out) {  // out = C in
    check_hypre(HYPRE_ParVectorSetConstantValues(out, 0.0), "HYPRE_ParVectorSetConstantValues");
    check_hypre(HYPRE_BoomerAMGSolve(amg, A, in, out), "HYPRE_BoomerAMGSolve");
  };
  auto true_residual = [&] {  // r = b - A x
    copy(b, r);
    matvec(-1.0, x, 1.0, r);
  };

  precondition(b, p);
  const double b_norm_squared = dot(p, b);  // (b, C b)
  require(std::isfinite(b_norm_squared) && b_norm_squared > 0.0,
          "AMG-preconditioned CG: (b, C b) = {} for a nonzero right-hand side (non-finite "
          "input, or a preconditioner that is not positive definite)",
          b_norm_squared);
  const double eps = tolerance * tolerance;
  true_residual();
  precondition(r, p);
  double gamma = dot(r, p);
  require(std::isfinite(gamma), "AMG-preconditioned CG: (r, C r) = {} at the start", gamma);
  double r_norm_squared = gamma;  // (r, C r) of the last iterate
  PcgResult result;
  int i = 0;
  while (i < max_iterations) {
    ++i;
    matvec(1.0, p, 0.0, s);
    const double sp = dot(s, p);
    if (sp == 0.0) {
      result.breakdown = "(A p, p) = 0";
      break;
    }
    const double alpha = gamma / sp;
    if (!(alpha >= HYPRE_REAL_MIN)) {
      result.breakdown = "step length not a positive normal number";
      break;
    }
    const double gamma_old = gamma;
    axpy(alpha, p, x);
    axpy(-alpha, s, r);
    precondition(r, s);
    gamma = r_norm_squared = dot(r, s);
    bool converged = r_norm_squared / b_norm_squared < eps;
    if (converged) {  // hypre's RecomputeResidual: only the true residual counts
      true_residual();
      precondition(r, s);
      gamma = r_norm_squared = dot(r, s);
      converged = r_norm_squared / b_norm_squared < eps;
    }
    if (progress) progress->iteration(i, std::sqrt(r_norm_squared / b_norm_squared));
    if (converged) {
      result.converged = true;
      break;
    }
    if (!(gamma >= HYPRE_REAL_MIN)) {
      result.breakdown = "(r, C r) not a positive normal number";
      break;
    }
    check_hypre(HYPRE_ParVectorScale(gamma / gamma_old, p), "HYPRE_ParVectorScale");
    axpy(1.0, s, p);
  }
  result.iterations = i;
  result.relative_residual = std::sqrt(r_norm_squared / b_norm_squared);
  return result;
}

Eigen::MatrixXd AmgSolver::solve(const Eigen::MatrixXd& rhs) {
  Impl& m = *impl_;
  require(m.amg != nullptr, "AMG solve called before setup");
  const SymmetricUpperMatrix& K = *m.matrix;
  require(rhs.rows() == K.rows(), "AMG: right-hand side has {} rows, K_ff {}", rhs.rows(),
          K.rows());
  Stopwatch block_clock;
  const Index n_dof = Index(m.equation.size()), cases = rhs.cols();
  Eigen::MatrixXd X(K.rows(), cases);
  stats_.iterations.assign(size_t(cases), 0);
  stats_.relative_residuals.assign(size_t(cases), 0.0);
  stats_.solve_seconds.assign(size_t(cases), 0.0);
  Eigen::VectorXd full(n_dof), local(m.last_row - m.first_row);
  std::vector<HYPRE_BigInt> rows(static_cast<size_t>(m.last_row - m.first_row));
  std::iota(rows.begin(), rows.end(), HYPRE_BigInt(m.first_row));
  // Progress lines on the rank that prints (the residuals are global).
  std::optional<PcgProgress> progress;
  if (log_ && m.rank == 0) progress.emplace(*log_, options_.progress_interval_s);
  for (Index k = 0; k < cases; ++k) {
    Stopwatch clock;
    const double b_norm = rhs.col(k).norm();
    if (b_norm == 0.0) {  // PCG would divide by ||b||
      X.col(k).setZero();
      continue;
    }
    for (Index d = 0; d < n_dof; ++d) {
      const Index eq = m.equation[size_t(d)];
      full[d] = eq >= 0 ? rhs(eq, k) : 0.0;
    }
    m.set_vector(m.b_ij, full.data());
    check_hypre(HYPRE_ParVectorSetConstantValues(m.x, 0.0), "HYPRE_ParVectorSetConstantValues");
    if (progress)
      progress->start(fmt::format("AMG-PCG column {}/{}", k + 1, cases),
                      options_.relative_tolerance);
    const Impl::PcgResult outcome = m.pcg(options_.relative_tolerance, options_.max_iterations,
                                          progress ? &*progress : nullptr);
    const int iterations = outcome.iterations;
    if (!outcome.converged)
      fail("AMG-preconditioned CG did not converge for right-hand side {} of {}: relative "
           "residual {:.3g} after {} iterations{} (tolerance {:.3g}); raise max_iterations or use "
           "the direct solver",
           k, cases, outcome.relative_residual, iterations,
           outcome.breakdown ? fmt::format(", stopped by a breakdown: {}", outcome.breakdown) : "",
           options_.relative_tolerance);
    check_hypre(HYPRE_IJVectorGetValues(m.x_ij, HYPRE_Int(rows.size()), rows.data(), local.data()),
                "HYPRE_IJVectorGetValues");
    MPI_Allgatherv(local.data(), int(local.size()), MPI_DOUBLE, full.data(), m.rows_of_rank.data(),
                   m.first_row_of_rank.data(), MPI_DOUBLE, m.comm);
    for (Index d = 0; d < n_dof; ++d) {
      const Index eq = m.equation[size_t(d)];
      if (eq >= 0) X(eq, k) = full[d];
    }
    // Independent check with the assembled K_ff: the true 2-norm residual,
    // held to the same bound as the direct solver's (CholmodOptions).
    const Eigen::VectorXd residual = K.selfadjointView<Eigen::Upper>() * X.col(k) - rhs.col(k);
    const double relative = residual.norm() / b_norm;
    require(std::isfinite(relative) && relative <= options_.max_relative_residual,
            "AMG-preconditioned CG: right-hand side {} of {} ended with relative residual {:.3g} "
            "after {} iterations, above the {:.3g} allowed",
            k, cases, relative, iterations, options_.max_relative_residual);
    stats_.iterations[size_t(k)] = iterations;
    stats_.relative_residuals[size_t(k)] = relative;
    stats_.solve_seconds[size_t(k)] = clock.seconds();
  }
  stats_.last_solve_seconds = block_clock.seconds();
  stats_.total_solve_seconds += stats_.last_solve_seconds;
  stats_.total_rhs += cases;
  if (log_ && m.rank == 0)
    log_->info("  AMG-PCG solve: {} right-hand side{}, {} to {} iterations, max relative residual "
               "{:.2e}, {:.2f} s ({:.2f} s per right-hand side)",
               cases, cases == 1 ? "" : "s",
               cases ? *std::min_element(stats_.iterations.begin(), stats_.iterations.end()) : 0,
               stats_.max_iterations(), stats_.max_relative_residual(), stats_.last_solve_seconds,
               cases ? stats_.last_solve_seconds / double(cases) : 0.0);
  return X;
}

}  // namespace kinetofem::fem
