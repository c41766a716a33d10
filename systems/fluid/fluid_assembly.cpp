#include "systems/fluid/fluid_assembly.hpp"

#include <algorithm>
#include <bit>

#include "engine/schedule/parallel.hpp"
#include "kernels/fluid_convection_subscale.hpp"

namespace rift::fluid {

// Greedy colouring of the blocks in block order: a block takes the lowest colour that no earlier block
// sharing one of its nodes has. Each node keeps the set of colours of the blocks around it as a bit mask.
// More than 64 colours (a mesh numbered without locality) fall back to one colour per block: the blocks
// then run one at a time, still deterministic.
FluidAssembly::FluidAssembly(std::span<const int32_t> tet_nodes, size_t n_nodes)
    : n_tets_(tet_nodes.size() / 4) {
  const size_t blocks = (n_tets_ + kTetGrain - 1) / kTetGrain;
  std::vector<uint64_t> node_colours(n_nodes, 0);
  std::vector<int32_t> colour(blocks, 0);
  bool overflow = false;
  for (size_t b = 0; b < blocks && !overflow; ++b) {
    const size_t begin = 4 * b * kTetGrain, end = 4 * std::min(n_tets_, (b + 1) * kTetGrain);
    uint64_t used = 0;
    for (size_t k = begin; k < end; ++k) used |= node_colours[tet_nodes[k]];
    if (used == ~uint64_t{0}) {
      overflow = true;
      break;
    }
    colour[b] = std::countr_one(used);
    for (size_t k = begin; k < end; ++k) node_colours[tet_nodes[k]] |= uint64_t{1} << colour[b];
  }
  if (overflow)
    for (size_t b = 0; b < blocks; ++b) colour[b] = static_cast<int32_t>(b);
  const int32_t n_colours = blocks == 0 ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
  colour_ptr_.assign(static_cast<size_t>(n_colours) + 1, 0);
  for (int32_t c : colour) ++colour_ptr_[c + 1];
  for (size_t c = 1; c < colour_ptr_.size(); ++c) colour_ptr_[c] += colour_ptr_[c - 1];
  colour_blocks_.resize(blocks);
  std::vector<int32_t> next(colour_ptr_.begin(), colour_ptr_.end() - (n_colours > 0 ? 1 : 0));
  for (size_t b = 0; b < blocks; ++b) colour_blocks_[next[colour[b]]++] = static_cast<int32_t>(b);
}

template <class Body>
void FluidAssembly::for_each_block(const Body& body) const {
  for (size_t c = 0; c + 1 < colour_ptr_.size(); ++c) {
    const int32_t* list = colour_blocks_.data() + colour_ptr_[c];
    parallel_for(static_cast<size_t>(colour_ptr_[c + 1] - colour_ptr_[c]), 1, [&](size_t first, size_t last) {
      for (size_t i = first; i < last; ++i) {
        const size_t b = static_cast<size_t>(list[i]);
        body(b * kTetGrain, std::min(n_tets_, (b + 1) * kTetGrain));
      }
    });
  }
}

void FluidAssembly::momentum(const kernels::FluidMomentumArgs& a) const {
  std::fill(a.matrix_values.begin(), a.matrix_values.end(), 0.0);
  std::fill(a.rhs.begin(), a.rhs.end(), 0.0);
  for_each_block([&](size_t begin, size_t end) { kernels::fluid_assemble_momentum(a, begin, end); });
}

void FluidAssembly::laplacian_matrix(const kernels::ScalarLaplacianArgs& a) const {
  std::fill(a.matrix_values.begin(), a.matrix_values.end(), 0.0);
  for_each_block([&](size_t begin, size_t end) { kernels::scalar_laplacian_matrix(a, begin, end); });
  kernels::scalar_laplacian_fix_rows(a);
}

void FluidAssembly::pressure_rhs(const kernels::FluidPressureRhsArgs& a, std::span<double> rhs) const {
  std::fill(rhs.begin(), rhs.end(), 0.0);
  for_each_block([&](size_t begin, size_t end) { kernels::fluid_pressure_rhs(a, rhs, begin, end); });
}

void FluidAssembly::weighted_gradient(const kernels::WeightedGradientArgs& a, std::span<double> grad) const {
  std::fill(grad.begin(), grad.end(), 0.0);
  for_each_block([&](size_t begin, size_t end) { kernels::p1_weighted_gradient(a, grad, begin, end); });
}

void FluidAssembly::convective_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                                          std::span<const double> grad, std::span<const double> w,
                                          std::span<double> out) const {
  std::fill(out.begin(), out.end(), 0.0);
  for_each_block([&](size_t begin, size_t end) {
    kernels::convective_derivative_projection(tet_nodes, volume, grad, w, out, begin, end);
  });
}

}  // namespace rift::fluid
