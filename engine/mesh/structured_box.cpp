#include "engine/mesh/structured_box.hpp"

#include <algorithm>
#include <stdexcept>

namespace rift {

namespace {

double det3(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

}  // namespace

TetMesh structured_box(const StructuredBoxSpec& spec) {
  const int nx = spec.cells[0], ny = spec.cells[1], nz = spec.cells[2];
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("structured_box: cells must be >= 1");
  for (int d = 0; d < 3; ++d)
    if (!(spec.hi[d] > spec.lo[d])) throw std::invalid_argument("structured_box: hi must exceed lo");
  TetMesh mesh;
  const auto node_id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  mesh.nodes.reserve(static_cast<size_t>(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        // The last node of each row is set to hi exactly so boundary tests can compare coordinates.
        const double x = i == nx ? spec.hi[0] : spec.lo[0] + (spec.hi[0] - spec.lo[0]) * i / nx;
        const double y = j == ny ? spec.hi[1] : spec.lo[1] + (spec.hi[1] - spec.lo[1]) * j / ny;
        const double z = k == nz ? spec.hi[2] : spec.lo[2] + (spec.hi[2] - spec.lo[2]) * k / nz;
        mesh.nodes.push_back({x, y, z});
      }
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  mesh.tets.reserve(static_cast<size_t>(6) * nx * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& perm : kPerm) {
          std::array<int, 3> c{i, j, k};
          std::array<int32_t, 4> t{};
          t[0] = node_id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[perm[s]];
            t[s + 1] = node_id(c[0], c[1], c[2]);
          }
          const auto& x0 = mesh.nodes[t[0]];
          std::array<std::array<double, 3>, 3> e{};
          for (int s = 0; s < 3; ++s)
            for (int d = 0; d < 3; ++d) e[s][d] = mesh.nodes[t[s + 1]][d] - x0[d];
          if (det3(e[0], e[1], e[2]) < 0.0) std::swap(t[2], t[3]);
          mesh.tets.push_back(t);
        }
  mesh.tet_region.assign(mesh.tets.size(), 0);
  mesh.region_names = {"domain"};
  mesh.surface_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  // Boundary triangles: the tet faces whose three nodes lie on one box plane (only boundary faces can).
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (const auto& t : mesh.tets)
    for (const auto& f : kFace) {
      for (int d = 0; d < 3; ++d)
        for (int side = 0; side < 2; ++side) {
          const double plane = side == 0 ? spec.lo[d] : spec.hi[d];
          bool on = true;
          for (int a = 0; a < 3; ++a) on = on && mesh.nodes[t[f[a]]][d] == plane;
          if (on) {
            mesh.triangles.push_back({t[f[0]], t[f[1]], t[f[2]]});
            mesh.triangle_surface.push_back(2 * d + side);
          }
        }
    }
  return mesh;
}

}  // namespace rift
