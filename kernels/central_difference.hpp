#pragma once
// Explicit central-difference update of node velocities and positions (leapfrog form):
//   v(t+dt/2) = v(t-dt/2) + dt * (f / m + g)
//   x(t+dt)   = x(t) + dt * v(t+dt/2)
// and the force column is zeroed for the next step, fused here so the node arrays are streamed once.
// Constrained components (fixed or prescribed velocity) are skipped by a per-component mask.
#include <cstdint>
#include <span>

namespace rift::kernels {

struct CentralDifferenceInput {
  double dt;
  double gravity[3];
};

// x, v, f: 3 values per node; inv_mass: 1 per node; free_mask: 3 per node, 1 = integrate, 0 = held.
// Nodes [begin, end) are updated.
void central_difference(const CentralDifferenceInput& in, std::span<double> x, std::span<double> v,
                        std::span<double> f, std::span<const double> inv_mass,
                        std::span<const uint8_t> free_mask, size_t begin, size_t end);

}  // namespace rift::kernels
