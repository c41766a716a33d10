// Munjiza's distributed-potential tet-tet contact with Coulomb friction (contact_potential.hpp): no force
// without overlap, force and moment balance, contactor/target symmetry, a vertex pushed into a face (along
// the face normal, exact cubic growth with depth), conservation (zero work round closed paths, and the
// work equals the overlap energy p ∫(phi_A + phi_B) dV integrated on a grid), and the friction law (stick,
// slip at the cap, dissipation = cap x slip distance) alone and through contact_forces. The kernel's
// overlap energy is checked against the grid integral and as the potential of the force.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "kernels/contact_potential.hpp"

namespace rift::kernels {
namespace {

using Tet = std::array<std::array<double, 3>, 4>;

TetPairForce pair_force(const Tet& a, const Tet& b, double p) {
  double xa[4][3], xb[4][3];
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 3; ++d) {
      xa[c][d] = a[c][d];
      xb[c][d] = b[c][d];
    }
  return tet_pair_potential_force(xa, xb, p);
}

Tet translated(const Tet& t, const double u[3]) {
  Tet r = t;
  for (auto& v : r)
    for (int d = 0; d < 3; ++d) v[d] += u[d];
  return r;
}

double phi(const Tet& t, const double x[3]) {
  double xt[4][3];
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 3; ++d) xt[c][d] = t[c][d];
  return tet_potential(xt, x);
}

// A random tet of size ~1 around centre c, not too flat.
Tet random_tet(std::mt19937_64& rng, const double c[3]) {
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (;;) {
    Tet t;
    for (auto& v : t)
      for (int d = 0; d < 3; ++d) v[d] = c[d] + u(rng);
    double e[3][3];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d) e[i][d] = t[i + 1][d] - t[0][d];
    const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                       e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                       e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
    if (std::abs(det) > 0.05) return t;  // volume > 1/120
  }
}

double max_abs(const TetPairForce& r) {
  double m = 0;
  for (const auto& f : r.f)
    for (double v : f) m = std::max(m, std::abs(v));
  return m;
}

constexpr double kP = 1e9;  // penalty [Pa]

TEST(ContactPotential, NoOverlapNoForce) {
  const Tet a = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const double apart[3] = {1.2, 0.1, 0.0};
  const TetPairForce r = pair_force(a, translated(a, apart), kP);
  EXPECT_EQ(r.weight, 0.0);
  EXPECT_EQ(max_abs(r), 0.0);
  // Boxes overlap but the tets do not: a and its point reflection through (0.5, 0.5, 0.5) shifted apart.
  Tet b;
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 3; ++d) b[c][d] = 1.0 - a[c][d] + 0.01;
  EXPECT_EQ(max_abs(pair_force(a, b, kP)), 0.0);
  // Face to face neighbours: phi_target = 0 on the shared face, so the force is zero.
  Tet m = a;
  for (auto& v : m) v[0] = -v[0];
  EXPECT_EQ(max_abs(pair_force(a, m, kP)), 0.0);
  // The same with a face in a slanted plane (coordinates not exact there): still exactly zero.
  Tet s = a;  // reflect corner 0 through the plane x + y + z = 1 of the face (1, 2, 3)
  s[0] = {2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
  EXPECT_EQ(max_abs(pair_force(a, s, kP)), 0.0);
}

TEST(ContactPotential, ForceAndMomentBalance) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  int overlapping = 0;
  for (int k = 0; k < 200; ++k) {
    const double ca[3] = {0, 0, 0}, cb[3] = {u(rng), u(rng), u(rng)};
    const Tet a = random_tet(rng, ca), b = random_tet(rng, cb);
    const TetPairForce r = pair_force(a, b, kP);
    if (r.weight == 0.0) continue;
    ++overlapping;
    const double scale = max_abs(r);
    ASSERT_GT(scale, 0.0);
    double f[3] = {0, 0, 0}, m[3] = {0, 0, 0};
    for (int c = 0; c < 8; ++c) {
      const auto& x = c < 4 ? a[c] : b[c - 4];
      const double* fc = r.f[c];
      for (int d = 0; d < 3; ++d) f[d] += fc[d];
      m[0] += x[1] * fc[2] - x[2] * fc[1];
      m[1] += x[2] * fc[0] - x[0] * fc[2];
      m[2] += x[0] * fc[1] - x[1] * fc[0];
    }
    for (int d = 0; d < 3; ++d) {
      EXPECT_LT(std::abs(f[d]), 1e-12 * scale) << k;
      EXPECT_LT(std::abs(m[d]), 1e-12 * scale) << k;  // lever arms are ~1
    }
  }
  EXPECT_GT(overlapping, 50);
}

