#pragma once
// The fluid's per-tet loops that scatter into shared rows (momentum matrix and right-hand side, pressure
// matrix, pressure right-hand side, projected gradients), run in parallel and bitwise deterministic: an
// element pass over fixed blocks of tets writes every tet's contributions into positions of its own in a
// buffer sorted by target, then a gather pass over fixed blocks of targets (CSR entries, nodes) sums each
// target's run of contributions, which lie in tet order (kernels/element_gather.hpp). No double is
// accumulated across threads, so the result is the same on 1, 2 or 8 threads, and equal to the sequential
// loop's bit for bit (the order is the same). Maps and buffers are built once for a fixed mesh and pattern;
// the calls allocate nothing. Loops run in the caller's TBB arena (engine/schedule/parallel.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "engine/linear/csr_matrix.hpp"
#include "kernels/fluid_element.hpp"

namespace rift::fluid {

class FluidAssembly {
 public:
  FluidAssembly() = default;
  // tet_nodes: 4 per tet; slot: 16 per tet into the values of pattern (p1_tet_slots).
  FluidAssembly(std::span<const int32_t> tet_nodes, std::span<const int32_t> slot, const CsrMatrix& pattern,
                size_t n_nodes);

  // kernels::fluid_assemble_momentum, but written (not accumulated) into a.matrix_values and a.rhs.
  void momentum(const kernels::FluidMomentumArgs& a);
  // The matrix of kernels::scalar_laplacian_assemble, written into a.matrix_values (a.rhs unused).
  void laplacian_matrix(const kernels::ScalarLaplacianArgs& a);
  // kernels::fluid_pressure_rhs, written into rhs (1 per node).
  void pressure_rhs(const kernels::FluidPressureRhsArgs& a, std::span<double> rhs);
  // kernels::p1_weighted_gradient, written into out (3 per node).
  void weighted_gradient(const kernels::WeightedGradientArgs& a, std::span<double> out);

  // Fixed block sizes (independent of the thread count, as determinism needs).
  static constexpr size_t kTetGrain = 1024, kEntryGrain = 4096, kNodeGrain = 1024;

 private:
  void gather_entries(std::span<double> values);
  kernels::ElementOutput output() { return {entry_pos_, corner_pos_, elem_matrix_, elem_corner_}; }

  size_t n_tets_ = 0, n_nodes_ = 0;
  // Runs per CSR entry (of the tets' 16 t + 4 i + j) and per node (of their corners 4 t + a), and where
  // each of those sources goes.
  std::vector<int32_t> entry_ptr_, entry_pos_, node_ptr_, corner_pos_;
  std::vector<double> elem_matrix_, elem_corner_;  // 16 and 12 per tet
};

}  // namespace rift::fluid
