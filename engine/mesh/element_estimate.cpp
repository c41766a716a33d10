#include "engine/mesh/element_estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/mesh/borehole_box.hpp"
#include "engine/mesh/graded_axis.hpp"

namespace rift {
namespace {

// Deep enough for a 1 km box to reach cells of 1e-9 m; below that every cell counts whole.
constexpr int kMaxDepth = 40;

struct Cell {
  Vec3 lo, hi;
  int depth;
};

}  // namespace

double enclosed_volume(std::span<const PolyhedralSurface> patches) {
  double six_volume = 0.0;
  for (const PolyhedralSurface& s : patches)
    for (const auto& face : s.faces)
      for (size_t k = 1; k + 1 < face.size(); ++k) {  // a fan: signed, so non-convex polygons add up
        six_volume += dot(s.points[face[0]], cross(s.points[face[k]], s.points[face[k + 1]]));
      }
  return six_volume / 6.0;
}

TetEstimate estimate_mesh3_tets(std::span<const PolyhedralSurface> patches,
                                const std::function<double(const Vec3&)>& size, double stop_above) {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  for (const PolyhedralSurface& s : patches)
    for (const Vec3& p : s.points)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  const double box_volume = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  if (!(box_volume > 0.0)) return {};
  const double fill = std::clamp(enclosed_volume(patches) / box_volume, 0.0, 1.0);

  // Depth first, so the stack stays at 7 cells per level; the sum is over the box, scaled by `fill`.
  TetEstimate estimate;
  double box_tets = 0.0, counted_volume = 0.0;
  double h_min = std::numeric_limits<double>::infinity(), h_max = -h_min;
  std::vector<Cell> stack{{lo, hi, 0}};
  while (!stack.empty()) {
    const Cell c = stack.back();
    stack.pop_back();
    const Vec3 centre{0.5 * (c.lo[0] + c.hi[0]), 0.5 * (c.lo[1] + c.hi[1]), 0.5 * (c.lo[2] + c.hi[2])};
    const double h = size(centre);
    h_min = std::min(h_min, h), h_max = std::max(h_max, h);
    const double edge = std::max({c.hi[0] - c.lo[0], c.hi[1] - c.lo[1], c.hi[2] - c.lo[2]});
    if (edge > 2.0 * h && c.depth < kMaxDepth && std::isfinite(h) && h > 0.0) {
      for (int k = 0; k < 8; ++k) {
        Cell child{c.lo, c.hi, c.depth + 1};
        for (int a = 0; a < 3; ++a) ((k >> a) & 1 ? child.lo : child.hi)[a] = centre[a];
        stack.push_back(child);
      }
      continue;
    }
    const double volume = (c.hi[0] - c.lo[0]) * (c.hi[1] - c.lo[1]) * (c.hi[2] - c.lo[2]);
    const double tets =
        h > 0.0 ? volume / (kMesh3TetVolume * h * h * h) : std::numeric_limits<double>::infinity();
    box_tets += std::isnan(tets) ? std::numeric_limits<double>::infinity() : tets;
    counted_volume += volume;
    if (fill * box_tets > stop_above) {
      estimate.lower_bound = !stack.empty() && h_min != h_max;
      if (!stack.empty() && h_min == h_max) box_tets *= box_volume / counted_volume;
      break;
    }
  }
  estimate.tets = fill * box_tets;
  return estimate;
}

void check_lattice_budget(const MeshGenerateSpec& spec) {
  auto tets = [](const std::array<int, 3>& c) { return 6.0 * c[0] * c[1] * c[2]; };
  double total = 0.0;
  if (spec.cells) total = tets(*spec.cells);
  if (const auto& g = spec.graded) {
    const auto n = graded_lattice_nodes(spec.origin, spec.size, g->fine_min, g->fine_max, g->size, g->growth);
    total =
        6.0 * static_cast<double>(n[0] - 1) * static_cast<double>(n[1] - 1) * static_cast<double>(n[2] - 1);
  }
  if (const auto& hole = spec.borehole)
    total = static_cast<double>(borehole_box_counts(borehole_box_spec(spec.origin, spec.size, *hole)).tets());
  // An unstructured block: its volume over that of a regular tet of its element size (h^3 / (6 sqrt 2)).
  for (const BlockSpec& b : spec.blocks)
    total += b.element_size ? b.size[0] * b.size[1] * b.size[2] * 6.0 * std::sqrt(2.0) /
                                  (*b.element_size * *b.element_size * *b.element_size)
                            : tets(b.cells);
  if (total <= static_cast<double>(spec.max_elements)) return;
  throw Error(fmt::format(
      "mesh.generate: the lattice has {:.6g} tets (6 per cell), more than {} = {}; about {:.3g} GB of memory "
      "to run. Use fewer cells, or raise {} to build it anyway",
      total, spec.max_elements_key, spec.max_elements, total * kBytesPerTet / 1e9, spec.max_elements_key));
}

}  // namespace rift
