#include "engine/linear/hypre_pcg.hpp"

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <HYPRE_utilities.h>
#include <mpi.h>

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

#include "engine/distributed/mpi_runtime.hpp"

namespace rift {

namespace {

void finalise_hypre() {
  HYPRE_Finalize();
}

void check(HYPRE_Int err, const char* what) {
  if (err != 0) {
    HYPRE_ClearAllErrors();
    throw std::runtime_error(std::string("hypre: ") + what + " failed (error " + std::to_string(err) + ")");
  }
}

}  // namespace

void hypre_runtime_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    mpi_runtime_init();  // registers MPI's finalisation first, so hypre's runs before it
    HYPRE_Init();
    std::atexit(finalise_hypre);
  });
}

struct HypreAmgPcg::Impl {
  HYPRE_IJMatrix a = nullptr;
  HYPRE_IJVector b = nullptr, x = nullptr;
  HYPRE_Solver pcg = nullptr, amg = nullptr;
  int32_t n = 0;
  bool needs_setup = true;
  std::vector<HYPRE_Int> rows, ncols, cols;
  std::vector<double> values;
};

HypreAmgPcg::HypreAmgPcg(AmgPcgSettings settings) : impl_(new Impl), settings_(settings) {
  hypre_runtime_init();
}

HypreAmgPcg::~HypreAmgPcg() {
  if (impl_->pcg) HYPRE_ParCSRPCGDestroy(impl_->pcg);
  if (impl_->amg) HYPRE_BoomerAMGDestroy(impl_->amg);
  if (impl_->a) HYPRE_IJMatrixDestroy(impl_->a);
  if (impl_->b) HYPRE_IJVectorDestroy(impl_->b);
  if (impl_->x) HYPRE_IJVectorDestroy(impl_->x);
  delete impl_;
}

void HypreAmgPcg::set_matrix(const CsrMatrix& m) {
  Impl& s = *impl_;
  const MPI_Comm comm = MPI_COMM_SELF;
  if (!s.a) {
    s.n = m.rows;
    check(HYPRE_IJMatrixCreate(comm, 0, m.rows - 1, 0, m.rows - 1, &s.a), "IJMatrixCreate");
    check(HYPRE_IJMatrixSetObjectType(s.a, HYPRE_PARCSR), "IJMatrixSetObjectType");
    s.rows.resize(m.rows);
    s.ncols.resize(m.rows);
    std::vector<HYPRE_Int> sizes(m.rows);
    for (int32_t i = 0; i < m.rows; ++i) {
      s.rows[i] = i;
      s.ncols[i] = m.row_ptr[i + 1] - m.row_ptr[i];
      sizes[i] = s.ncols[i];
    }
    check(HYPRE_IJMatrixSetRowSizes(s.a, sizes.data()), "IJMatrixSetRowSizes");
    s.cols.assign(m.col.begin(), m.col.end());
    for (auto* v : {&s.b, &s.x}) {
      check(HYPRE_IJVectorCreate(comm, 0, m.rows - 1, v), "IJVectorCreate");
      check(HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR), "IJVectorSetObjectType");
      check(HYPRE_IJVectorInitialize(*v), "IJVectorInitialize");
      check(HYPRE_IJVectorAssemble(*v), "IJVectorAssemble");
    }
  } else if (m.rows != s.n || m.nnz() != s.cols.size()) {
    throw std::invalid_argument("HypreAmgPcg::set_matrix: the pattern changed");
  }
  // Initialize on an assembled IJ matrix re-opens it for new coefficients (hypre reference manual).
  check(HYPRE_IJMatrixInitialize(s.a), "IJMatrixInitialize");
  check(HYPRE_IJMatrixSetValues(s.a, m.rows, s.ncols.data(), s.rows.data(), s.cols.data(), m.val.data()),
        "IJMatrixSetValues");
  check(HYPRE_IJMatrixAssemble(s.a), "IJMatrixAssemble");
  s.needs_setup = true;
}

AmgPcgResult HypreAmgPcg::solve(std::span<const double> b, std::span<double> x, double rel_tol) {
  Impl& s = *impl_;
  if (!s.a) throw std::logic_error("HypreAmgPcg::solve before set_matrix");
  check(HYPRE_IJVectorSetValues(s.b, s.n, s.rows.data(), b.data()), "IJVectorSetValues");
  check(HYPRE_IJVectorSetValues(s.x, s.n, s.rows.data(), x.data()), "IJVectorSetValues");
  HYPRE_ParCSRMatrix pa;
  HYPRE_ParVector pb, px;
  HYPRE_IJMatrixGetObject(s.a, reinterpret_cast<void**>(&pa));
  HYPRE_IJVectorGetObject(s.b, reinterpret_cast<void**>(&pb));
  HYPRE_IJVectorGetObject(s.x, reinterpret_cast<void**>(&px));
  if (s.needs_setup) {
    if (s.pcg) HYPRE_ParCSRPCGDestroy(s.pcg);
    if (s.amg) HYPRE_BoomerAMGDestroy(s.amg);
    const AmgPcgSettings& c = settings_;
    HYPRE_BoomerAMGCreate(&s.amg);
    HYPRE_BoomerAMGSetCoarsenType(s.amg, c.coarsen_type);
    HYPRE_BoomerAMGSetInterpType(s.amg, c.interp_type);
    HYPRE_BoomerAMGSetPMaxElmts(s.amg, c.p_max);
    HYPRE_BoomerAMGSetStrongThreshold(s.amg, c.strong_threshold);
    HYPRE_BoomerAMGSetAggNumLevels(s.amg, c.agg_levels);
    HYPRE_BoomerAMGSetRelaxType(s.amg, c.relax_type);
    HYPRE_BoomerAMGSetNumSweeps(s.amg, 1);
    HYPRE_BoomerAMGSetMaxIter(s.amg, 1);
    HYPRE_BoomerAMGSetTol(s.amg, 0.0);
    HYPRE_BoomerAMGSetPrintLevel(s.amg, c.print_level);
    HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &s.pcg);
    HYPRE_PCGSetTol(s.pcg, c.rel_tol);
    HYPRE_PCGSetAbsoluteTol(s.pcg, c.abs_tol);
    HYPRE_PCGSetMaxIter(s.pcg, c.max_iterations);
    HYPRE_PCGSetTwoNorm(s.pcg, 1);
    HYPRE_PCGSetPrintLevel(s.pcg, c.print_level);
    HYPRE_PCGSetPrecond(s.pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), s.amg);
    check(HYPRE_ParCSRPCGSetup(s.pcg, pa, pb, px), "PCGSetup");
    s.needs_setup = false;
  }
  HYPRE_PCGSetTol(s.pcg, rel_tol > 0.0 ? rel_tol : settings_.rel_tol);
  const HYPRE_Int err = HYPRE_ParCSRPCGSolve(s.pcg, pa, pb, px);
  // A non-converged solve sets an error flag; it is reported through the result, not thrown.
  if (err != 0) HYPRE_ClearAllErrors();
  AmgPcgResult r;
  HYPRE_Int its = 0;
  HYPRE_PCGGetNumIterations(s.pcg, &its);
  HYPRE_PCGGetFinalRelativeResidualNorm(s.pcg, &r.rel_residual);
  r.iterations = static_cast<int>(its);
  r.converged = err == 0;
  check(HYPRE_IJVectorGetValues(s.x, s.n, s.rows.data(), x.data()), "IJVectorGetValues");
  return r;
}

}  // namespace rift
