#pragma once
// Tet mesh of an axis-aligned box, fine near a surface and coarse away from it: the adaptive fluid mesh
// around an immersed solid (docs/fluid.md, "Adaptive mesh"). CGAL Mesh_3 through polyhedral_mesher.hpp,
// which states how sizes are enforced, the determinism (same input and seed, same arrays) and the layout.
//
// Sizing: h(p) = min(size_max, size_min + grading * d(p)), d = distance to the nearest triangle of the
// surface (surface_distance.hpp). grading is the growth of the size per unit distance: Delaunay
// refinement keeps neighbouring tets within a bounded ratio only if it is moderate (<= ~0.5).
// Surfaces: xmin xmax ymin ymax zmin zmax (the box's faces; Mesh_3 puts their vertices on the planes).
#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "engine/mesh/polyhedral_mesher.hpp"
#include "engine/mesh/tet_mesh.hpp"

namespace rift {

struct GradedBoxSpec {
  std::array<double, 3> lo{0, 0, 0}, hi{1, 1, 1};
  double size_min = 0.1, size_max = 0.1;  // [m], 0 < size_min <= size_max
  double grading = 0.3;                   // > 0
  uint32_t seed = 1;
  uint64_t max_tets = 0;  // 0: no bound (polyhedral_mesher.hpp); max_tets_key names the key that raises it
  std::string max_tets_key;
};

// surface: 9 values (3 corners) per triangle, anywhere (outside the box too). Throws rift::Error for an
// invalid spec or if meshing fails.
TetMesh generate_graded_box(const GradedBoxSpec& spec, std::span<const double> surface,
                            Mesh3Stats* stats = nullptr);

}  // namespace rift
