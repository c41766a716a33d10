// Tet-tet intersection volume (tet_intersection.hpp) and the solid volume fraction on a fluid mesh
// (volume_fraction.hpp): exact cases (a tet with itself, disjoint and touching tets, a tet cut by a plane),
// invariance under corner order, orientation and the exchange of the two tets, robustness on tets whose
// corners sit on a coarse grid (coincident vertices, coplanar faces), conservation of the solid volume on
// a rotated fluid mesh of another resolution, exact fractions of an axis-aligned block on a lattice, the
// broad phase against its O(n_f n_s) reference, bitwise identical fractions on 1 and 2 threads, and no heap
// allocation in the kernel (nor in the broad phase once its workspace has grown).
//
// Round-off bound used below: tet_intersection.hpp states an absolute error of O(10^2 eps D^3) for a pair
// whose bounding box has diagonal D (~30 fan tets of size <= D, vertices placed to eps D); kBound =
// 256 eps D^3 is that with the constant rounded up to a power of two, not fitted to the measured errors
// (which are ~10x smaller, printed by the symmetry test).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "engine/mesh/lattice_box.hpp"
#include "engine/mesh/structured_box.hpp"
#include "engine/schedule/parallel.hpp"
#include "kernels/contact_broad_phase.hpp"
#include "kernels/tet_intersection.hpp"
#include "kernels/vec3_ops.hpp"
#include "kernels/volume_fraction.hpp"
#include "tests/unit/test_allocation_counter.hpp"

namespace rift::kernels {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Tet {
  double c[4][3];
};

double volume(const Tet& a, const Tet& b) {
  return tet_intersection_volume(a.c, b.c);
}

// The diagonal of the bounding box of both tets, and the round-off bound 256 eps D^3 (see the top).
double bound(const Tet& a, const Tet& b) {
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d) {
    double lo = a.c[0][d], hi = a.c[0][d];
    for (int k = 0; k < 4; ++k) {
      lo = std::min({lo, a.c[k][d], b.c[k][d]});
      hi = std::max({hi, a.c[k][d], b.c[k][d]});
    }
    d2 += (hi - lo) * (hi - lo);
  }
  return 256.0 * kEps * d2 * std::sqrt(d2);
}

Tet corner_tet(double s = 1.0) {
  return {{{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}}};
}

Tet translated(Tet t, double dx, double dy, double dz) {
  for (auto& p : t.c) {
    p[0] += dx;
    p[1] += dy;
    p[2] += dz;
  }
  return t;
}

// Corners uniform in a cube of side `size` around `centre`, rejected until the tet is not a sliver
// (volume >= 0.01 size^3; a regular tet of edge `size` has 0.118 size^3), so that the volume-relative
// tolerances below mean something.
Tet random_tet(std::mt19937_64& rng, const double centre[3], double size) {
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (;;) {
    Tet t;
    for (auto& p : t.c)
      for (int d = 0; d < 3; ++d) p[d] = centre[d] + size * u(rng);
    if (tet_volume(t.c) >= 0.01 * size * size * size) return t;
  }
}

TEST(TetIntersection, WithItselfIsItsVolumeExactly) {
  std::mt19937_64 rng(1);
  const double centre[3] = {10.0, -3.0, 7.0};
  for (int i = 0; i < 200; ++i) {
    const Tet a = random_tet(rng, centre, 0.01);
    EXPECT_EQ(volume(a, a), tet_volume(a.c));
    Tet b = a;  // the same tet, corners in another order: equal to the corner-order round-off
    std::swap(b.c[0], b.c[3]);
    EXPECT_NEAR(volume(a, b), tet_volume(a.c), 1e-14 * tet_volume(a.c));
  }
}