TEST(ContactPotential, PerTetPenaltiesScaleEachWayAndKeepTheBalance) {
  // F(p_a, p_b) is linear in the two penalties, one per way: F(p_a, p_b) = F(p_a, 0) + F(0, p_b),
  // F(p, p) is the one-penalty force, and every split keeps the force and moment balance.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  int overlapping = 0;
  for (int k = 0; k < 100; ++k) {
    const double ca[3] = {0, 0, 0}, cb[3] = {u(rng), u(rng), u(rng)};
    const Tet a = random_tet(rng, ca), b = random_tet(rng, cb);
    double xa[4][3], xb[4][3];
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) xa[c][d] = a[c][d], xb[c][d] = b[c][d];
    const TetPairForce one = tet_pair_potential_force(xa, xb, kP);
    if (one.weight == 0.0) continue;
    ++overlapping;
    const TetPairForce same = tet_pair_potential_force(xa, xb, kP, kP);
    const TetPairForce both = tet_pair_potential_force(xa, xb, 2 * kP, 0.5 * kP);
    const TetPairForce only_a = tet_pair_potential_force(xa, xb, 2 * kP, 0.0);
    const TetPairForce only_b = tet_pair_potential_force(xa, xb, 0.0, 0.5 * kP);
    const double scale = max_abs(both);
    double f[3] = {0, 0, 0}, m[3] = {0, 0, 0};
    for (int c = 0; c < 8; ++c) {
      const auto& x = c < 4 ? a[c] : b[c - 4];
      for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(same.f[c][d], one.f[c][d]);
        EXPECT_NEAR(both.f[c][d], only_a.f[c][d] + only_b.f[c][d], 1e-12 * scale);
        f[d] += both.f[c][d];
      }
      m[0] += x[1] * both.f[c][2] - x[2] * both.f[c][1];
      m[1] += x[2] * both.f[c][0] - x[0] * both.f[c][2];
      m[2] += x[0] * both.f[c][1] - x[1] * both.f[c][0];
    }
    for (int d = 0; d < 3; ++d) {
      EXPECT_LT(std::abs(f[d]), 1e-12 * scale) << k;
      EXPECT_LT(std::abs(m[d]), 1e-12 * scale) << k;
    }
  }
  EXPECT_GT(overlapping, 25);
}

TEST(ContactPotential, SwappingContactorAndTarget) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (int k = 0; k < 50; ++k) {
    const double ca[3] = {0, 0, 0}, cb[3] = {u(rng), u(rng), u(rng)};
    const Tet a = random_tet(rng, ca), b = random_tet(rng, cb);
    const TetPairForce ab = pair_force(a, b, kP), ba = pair_force(b, a, kP);
    const double scale = max_abs(ab);
    // The same corner forces, in swapped slots (only the order of the additions differs) ...
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) {
        EXPECT_NEAR(ab.f[c][d], ba.f[4 + c][d], 1e-13 * scale);
        EXPECT_NEAR(ab.f[4 + c][d], ba.f[c][d], 1e-13 * scale);
      }
    // ... so the total on the first tet changes sign with the swap.
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(ab.normal[d], -ba.normal[d], 1e-13 * scale);
  }
}

// Tet B's top face is z = 0 (B below); tet A points its apex down into it at depth delta, A's three faces
// through the apex symmetric about the vertical axis. The force on A is +z (B's outward face normal), the
// lateral parts of A's faces cancel, and it grows exactly as delta^3 (both potentials are homogeneous of
// degree 1 about the apex / the face in the small tip).
TEST(ContactPotential, VertexIntoFace) {
  const Tet b = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, -1.0}}};
  const double r = 0.2, h = 0.5;
  auto a_at = [&](double delta) {
    Tet a;
    a[0] = {0.3, 0.3, -delta};
    for (int k = 0; k < 3; ++k) {
      const double t = 2.0 * std::numbers::pi * k / 3.0 + 0.1;
      a[k + 1] = {0.3 + r * std::cos(t), 0.3 + r * std::sin(t), h - delta};
    }
    return a;
  };
  double previous = 0.0;
  for (double delta : {0.005, 0.01, 0.02, 0.04}) {
    const TetPairForce f = pair_force(a_at(delta), b, kP);
    const double fz = f.normal[2];
    EXPECT_GT(fz, 0.0);
    EXPECT_LT(std::hypot(f.normal[0], f.normal[1]), 1e-10 * fz) << delta;
    if (previous > 0.0) {
      EXPECT_NEAR(fz / previous, 8.0, 8e-9) << delta;
    }
    previous = fz;
    // Linear in p.
    EXPECT_NEAR(pair_force(a_at(delta), b, 2 * kP).normal[2], 2 * fz, 1e-12 * fz);
  }
}

