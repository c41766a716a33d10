#include "kernels/contact_potential.hpp"

#include <algorithm>
#include <cmath>

#include "kernels/node_rows.hpp"
#include "kernels/tet_geometry.hpp"
#include "kernels/vec3_ops.hpp"

namespace rift::kernels {

namespace {

// A tet's barycentric coordinates as affine functions B_j(x) = grad[j] . x + c[j], its outward faces and
// its box.
struct TetGeometry {
  double x[4][3];
  double grad[4][3], c[4];
  int face[4][3];  // face j: the corners other than j, ordered so that the right-hand normal points out
  double n[4][3];  // outward unit normal of face j
  double g[3];     // centroid
  double lo[3], hi[3];
  bool ok;  // volume non-zero and finite

  void bary(const double p[3], double b[4]) const {
    for (int j = 0; j < 4; ++j) b[j] = dot(grad[j], p) + c[j];
  }
};

TetGeometry tet_geometry(const double t[4][3]) {
  TetGeometry g;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) g.x[i][k] = t[i][k];
  double e[3][3], r[3][3];
  tet_edges(t, e);
  const double det = tet_inverse_rows(e, r);
  g.ok = det != 0.0 && std::isfinite(det);
  const double inv = g.ok ? 1.0 / det : 0.0;
  double sum_c = 0.0;
  for (int k = 0; k < 3; ++k) g.grad[0][k] = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      g.grad[i + 1][k] = r[i][k] * inv;
      g.grad[0][k] -= g.grad[i + 1][k];
    }
    g.c[i + 1] = -dot(g.grad[i + 1], t[0]);
    sum_c += g.c[i + 1];
  }
  g.c[0] = 1.0 - sum_c;
  for (int j = 0; j < 4; ++j) {
    int f[3] = {(j + 1) % 4, (j + 2) % 4, (j + 3) % 4};
    double u[3], w[3], nn[3], d[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = t[f[1]][k] - t[f[0]][k];
      w[k] = t[f[2]][k] - t[f[0]][k];
      d[k] = t[j][k] - t[f[0]][k];
    }
    cross(u, w, nn);
    if (dot(nn, d) > 0.0) {
      std::swap(f[1], f[2]);
      for (double& v : nn) v = -v;
    }
    const double len = std::sqrt(dot(nn, nn));
    const double il = len > 0.0 ? 1.0 / len : 0.0;
    for (int k = 0; k < 3; ++k) {
      g.face[j][k] = f[k];
      g.n[j][k] = nn[k] * il;
    }
  }
  for (int k = 0; k < 3; ++k) {
    g.g[k] = 0.25 * (t[0][k] + t[1][k] + t[2][k] + t[3][k]);
    g.lo[k] = std::min({t[0][k], t[1][k], t[2][k], t[3][k]});
    g.hi[k] = std::max({t[0][k], t[1][k], t[2][k], t[3][k]});
  }
  return g;
}

// A polygon vertex: the target's 4 barycentric coordinates there (interpolated along edges, which is
// exact for affine functions and keeps the clipping consistent with the integration); its position is
// sum_i b_i X_i over the target's corners, formed only when the polygon is integrated.
struct Vertex {
  double b[4];
};
constexpr double kSnap = 1e-12;
constexpr int kMaxVertices = 16;  // 3 + 4 (outer planes) + 3 (sub-tet planes) = 10 at most
struct Polygon {
  Vertex v[kMaxVertices];
  int n = 0;
};