TEST(TetIntersection, DisjointAndTouchingGiveExactlyZero) {
  const Tet a = corner_tet();
  EXPECT_EQ(volume(a, translated(a, 3.0, 0.0, 0.0)), 0.0);  // far apart
  // Point reflections of a through a point c with c_x + c_y + c_z = 1 + delta lie in x + y + z >= 1 + delta:
  // their boxes overlap a's, delta = 0 makes a's slanted face and the image's coplanar (a hexagram of
  // contact), delta > 0 separates them.
  for (double delta : {0.0, 1e-3}) {
    Tet b;
    const double c = (1.0 + delta) / 3.0;
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) b.c[k][d] = 2.0 * c - a.c[k][d];
    EXPECT_EQ(volume(a, b), 0.0) << delta;
    EXPECT_EQ(volume(b, a), 0.0) << delta;
  }
  // A shared vertex only; a vertex on a's slanted face (1/3 is not exact: on the plane to round-off).
  EXPECT_EQ(volume(a, translated(a, 1.0, 0.0, 0.0)), 0.0);
  const Tet on_face = translated(a, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
  EXPECT_EQ(volume(a, on_face), 0.0);
  EXPECT_EQ(volume(on_face, a), 0.0);
  // The 6 Kuhn tets of a cube share faces and edges pairwise; each pair touches only.
  const TetMesh cube = generate_lattice_box({1, 1, 1}, {1.0, 1.0, 1.0});
  ASSERT_EQ(cube.tets.size(), 6u);
  std::vector<Tet> kuhn(6);
  for (size_t t = 0; t < 6; ++t)
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) kuhn[t].c[k][d] = cube.nodes[cube.tets[t][k]][d];
  for (size_t i = 0; i < 6; ++i)
    for (size_t j = 0; j < 6; ++j)
      if (i != j) {
        EXPECT_EQ(volume(kuhn[i], kuhn[j]), 0.0) << i << " " << j;
      }
}

TEST(TetIntersection, FlatTetsGiveZero) {
  const Tet a = corner_tet();
  const Tet flat = {{{0.1, 0.1, 0}, {0.5, 0.1, 0}, {0.1, 0.5, 0}, {0.3, 0.3, 0}}};  // in the plane z = 0
  const Tet flat_inside = {{{0.1, 0.1, 0.1}, {0.3, 0.1, 0.1}, {0.1, 0.3, 0.1}, {0.2, 0.2, 0.1}}};
  EXPECT_EQ(volume(a, flat), 0.0);
  EXPECT_EQ(volume(flat, a), 0.0);
  EXPECT_EQ(volume(a, flat_inside), 0.0);
  EXPECT_EQ(volume(flat_inside, a), 0.0);
}

// A big tet (10x A's size) whose face 0-1-2 lies in the plane n . (x - p) = 0 and which holds the side
// n . (x - p) < 0 of A: its intersection with A is the piece of A on that side.
Tet half_space_tet(const double p[3], const double n_in[3], double size) {
  double n[3], u[3], w[3];
  const double len = std::sqrt(dot(n_in, n_in));
  for (int d = 0; d < 3; ++d) n[d] = n_in[d] / len;
  const double helper[3] = {std::fabs(n[0]) < 0.6 ? 1.0 : 0.0, std::fabs(n[0]) < 0.6 ? 0.0 : 1.0, 0.0};
  cross(n, helper, u);
  const double lu = std::sqrt(dot(u, u));
  for (double& v : u) v /= lu;
  cross(n, u, w);
  Tet t;
  for (int k = 0; k < 3; ++k) {
    const double angle = 2.0 * M_PI * k / 3.0;
    for (int d = 0; d < 3; ++d) t.c[k][d] = p[d] + size * (std::cos(angle) * u[d] + std::sin(angle) * w[d]);
  }
  for (int d = 0; d < 3; ++d) t.c[3][d] = p[d] - size * n[d];
  return t;
}