// Rigid translation of A round closed loops: the work of the force on A is zero (to the quadrature error
// of the loop integral), while the energy changes by a good part of the total |work| along the way.
TEST(ContactPotential, ClosedPathWorkIsZero) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 5; ++k) {
    const double c0[3] = {0, 0, 0}, c1[3] = {0.25, 0.1, -0.1};
    const Tet a = random_tet(rng, c0), b = random_tet(rng, c1);
    const int steps = 4000;
    const double R = 0.3;
    double work = 0.0, abs_work = 0.0, swing = 0.0;
    for (int s = 0; s < steps; ++s) {
      const double t0 = 2 * std::numbers::pi * s / steps, t1 = 2 * std::numbers::pi * (s + 1) / steps;
      const double tm = 0.5 * (t0 + t1);
      auto at = [&](double t, double u[3]) {  // a tilted circle plus a vertical wobble
        u[0] = R * std::cos(t);
        u[1] = R * std::sin(t) * 0.8;
        u[2] = 0.2 * R * std::sin(2 * t) + 0.3 * R * std::sin(t);
      };
      double u0[3], u1[3], um[3];
      at(t0, u0);
      at(t1, u1);
      at(tm, um);
      const TetPairForce f = pair_force(translated(a, um), b, kP);
      double dw = 0;
      for (int d = 0; d < 3; ++d) dw += f.normal[d] * (u1[d] - u0[d]);
      work += dw;
      abs_work += std::abs(dw);
      swing = std::max(swing, std::abs(work));  // |E(u) - E(u_0)| along the way
    }
    ASSERT_GT(abs_work, 0.0);
    EXPECT_LT(std::abs(work), 1e-5 * abs_work) << k;
    EXPECT_GT(swing, 0.1 * abs_work) << k;
  }
}

// The work from a separated position to an overlapping one equals the overlap energy there,
// E = p ∫_{A∩B} (phi_A + phi_B) dV, integrated with the midpoint rule on a 120^3 grid over the overlap's
// box (phi is piecewise linear with kinks: ~1e-3 relative error).
TEST(ContactPotential, WorkEqualsOverlapEnergy) {
  const Tet a = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  const Tet b = {{{0.2, 0.2, 0.1}, {0.9, 0.1, 0.2}, {0.3, 0.8, 0.15}, {0.35, 0.3, 0.8}}};
  const double start[3] = {-1.5, -0.5, -0.2}, end[3] = {0.05, 0.02, -0.03};
  // -∫ F_A . du along the straight path (E = 0 at the start: no overlap).
  const int steps = 3000;
  double work = 0.0;
  for (int s = 0; s < steps; ++s) {
    const double t = (s + 0.5) / steps;
    double u[3], du[3];
    for (int d = 0; d < 3; ++d) {
      u[d] = start[d] + t * (end[d] - start[d]);
      du[d] = (end[d] - start[d]) / steps;
    }
    const TetPairForce f = pair_force(translated(a, u), b, kP);
    for (int d = 0; d < 3; ++d) work -= f.normal[d] * du[d];
  }
  EXPECT_EQ(pair_force(translated(a, start), b, kP).weight, 0.0);
  const Tet ae = translated(a, end);
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::max(std::min({ae[0][d], ae[1][d], ae[2][d], ae[3][d]}),
                     std::min({b[0][d], b[1][d], b[2][d], b[3][d]}));
    hi[d] = std::min(std::max({ae[0][d], ae[1][d], ae[2][d], ae[3][d]}),
                     std::max({b[0][d], b[1][d], b[2][d], b[3][d]}));
  }
  const int n = 120;
  double energy = 0.0;
  const double cell = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]) / (double(n) * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const double x[3] = {lo[0] + (i + 0.5) * (hi[0] - lo[0]) / n, lo[1] + (j + 0.5) * (hi[1] - lo[1]) / n,
                             lo[2] + (k + 0.5) * (hi[2] - lo[2]) / n};
        const double pa = phi(ae, x), pb = phi(b, x);
        if (pa > 0.0 && pb > 0.0) energy += kP * (pa + pb) * cell;
      }
  ASSERT_GT(work, 0.0);
  EXPECT_NEAR(work / energy, 1.0, 5e-3) << "work " << work << " energy " << energy;
  RecordProperty("work_over_grid_energy", testing::PrintToString(work / energy));
  // The kernel's E (exact, from the boundary polygons) against both.
  const double e_kernel = pair_force(ae, b, kP).energy;
  EXPECT_NEAR(e_kernel / energy, 1.0, 5e-3);
  EXPECT_NEAR(work / e_kernel, 1.0, 1e-5);  // the path quadrature error only (~1e-6)
  RecordProperty("work_over_kernel_energy", testing::PrintToString(work / e_kernel));
}

