#pragma once
// hypre BoomerAMG-preconditioned conjugate gradients on a symmetric positive definite CsrMatrix (the fluid
// pressure equation). Serial: one MPI rank on MPI_COMM_SELF.
//
// Debian's libhypre 2.26 is built against OpenMPI, so hypre needs MPI even in a serial program.
// hypre_runtime_init() starts MPI (engine/distributed/mpi_runtime.hpp) and then HYPRE_Init(); both are
// finalised at exit. Call it before any hypre object is made (HypreAmgPcg does).
//
// Default settings: fluid.md 5.3 (hypre manual, 3-D diffusion): HMIS coarsening (10), extended+i
// interpolation (6) truncated to 4 per row, strong threshold 0.5, one level of aggressive coarsening,
// l1-symmetric Gauss-Seidel smoothing (8, symmetric so PCG-safe), V(1,1), one V-cycle per PCG iteration.
// The AMG hierarchy is rebuilt only when set_matrix is called (the pressure matrix is constant while the
// mesh and the absorption are).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/linear/csr_matrix.hpp"

namespace rift {

void hypre_runtime_init();

struct AmgPcgSettings {
  double rel_tol = 1e-8;  // on ||r||_2 / ||b||_2
  double abs_tol = 0.0;   // on ||r||_2
  int max_iterations = 200;
  double strong_threshold = 0.5;
  int coarsen_type = 10;  // HMIS
  int interp_type = 6;    // extended+i
  int p_max = 4;          // interpolation truncation (elements per row)
  int agg_levels = 1;     // levels of aggressive coarsening
  int relax_type = 8;     // l1-scaled symmetric Gauss-Seidel
  int print_level = 0;
};

struct AmgPcgResult {
  int iterations = 0;
  double rel_residual = 0.0;
  bool converged = false;
};

class HypreAmgPcg {
 public:
  explicit HypreAmgPcg(AmgPcgSettings settings = {});
  ~HypreAmgPcg();
  HypreAmgPcg(const HypreAmgPcg&) = delete;
  HypreAmgPcg& operator=(const HypreAmgPcg&) = delete;

  // Copies the values (and, the first time, the pattern) and rebuilds the AMG hierarchy. A later call
  // must have the same pattern.
  void set_matrix(const CsrMatrix& a);
  // x holds the initial guess on entry. rel_tol > 0 replaces settings().rel_tol for this solve.
  AmgPcgResult solve(std::span<const double> b, std::span<double> x, double rel_tol = 0.0);
  const AmgPcgSettings& settings() const { return settings_; }

 private:
  struct Impl;
  Impl* impl_;
  AmgPcgSettings settings_;
};

}  // namespace rift
