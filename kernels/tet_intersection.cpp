#include "kernels/tet_intersection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernels/vec3_ops.hpp"

namespace rift::kernels {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// tol = 16 eps |n|_1 D_1 (header: the error of s is a few eps |n| D). L1 norms, between 1 and 3 times the
// Euclidean product, so that no square root is taken per pair.
constexpr double kTolFactor = 16.0 * kEps;

// A clip adds one vertex per edge from a kept to a removed vertex: at most 3 min(kept, removed) <= 1.5 V new
// ones, and kept + new <= 2 V remain. From 4 vertices, 4 clips leave <= 8, 16, 32, 64, and the 4th clip
// holds at most 32 + 48 = 80 before compaction. The bound counts graph vertices only (no geometry), so it
// holds even when round-off makes the signs inconsistent. Geometrically the maximum is 12 (+ 15 in flight).
constexpr int kMaxVertices = 80;

// Faces for a positively oriented tet: face k = corners (i, j, l) with (i, j, l, k) an even permutation,
// so (x_j - x_i) x (x_l - x_i) points into the tet.
constexpr int kFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

// Neighbours of each corner of a positively oriented tet, counter-clockwise seen from outside.
constexpr int kTetNeighbours[4][3] = {{1, 3, 2}, {2, 3, 0}, {0, 3, 1}, {1, 2, 0}};

// The slot of w in v's neighbour list (w must be there); branch-free, as the walks below do this per step.
inline int slot_of(const int nbr[3], int w) {
  return nbr[0] == w ? 0 : (nbr[1] == w ? 1 : 2);
}

struct Polyhedron {
  double x[kMaxVertices][3];
  int nbr[kMaxVertices][3];
  int n = 0;
};

double det3(const double a[3], const double b[3], const double c[3]) {
  double bc[3];
  cross(b, c, bc);
  return dot(a, bc);
}

double norm1(const double a[3]) {
  return std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]);
}

// Inner normals (for either orientation: `sign` = sign of det) and offsets of a tet's 4 faces.
void face_planes(const double c[4][3], double sign, double normal[4][3], double offset[4], double norm[4]) {
  for (int k = 0; k < 4; ++k) {
    const double* p = c[kFace[k][0]];
    double e1[3], e2[3];
    for (int d = 0; d < 3; ++d) {
      e1[d] = c[kFace[k][1]][d] - p[d];
      e2[d] = c[kFace[k][2]][d] - p[d];
    }
    cross(e1, e2, normal[k]);
    for (int d = 0; d < 3; ++d) normal[k][d] *= sign;
    offset[k] = dot(normal[k], p);
    norm[k] = norm1(normal[k]);
  }
}

// Signed distance (scaled by |n|) with round-off-level values snapped to exactly 0: "on the plane".
inline double side(const double n[3], double offset, double tol, const double x[3]) {
  const double s = dot(n, x) - offset;
  return std::fabs(s) <= tol ? 0.0 : s;
}

enum class Relation { disjoint, inside, cut };

// Where the 4 points q lie with respect to the 4 planes: disjoint when some plane has none strictly inside,
// inside when all are inside or on every plane.
Relation classify(const double q[4][3], const double normal[4][3], const double offset[4],
                  const double tol[4]) {
  bool all_inside = true;
  for (int k = 0; k < 4; ++k) {
    bool any_in = false;
    for (int v = 0; v < 4; ++v) {
      const double s = side(normal[k], offset[k], tol[k], q[v]);
      any_in |= s > 0.0;
      all_inside &= s >= 0.0;
    }
    if (!any_in) return Relation::disjoint;
  }
  return all_inside ? Relation::inside : Relation::cut;
}

// Keeps the part of P with s >= 0. Returns false when nothing with volume is left.
bool clip(Polyhedron& P, const double n[3], double offset, double tol) {
  double s[kMaxVertices];
  bool any_in = false, any_out = false;
  for (int v = 0; v < P.n; ++v) {
    s[v] = side(n, offset, tol, P.x[v]);
    any_in |= s[v] > 0.0;
    any_out |= s[v] < 0.0;
  }
  if (!any_out) return true;
  if (!any_in) {
    P.n = 0;
    return false;
  }
  const int old = P.n;
  // One new vertex per edge from a kept vertex to a removed one; it takes the removed one's place.
  for (int v = 0; v < old; ++v) {
    if (s[v] < 0.0) continue;
    for (int e = 0; e < 3; ++e) {
      const int w = P.nbr[v][e];
      if (w >= old || s[w] >= 0.0) continue;
      const int nv = P.n++;
      const double t = s[v] / (s[v] - s[w]);  // denominator > tol >= 0, t in [0, 1)
      for (int d = 0; d < 3; ++d) P.x[nv][d] = P.x[v][d] + t * (P.x[w][d] - P.x[v][d]);
      P.nbr[nv][0] = v;
      P.nbr[nv][1] = P.nbr[nv][2] = -1;
      P.nbr[v][e] = nv;
      s[nv] = 0.0;
    }
  }
  // Link the new vertices into the cap: from each, walk along the old face on its left through kept
  // vertices until the next new vertex, which is its neighbour 2 (and it is that vertex's neighbour 1).
  for (int start = old; start < P.n; ++start) {
    int cur = start, next = P.nbr[start][0];
    do {
      const int np = slot_of(P.nbr[next], cur);
      cur = next;
      next = P.nbr[cur][(np + 1) % 3];
    } while (cur < old);
    P.nbr[start][2] = cur;
    P.nbr[cur][1] = start;
  }
  // Drop the removed vertices, renumbering the rest in order.
  int map[kMaxVertices];
  int m = 0;
  for (int v = 0; v < P.n; ++v) {
    if (s[v] < 0.0) continue;
    map[v] = m;
    if (m != v)
      for (int d = 0; d < 3; ++d) {
        P.x[m][d] = P.x[v][d];
        P.nbr[m][d] = P.nbr[v][d];
      }
    ++m;
  }
  P.n = m;
  for (int v = 0; v < m; ++v)
    for (int e = 0; e < 3; ++e) P.nbr[v][e] = map[P.nbr[v][e]];
  return true;
}

