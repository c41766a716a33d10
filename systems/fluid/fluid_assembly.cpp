#include "systems/fluid/fluid_assembly.hpp"

#include "engine/schedule/parallel.hpp"
#include "kernels/element_gather.hpp"

namespace rift::fluid {

FluidAssembly::FluidAssembly(std::span<const int32_t> tet_nodes, std::span<const int32_t> slot,
                             const CsrMatrix& pattern, size_t n_nodes)
    : n_tets_(tet_nodes.size() / 4), n_nodes_(n_nodes) {
  entry_ptr_.assign(pattern.nnz() + 1, 0);
  entry_pos_.assign(slot.size(), 0);
  kernels::build_gather_positions(slot, entry_ptr_, entry_pos_);
  node_ptr_.assign(n_nodes + 1, 0);
  corner_pos_.assign(tet_nodes.size(), 0);
  kernels::build_gather_positions(tet_nodes, node_ptr_, corner_pos_);
  elem_matrix_.assign(16 * n_tets_, 0.0);
  elem_corner_.assign(12 * n_tets_, 0.0);
}

void FluidAssembly::gather_entries(std::span<double> values) {
  parallel_for(values.size(), kEntryGrain, [&](size_t begin, size_t end) {
    kernels::gather_sum(entry_ptr_, elem_matrix_, values, begin, end);
  });
}

void FluidAssembly::momentum(const kernels::FluidMomentumArgs& a) {
  const kernels::ElementOutput out = output();
  parallel_for(n_tets_, kTetGrain,
               [&](size_t begin, size_t end) { kernels::fluid_momentum_elements(a, out, begin, end); });
  gather_entries(a.matrix_values);
  parallel_for(n_nodes_, kNodeGrain, [&](size_t begin, size_t end) {
    kernels::gather_sum3(node_ptr_, elem_corner_, a.rhs, begin, end);
  });
}

void FluidAssembly::laplacian_matrix(const kernels::ScalarLaplacianArgs& a) {
  const kernels::ElementOutput out = output();
  parallel_for(n_tets_, kTetGrain,
               [&](size_t begin, size_t end) { kernels::scalar_laplacian_elements(a, out, begin, end); });
  gather_entries(a.matrix_values);
  kernels::scalar_laplacian_fix_rows(a);
}

void FluidAssembly::pressure_rhs(const kernels::FluidPressureRhsArgs& a, std::span<double> rhs) {
  const kernels::ElementOutput out = output();
  parallel_for(n_tets_, kTetGrain,
               [&](size_t begin, size_t end) { kernels::fluid_pressure_rhs_elements(a, out, begin, end); });
  parallel_for(n_nodes_, kNodeGrain, [&](size_t begin, size_t end) {
    kernels::gather_sum(node_ptr_, elem_corner_, rhs, begin, end);
  });
}

void FluidAssembly::weighted_gradient(const kernels::WeightedGradientArgs& a, std::span<double> grad) {
  const kernels::ElementOutput out = output();
  parallel_for(n_tets_, kTetGrain,
               [&](size_t begin, size_t end) { kernels::p1_weighted_gradient_elements(a, out, begin, end); });
  parallel_for(n_nodes_, kNodeGrain, [&](size_t begin, size_t end) {
    kernels::gather_sum3(node_ptr_, elem_corner_, grad, begin, end);
  });
}

}  // namespace rift::fluid