// Sutherland-Hodgman against the half-space s(v) >= 0, s affine in the barycentric coordinates:
// s = b[i] (kOuter: a target face plane) or s = b[i] - b[j] (a plane between two sub-tets).
template <bool kOuter>
inline double side(const Vertex& v, int i, int j) {
  if constexpr (kOuter)
    return v.b[i];
  else
    return v.b[i] - v.b[j];
}
// Returns the clipped polygon: `in` itself when no vertex is outside, else `out` (n = 0 when empty).
template <bool kOuter>
inline const Polygon* clip(const Polygon* in, int i, int j, Polygon* out) {
  const int n = in->n;
  double sd[kMaxVertices];
  bool any_out = false, any_in = false;
  for (int k = 0; k < n; ++k) {
    sd[k] = side<kOuter>(in->v[k], i, j);
    any_out |= sd[k] < 0.0;
    any_in |= sd[k] > 0.0;
  }
  if (!any_out) return in;
  out->n = 0;
  if (!any_in) return out;
  int prev = n - 1;
  for (int k = 0; k < n; ++k) {
    const double sp = sd[prev], sc = sd[k];
    if ((sp > 0.0 && sc < 0.0) || (sp < 0.0 && sc > 0.0)) {  // the edge prev -> k crosses the plane
      const double t = sp / (sp - sc);
      Vertex& c = out->v[out->n++];
      for (int d = 0; d < 4; ++d) c.b[d] = in->v[prev].b[d] + t * (in->v[k].b[d] - in->v[prev].b[d]);
    }
    if (sc >= 0.0) out->v[out->n++] = in->v[k];
    prev = k;
  }
  if (out->n < 3) out->n = 0;
  return out;
}

// ∫_P phi dA and ∫_P x phi dA over a planar polygon with vertex values phi, n its plane's unit normal
// (areas signed by n; the clipped face polygons keep the face's orientation).
// Also its area and ∫_P x dA, for the overlap energy.
struct PolygonIntegrals {
  double I, m[3];      // ∫ phi dA, ∫ x phi dA
  double area, xa[3];  // ∫ dA, ∫ x dA
};
void integrate(const Polygon& p, const double X[4][3], int j, const double n[3], PolygonIntegrals& r) {
  double& I = r.I;
  double* m = r.m;
  I = r.area = 0.0;
  for (int d = 0; d < 3; ++d) m[d] = r.xa[d] = 0.0;
  double x[kMaxVertices][3];
  for (int k = 0; k < p.n; ++k)
    for (int d = 0; d < 3; ++d)
      x[k][d] = p.v[k].b[0] * X[0][d] + p.v[k].b[1] * X[1][d] + p.v[k].b[2] * X[2][d] + p.v[k].b[3] * X[3][d];
  const double phi0 = 4.0 * p.v[0].b[j];
  for (int k = 1; k + 1 < p.n; ++k) {
    double e1[3], e2[3], c[3];
    for (int d = 0; d < 3; ++d) {
      e1[d] = x[k][d] - x[0][d];
      e2[d] = x[k + 1][d] - x[0][d];
    }
    cross(e1, e2, c);
    const double area = 0.5 * dot(c, n);
    const double phi1 = 4.0 * p.v[k].b[j], phi2 = 4.0 * p.v[k + 1].b[j];
    const double s = phi0 + phi1 + phi2;
    I += area * s / 3.0;
    r.area += area;
    for (int d = 0; d < 3; ++d) r.xa[d] += area / 3.0 * (x[0][d] + x[k][d] + x[k + 1][d]);
    for (int d = 0; d < 3; ++d)
      m[d] += area / 12.0 *
              (phi0 * x[0][d] + phi1 * x[k][d] + phi2 * x[k + 1][d] + s * (x[0][d] + x[k][d] + x[k + 1][d]));
  }
}