TEST(TetIntersection, CutByAPlaneGivesTheAnalyticPiece) {
  // Axis-aligned, exactly representable: the corner tet cut by x = 0.25 (the piece x >= 0.25 is a tet
  // with edges 0.75 of a's: 0.75^3 / 6; all numbers exact, so only the fan sums round).
  const Tet a = corner_tet();
  const Tet big = {{{0.25, -10, -10}, {0.25, 30, -10}, {0.25, -10, 30}, {-20, 0, 0}}};
  const double expected = (1.0 - 0.75 * 0.75 * 0.75) / 6.0;
  EXPECT_NEAR(volume(a, big), expected, 4 * kEps * expected);
  // The other way round the new vertices lie on big's edges (length ~50), placed to ~50 eps each: the cut
  // face moves by that, over an area <= 1: 64 eps x 50 x 1.
  EXPECT_NEAR(volume(big, a), expected, 64 * kEps * 50.0);

  // Random tets cut by random planes that leave one corner alone on its side (the piece there is the tet
  // of that corner's 3 edges cut at t_i = s_v / (s_v - s_i): V t_1 t_2 t_3; the other piece is the rest).
  // The big tet is 10x A's size, so its plane is known to ~10 eps size: tolerance kBound of the pair
  // (D ~ 20 size), which is ~1e-11 V_A.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double centre[3] = {0.3, 0.2, -0.1};
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const Tet t = random_tet(rng, centre, 1.0);
    double n[3] = {u(rng), u(rng), u(rng)};
    double w[4] = {u(rng) + 1.0, u(rng) + 1.0, u(rng) + 1.0, u(rng) + 1.0};
    const double wsum = w[0] + w[1] + w[2] + w[3];
    double p[3] = {0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) p[d] += w[k] / wsum * t.c[k][d];
    double s[4];
    int positive = 0;
    for (int k = 0; k < 4; ++k) {
      s[k] = n[0] * (t.c[k][0] - p[0]) + n[1] * (t.c[k][1] - p[1]) + n[2] * (t.c[k][2] - p[2]);
      positive += s[k] > 0.0;
    }
    if (positive != 1 && positive != 3) continue;  // a 2-2 split has no one-line formula
    const bool lone_positive = positive == 1;
    int lone = 0;
    while ((s[lone] > 0.0) != lone_positive) ++lone;
    double t3 = 1.0;
    for (int k = 0; k < 4; ++k)
      if (k != lone) t3 *= s[lone] / (s[lone] - s[k]);
    const double v = tet_volume(t.c);
    const double kept = lone_positive ? v * (1.0 - t3) : v * t3;  // the side s < 0
    const Tet h = half_space_tet(p, n, 10.0);
    EXPECT_NEAR(volume(t, h), kept, bound(t, h)) << i;
    EXPECT_NEAR(volume(h, t), kept, bound(t, h)) << i;
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

// Overlapping random pairs: B near A, of similar size.
std::vector<std::pair<Tet, Tet>> random_pairs(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<std::pair<Tet, Tet>> pairs;
  const double centre[3] = {1.0, 2.0, 3.0};
  for (size_t i = 0; i < n; ++i) {
    const Tet a = random_tet(rng, centre, 1.0);
    const double shifted[3] = {centre[0] + u(rng), centre[1] + u(rng), centre[2] + u(rng)};
    pairs.push_back({a, random_tet(rng, shifted, 0.5 + std::fabs(u(rng)) * 2.0)});
  }
  return pairs;
}

TEST(TetIntersection, InvariantUnderCornerOrderAndOrientation) {
  const auto pairs = random_pairs(20, 3);
  int perm[4] = {0, 1, 2, 3};
  std::vector<std::array<int, 4>> perms;
  do perms.push_back({perm[0], perm[1], perm[2], perm[3]});
  while (std::next_permutation(perm, perm + 4));
  ASSERT_EQ(perms.size(), 24u);  // 12 of them reverse the orientation
  for (const auto& [a, b] : pairs) {
    const double ref = volume(a, b), tol = bound(a, b);
    for (const auto& pa : perms)
      for (const auto& pb : perms) {
        Tet ap, bp;
        for (int k = 0; k < 4; ++k)
          for (int d = 0; d < 3; ++d) {
            ap.c[k][d] = a.c[pa[k]][d];
            bp.c[k][d] = b.c[pb[k]][d];
          }
        ASSERT_NEAR(volume(ap, bp), ref, tol);
      }
    // Mirror image of both (x -> -x): every orientation reversed.
    Tet am = a, bm = b;
    for (int k = 0; k < 4; ++k) {
      am.c[k][0] = -am.c[k][0];
      bm.c[k][0] = -bm.c[k][0];
    }
    EXPECT_NEAR(volume(am, bm), ref, tol);
  }
}

// Stated relative tolerance: 1e-9 min(V_A, V_B). That is kBound for the worst pair these draws allow (A of
// size 1 and B of size >= 0.5, volumes >= 0.01 size^3, D <= 2.7: 256 eps D^3 / min V <= 256 eps x 20 /
// 1.25e-3 = 9e-10), not a fit; the measured figures (printed) are far below it.
TEST(TetIntersection, SymmetricOnRandomPairs) {
  const auto pairs = random_pairs(3000, 11);
  double worst = 0.0, worst_relative = 0.0;  // |V(A,B) - V(B,A)| / (eps D^3), and / min(V_A, V_B)
  int nonzero = 0;
  for (const auto& [a, b] : pairs) {
    const double ab = volume(a, b), ba = volume(b, a), tol = bound(a, b);
    const double smaller = std::min(tet_volume(a.c), tet_volume(b.c));
    ASSERT_NEAR(ab, ba, tol);
    ASSERT_NEAR(ab, ba, 1e-9 * smaller);
    ASSERT_GE(ab, 0.0);
    ASSERT_LE(ab, smaller);
    worst = std::max(worst, std::fabs(ab - ba) / (tol / 256.0));
    worst_relative = std::max(worst_relative, std::fabs(ab - ba) / smaller);
    nonzero += ab > 0.0;
  }
  EXPECT_GT(nonzero, 1000);
  std::printf("max |V(A,B) - V(B,A)| = %.3g eps D^3 = %.3g min(V_A, V_B) over %d intersecting pairs\n", worst,
              worst_relative, nonzero);
}

// Corners on a 3 x 3 x 3 integer grid: coincident vertices, shared edges and faces, coplanar faces and
// collinear edges everywhere. Every result is finite, within [0, min(V_A, V_B)], symmetric to kBound, and
// splits additively: the 6 Kuhn tets of the cube [0, 2]^3 tile it, so sum_k |A ∩ K_k| = |A| for A inside.
TEST(TetIntersection, RobustOnGridCornersWithDegenerateContacts) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> g(0, 2);
  const TetMesh cube = generate_lattice_box({1, 1, 1}, {2.0, 2.0, 2.0});
  std::vector<Tet> kuhn(6);
  for (size_t t = 0; t < 6; ++t)
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) kuhn[t].c[k][d] = cube.nodes[cube.tets[t][k]][d];
  int tested = 0;
  while (tested < 2000) {
    Tet a, b;
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) {
        a.c[k][d] = g(rng);
        b.c[k][d] = g(rng);
      }
    const double va = tet_volume(a.c), vb = tet_volume(b.c);
    const double ab = volume(a, b), ba = volume(b, a);
    ASSERT_TRUE(std::isfinite(ab) && std::isfinite(ba));
    ASSERT_GE(ab, 0.0);
    ASSERT_LE(ab, std::min(va, vb));
    ASSERT_NEAR(ab, ba, bound(a, b));
    double sum = 0.0;
    for (const Tet& k : kuhn) sum += volume(a, k);
    ASSERT_NEAR(sum, va, 6 * bound(a, kuhn[0]));
    ++tested;
  }
}

