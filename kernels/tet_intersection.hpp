#pragma once
// Exact volume of the intersection of two tetrahedra (fluid.md 1.5: Fluidity clips tet against tet by the
// 4 face planes; here the polyhedron is clipped as a vertex graph, after Powell & Abel's r3d, JCP 2015).
//
// Method. Tet A is a convex polyhedron stored as a graph of vertices of degree 3 (each vertex lists its
// neighbours counter-clockwise seen from outside). It is clipped by the 4 inner half-spaces of tet B in turn:
// a vertex with signed distance s < 0 is removed, every edge from a kept vertex to a removed one gets a new
// vertex on the plane, and the new vertices are linked into the cap face by walking the old faces. The cut
// depends only on the signs of s, so the graph stays a valid closed polyhedron whatever the round-off
// (no case analysis, no sorting of cap vertices), and a new vertex is always placed with a denominator
// s_kept - s_removed >= tol > 0: no NaN, no division by zero. The volume is the sum over faces of the fan
// triangles' tets with one vertex of the polyhedron as apex.
//
// Touching and degenerate cases. Signed distances with |s| <= tol (below) are set to 0: the vertex is on the
// plane. Before clipping, each tet's 4 vertices are tested against the other's 4 planes: if one plane has no
// vertex of the other tet strictly inside, the interiors are disjoint and the result is exactly 0 (shared
// faces, coplanar faces, a shared vertex or a vertex on a face, disjoint tets); if every vertex of one tet
// is inside or on every plane of the other, the result is that tet's volume, exactly (A with itself gives
// V_A bit for bit). Flat tets (det = 0) give 0. Either orientation of either tet is accepted.
//
// Precision. All coordinates are taken relative to B's vertex 0, so the result does not depend on where the
// pair sits in space. tol = 16 eps |n|_1 D_1 for a plane with (unnormalised) normal n, D_1 = the L1 length
// of the diagonal of the pair's bounding box (L1 norms: 1-3 x the Euclidean product, no square roots): the
// computed s = n . (x - q) carries an error of a few eps |n| D (one cross product, one difference, one dot),
// so tol only catches values that round-off could not separate from 0, and moving those vertices onto the
// plane changes the volume by at most tol / |n| x area = O(eps D^3).
// Otherwise the result is the exact volume up to round-off: an absolute error of O(10^2 eps D^3) (at most
// ~30 fan tets of size <= D, plus vertices placed to eps D). The result is clamped to [0, min(V_A, V_B)]
// (which only acts on round-off). Tests: tests/unit/test_volume_fraction.cpp.
//
// No allocation: fixed-size stack buffers (kMaxVertices below; the bound is combinatorial, so it holds even
// where round-off makes the signs geometrically inconsistent).
#include <cstddef>

#include "kernels/tet_geometry.hpp"  // tet_volume, for the callers of the intersection

namespace rift::kernels {

// The 4 inner half-spaces of a tet (s(x) = n . (x - origin) - offset >= 0 inside), its corners, volume and
// bounding box, all relative to `origin` (its corner 0). Built once per clipping tet and reused for every
// tet clipped by it (the volume fraction kernel builds one per fluid tet).
struct TetHalfSpaces {
  double origin[3];     // corner 0 of the tet, absolute coordinates
  double corner[4][3];  // corners relative to origin (corner[0] = 0)
  double normal[4][3];  // inner normal of the face opposite corner k, |n| = twice the face area
  double offset[4];     // n_k . (a corner of face k), relative to origin
  double norm[4];       // |n_k|_1 (L1 norm, for the snapping tolerance)
  double lo[3], hi[3];  // bounding box, relative to origin
  double volume;        // |det| / 6 >= 0; 0 for a flat tet
};

TetHalfSpaces tet_half_spaces(const double tet[4][3]);

// |A ∩ B| with B given by its half-spaces: the same value, bit for bit, as tet_intersection_volume(a, b).
double clipped_tet_volume(const double a[4][3], const TetHalfSpaces& b);

// |A ∩ B| [m^3] for two tets given by their 4 corners (any order, any orientation).
double tet_intersection_volume(const double a[4][3], const double b[4][3]);

}  // namespace rift::kernels
