#include "engine/mesh/tet_partition.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>
#include <unordered_map>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_faces.hpp"

namespace rift {

TetDualGraph tet_dual_graph(const TetMesh& mesh) {
  const size_t n = mesh.tets.size();
  // Each face's first tet and local face; the second tet to meet it closes the pair.
  std::vector<std::array<int32_t, 4>> across(n, {-1, -1, -1, -1});
  std::unordered_map<FaceKey, int64_t, FaceKeyHash> open;
  open.reserve(2 * n);
  for (size_t t = 0; t < n; ++t)
    for (int f = 0; f < 4; ++f) {
      const auto& c = kTetFaceCorners[f];
      const FaceKey key =
          face_key({mesh.tets[t][size_t(c[0])], mesh.tets[t][size_t(c[1])], mesh.tets[t][size_t(c[2])]});
      const auto [it, inserted] = open.try_emplace(key, int64_t(4 * t + size_t(f)));
      if (inserted) continue;
      const int64_t other = it->second;
      across[t][size_t(f)] = int32_t(other / 4);
      across[size_t(other / 4)][size_t(other % 4)] = int32_t(t);
      open.erase(it);
    }
  TetDualGraph g;
  g.start.assign(n + 1, 0);
  for (size_t t = 0; t < n; ++t) {
    g.start[t + 1] = g.start[t];
    for (int32_t o : across[t])
      if (o >= 0) {
        g.adjacency.push_back(o);
        ++g.start[t + 1];
      }
  }
  return g;
}

TetPartition partition_tets(const TetMesh& mesh, int32_t parts, std::span<const int32_t> weight) {
  const size_t n = mesh.tets.size();
  if (parts < 1 || size_t(parts) > n)
    throw Error(fmt::format("partition: {} parts of a mesh of {} tets; give 1 to {}", parts, n, n));
  if (!weight.empty() && weight.size() != n)
    throw Error(fmt::format("partition: {} weights for {} tets", weight.size(), n));
  if (std::any_of(weight.begin(), weight.end(), [](int32_t w) { return w < 1; }))
    throw Error("partition: every tet's weight must be at least 1");
  TetPartition out;
  out.parts = parts;
  out.part.assign(n, 0);
  const TetDualGraph g = tet_dual_graph(mesh);
  if (parts > 1) {
    std::vector<idx_t> xadj(g.start.begin(), g.start.end()), adjncy(g.adjacency.begin(), g.adjacency.end());
    std::vector<idx_t> vwgt(weight.begin(), weight.end()), part(n, 0);
    idx_t nvtxs = idx_t(n), ncon = 1, nparts = parts, objval = 0;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;  // the same parts on every run
    options[METIS_OPTION_NUMBERING] = 0;
    const int status =
        METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.empty() ? nullptr : vwgt.data(),
                            nullptr, nullptr, &nparts, nullptr, nullptr, options, &objval, part.data());
    if (status != METIS_OK)
      throw Error(fmt::format("partition: METIS_PartGraphKway failed ({}) on {} tets into {} parts",
                              status == METIS_ERROR_MEMORY ? "out of memory" : "error", n, parts));
    std::copy(part.begin(), part.end(), out.part.begin());
  }
  out.part_weight.assign(size_t(parts), 0);
  for (size_t t = 0; t < n; ++t) out.part_weight[size_t(out.part[t])] += weight.empty() ? 1 : weight[t];
  for (size_t t = 0; t < n; ++t)
    for (int32_t k = g.start[t]; k < g.start[t + 1]; ++k) {
      const auto o = size_t(g.adjacency[size_t(k)]);
      if (o > t && out.part[o] != out.part[t]) ++out.edge_cut;
    }
  int64_t total = 0, heaviest = 0;
  for (int64_t w : out.part_weight) {
    total += w;
    heaviest = std::max(heaviest, w);
  }
  out.imbalance = double(heaviest) * double(parts) / double(total);
  return out;
}

}  // namespace rift