// The force on A is minus the gradient of the kernel's E under translation of A, and its moment minus the
// derivative under rotation of A (central differences), on random overlapping pairs; E >= 0, E = 0 without
// overlap; E is symmetric in A and B. (Under a deformation of A the corner forces are not -dE/dx: on such
// pairs they differ by 10-50 % of the largest corner force; not asserted.)
TEST(ContactPotential, ForceIsMinusEnergyGradient) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  int checked = 0;
  for (int k = 0; k < 60; ++k) {
    const double ca[3] = {0, 0, 0}, cb[3] = {u(rng), u(rng), u(rng)};
    const Tet a = random_tet(rng, ca), b = random_tet(rng, cb);
    const TetPairForce r = pair_force(a, b, kP);
    EXPECT_GE(r.energy, 0.0);
    EXPECT_NEAR(pair_force(b, a, kP).energy, r.energy, 1e-12 * std::max(r.energy, 1.0));
    if (r.weight == 0.0) {
      EXPECT_EQ(r.energy, 0.0);
      continue;
    }
    const double fmag = std::hypot(r.normal[0], r.normal[1], r.normal[2]);
    if (fmag < 1e-3 * kP) continue;  // barely touching: the difference step would leave the overlap
    ++checked;
    const double h = 1e-6;
    for (int d = 0; d < 3; ++d) {
      double up[3] = {0, 0, 0}, dn[3] = {0, 0, 0};
      up[d] = h;
      dn[d] = -h;
      const double grad =
          (pair_force(translated(a, up), b, kP).energy - pair_force(translated(a, dn), b, kP).energy) /
          (2 * h);
      EXPECT_NEAR(r.normal[d], -grad, 1e-5 * fmag) << k << " axis " << d;
    }
    // Rigid rotation of A about each axis through the origin: the moment of A's corner forces is
    // -dE/dtheta (the lever arms are ~1).
    double moment[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c) {
      const auto& x = a[c];
      const double* f = r.f[c];
      moment[0] += x[1] * f[2] - x[2] * f[1];
      moment[1] += x[2] * f[0] - x[0] * f[2];
      moment[2] += x[0] * f[1] - x[1] * f[0];
    }
    for (int axis = 0; axis < 3; ++axis) {
      auto energy_at = [&](double theta) {
        Tet rot = a;
        const int i = (axis + 1) % 3, j = (axis + 2) % 3;
        for (int c = 0; c < 4; ++c) {
          rot[c][i] = std::cos(theta) * a[c][i] - std::sin(theta) * a[c][j];
          rot[c][j] = std::sin(theta) * a[c][i] + std::cos(theta) * a[c][j];
        }
        return pair_force(rot, b, kP).energy;
      };
      const double grad = (energy_at(h) - energy_at(-h)) / (2 * h);
      EXPECT_NEAR(moment[axis], -grad, 1e-5 * fmag) << k << " axis " << axis;
    }
  }
  EXPECT_GE(checked, 15);
}

TEST(ContactFriction, StickThenSlipAtTheCap) {
  const double n[3] = {0, 0, 1}, fn = 10.0, mu = 0.5, kt = 1000.0, cap = mu * fn;
  double hist[3] = {0, 0, 0};
  const double s = 1e-4, du[3] = {s, 0, 0};
  double travel = 0.0, dissipation = 0.0, work = 0.0;
  for (int step = 1; step <= 200; ++step) {
    const FrictionStep r = coulomb_friction_update(hist, n, fn, du, kt, mu);
    travel += s;
    dissipation += r.dissipation;
    work -= r.force[0] * s;
    if (kt * travel <= cap * (1 - 1e-12)) {  // stick: elastic, no dissipation
      EXPECT_FALSE(r.slip) << step;
      EXPECT_NEAR(r.force[0], -kt * travel, 1e-12);
      EXPECT_EQ(r.dissipation, 0.0);
    } else if (kt * travel > cap * (1 + 1e-12)) {  // slide at mu f_n against the motion
      EXPECT_TRUE(r.slip) << step;
      EXPECT_NEAR(r.force[0], -cap, 1e-12);
      EXPECT_NEAR(r.force[1], 0.0, 1e-15);
    }
    EXPECT_NEAR(std::hypot(hist[0], hist[1], hist[2]), std::min(kt * travel, cap), 1e-9);
  }
  // Dissipation = cap x slip distance, the slip being the travel beyond the elastic cap / k_t.
  EXPECT_NEAR(dissipation, cap * (travel - cap / kt), 1e-12);
  // Energy balance: work done against friction = dissipation + stored cap^2 / (2 k_t), up to the
  // O(s) error of the incremental loading (cap s / 2).
  EXPECT_NEAR(work, dissipation + cap * cap / (2 * kt), 0.51 * cap * s);
  // Reverse: elastic unloading first (no dissipation for 2 cap / k_t of travel), then slip the other way.
  const double back[3] = {-s, 0, 0};
  double back_dissipation = 0.0;
  for (int step = 1; step <= 99; ++step)
    back_dissipation += coulomb_friction_update(hist, n, fn, back, kt, mu).dissipation;
  EXPECT_EQ(back_dissipation, 0.0);
  EXPECT_NEAR(hist[0], -cap + 99 * kt * s, 1e-9);
  // A larger normal force lifts the cap; f_n = 0 gives no friction at all.
  double h2[3] = {0, 0, 0};
  const double big[3] = {0.1, 0, 0};
  EXPECT_NEAR(coulomb_friction_update(h2, n, 0.0, big, kt, mu).force[0], 0.0, 0.0);
  // The normal part of du is ignored, and a stored force is turned into a new tangent plane, length kept.
  double h3[3] = {-2, 0, 0};
  const double nz[3] = {0, 0.6, 0.8}, zero[3] = {0, 0, 0}, normal_du[3] = {0, 0.6e-3, 0.8e-3};
  FrictionStep r = coulomb_friction_update(h3, nz, 100.0, normal_du, kt, mu);
  EXPECT_NEAR(r.force[0], -2.0, 1e-12);
  const double tilted[3] = {0.6, 0, 0.8};  // history (-2, 0, 0) has normal component -1.2 along it
  r = coulomb_friction_update(h3, tilted, 100.0, zero, kt, mu);
  EXPECT_NEAR(r.force[0] * tilted[0] + r.force[2] * tilted[2], 0.0, 1e-12);
  EXPECT_NEAR(std::hypot(r.force[0], r.force[1], r.force[2]), 2.0, 1e-12);
}

