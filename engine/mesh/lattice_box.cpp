#include "engine/mesh/lattice_box.hpp"

#include <algorithm>
#include <string>

#include "engine/core/error.hpp"

namespace rift {

namespace {

// Cube corner c has offset (c & 1, (c >> 1) & 1, (c >> 2) & 1).
constexpr int axis_bit[3] = {1, 2, 4};
constexpr int axis_orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

double orientation(const std::array<double, 3>& a, const std::array<double, 3>& b,
                   const std::array<double, 3>& c, const std::array<double, 3>& d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

}  // namespace

TetMesh generate_lattice_box(std::array<int, 3> cells, std::array<double, 3> size) {
  for (int a = 0; a < 3; ++a) {
    if (cells[a] < 1)
      throw Error("lattice box: cell count " + std::to_string(cells[a]) + " along axis " + "xyz"[a] +
                  " must be at least 1");
    if (!(size[a] > 0.0))
      throw Error("lattice box: size along axis " + std::string(1, "xyz"[a]) + " must be positive");
  }
  const int nx = cells[0] + 1, ny = cells[1] + 1, nz = cells[2] + 1;
  auto node = [&](int i, int j, int k) { return static_cast<int32_t>(i + nx * (j + ny * k)); };
  TetMesh mesh;
  mesh.region_names = {"domain"};
  mesh.surface_names = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  mesh.nodes.reserve(static_cast<size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.nodes.push_back({size[0] * i / cells[0], size[1] * j / cells[1], size[2] * k / cells[2]});

  mesh.tets.reserve(6ull * cells[0] * cells[1] * cells[2]);
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) {
        auto corner = [&](int c) { return node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)); };
        for (const auto& order : axis_orders) {
          std::array<int32_t, 4> t;
          int c = 0;
          t[0] = corner(c);
          for (int s = 0; s < 3; ++s) t[s + 1] = corner(c |= axis_bit[order[s]]);
          if (orientation(mesh.nodes[t[0]], mesh.nodes[t[1]], mesh.nodes[t[2]], mesh.nodes[t[3]]) < 0)
            std::swap(t[2], t[3]);
          mesh.tets.push_back(t);
        }
      }
  mesh.tet_region.assign(mesh.tets.size(), 0);

  // Boundary: two triangles per cube face on each side of the box, split along the face diagonal the
  // Kuhn tets use (the one through the cube's (0,0,0)-side corner and its opposite in that face).
  auto quad = [&](int32_t a, int32_t b, int32_t c, int32_t d, int32_t surface) {
    // a b c d counter-clockwise seen from outside; the diagonal a-c is the one through the lower corner.
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
    mesh.triangle_surface.push_back(surface);
    mesh.triangle_surface.push_back(surface);
  };
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j) {
      quad(node(0, j, k), node(0, j, k + 1), node(0, j + 1, k + 1), node(0, j + 1, k), 0);
      const int x = cells[0];
      quad(node(x, j, k), node(x, j + 1, k), node(x, j + 1, k + 1), node(x, j, k + 1), 1);
    }
  for (int k = 0; k < cells[2]; ++k)
    for (int i = 0; i < cells[0]; ++i) {
      quad(node(i, 0, k), node(i + 1, 0, k), node(i + 1, 0, k + 1), node(i, 0, k + 1), 2);
      const int y = cells[1];
      quad(node(i, y, k), node(i, y, k + 1), node(i + 1, y, k + 1), node(i + 1, y, k), 3);
    }
  for (int j = 0; j < cells[1]; ++j)
    for (int i = 0; i < cells[0]; ++i) {
      quad(node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0), node(i + 1, j, 0), 4);
      const int z = cells[2];
      quad(node(i, j, z), node(i + 1, j, z), node(i + 1, j + 1, z), node(i, j + 1, z), 5);
    }
  return mesh;
}

}  // namespace rift
