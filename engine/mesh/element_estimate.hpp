#pragma once
// How many tets CGAL Mesh_3 makes for a sizing field h(p) in a closed polyhedral solid, estimated in
// milliseconds before meshing, so that sizes that would mesh for hours into all memory are refused
// with a figure instead (mesh.max_elements).
//
// Mesh_3 bounds every tet's circumradius by h at its circumcentre; its tets then have a mean volume of
// about kMesh3TetVolume h^3 (measured on boxes at h = 4, 2, 1, 0.7 mm: 0.213, 0.223, 0.228, 0.229; on
// the Brazilian disc: 0.188). The estimate is the integral of 1 / (kMesh3TetVolume h^3) over the solid,
// summed on an octree of its bounding box whose cells are refined until they are at most twice h at
// their centre, times the solid's volume over the box's (the divergence theorem on the patches' faces).
// Graded fields are followed down to the finest size, so a tiny size_min on a notch is counted.
// Accuracy (tests/unit/test_mesh_budget.cpp): within 10 % for one size everywhere; for a graded size
// (grading 0.5) Mesh_3 makes 2.0 - 2.2 times the estimate, its radius-edge bound carrying the fine
// size into the coarse region, so there the estimate is a lower bound.
#include <functional>
#include <span>

#include "engine/core/vec3.hpp"
#include "engine/mesh/polyhedral_mesher.hpp"
#include "engine/scene/scene.hpp"

namespace rift {

inline constexpr double kMesh3TetVolume = 0.21;
// Memory to mesh and run an unjointed solid, per tet (peak resident size over tets: 0.66 kB at 5e5
// tets, 0.75 kB at 1.8e5 with the process's fixed 20 MB); joints and a fluid add to it.
inline constexpr double kBytesPerTet = 660.0;

struct TetEstimate {
  double tets = 0.0;
  // The sum passed stop_above before the whole box was counted and the size varied: tets is the count
  // so far, a lower bound. (With one size everywhere the count so far is scaled to the whole box: exact.)
  bool lower_bound = false;
};

// Signed volume enclosed by the patches (outward faces): positive for a closed outward surface.
double enclosed_volume(std::span<const PolyhedralSurface> patches);

TetEstimate estimate_mesh3_tets(std::span<const PolyhedralSurface> patches,
                                const std::function<double(const Vec3&)>& size, double stop_above);

// A lattice (mesh.generate.cells or blocks) makes exactly 6 tets per cell: refused, before anything is
// allocated, when that passes spec.max_elements.
void check_lattice_budget(const MeshGenerateSpec& spec);

}  // namespace rift
