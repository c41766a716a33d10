#include "engine/mesh/tet_partition.hpp"

#include <fmt/format.h>
#include <metis.h>

#include <algorithm>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_faces.hpp"

namespace rift {

TetDualGraph tet_dual_graph(std::span<const std::array<int32_t, 4>> tets) {
  const size_t n = tets.size();
  // The tet across each face (-1: the boundary).
  std::vector<std::array<int32_t, 4>> across(n, {-1, -1, -1, -1});
  for_each_shared_face(tets, [&](int32_t a, int32_t fa, int32_t b, int32_t fb) {
    across[size_t(a)][size_t(fa)] = b;
    across[size_t(b)][size_t(fb)] = a;
  });
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

TetPartition partition_tets(std::span<const std::array<int32_t, 4>> tets, int32_t parts,
                            std::span<const int32_t> weight) {
  const size_t n = tets.size();
  if (parts < 1 || size_t(parts) > n)
    throw Error(fmt::format("partition: {} parts of a mesh of {} tets; give 1 to {}", parts, n, n));
  if (!weight.empty() && weight.size() != n)
    throw Error(fmt::format("partition: {} weights for {} tets", weight.size(), n));
  if (std::any_of(weight.begin(), weight.end(), [](int32_t w) { return w < 1; }))
    throw Error("partition: every tet's weight must be at least 1");
  TetPartition out;
  out.parts = parts;
  out.part.assign(n, 0);
  const TetDualGraph g = tet_dual_graph(tets);
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
