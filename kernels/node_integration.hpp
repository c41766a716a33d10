#pragma once
// The node pass of an explicit step, fused so node arrays are streamed once:
//   1. gather: the total force on a node is the sum of the corner forces that elements and loads
//      wrote into their own rows (each node lists its "slots"; the order is fixed at set-up, so the
//      sum is bitwise identical on any thread count, and no atomics are needed);
//   2. central difference (leapfrog): v(t+dt/2) = v(t-dt/2) + dt (f/m + g);  x(t+dt) = x(t) + dt v(t+dt/2);
//      held components take the prescribed velocity of their boundary condition instead.
#include <cstdint>
#include <span>

namespace rift::kernels {

// Corner forces of all producers, seen as one list of slots: slot s < split_slot reads
// primary[3s..3s+2], otherwise secondary[3(s - split_slot)..].
struct ForceSlots {
  std::span<const double> primary;    // e.g. tet corner forces, 12 per tet = 4 slots
  std::span<const double> secondary;  // e.g. loaded-face corner forces, 9 per face = 3 slots
  int64_t split_slot;
  std::span<const int32_t> node_range;  // 2 per node: [begin, end) of its entries in `slots`
  std::span<const int32_t> slots;
};

struct NodeIntegrationArgs {
  double dt;
  double gravity[3];
  std::span<double> x, v, f;               // 3 per node; f is overwritten with the gathered total force
  std::span<const double> inv_mass;        // 1 per node (0 for a massless node: it then only follows BCs)
  std::span<const uint8_t> free_mask;      // 3 per node: 1 integrate, 0 held at the prescribed velocity
  std::span<const int32_t> held_velocity;  // 1 per node: index into prescribed (-1: none, velocity 0)
  std::span<const double> prescribed;      // 3 per boundary condition: velocity at t + dt/2
};

// Returns the number of nodes whose new position or velocity is not finite (0 in a healthy run).
size_t integrate_nodes(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end);

}  // namespace rift::kernels
