#pragma once
// A continuous (node-sharing) tetrahedral mesh as it comes from a generator or a file, before any
// physics system turns it into its own tables. Plain arrays, 0-based indices.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rift {

struct TetMesh {
  std::vector<std::array<double, 3>> nodes;       // coordinates [m]
  std::vector<std::array<int32_t, 4>> tets;       // positively oriented: det[x1-x0, x2-x0, x3-x0] > 0
  std::vector<int32_t> tet_region;                // index into region_names, one per tet
  std::vector<std::array<int32_t, 3>> triangles;  // boundary / named surface triangles
  std::vector<int32_t> triangle_surface;          // index into surface_names, one per triangle
  std::vector<std::string> region_names;          // e.g. "domain" or Gmsh physical volume names
  std::vector<std::string> surface_names;         // e.g. "xmin", "notch" or Gmsh physical surface names

  int32_t region_index(const std::string& name) const;   // -1 when absent
  int32_t surface_index(const std::string& name) const;  // -1 when absent
};

inline int32_t TetMesh::region_index(const std::string& name) const {
  for (size_t i = 0; i < region_names.size(); ++i)
    if (region_names[i] == name) return static_cast<int32_t>(i);
  return -1;
}
inline int32_t TetMesh::surface_index(const std::string& name) const {
  for (size_t i = 0; i < surface_names.size(); ++i)
    if (surface_names[i] == name) return static_cast<int32_t>(i);
  return -1;
}

}  // namespace rift