// ---------------------------------------------------------------------------------------------------------
// Volume fraction on meshes

struct Mesh {
  std::vector<double> x;
  std::vector<int32_t> tets;
  size_t num_tets() const { return tets.size() / 4; }
};

Mesh flatten(const TetMesh& m) {
  Mesh out;
  for (const auto& p : m.nodes) out.x.insert(out.x.end(), p.begin(), p.end());
  for (const auto& t : m.tets) out.tets.insert(out.tets.end(), t.begin(), t.end());
  return out;
}

// Rotation by `angle` about the unit axis `k`, about the point `c`.
void rotate(Mesh& m, const double axis[3], double angle, const double c[3]) {
  double k[3];
  const double len = std::sqrt(dot(axis, axis));
  for (int d = 0; d < 3; ++d) k[d] = axis[d] / len;
  const double cs = std::cos(angle), sn = std::sin(angle);
  for (size_t i = 0; i < m.x.size() / 3; ++i) {
    double v[3], kv[3];
    for (int d = 0; d < 3; ++d) v[d] = m.x[3 * i + d] - c[d];
    cross(k, v, kv);
    const double kd = dot(k, v);
    for (int d = 0; d < 3; ++d) m.x[3 * i + d] = c[d] + v[d] * cs + kv[d] * sn + k[d] * kd * (1.0 - cs);
  }
}

std::vector<double> tet_volumes(const Mesh& m) {
  std::vector<double> v(m.num_tets());
  for (size_t t = 0; t < v.size(); ++t) {
    double c[4][3];
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) c[a][d] = m.x[3 * static_cast<size_t>(m.tets[4 * t + a]) + d];
    v[t] = tet_volume(c);
  }
  return v;
}

