#pragma once
// The solid's part in splitting a run across processes (engine/mesh/halo_plan.hpp): its tets and joints as
// the elements on its nodes, and each tet's weight for the partitioner.
//
// Work units are 25 ns of one core per step, from the kernels' measured times at 1e6 elements
// (docs/performance.md, "Kernels"): a tet's forces (23.5 ns) and the central-difference update of its 4
// nodes (23.7 ns) are 2 units; a joint's forces (3 points, 54 ns) are 2 units, given half to each of its
// two tets for the partitioner. A jointed tet inside a fracture zone thus weighs 6, a tet outside 2. A
// ghost node receives its position and velocity each step: 48 bytes.
#include <cstdint>
#include <span>

#include "engine/mesh/halo_plan.hpp"

namespace rift {

inline constexpr int32_t kTetWorkUnits = 2;
inline constexpr int32_t kJointWorkUnits = 2;
inline constexpr int32_t kSolidGhostNodeBytes = 48;

// tet_nodes: 4 per tet; node_vertex: the mesh vertex each node copies (the tets on it make the continuous
// mesh the partitioner splits); joint_nodes: 6 per joint; joint_tets: the 2 tets of each joint. The spans
// must outlive the result, which points into them.
PartitionWork solid_partition_work(std::span<const int32_t> tet_nodes, std::span<const int32_t> node_vertex,
                                   std::span<const int32_t> joint_nodes, std::span<const int32_t> joint_tets);

}  // namespace rift
