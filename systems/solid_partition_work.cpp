#include "systems/solid_partition_work.hpp"

namespace rift {

PartitionWork solid_partition_work(std::span<const int32_t> tet_nodes, std::span<const int32_t> node_vertex,
                                   std::span<const int32_t> joint_nodes,
                                   std::span<const int32_t> joint_tets) {
  PartitionWork work;
  work.domain = "solid";
  work.nodes = int32_t(node_vertex.size());
  work.node_bytes = kSolidGhostNodeBytes;
  work.timed = true;
  work.graph_tets.resize(tet_nodes.size() / 4);
  for (size_t t = 0; t < work.graph_tets.size(); ++t)
    for (size_t c = 0; c < 4; ++c) work.graph_tets[t][c] = node_vertex[size_t(tet_nodes[4 * t + c])];
  work.tet_weight.assign(work.graph_tets.size(), kTetWorkUnits);
  for (int32_t t : joint_tets) work.tet_weight[size_t(t)] += kJointWorkUnits / 2;
  work.elements.push_back({"tets", 4, tet_nodes, kTetWorkUnits});
  if (!joint_nodes.empty()) work.elements.push_back({"joints", 6, joint_nodes, kJointWorkUnits});
  return work;
}

}  // namespace rift
