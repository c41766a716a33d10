#pragma once
// Shared helpers of the tet kernel tests: a small mesh with every array tet_forces needs, two reference
// meshes (one general tet, a jittered patch of 48 tets), and the fixture that runs a test on both paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "kernels/tet_forces.hpp"

namespace rift::kernels::tet_test {

using Mat3 = std::array<std::array<double, 3>, 3>;
using ForceFn = TetForceStatus (*)(const TetForceArgs&, size_t, size_t);

// Limestone of femdem.md 1e: E = 40 GPa, nu = 0.25 -> lambda = mu = 16 GPa.
constexpr double kE = 40e9;
constexpr TetMaterial kRock{16e9, 16e9, 0.0};

// A tet mesh with everything tet_forces needs, built from reference positions. initial_stress stays empty
// (no prestress) unless a test fills it.
struct Mesh {
  std::vector<double> x0, x, v;
  std::vector<int32_t> tets, material;
  std::vector<TetMaterial> materials{kRock};
  std::vector<double> initial_stress;
  std::vector<double> dm_inv, volume0, force, stress, energy, power;

  size_t num_tets() const { return tets.size() / 4; }
  size_t prepare() {
    dm_inv.assign(9 * num_tets(), 0.0);
    volume0.assign(num_tets(), 0.0);
    material.resize(num_tets(), 0);
    force.assign(12 * num_tets(), -1.0);
    stress.assign(6 * num_tets(), -1.0);
    energy.assign(num_tets(), -1.0);
    power.assign(num_tets(), -1.0);
    if (x.empty()) x = x0;
    v.resize(x0.size(), 0.0);
    return tet_prepare(x0, tets, dm_inv, volume0, 0, num_tets());
  }
  TetForceArgs args() {
    return {x, v, tets, dm_inv, volume0, material, materials, force, stress, energy, power, initial_stress};
  }
  TetForceStatus run(ForceFn fn) { return fn(args(), 0, num_tets()); }
  // x = A X + b for every node.
  void map(const Mat3& A, const std::array<double, 3>& b) {
    x.resize(x0.size());
    for (size_t n = 0; n < x0.size() / 3; ++n)
      for (int i = 0; i < 3; ++i)
        x[3 * n + i] = A[i][0] * x0[3 * n] + A[i][1] * x0[3 * n + 1] + A[i][2] * x0[3 * n + 2] + b[i];
  }
};

// A general (no two edges equal, no right angles) positively oriented tet.
inline Mesh general_tet() {
  Mesh m;
  m.x0 = {0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.9, 0.3, -0.15, 0.25, 1.1};
  m.tets = {0, 1, 2, 3};
  return m;
}

// 2 x 2 x 2 cubes of side h, 6 Kuhn tets each (48 tets, 27 nodes, node 13 interior), every node moved by up
// to +-10 % of h so no tet is regular or axis-aligned.
inline Mesh cube_patch() {
  Mesh m;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        m.x0.push_back(i + jitter(rng));
        m.x0.push_back(j + jitter(rng));
        m.x0.push_back(k + jitter(rng));
      }
  auto node = [](int i, int j, int k) { return static_cast<int32_t>(i + 3 * j + 9 * k); };
  static constexpr int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int32_t, 4> t;
          t[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = node(c[0], c[1], c[2]);
          }
          // Odd permutations of the axes give negatively oriented tets: swap two corners.
          const bool odd = (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]) == 1 ||
                           (p[0] > p[1]) + (p[0] > p[2]) + (p[1] > p[2]) == 3;
          if (odd) std::swap(t[2], t[3]);
          m.tets.insert(m.tets.end(), t.begin(), t.end());
        }
  return m;
}

// Checks every corner force of a one-tet mesh against minus the central difference (step h) of the energy
// output, to `tolerance` times the largest force. Leaves m.x unchanged.
inline void expect_force_is_minus_energy_gradient(Mesh& m, ForceFn kernel, double h, double tolerance,
                                                  const std::string& context) {
  m.run(kernel);
  const std::vector<double> force = m.force;
  double largest = 0.0;
  for (double f : force) largest = std::max(largest, std::fabs(f));
  for (size_t c = 0; c < 12; ++c) {
    const double keep = m.x[c];
    m.x[c] = keep + h;
    m.run(kernel);
    const double e_plus = m.energy[0];
    m.x[c] = keep - h;
    m.run(kernel);
    const double e_minus = m.energy[0];
    m.x[c] = keep;
    EXPECT_NEAR(-(e_plus - e_minus) / (2 * h), force[c], tolerance * largest) << "component " << c << context;
  }
}

inline Mat3 identity_plus(const Mat3& eps) {
  Mat3 A = eps;
  for (int i = 0; i < 3; ++i) A[i][i] += 1.0;
  return A;
}

inline double norm6(const double* s) {  // Frobenius norm of a symmetric tensor in Voigt order
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

// Runs a test on the scalar reference and on the vector path (named, so CTest names carry no addresses).
// Each test file instantiates it: INSTANTIATE_TEST_SUITE_P(TetForces, BothPaths, both_paths, path_name).
enum class Path { scalar, vector };
inline void PrintTo(Path p, std::ostream* os) {
  *os << (p == Path::scalar ? "scalar" : "vector");
}
class BothPaths : public ::testing::TestWithParam<Path> {
 protected:
  static ForceFn kernel() { return GetParam() == Path::scalar ? &tet_forces_scalar : &tet_forces; }
};
inline const auto both_paths = ::testing::Values(Path::scalar, Path::vector);
inline std::string path_name(const ::testing::TestParamInfo<Path>& info) {
  return info.param == Path::scalar ? "scalar" : "vector";
}

}  // namespace rift::kernels::tet_test
