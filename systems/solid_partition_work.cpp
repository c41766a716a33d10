#include "systems/solid_partition_work.hpp"

namespace rift {

PartitionWork solid_partition_work(std::span<const int32_t> tet_nodes, std::span<const int32_t> joint_nodes,
                                   std::span<const int32_t> joint_tets, int32_t nodes) {
  PartitionWork work;
  work.nodes = nodes;
  work.node_bytes = kSolidGhostNodeBytes;
  work.tet_weight.assign(tet_nodes.size() / 4, kTetWorkUnits);
  for (int32_t t : joint_tets) work.tet_weight[size_t(t)] += kJointWorkUnits / 2;
  work.elements.push_back({"tets", 4, tet_nodes, kTetWorkUnits});
  if (!joint_nodes.empty()) work.elements.push_back({"joints", 6, joint_nodes, kJointWorkUnits});
  return work;
}

}  // namespace rift