// Nodes 0-3: tet A, its apex delta deep in the top face (z = 0) of tet B, nodes 4-7.
std::vector<double> apex_in_top_face(double delta) {
  const double r = 0.2, h = 0.5;
  std::vector<double> x = {0.3, 0.3, -delta};
  for (int k = 0; k < 3; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 3.0 + 0.1;
    x.insert(x.end(), {0.3 + r * std::cos(t), 0.3 + r * std::sin(t), h - delta});
  }
  x.insert(x.end(), {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, -1.0});
  return x;
}

// Through contact_forces: A's apex in B's top face, A sliding along x with B at rest. The friction force on
// A opposes the motion, reaches mu f_n and then dissipates mu f_n v dt per step; force and moment balance
// hold with friction and damping; and splitting the range does not change anything.
TEST(ContactFriction, PairsThroughTheDriver) {
  const double delta = 0.02;
  std::vector<double> x = apex_in_top_face(delta);
  const double vx = 0.1, dt = 1e-3;
  std::vector<double> v(24, 0.0);
  for (int c = 0; c < 4; ++c) v[3 * c] = vx;
  const std::vector<int32_t> tet_nodes = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<ContactPair> pairs = {{0, 1}};
  std::vector<double> history(3, 0.0), force(24), fn(1), fdiss(1), ddiss(1);
  ContactLaw law;
  law.penalty = kP;
  law.friction = 0.6;
  ContactArgs args{x, v, tet_nodes, pairs, law, dt, history, force, fn, fdiss, ddiss};
  // First without friction: the normal force.
  ContactStatus st = contact_forces(args, 0, 1);
  EXPECT_EQ(st.touching, 1u);
  const double f_n = fn[0];
  ASSERT_GT(f_n, 0.0);
  // Friction stiffness such that the cap is reached in ~20 steps.
  args.law.tangential_stiffness = law.friction * f_n / (20 * vx * dt);
  const double cap = law.friction * f_n;
  double total_diss = 0.0;
  for (int step = 1; step <= 60; ++step) {
    st = contact_forces(args, 0, 1);
    double ft[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) ft[d] += force[3 * c + d];
    EXPECT_NEAR(ft[2], f_n, 1e-9 * f_n);  // friction is tangential here
    EXPECT_LT(ft[0], 0.0);
    EXPECT_LE(-ft[0], cap * (1 + 1e-12));
    if (step > 21) {
      EXPECT_EQ(st.sliding, 1u) << step;
      EXPECT_NEAR(-ft[0], cap, 1e-9 * cap);
      EXPECT_NEAR(fdiss[0], cap * vx * dt, 1e-9 * cap * vx * dt);
    }
    if (step < 20) {
      EXPECT_EQ(st.sliding, 0u) << step;
    }
    total_diss += fdiss[0];
    // Balance of the 8 corner forces, friction included.
    double f[3] = {0, 0, 0}, m[3] = {0, 0, 0};
    for (int c = 0; c < 8; ++c) {
      const double* xc = &x[3 * c];
      const double* fc = &force[3 * c];
      for (int d = 0; d < 3; ++d) f[d] += fc[d];
      m[0] += xc[1] * fc[2] - xc[2] * fc[1];
      m[1] += xc[2] * fc[0] - xc[0] * fc[2];
      m[2] += xc[0] * fc[1] - xc[1] * fc[0];
    }
    for (int d = 0; d < 3; ++d) {
      EXPECT_LT(std::abs(f[d]), 1e-12 * f_n);
      EXPECT_LT(std::abs(m[d]), 1e-12 * f_n);
    }
  }
  EXPECT_NEAR(total_diss, cap * (60 * vx * dt - cap / args.law.tangential_stiffness), 1e-9 * total_diss);
  // The spring holds cap^2 / (2 k_t) while sliding; the pair's overlap energy is reported too.
  std::vector<double> spring(1), overlap(1);
  args.friction_energy = spring;
  args.energy = overlap;
  contact_forces(args, 0, 1);
  EXPECT_NEAR(spring[0], cap * cap / (2 * args.law.tangential_stiffness), 1e-9 * spring[0]);
  EXPECT_GT(overlap[0], 0.0);
  args.friction_energy = {};
  args.energy = {};
  // Normal damping: approaching adds repulsion and dissipates; separating never pulls.
  args.law.tangential_stiffness = 0.0;
  args.law.normal_damping = f_n / 0.1;  // eta_n v = f_n at v = 0.1
  for (int c = 0; c < 4; ++c) v[3 * c] = 0.0, v[3 * c + 2] = -0.05;
  contact_forces(args, 0, 1);
  double fz = 0;
  for (int c = 0; c < 4; ++c) fz += force[3 * c + 2];
  EXPECT_NEAR(fz, 1.5 * f_n, 1e-9 * f_n);
  EXPECT_NEAR(ddiss[0], 0.5 * f_n * 0.05 * dt, 1e-9 * f_n * dt);
  for (int c = 0; c < 4; ++c) v[3 * c + 2] = 0.5;
  contact_forces(args, 0, 1);
  fz = 0;
  for (int c = 0; c < 4; ++c) fz += force[3 * c + 2];
  EXPECT_NEAR(fz, 0.0, 1e-9 * f_n);
  EXPECT_GE(ddiss[0], 0.0);
  // Contact lost: zero force and the history reset.
  history = {1, 2, 3};
  args.law.tangential_stiffness = 1.0;
  for (int c = 0; c < 4; ++c) x[3 * c + 2] += 2 * delta;
  st = contact_forces(args, 0, 1);
  EXPECT_EQ(st.touching, 0u);
  EXPECT_EQ(*std::max_element(force.begin(), force.end()), 0.0);
  EXPECT_EQ(history, std::vector<double>(3, 0.0));
}

