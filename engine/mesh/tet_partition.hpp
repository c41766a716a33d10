#pragma once
// A tet mesh cut into parts of equal work, the first step of running one scene on several processes: METIS's
// multilevel k-way partition of the mesh's dual graph (each tet a vertex, each face two tets share an edge),
// which keeps the faces between parts, and so the halo each part must exchange, few.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/mesh/tet_mesh.hpp"

namespace rift {

// The dual graph in compressed rows: the tets across tet t's shared faces are
// adjacency[start[t]] .. adjacency[start[t + 1] - 1], in the order of t's faces.
struct TetDualGraph {
  std::vector<int32_t> start, adjacency;
};

TetDualGraph tet_dual_graph(std::span<const std::array<int32_t, 4>> tets);

struct TetPartition {
  int32_t parts = 1;
  std::vector<int32_t> part;         // per tet, in [0, parts)
  std::vector<int64_t> part_weight;  // per part: the sum of its tets' weights
  int64_t edge_cut = 0;              // shared faces whose two tets lie in different parts
  double imbalance = 1.0;            // the heaviest part's weight over the mean part weight
};

// `weight` per tet (empty: 1 each), e.g. more for a tet whose faces carry joints. Deterministic: METIS's
// random seed is fixed, so the same mesh and weights give the same parts on every run. Throws Error when
// parts < 1, parts exceeds the tets, a weight is not positive, or METIS fails.
TetPartition partition_tets(std::span<const std::array<int32_t, 4>> tets, int32_t parts,
                            std::span<const int32_t> weight = {});

inline TetDualGraph tet_dual_graph(const TetMesh& mesh) {
  return tet_dual_graph(mesh.tets);
}
inline TetPartition partition_tets(const TetMesh& mesh, int32_t parts, std::span<const int32_t> weight = {}) {
  return partition_tets(mesh.tets, parts, weight);
}

}  // namespace rift
