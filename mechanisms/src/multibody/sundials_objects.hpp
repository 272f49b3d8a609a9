#pragma once
// Private to the mechanisms library: RAII owners of the SUNDIALS objects used by
// the integrators (context, serial vectors, dense matrix + solver, IDAS and
// CVODES memory). Constructors go through sundials_check.
#include <Eigen/Core>
#include <cvodes/cvodes.h>
#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "kinetofem/mechanisms/multibody/sundials_check.hpp"

namespace kinetofem::mech::sundials {

struct Context {
  SUNContext ctx = nullptr;
  Context() { sundials_check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create"); }
  ~Context() { SUNContext_Free(&ctx); }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
};

struct Vector {
  N_Vector v = nullptr;
  Vector(sunindextype n, SUNContext ctx) : v(sundials_check_ptr(N_VNew_Serial(n, ctx), "N_VNew_Serial")) {
    N_VConst(0.0, v);
  }
  ~Vector() { N_VDestroy(v); }
  Vector(const Vector&) = delete;
  Vector& operator=(const Vector&) = delete;
  double* data() { return N_VGetArrayPointer(v); }
  Eigen::Map<Eigen::VectorXd> map() { return {data(), static_cast<Eigen::Index>(N_VGetLength(v))}; }
};

struct DenseSolver {
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  DenseSolver(sunindextype n, N_Vector y, SUNContext ctx) {
    matrix = sundials_check_ptr(SUNDenseMatrix(n, n, ctx), "SUNDenseMatrix");
    solver = SUNLinSol_Dense(y, matrix, ctx);
    if (solver == nullptr) {
      SUNMatDestroy(matrix);
      fail("SUNDIALS SUNLinSol_Dense returned null");
    }
  }
  ~DenseSolver() {
    SUNLinSolFree(solver);
    SUNMatDestroy(matrix);
  }
  DenseSolver(const DenseSolver&) = delete;
  DenseSolver& operator=(const DenseSolver&) = delete;
};

// SUNDIALS prints its own error messages to stderr by default; ours are
// thrown as one-line Errors (flag and time), so its printing is switched off.
struct IdaMemory {
  void* mem = nullptr;
  explicit IdaMemory(SUNContext ctx) : mem(sundials_check_ptr(IDACreate(ctx), "IDACreate")) {
    IDASetErrFile(mem, nullptr);
  }
  ~IdaMemory() { IDAFree(&mem); }
  IdaMemory(const IdaMemory&) = delete;
  IdaMemory& operator=(const IdaMemory&) = delete;
};

struct CvodeMemory {
  void* mem = nullptr;
  explicit CvodeMemory(SUNContext ctx) : mem(sundials_check_ptr(CVodeCreate(CV_BDF, ctx), "CVodeCreate")) {
    CVodeSetErrFile(mem, nullptr);
  }
  ~CvodeMemory() { CVodeFree(&mem); }
  CvodeMemory(const CvodeMemory&) = delete;
  CvodeMemory& operator=(const CvodeMemory&) = delete;
};

}  // namespace kinetofem::mech::sundials
