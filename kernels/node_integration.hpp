#pragma once
// The node pass of an explicit step, fused so node arrays are streamed once:
//   1. gather: the total force on a node is the sum of the corner forces that elements and loads
//      wrote into their own rows (each node lists its "slots"; the order is fixed at set-up, so the
//      sum is bitwise identical on any thread count, and no atomics are needed), then the rows that
//      producers gathered per node themselves (NodeIntegrationArgs::node_rows), in a fixed order;
//   2. central difference (leapfrog): v(t+dt/2) = v(t-dt/2) + dt (f/m + g);  x(t+dt) = x(t) + dt v(t+dt/2);
//      held components take the prescribed velocity of their boundary condition instead;
//   3. work: each force source's work over the step, f(t) . dx with dx = dt (v(t-dt/2) + v(t+dt/2)) / 2
//      (the trapezoid increment that makes the sum of all works equal the change of the half-step kinetic
//      energy exactly). The external work includes gravity and the reactions of held components.
#include <cstdint>
#include <span>

namespace rift::kernels {

// Corner forces of up to three producers, seen as one list of slots: source k covers the slots
// [first_slot[k], first_slot[k + 1]) (first_slot[3] = total slot count). Sources 0 and 1 are internal
// forces (tets, joints), source 2 external (loaded faces).
// Sources 0 and 2 hold 3 doubles per slot. Source 1 holds one 3-vector per pair of slots, for forces that
// come in equal and opposite pairs (a joint's facing corners): slot first_slot[1] + 2 r reads row r as it
// is, slot first_slot[1] + 2 r + 1 reads it negated. A joint then writes and the pass reads 9 doubles
// instead of 18; negation is exact, so the sums are those of a row of 18.
struct ForceSlots {
  std::span<const double> source[3];
  int64_t first_slot[4];
  std::span<const int32_t> node_range;  // 2 per node: [begin, end) of its entries in `slots`
  std::span<const int32_t> slots;
};

struct NodeIntegrationArgs {
  double dt;
  double gravity[3];
  std::span<double> x, v;                  // 3 per node
  std::span<double> f;                     // 3 per node, or empty: overwritten with the gathered total force
  std::span<const double> mass, inv_mass;  // 1 per node (inv_mass 0 for a massless node: it then only
                                           // follows BCs)
  std::span<const uint8_t> free_mask;      // 3 per node: 1 integrate, 0 held at the prescribed velocity
  std::span<const int32_t> held_velocity;  // 3 per node: condition index per component (-1: velocity 0)
  std::span<const double> prescribed;      // 3 per boundary condition: velocity at t + dt/2
  // c [1/s]: a drag -c m v on every free component (dynamic relaxation). The damped leapfrog
  //   v(t+dt/2) = ((1 - c dt/2) v(t-dt/2) + dt (f/m + g)) / (1 + c dt/2)
  // is the undamped one with the drag taken at the mean of the two half-step velocities, so its work,
  // -c m v_mean . dx, keeps the energy identity exact; it is booked as `damping` (dissipated, >= 0).
  double mass_damping = 0.0;
  // Forces a producer has already gathered per node (3 per node), added after the slots, in array
  // order: to the external forces (source 2), or, when `internal`, to the internal forces as a fourth
  // source whose work is booked as work[3] (contact).
  struct NodeRows {
    std::span<const double> force;
    bool internal = false;
  };
  static constexpr size_t kMaxNodeRows = 4;
  NodeRows node_rows[kMaxNodeRows] = {};
  size_t node_row_count = 0;
};

struct NodeStepResult {
  size_t non_finite = 0;  // nodes whose new position or velocity is not finite (0 in a healthy run)
  // work of source 0, source 1, everything external, and the internal node rows [J]
  double work[4] = {0.0, 0.0, 0.0, 0.0};
  double damping = 0.0;  // energy the mass damping took out [J]
  NodeStepResult& operator+=(const NodeStepResult& o) {
    non_finite += o.non_finite;
    damping += o.damping;
    for (int k = 0; k < 4; ++k) work[k] += o.work[k];
    return *this;
  }
};

// Nodes [begin, end). The sums continue from `so_far` node by node, so a range cut into consecutive calls,
// each passed the previous result, books the same bits as one call over the whole range.
NodeStepResult integrate_nodes(const NodeIntegrationArgs& a, const ForceSlots& s, size_t begin, size_t end,
                               const NodeStepResult& so_far = {});

// The nodes of tets that own them (a fracture zone's: corner k of tet e is node first_node + 4 (e -
// tet_first) + k, and no other tet acts on it), gathered per tet instead of per node: the tet's own corner
// forces, then each of its faces' joint row once (9 values) handed to the three corners on that face, then
// loaded faces through the nodes' slot lists where `loaded` says there are some. A node's sum then runs
// tet, joints in face order, loads, where the slot-list pass runs tet, joints in slot order, loads: the
// same terms, added in another order when a node sits in two or three joints.
struct PrivateTetForces {
  std::span<const double> tet_force;  // 12 per tet, tet `tet_first` first (the tet pass's scratch)
  size_t tet_first = 0;
  size_t first_node = 0;                  // node of corner 0 of tet `tet_first`
  std::span<const double> joint_rows;     // 9 per joint: forces on its side-B corners (ForceSlots source 1)
  std::span<const int32_t> face_joint;    // 4 per tet (all tets): 2 j + 1 if the tet is the joint's side A
                                          // (it takes the rows negated), 2 j if side B; -1: no joint
  std::span<const uint8_t> face_corners;  // 4 per tet: the tet corner of the joint's corner i, bits 2i, 2i+1
  std::span<const uint8_t> loaded;        // 1 per tet: some node of it has loaded-face slots
};

// Tets [begin, end) of p, their nodes integrated as integrate_nodes does (same update, same work booking).
// s gives the slot lists, read only for loaded tets. Continues from so_far as integrate_nodes does.
NodeStepResult integrate_private_tets(const NodeIntegrationArgs& a, const PrivateTetForces& p,
                                      const ForceSlots& s, size_t begin, size_t end,
                                      const NodeStepResult& so_far = {});

}  // namespace rift::kernels