struct Boxes {
  std::vector<double> lo, hi;
};

Boxes boxes_of(const Mesh& m) {
  Boxes b;
  std::vector<int32_t> ids(m.num_tets());
  std::iota(ids.begin(), ids.end(), 0);
  b.lo.resize(3 * ids.size());
  b.hi.resize(3 * ids.size());
  tet_bounding_boxes(m.x, m.tets, ids, b.lo, b.hi, 0, ids.size());
  return b;
}

struct Fractions {
  std::vector<double> solid_volume, fraction;
  VolumeFractionStatus status;
};

// The candidate pairs (checked against the brute-force reference) and the fractions, sequentially.
Fractions fractions(const Mesh& fluid, const Mesh& solid, std::vector<CouplingPair>* pairs_out = nullptr) {
  const Boxes fb = boxes_of(fluid), sb = boxes_of(solid);
  const CouplingBroadPhaseArgs bp{fb.lo, fb.hi, sb.lo, sb.hi, 0.0};
  CouplingBroadPhaseWorkspace ws;
  coupling_broad_phase(bp, ws);
  EXPECT_EQ(ws.pairs, coupling_broad_phase_brute_force(bp));
  Fractions f;
  f.solid_volume.assign(fluid.num_tets(), -1.0);
  f.fraction.assign(fluid.num_tets(), -1.0);
  const VolumeFractionArgs args{fluid.x,  fluid.tets,     solid.x,   solid.tets,
                                ws.pairs, f.solid_volume, f.fraction};
  f.status = volume_fraction(args, 0, fluid.num_tets());
  if (pairs_out) *pairs_out = ws.pairs;
  return f;
}

// A 5^3-cell lattice (side 1.5, 750 tets) turned by 0.4 rad about (1, 2, 3) around its centre, and a
// 7 x 6 x 5-cell block (0.7 x 0.6 x 0.5, cells 0.1 against the fluid's 0.3: 1260 tets) inside it (its
// half-diagonal 0.52 < the lattice's inner radius 0.75), not aligned with anything.
TEST(VolumeFraction, ConservesTheSolidVolumeOnARotatedMeshOfAnotherResolution) {
  Mesh fluid = flatten(generate_lattice_box({5, 5, 5}, {1.5, 1.5, 1.5}));
  const double axis[3] = {1.0, 2.0, 3.0}, centre[3] = {0.75, 0.75, 0.75};
  rotate(fluid, axis, 0.4, centre);
  const Mesh solid = flatten(structured_box({{0.4, 0.45, 0.5}, {1.1, 1.05, 1.0}, {7, 6, 5}}));
  const Fractions f = fractions(fluid, solid);
  const std::vector<double> vf = tet_volumes(fluid), vs = tet_volumes(solid);
  const double solid_volume = std::accumulate(vs.begin(), vs.end(), 0.0);
  EXPECT_NEAR(solid_volume, 0.7 * 0.6 * 0.5, 1e-14);
  double sum_volume = 0.0, sum_fraction = 0.0;
  size_t full = 0;
  for (size_t t = 0; t < vf.size(); ++t) {
    ASSERT_GE(f.fraction[t], 0.0);
    ASSERT_LE(f.fraction[t], 1.0);
    ASSERT_LE(f.solid_volume[t], vf[t] * (1.0 + 1e-12));
    sum_volume += f.solid_volume[t];
    sum_fraction += f.fraction[t] * vf[t];
    full += f.fraction[t] > 1.0 - 1e-12;
  }
  // Requested 1e-10 relative; what is expected is ~1e-14 (each of ~1e4 pairs within kBound, with D ~ the
  // fluid cell, ~1e-13 of a fluid tet, errors of both signs).
  EXPECT_NEAR(sum_volume, solid_volume, 1e-10 * solid_volume);
  EXPECT_NEAR(sum_fraction, solid_volume, 1e-10 * solid_volume);
  EXPECT_GT(f.status.cut, 100u);
  EXPECT_GT(full, 0u);
  std::printf("solid volume %.17g, sum over fluid tets %.17g (relative %.1e); %zu pairs, %zu cut tets\n",
              solid_volume, sum_volume, std::fabs(sum_volume - solid_volume) / solid_volume, f.status.pairs,
              f.status.cut);
}