// The pair's stiffness k_pair (sum of p A_P |grad phi| over its polygons) is the rate at which its normal
// force grows with the overlap: two tets face to face (B below z = 0, A above z = -delta, the same
// triangle), against a central difference of f_n in delta. At small delta the polygons of the sub-tets
// beside the face's edges (whose gradients are not along n) are strips of width ~delta: 1.3 % at
// delta = 1e-3, so 1 % at delta = 1e-4 leaves a factor of 10 for the O(delta) term.
TEST(ContactPotential, PairStiffnessIsTheRateOfTheNormalForce) {
  auto force_at = [](double delta) {
    const double a[4][3] = {{0, 0, -delta}, {1, 0, -delta}, {0, 1, -delta}, {0.3, 0.3, 1 - delta}};
    const double b[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, -1}};
    return tet_pair_potential_force(a, b, kP);
  };
  const double delta = 1e-4, eps = 1e-7;
  const TetPairForce r = force_at(delta);
  const double rate = (std::hypot(force_at(delta + eps).normal[0], force_at(delta + eps).normal[1],
                                  force_at(delta + eps).normal[2]) -
                       std::hypot(force_at(delta - eps).normal[0], force_at(delta - eps).normal[1],
                                  force_at(delta - eps).normal[2])) /
                      (2 * eps);
  EXPECT_NEAR(r.stiffness / rate, 1.0, 0.01);
  // Face to face over the triangle's area A = 1/2 with H = 1 on both sides: 8 p A / H.
  EXPECT_NEAR(r.stiffness / (8 * kP * 0.5), 1.0, 0.01);
  EXPECT_EQ(force_at(-1e-3).stiffness, 0.0);  // apart
}