// Contactor C's faces against target T's sub-tets (the first boundary term). fc, ft: the corner forces of
// C and T, accumulated.
void one_way(const TetGeometry& C, const TetGeometry& T, double p, double fc[4][3], double ft[4][3],
             TetPairForce& out) {
  double sub_tet_area[4] = {0.0, 0.0, 0.0, 0.0};  // polygon area per target sub-tet, for the stiffness
  for (int f = 0; f < 4; ++f) {
    const double* n = C.n[f];
    double rel[3];
    for (int d = 0; d < 3; ++d) rel[d] = C.x[C.face[f][0]][d] - C.g[d];
    const double h_face = dot(rel, n);  // distance of the face plane from C's centroid
    Polygon face;
    face.n = 3;
    for (int k = 0; k < 3; ++k) {
      Vertex& v = face.v[k];
      T.bary(C.x[C.face[f][k]], v.b);
      // A corner on a target face plane (coplanar neighbours) gets exactly 0 there, not +-1e-17: no
      // round-off force between touching tets. Shifts phi by < 1e-12, negligible against any real overlap.
      for (double& bj : v.b)
        if (std::abs(bj) < kSnap) bj = 0.0;
    }
    // face ∩ T: the 4 outer half-spaces B_j >= 0 (a corner with all 4 >= 0 needs no clipping).
    Polygon buf[4];
    const Polygon* q = &face;
    for (int i = 0; i < 4 && q->n > 0; ++i) q = clip<true>(q, i, -1, &buf[i]);
    if (q->n == 0) continue;
    for (int j = 0; j < 4; ++j) {  // sub-tet j: B_i >= B_j for the 3 corners i != j
      Polygon sub[3];
      const Polygon* r = q;
      for (int k = 1; k < 4 && r->n > 0; ++k) r = clip<false>(r, (j + k) % 4, j, &sub[k - 1]);
      if (r->n == 0) continue;
      const Polygon& a = *r;
      PolygonIntegrals pi;
      integrate(a, T.x, j, n, pi);
      const double I = pi.I;
      const double* m = pi.m;
      if (!(I > 0.0)) continue;
      // Overlap energy, this piece of the boundary of c∩t (see the header): phi_C = 0 here, so
      //   ∫_P [(x - g_C).n / 12 + (x - g_T).n (phi_T / 4 + 1 / 12)] dA, (x - g_C).n = h_face constant.
      const double gt_n = dot(T.g, n);
      out.energy += p * (h_face * pi.area / 12.0 + 0.25 * (dot(n, m) - gt_n * I) +
                         (dot(n, pi.xa) - gt_n * pi.area) / 12.0);
      const double F = p * I;
      sub_tet_area[j] += std::abs(pi.area);
      double xf[3], bc[4], bt[4];
      for (int d = 0; d < 3; ++d) xf[d] = m[d] / I;
      // The consistent distribution: C's corners by C's barycentric coordinates at x_F (the face's, as x_F
      // lies on it), T's by T's (the sub-tet's, with g_T's share split 1/4 each: L_i + L_g / 4 = B_i).
      C.bary(xf, bc);
      T.bary(xf, bt);
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 3; ++d) {
          fc[c][d] -= F * n[d] * bc[c];
          ft[c][d] += F * n[d] * bt[c];
        }
      for (int d = 0; d < 3; ++d) out.centre[d] += F * xf[d];
      out.weight += F;
      ++out.polygons;
    }
  }
  // k_pair's share of this way: p A |grad phi_T| per sub-tet, phi_T = 4 B_j there (one root per sub-tet
  // touched, not per polygon).
  for (int j = 0; j < 4; ++j)
    if (sub_tet_area[j] > 0.0)
      out.stiffness += 4.0 * p * sub_tet_area[j] * std::sqrt(dot(T.grad[j], T.grad[j]));
}

inline bool boxes_overlap(const TetGeometry& a, const TetGeometry& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < b.lo[k] || b.hi[k] < a.lo[k]) return false;
  return true;
}

// True when a face plane of P has all of Q's corners on its outer side or on it (Q's corners all have
// P's B_j <= 0 for some j): then P ∩ Q has no volume and every polygon either way is empty or carries
// phi = 0. A cheap exit for the candidates of a buffered broad phase (and for touching neighbours).
bool face_separated(const TetGeometry& P, const TetGeometry& Q) {
  for (int j = 0; j < 4; ++j) {
    bool all_out = true;
    for (int c = 0; c < 4 && all_out; ++c) all_out = dot(P.grad[j], Q.x[c]) + P.c[j] <= 0.0;
    if (all_out) return true;
  }
  return false;
}

}  // namespace