// Fluid: the 6^3-cell lattice of h = 0.1. Solid: the block [0.1, 0.45] x [0.1, 0.5] x [0.1, 0.4] in cells of
// 0.05 (another resolution, but all its faces on lattice planes except x = 0.45, half-way through the
// cells of column i = 4). Fluid tets in cells inside the block get 1, outside 0, and in column 4 the piece
// x <= 0.45 of the tet: with m of its 4 corners at x = 0.4, 1/8 (m = 1: a corner tet of half the edges),
// 1/2 (m = 2: the section area is proportional to t (1 - t), symmetric about t = 1/2) or 7/8 (m = 3).
// Tolerance 1e-12: each fluid tet sums <= ~50 pairs, each within kBound (D <= 0.2: 256 eps (0.2)^3 / V_f =
// 1.7e-12 V_f at worst; typically 10-100x less).
TEST(VolumeFraction, AxisAlignedBlockGivesExactFractions) {
  const double h = 0.1;
  const Mesh fluid = flatten(generate_lattice_box({6, 6, 6}, {0.6, 0.6, 0.6}));
  const Mesh solid = flatten(structured_box({{0.1, 0.1, 0.1}, {0.45, 0.5, 0.4}, {7, 8, 6}}));
  const Fractions f = fractions(fluid, solid);
  size_t ones = 0, zeros = 0, partial[4] = {0, 0, 0, 0};
  for (size_t t = 0; t < fluid.num_tets(); ++t) {
    double centroid[3] = {0, 0, 0};
    int at_04 = 0;
    for (int a = 0; a < 4; ++a) {
      const double* p = &fluid.x[3 * static_cast<size_t>(fluid.tets[4 * t + a])];
      for (int d = 0; d < 3; ++d) centroid[d] += p[d] / 4.0;
      at_04 += std::fabs(p[0] - 0.4) < 1e-9;
    }
    const int cell[3] = {static_cast<int>(centroid[0] / h), static_cast<int>(centroid[1] / h),
                         static_cast<int>(centroid[2] / h)};
    const bool in_yz = cell[1] >= 1 && cell[1] < 5 && cell[2] >= 1 && cell[2] < 4;
    double expected = 0.0;
    if (in_yz && cell[0] >= 1 && cell[0] < 4) {
      expected = 1.0;
      ++ones;
    } else if (in_yz && cell[0] == 4) {
      ASSERT_GE(at_04, 1);
      ASSERT_LE(at_04, 3);
      expected = at_04 == 1 ? 1.0 / 8.0 : at_04 == 2 ? 0.5 : 7.0 / 8.0;
      ++partial[at_04];
    } else {
      ++zeros;
    }
    EXPECT_NEAR(f.fraction[t], expected, 1e-12) << "tet " << t << " cell " << cell[0] << cell[1] << cell[2];
  }
  EXPECT_EQ(ones, 6u * 3 * 4 * 3);
  EXPECT_EQ(partial[1] + partial[2] + partial[3], 6u * 4 * 3);
  EXPECT_EQ(partial[1], partial[3]);
  EXPECT_GT(zeros, 0u);
}

TEST(VolumeFraction, BitwiseIdenticalOnOneAndTwoThreadsAndAnySplit) {
  Mesh fluid = flatten(generate_lattice_box({10, 10, 10}, {1.0, 1.0, 1.0}));
  const double axis[3] = {-0.3, 1.0, 0.2}, centre[3] = {0.5, 0.5, 0.5};
  rotate(fluid, axis, 0.3, centre);
  const Mesh solid = flatten(structured_box({{0.25, 0.3, 0.2}, {0.75, 0.7, 0.65}, {9, 7, 8}}));
  std::vector<CouplingPair> pairs;
  const Fractions reference = fractions(fluid, solid, &pairs);
  const size_t n = fluid.num_tets();
  for (int threads : {1, 2})
    for (size_t grain : {size_t{7}, size_t{256}}) {
      std::vector<double> volume(n, -1.0), fraction(n, -1.0);
      const VolumeFractionArgs args{fluid.x, fluid.tets, solid.x, solid.tets, pairs, volume, fraction};
      tbb::task_arena arena(threads);
      arena.execute(
          [&] { parallel_for(n, grain, [&](size_t b, size_t e) { volume_fraction(args, b, e); }); });
      EXPECT_EQ(std::memcmp(volume.data(), reference.solid_volume.data(), n * sizeof(double)), 0)
          << threads << " threads, grain " << grain;
      EXPECT_EQ(std::memcmp(fraction.data(), reference.fraction.data(), n * sizeof(double)), 0)
          << threads << " threads, grain " << grain;
    }
  // The kernel's value for a pair is tet_intersection_volume(solid tet, fluid tet), bit for bit.
  for (size_t i = 0; i < pairs.size(); i += 97) {
    Tet ft, st;
    for (int a = 0; a < 4; ++a)
      for (int d = 0; d < 3; ++d) {
        ft.c[a][d] = fluid.x[3 * static_cast<size_t>(fluid.tets[4 * pairs[i].fluid + a]) + d];
        st.c[a][d] = solid.x[3 * static_cast<size_t>(solid.tets[4 * pairs[i].solid + a]) + d];
      }
    const TetHalfSpaces planes = tet_half_spaces(ft.c);
    EXPECT_EQ(clipped_tet_volume(st.c, planes), volume(st, ft));
  }
}

