#include "engine/mesh/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rift {

namespace {

// Spreads the low 21 bits of v so that two zero bits follow each one.
uint64_t spread(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

struct Grid {
  std::array<double, 3> lo{}, scale{};
  uint64_t key(const std::array<double, 3>& p) const {
    uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const double cell = std::clamp((p[a] - lo[a]) * scale[a], 0.0, 2097151.0);
      k |= spread(static_cast<uint64_t>(cell)) << a;
    }
    return k;
  }
};

// Indices 0..n-1 sorted by key, ties by index.
std::vector<int32_t> order_by(const std::vector<uint64_t>& keys) {
  std::vector<int32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int32_t a, int32_t b) { return keys[a] < keys[b] || (keys[a] == keys[b] && a < b); });
  return order;
}

}  // namespace

void order_along_curve(TetMesh& mesh) {
  if (mesh.nodes.empty()) return;
  Grid grid;
  std::array<double, 3> hi{};
  grid.lo = hi = mesh.nodes[0];
  for (const auto& p : mesh.nodes)
    for (int a = 0; a < 3; ++a) grid.lo[a] = std::min(grid.lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double extent = std::max({hi[0] - grid.lo[0], hi[1] - grid.lo[1], hi[2] - grid.lo[2], 1e-300});
  grid.scale.fill(2097151.0 / extent);  // one scale for all axes keeps the curve's cells cubic

  std::vector<uint64_t> keys(mesh.nodes.size());
  for (size_t v = 0; v < keys.size(); ++v) keys[v] = grid.key(mesh.nodes[v]);
  const std::vector<int32_t> vertex_order = order_by(keys);
  std::vector<int32_t> new_id(mesh.nodes.size());
  std::vector<std::array<double, 3>> nodes(mesh.nodes.size());
  for (size_t i = 0; i < vertex_order.size(); ++i) {
    new_id[vertex_order[i]] = static_cast<int32_t>(i);
    nodes[i] = mesh.nodes[vertex_order[i]];
  }
  mesh.nodes = std::move(nodes);
  for (auto& t : mesh.tets)
    for (int32_t& v : t) v = new_id[v];
  for (auto& t : mesh.triangles)
    for (int32_t& v : t) v = new_id[v];

  keys.resize(mesh.tets.size());
  for (size_t e = 0; e < mesh.tets.size(); ++e) {
    std::array<double, 3> c{0, 0, 0};
    for (int32_t v : mesh.tets[e])
      for (int a = 0; a < 3; ++a) c[a] += 0.25 * mesh.nodes[v][a];
    keys[e] = grid.key(c);
  }
  const std::vector<int32_t> tet_order = order_by(keys);
  std::vector<std::array<int32_t, 4>> tets(mesh.tets.size());
  std::vector<int32_t> region(mesh.tet_region.size());
  for (size_t i = 0; i < tet_order.size(); ++i) {
    tets[i] = mesh.tets[tet_order[i]];
    if (!region.empty()) region[i] = mesh.tet_region[tet_order[i]];
  }
  mesh.tets = std::move(tets);
  mesh.tet_region = std::move(region);
}

}  // namespace rift