// Volume of the closed polyhedron: each face loop (walked clockwise seen from outside) fanned from its first
// vertex, each fan triangle closed into a tet by the apex vertex 0.
double polyhedron_volume(const Polyhedron& P) {
  double r[kMaxVertices][3];
  for (int v = 0; v < P.n; ++v)
    for (int d = 0; d < 3; ++d) r[v][d] = P.x[v][d] - P.x[0][d];
  bool used[kMaxVertices][3] = {};
  double six = 0.0;
  for (int v = 0; v < P.n; ++v)
    for (int e = 0; e < 3; ++e) {
      if (used[v][e]) continue;
      used[v][e] = true;
      int a = v, b = P.nbr[v][e];
      auto step = [&] {
        const int np = slot_of(P.nbr[b], a);
        const int out = np == 2 ? 0 : np + 1;
        used[b][out] = true;
        a = b;
        b = P.nbr[b][out];
      };
      step();
      while (b != v) {
        six += det3(r[v], r[b], r[a]);  // clockwise loop: (v, b, a) is counter-clockwise
        step();
      }
    }
  return six / 6.0;
}

}  // namespace

TetHalfSpaces tet_half_spaces(const double tet[4][3]) {
  TetHalfSpaces h;
  for (int d = 0; d < 3; ++d) h.origin[d] = tet[0][d];
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) h.corner[k][d] = tet[k][d] - h.origin[d];
  const double det = tet_six_volume(h.corner + 1);  // corner k is edge k - 1: corner 0 is the origin
  h.volume = std::fabs(det) / 6.0;
  face_planes(h.corner, det < 0.0 ? -1.0 : 1.0, h.normal, h.offset, h.norm);
  for (int d = 0; d < 3; ++d) {
    h.lo[d] = std::min({h.corner[0][d], h.corner[1][d], h.corner[2][d], h.corner[3][d]});
    h.hi[d] = std::max({h.corner[0][d], h.corner[1][d], h.corner[2][d], h.corner[3][d]});
  }
  return h;
}

double clipped_tet_volume(const double a[4][3], const TetHalfSpaces& b) {
  if (!(b.volume > 0.0)) return 0.0;
  double p[4][3], lo[3], hi[3];
  for (int k = 0; k < 4; ++k)
    for (int d = 0; d < 3; ++d) p[k][d] = a[k][d] - b.origin[d];
  double diag = 0.0;  // D_1: the L1 length of the pair box's diagonal
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min({p[0][d], p[1][d], p[2][d], p[3][d]});
    hi[d] = std::max({p[0][d], p[1][d], p[2][d], p[3][d]});
    if (hi[d] <= b.lo[d] || b.hi[d] <= lo[d]) return 0.0;  // boxes at most touching
    const double span = std::max(hi[d], b.hi[d]) - std::min(lo[d], b.lo[d]);
    diag += span;
  }
  const double D = diag;
  double e[3][3];
  tet_edges(p, e);
  const double det = tet_six_volume(e);
  if (det == 0.0 || !std::isfinite(det)) return 0.0;
  if (det < 0.0)  // the vertex graph below assumes a positive orientation
    for (int d = 0; d < 3; ++d) std::swap(p[2][d], p[3][d]);
  const double volume_a = std::fabs(det) / 6.0;
  const double cap = std::min(volume_a, b.volume);

  double tol_b[4];
  for (int k = 0; k < 4; ++k) tol_b[k] = kTolFactor * b.norm[k] * D;
  const Relation a_in_b = classify(p, b.normal, b.offset, tol_b);
  if (a_in_b == Relation::disjoint) return 0.0;
  if (a_in_b == Relation::inside) return cap;
  double normal_a[4][3], offset_a[4], norm_a[4], tol_a[4];
  face_planes(p, 1.0, normal_a, offset_a, norm_a);
  for (int k = 0; k < 4; ++k) tol_a[k] = kTolFactor * norm_a[k] * D;
  const Relation b_in_a = classify(b.corner, normal_a, offset_a, tol_a);
  if (b_in_a == Relation::disjoint) return 0.0;
  if (b_in_a == Relation::inside) return cap;

  Polyhedron P;
  P.n = 4;
  for (int v = 0; v < 4; ++v)
    for (int d = 0; d < 3; ++d) {
      P.x[v][d] = p[v][d];
      P.nbr[v][d] = kTetNeighbours[v][d];
    }
  for (int k = 0; k < 4; ++k)
    if (!clip(P, b.normal[k], b.offset[k], tol_b[k])) return 0.0;
  return std::clamp(polyhedron_volume(P), 0.0, cap);
}

double tet_intersection_volume(const double a[4][3], const double b[4][3]) {
  return clipped_tet_volume(a, tet_half_spaces(b));
}

}  // namespace rift::kernels