TEST(CouplingBroadPhase, MatchesTheReferenceOnRandomBoxesWithABuffer) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto make = [&](size_t n, double span, double size) {
    Boxes b;
    for (size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        const double lo = span * u(rng);
        b.lo.push_back(lo);
        b.hi.push_back(lo + size * u(rng));
      }
    return b;
  };
  const Boxes fluid = make(800, 1.0, 0.15), solid = make(500, 0.6, 0.05);
  CouplingBroadPhaseWorkspace ws;
  for (double buffer : {0.0, 0.02}) {
    const CouplingBroadPhaseArgs args{fluid.lo, fluid.hi, solid.lo, solid.hi, buffer};
    const CouplingBroadPhaseStats stats = coupling_broad_phase(args, ws);
    const std::vector<CouplingPair> expected = coupling_broad_phase_brute_force(args);
    EXPECT_EQ(ws.pairs, expected) << buffer;
    EXPECT_EQ(stats.pairs, expected.size());
    EXPECT_TRUE(std::is_sorted(ws.pairs.begin(), ws.pairs.end()));
    EXPECT_GT(expected.size(), 300u);
  }
  // Steady state: the same call again grows nothing.
  const size_t grows = ws.grows;
  const CouplingBroadPhaseArgs args{fluid.lo, fluid.hi, solid.lo, solid.hi, 0.02};
  coupling_broad_phase(args, ws);
  EXPECT_EQ(ws.grows, grows);
  // No solid, no fluid: no pairs.
  coupling_broad_phase({fluid.lo, fluid.hi, {}, {}, 0.0}, ws);
  EXPECT_TRUE(ws.pairs.empty());
}

// The kernel allocates nothing (fixed-size stack buffers), and the broad phase nothing once its workspace
// has grown to the problem (heap allocations counted through operator new).
TEST(VolumeFraction, AllocatesNothing) {
  Mesh fluid = flatten(generate_lattice_box({6, 6, 6}, {1.0, 1.0, 1.0}));
  const double axis[3] = {0.2, 0.1, 1.0}, centre[3] = {0.5, 0.5, 0.5};
  rotate(fluid, axis, 0.7, centre);
  const Mesh solid = flatten(structured_box({{0.3, 0.3, 0.3}, {0.7, 0.7, 0.7}, {5, 5, 5}}));
  const Boxes fb = boxes_of(fluid), sb = boxes_of(solid);
  const CouplingBroadPhaseArgs bp{fb.lo, fb.hi, sb.lo, sb.hi, 0.01};
  CouplingBroadPhaseWorkspace ws;
  coupling_broad_phase(bp, ws);
  std::vector<double> volume(fluid.num_tets()), fraction(fluid.num_tets());
  const VolumeFractionArgs args{fluid.x, fluid.tets, solid.x, solid.tets, ws.pairs, volume, fraction};
  const long before = allocations.load();
  coupling_broad_phase(bp, ws);
  const VolumeFractionStatus status = volume_fraction(args, 0, fluid.num_tets());
  EXPECT_EQ(allocations.load(), before);
  EXPECT_GT(status.intersecting, 100u);
}

}  // namespace
}  // namespace rift::kernels