// With a reference stiffness the pair's damping is eta_n k_pair / k_ref (a pair that barely touches barely
// damps: on fine meshes many such pairs share a node, where a full eta_n each lifts a block off its
// friction and makes the explicit damping unstable), and friction caps at mu times the potential's normal
// force, the dashpot apart (kernels/contact_potential.hpp says why).
TEST(ContactFriction, DampingFollowsThePairsStiffnessAndFrictionThePotentialsNormalForce) {
  std::vector<double> x = apex_in_top_face(0.02);
  const double vx = 0.1, vz = -0.05, dt = 1e-3;
  std::vector<double> v(24, 0.0);
  for (int c = 0; c < 4; ++c) v[3 * c] = vx, v[3 * c + 2] = vz;  // sliding along x and approaching
  const std::vector<int32_t> tet_nodes = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::vector<ContactPair> pairs = {{0, 1}};
  std::vector<double> history(3, 0.0), force(24), fn(1), fdiss(1), ddiss(1);
  ContactLaw law;
  law.penalty = kP;
  law.friction = 0.6;
  law.tangential_stiffness = 1e3 * kP;  // stiff: the cap is reached in the first step
  law.normal_damping = 1e-3 * kP;
  double a[4][3], b[4][3];
  for (int c = 0; c < 4; ++c)
    for (int d = 0; d < 3; ++d) a[c][d] = x[3 * c + d], b[c][d] = x[12 + 3 * c + d];
  const double k_pair = tet_pair_potential_force(a, b, kP).stiffness;
  ASSERT_GT(k_pair, 0.0);
  for (const double k_ref : {0.0, k_pair, 4 * k_pair}) {
    law.reference_stiffness = k_ref;
    const double share = k_ref > 0 ? k_pair / k_ref : 1.0;
    std::fill(history.begin(), history.end(), 0.0);
    ContactArgs args{x, v, tet_nodes, pairs, law, dt, history, force, fn, fdiss, ddiss};
    contact_forces(args, 0, 1);
    double f[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c)
      for (int d = 0; d < 3; ++d) f[d] += force[3 * c + d];
    const double damping = -share * law.normal_damping * vz;  // along +z, the pair's normal
    EXPECT_NEAR(f[2], fn[0] + damping, 1e-9 * fn[0]) << k_ref;
    EXPECT_NEAR(-f[0], law.friction * fn[0], 1e-9 * fn[0]) << k_ref;
    EXPECT_NEAR(ddiss[0], damping * -vz * dt, 1e-9 * fn[0] * dt) << k_ref;
  }
}

// Many pairs: a range split into pieces gives the bits of the whole; the gather sums per node.
TEST(ContactPotential, SplitRangesAndGather) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  const int T = 40;
  std::vector<double> x;
  std::vector<int32_t> tet_nodes;
  for (int t = 0; t < T; ++t) {
    const double c[3] = {u(rng), u(rng), u(rng)};
    const Tet tet = random_tet(rng, c);
    for (const auto& p : tet) x.insert(x.end(), p.begin(), p.end());
    for (int k = 0; k < 4; ++k) tet_nodes.push_back(4 * t + k);
  }
  std::vector<ContactPair> pairs;
  for (int a = 0; a < T; ++a)
    for (int b = a + 1; b < T; ++b) pairs.push_back({a, b});
  const size_t P = pairs.size();
  std::vector<double> f1(24 * P), f2(24 * P);
  ContactLaw law;
  law.penalty = kP;
  ContactArgs a1{x, {}, tet_nodes, pairs, law, 1e-3, {}, f1};
  ContactArgs a2 = a1;
  a2.pair_force = f2;
  const ContactStatus s1 = contact_forces(a1, 0, P);
  ContactStatus s2;
  for (size_t b = 0; b < P; b += 37) s2 += contact_forces(a2, b, std::min(P, b + 37));
  EXPECT_EQ(f1, f2);
  EXPECT_EQ(s1.touching, s2.touching);
  EXPECT_GT(s1.touching, P / 4);
  std::vector<double> node_force(x.size(), 0.0);
  contact_gather(pairs, tet_nodes, f1, node_force);
  double sum[3] = {0, 0, 0}, scale = 0;
  for (size_t i = 0; i < node_force.size(); ++i) {
    sum[i % 3] += node_force[i];
    scale = std::max(scale, std::abs(node_force[i]));
  }
  for (double s : sum) EXPECT_LT(std::abs(s), 1e-11 * scale);
}

TEST(ContactFriction, HistoryFollowsThePairsAcrossRedetection) {
  const std::vector<ContactPair> before = {{0, 1}, {0, 5}, {2, 3}, {4, 9}};
  const std::vector<double> h_before = {1, 1, 1, 5, 5, 5, 23, 23, 23, 49, 49, 49};
  const std::vector<ContactPair> after = {{0, 2}, {0, 5}, {2, 3}, {3, 4}, {4, 9}, {7, 8}};
  std::vector<double> h_after(3 * after.size(), -1.0);
  remap_pair_history(before, h_before, after, h_after);
  EXPECT_EQ(h_after, (std::vector<double>{0, 0, 0, 5, 5, 5, 23, 23, 23, 0, 0, 0, 49, 49, 49, 0, 0, 0}));
  std::vector<double> none;
  remap_pair_history({}, {}, after, h_after);
  EXPECT_EQ(*std::max_element(h_after.begin(), h_after.end()), 0.0);
  remap_pair_history(before, h_before, {}, none);
}