TetPairForce tet_pair_potential_force(const double a[4][3], const double b[4][3], double penalty) {
  return tet_pair_potential_force(a, b, penalty, penalty);
}

TetPairForce tet_pair_potential_force(const double a[4][3], const double b[4][3], double penalty_a,
                                      double penalty_b) {
  TetPairForce out{};
  const TetGeometry A = tet_geometry(a), B = tet_geometry(b);
  if (!A.ok || !B.ok || !boxes_overlap(A, B) || face_separated(A, B) || face_separated(B, A)) return out;
  double fa[4][3] = {}, fb[4][3] = {};
  one_way(A, B, penalty_b, fa, fb, out);  // A's faces in B's potential: B's penalty
  one_way(B, A, penalty_a, fb, fa, out);
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 3; ++d) {
      out.f[c][d] = fa[c][d];
      out.f[4 + c][d] = fb[c][d];
      out.normal[d] += fa[c][d];
    }
  if (out.weight > 0.0)
    for (double& c : out.centre) c /= out.weight;
  return out;
}

double tet_potential(const double tet[4][3], const double x[3]) {
  const TetGeometry g = tet_geometry(tet);
  if (!g.ok) return 0.0;
  double b[4];
  g.bary(x, b);
  return std::max(0.0, 4.0 * std::min({b[0], b[1], b[2], b[3]}));
}

FrictionStep coulomb_friction_update(double history[3], const double n[3], double f_n, const double du[3],
                                     double k_t, double mu) {
  FrictionStep s{{0.0, 0.0, 0.0}, 0.0, false};
  // The stored force, turned into the current tangent plane with its length kept.
  const double len0 = std::sqrt(dot(history, history));
  const double hn = dot(history, n);
  double h[3];
  for (int d = 0; d < 3; ++d) h[d] = history[d] - hn * n[d];
  const double len1 = std::sqrt(dot(h, h));
  if (len1 > 0.0)
    for (double& v : h) v *= len0 / len1;
  // Elastic trial, then the Coulomb cap.
  const double dn = dot(du, n);
  double trial[3];
  for (int d = 0; d < 3; ++d) trial[d] = h[d] - k_t * (du[d] - dn * n[d]);
  const double t = std::sqrt(dot(trial, trial));
  const double cap = mu * std::max(f_n, 0.0);
  double scale = 1.0;
  if (t > cap) {
    scale = t > 0.0 ? cap / t : 0.0;
    s.slip = true;
    s.dissipation = k_t > 0.0 ? cap * (t - cap) / k_t : 0.0;
  }
  for (int d = 0; d < 3; ++d) {
    history[d] = trial[d] * scale;
    s.force[d] = history[d];
  }
  return s;
}

