#pragma once
// The fluid's per-tet loops that scatter into shared rows (momentum matrix and right-hand side, pressure
// matrix, pressure right-hand side, projected gradients), run in parallel and bitwise deterministic.
// The tets are cut into fixed blocks of kTetGrain consecutive tets, and the blocks are coloured once so
// that no two blocks of a colour share a node. Colours run one after the other; the blocks of a colour
// run in parallel, each scattering its tets in order with the sequential kernel. Two blocks that write
// the same row never run at the same time, and every row receives its contributions in the same order
// (colour by colour, tets in order within the one block of each colour that touches it) whatever the
// thread count: no atomics, no per-thread copies, and the traffic of the sequential loop. Meshes are
// numbered along a space-filling curve (docs/architecture.md), so consecutive tets form compact blocks
// and a handful of colours suffice.
// Blocks and colours are built once for a fixed mesh; the calls allocate nothing. Loops run in the
// caller's TBB arena (engine/schedule/parallel.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "kernels/fluid_element.hpp"

namespace rift::fluid {

class FluidAssembly {
 public:
  FluidAssembly() = default;
  FluidAssembly(std::span<const int32_t> tet_nodes, size_t n_nodes);

  // kernels::fluid_assemble_momentum, written (not accumulated) into a.matrix_values and a.rhs.
  void momentum(const kernels::FluidMomentumArgs& a) const;
  // The matrix of kernels::scalar_laplacian_assemble, written into a.matrix_values (a.rhs unused).
  void laplacian_matrix(const kernels::ScalarLaplacianArgs& a) const;
  // kernels::fluid_pressure_rhs, written into rhs (1 per node).
  void pressure_rhs(const kernels::FluidPressureRhsArgs& a, std::span<double> rhs) const;
  // kernels::p1_weighted_gradient, written into grad (3 per node).
  void weighted_gradient(const kernels::WeightedGradientArgs& a, std::span<double> grad) const;
  // kernels::convective_derivative_projection of w, written into out (3 per node).
  void convective_projection(std::span<const int32_t> tet_nodes, std::span<const double> volume,
                             std::span<const double> grad, std::span<const double> w,
                             std::span<double> out) const;

  size_t colours() const { return colour_ptr_.empty() ? 0 : colour_ptr_.size() - 1; }
  // Fixed block size (independent of the thread count, as determinism needs).
  static constexpr size_t kTetGrain = 1024;

 private:
  // body(begin, end) on every block's tet range, colour by colour, a colour's blocks in parallel.
  template <class Body>
  void for_each_block(const Body& body) const;

  size_t n_tets_ = 0;
  // The blocks of colour c are colour_blocks_[colour_ptr_[c] .. colour_ptr_[c + 1]), in ascending order.
  std::vector<int32_t> colour_ptr_, colour_blocks_;
};

}  // namespace rift::fluid