// femdem.md 2, item 15, at kernel level: the same trajectories with detection at every step (buffer 0) as
// with buffer-triggered detection (buffer b, re-detected only when some node has moved by more than b / 2
// since the last detection). 27 rigid tets (each moved as a whole by the sum of its corner forces) thrown
// at each other. The buffered list holds extra pairs, but they write exact zeros, and the touching pairs
// come in the same (sorted) order in both lists, so the gathered node forces and hence the trajectories are
// bitwise identical.
TEST(ContactDetection, BufferedDetectionGivesTheSameTrajectories) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int T = 27;
  std::vector<double> x0, v0;
  std::vector<int32_t> tet_nodes, ids(T);
  for (int t = 0; t < T; ++t) {
    const double c[3] = {0.8 * (t % 3), 0.8 * (t / 3 % 3), 0.8 * (t / 9)};
    const Tet tet = random_tet(rng, c);
    const double vel[3] = {-2.0 * (t % 3 - 1) + 0.5 * u(rng), -2.0 * (t / 3 % 3 - 1) + 0.5 * u(rng),
                           -2.0 * (t / 9 - 1) + 0.5 * u(rng)};
    for (const auto& p : tet) {
      x0.insert(x0.end(), p.begin(), p.end());
      v0.insert(v0.end(), vel, vel + 3);
    }
    for (int k = 0; k < 4; ++k) tet_nodes.push_back(4 * t + k);
    ids[t] = t;
  }
  const double mass = 1.0, dt = 2e-4;  // per tet [kg]; p below gives ~50 steps per contact
  ContactLaw law;
  law.penalty = 2e5;
  size_t touching = 0;  // pair-steps with a force, over both runs
  auto run = [&](double buffer, int& detections, size_t& max_pairs) {
    std::vector<double> x = x0, v = v0, x_ref = x0, lo(3 * T), hi(3 * T);
    BroadPhaseWorkspace ws;
    std::vector<ContactPair> pairs;
    std::vector<double> pf, nf(x.size());
    detections = 0;
    max_pairs = 0;
    for (int step = 0; step < 600; ++step) {
      const double d = max_node_displacement(x, x_ref, 0, x.size() / 3);
      if (step == 0 || buffer == 0.0 || contact_redetect_needed(d, buffer)) {
        tet_bounding_boxes(x, tet_nodes, ids, lo, hi, 0, T);
        contact_broad_phase({ids, lo, hi, buffer, {}}, ws);
        pairs = ws.pairs;
        x_ref = x;
        ++detections;
      }
      max_pairs = std::max(max_pairs, pairs.size());
      pf.assign(24 * pairs.size(), 0.0);
      ContactArgs args{x, v, tet_nodes, pairs, law, dt, {}, pf};
      touching += contact_forces(args, 0, pairs.size()).touching;
      std::fill(nf.begin(), nf.end(), 0.0);
      contact_gather(pairs, tet_nodes, pf, nf);
      for (int t = 0; t < T; ++t)
        for (int k = 0; k < 3; ++k) {
          double f = 0.0;
          for (int c = 0; c < 4; ++c) f += nf[3 * (4 * t + c) + k];
          for (int c = 0; c < 4; ++c) {
            double& vel = v[3 * (4 * t + c) + k];
            vel += dt * f / mass;
            x[3 * (4 * t + c) + k] += dt * vel;
          }
        }
    }
    return x;
  };
  int det_every = 0, det_buffered = 0;
  size_t pairs_every = 0, pairs_buffered = 0;
  const std::vector<double> a = run(0.0, det_every, pairs_every);
  const std::vector<double> b = run(0.05, det_buffered, pairs_buffered);
  EXPECT_EQ(det_every, 600);
  EXPECT_LT(det_buffered, 200);
  EXPECT_GT(pairs_buffered, pairs_every);
  EXPECT_GT(pairs_every, 0u);
  EXPECT_TRUE(a == b);
  // Something happened: many pair-steps in contact.
  EXPECT_GT(touching, 2u * 300);
  RecordProperty("detections_buffered", det_buffered);
  RecordProperty("touching_pair_steps", static_cast<int>(touching / 2));
  RecordProperty("max_pairs", testing::PrintToString(std::to_string(pairs_every) + " / " +
                                                     std::to_string(pairs_buffered)));
}

}  // namespace
}  // namespace rift::kernels