ContactStatus contact_forces(const ContactArgs& args, size_t begin, size_t end) {
  ContactStatus st;
  const ContactLaw& law = args.law;
  const bool friction = law.tangential_stiffness > 0.0 && !args.history.empty();
  const bool damping = law.normal_damping > 0.0;
  for (size_t q = begin; q < end; ++q) {
    const ContactPair pr = args.pairs[q];
    const int32_t* na = &args.tet_nodes[4 * static_cast<size_t>(pr.a)];
    const int32_t* nb = &args.tet_nodes[4 * static_cast<size_t>(pr.b)];
    double xa[4][3], xb[4][3];
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) {
        xa[c][d] = args.x[3 * static_cast<size_t>(na[c]) + d];
        xb[c][d] = args.x[3 * static_cast<size_t>(nb[c]) + d];
      }
    const bool per_tet = !args.tet_penalty.empty();
    TetPairForce r =
        tet_pair_potential_force(xa, xb, per_tet ? args.tet_penalty[static_cast<size_t>(pr.a)] : law.penalty,
                                 per_tet ? args.tet_penalty[static_cast<size_t>(pr.b)] : law.penalty);
    double* out = &args.pair_force[24 * q];
    const double fn = std::sqrt(dot(r.normal, r.normal));
    double fric_diss = 0.0, damp_diss = 0.0;
    if (!(fn > 0.0)) {
      if (friction) std::fill_n(&args.history[3 * q], 3, 0.0);
    } else {
      ++st.touching;
      if (friction || damping) {
        double n[3], vrel[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < 3; ++d) n[d] = r.normal[d] / fn;
        const TetGeometry A = tet_geometry(xa), B = tet_geometry(xb);
        double ba[4], bb[4];
        A.bary(r.centre, ba);
        B.bary(r.centre, bb);
        if (!args.v.empty())
          for (int c = 0; c < 4; ++c)
            for (int d = 0; d < 3; ++d)
              vrel[d] += ba[c] * args.v[3 * static_cast<size_t>(na[c]) + d] -
                         bb[c] * args.v[3 * static_cast<size_t>(nb[c]) + d];
        double extra[3] = {0.0, 0.0, 0.0};  // friction + damping force on A, applied at x_c
        const double share = law.reference_stiffness > 0.0 ? r.stiffness / law.reference_stiffness : 1.0;
        double fd = 0.0;  // the damping force along n, >= -fn (no adhesion)
        if (damping) {
          const double vn = dot(vrel, n);
          fd = std::max(-share * law.normal_damping * vn, -fn);
          for (int d = 0; d < 3; ++d) extra[d] += fd * n[d];
          damp_diss = -fd * vn * args.dt;
        }
        if (friction) {
          double du[3];
          for (int d = 0; d < 3; ++d) du[d] = vrel[d] * args.dt;
          const FrictionStep fs = coulomb_friction_update(&args.history[3 * q], n, fn, du,
                                                          law.tangential_stiffness, law.friction);
          for (int d = 0; d < 3; ++d) extra[d] += fs.force[d];
          fric_diss = fs.dissipation;
          if (fs.slip) ++st.sliding;
        }
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 3; ++d) {
            r.f[c][d] += ba[c] * extra[d];
            r.f[4 + c][d] -= bb[c] * extra[d];
          }
      }
    }
    for (int c = 0; c < 8; ++c)
      for (int d = 0; d < 3; ++d) out[3 * c + d] = r.f[c][d];
    if (!args.normal_force.empty()) args.normal_force[q] = fn;
    if (!args.energy.empty()) args.energy[q] = r.energy;
    if (!args.friction_energy.empty()) {
      const double* h = friction ? &args.history[3 * q] : nullptr;
      args.friction_energy[q] = h ? dot(h, h) / (2.0 * law.tangential_stiffness) : 0.0;
    }
    if (!args.friction_dissipation.empty()) args.friction_dissipation[q] = fric_diss;
    if (!args.damping_dissipation.empty()) args.damping_dissipation[q] = damp_diss;
  }
  return st;
}

void remap_pair_history(std::span<const ContactPair> old_pairs, std::span<const double> old_history,
                        std::span<const ContactPair> new_pairs, std::span<double> new_history) {
  size_t o = 0;
  for (size_t q = 0; q < new_pairs.size(); ++q) {
    while (o < old_pairs.size() && old_pairs[o] < new_pairs[q]) ++o;
    const bool kept = o < old_pairs.size() && old_pairs[o] == new_pairs[q];
    for (int d = 0; d < 3; ++d) new_history[3 * q + d] = kept ? old_history[3 * o + d] : 0.0;
  }
}

void contact_gather(std::span<const ContactPair> pairs, std::span<const int32_t> tet_nodes,
                    std::span<const double> pair_force, std::span<double> node_force) {
  // Corner k is corner k % 4 of side (k / 4) % 2 of pair k / 8; its force is row k of pair_force.
  add_corners_to_nodes<3>(
      8 * pairs.size(),
      [&](size_t k) {
        const ContactPair& q = pairs[k / 8];
        return tet_nodes[4 * static_cast<size_t>((k / 4) % 2 == 0 ? q.a : q.b) + k % 4];
      },
      [&](size_t k) { return &pair_force[3 * k]; }, 1.0, node_force);
}

}  // namespace rift::kernels
