#pragma once
// Where a point lies in a tet mesh, and a P1 (nodal) or P0 (per-tet) field read there: what a probe, a
// gauge or an interpolation between meshes needs. Nodes are x (3 per node), tets tet_nodes (4 per tet).
#include <cstddef>
#include <cstdint>
#include <span>

namespace rift::kernels {

// Barycentric coordinates of point q in the tet with corners c (Cramer's rule on [c1-c0, c2-c0, c3-c0]):
// q = sum_a lambda_a c_a, sum_a lambda_a = 1; all four >= 0 inside.
void tet_barycentric(const double c[4][3], const double* q, double lambda[4]);

struct TetPointLocation {
  int32_t tet = -1;                         // -1: the mesh has no tets
  double lambda[4] = {0.0, 0.0, 0.0, 0.0};  // q's barycentric coordinates in `tet`
  double lowest = -1e300;                   // min_a lambda_a: >= 0 inside, how far outside when < 0
};

// The tet whose smallest barycentric coordinate at q is largest: the containing tet (the first in id
// order when q lies on a shared face or corner), or, for q outside the mesh, the tet it is least outside
// of. Tets whose bounding box, grown by `slack` [m], misses q are skipped; none left: tet = -1. Cost:
// one pass over the tets (a set-up or remesh operation, not a per-step one).
TetPointLocation locate_in_tets(const double q[3], std::span<const double> x,
                                std::span<const int32_t> tet_nodes, double slack);

// sum_a lambda_a field[stride * n_a + component] over the corners n_a of where.tet.
double interpolate_p1(const TetPointLocation& where, std::span<const int32_t> tet_nodes,
                      std::span<const double> field, size_t stride, size_t component);

}  // namespace rift::kernels
