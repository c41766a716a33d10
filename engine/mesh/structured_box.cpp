#include "engine/mesh/structured_box.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

#include "engine/mesh/lattice_box.hpp"

namespace rift {

// The Kuhn lattice of lattice_box.hpp on [lo, hi]: its uniform axes, each coordinate lo + (hi - lo) i / n as
// the lattice computes it, and the last one hi exactly, so boundary tests can compare coordinates.
TetMesh structured_box(const StructuredBoxSpec& spec) {
  std::array<std::vector<double>, 3> axes;
  for (int d = 0; d < 3; ++d) {
    if (spec.cells[d] < 1) throw std::invalid_argument("structured_box: cells must be >= 1");
    if (!(spec.hi[d] > spec.lo[d])) throw std::invalid_argument("structured_box: hi must exceed lo");
    const double size = spec.hi[d] - spec.lo[d];
    for (int i = 0; i <= spec.cells[d]; ++i)
      axes[d].push_back(i == spec.cells[d] ? spec.hi[d] : spec.lo[d] + size * i / spec.cells[d]);
  }
  return structured_box_on_axes(axes);
}

TetMesh structured_box_on_axes(const std::array<std::vector<double>, 3>& coordinates) {
  std::array<int, 3> cells{};
  for (int d = 0; d < 3; ++d) {
    const auto& x = coordinates[d];
    if (x.size() < 2 || std::adjacent_find(x.begin(), x.end(), std::greater_equal<>()) != x.end())
      throw std::invalid_argument("structured_box_on_axes: coordinates must increase, at least 2 per axis");
    cells[d] = static_cast<int>(x.size()) - 1;
  }
  TetMesh mesh = generate_lattice_box(cells, {1.0, 1.0, 1.0});
  const size_t n[3] = {coordinates[0].size(), coordinates[1].size(), coordinates[2].size()};
  for (size_t v = 0; v < mesh.nodes.size(); ++v) {
    const size_t index[3] = {v % n[0], v / n[0] % n[1], v / (n[0] * n[1])};
    for (int d = 0; d < 3; ++d) mesh.nodes[v][d] = coordinates[d][index[d]];
  }
  return mesh;
}

}  // namespace rift
