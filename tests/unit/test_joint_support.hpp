#pragma once
// Shared helpers of the joint kernel tests (test_joint_law.cpp, test_joint_element.cpp,
// test_joint_initial_state.cpp): the limestone numbers of femdem.md 1e and 2.3-2.5 (E = 40 GPa, f_t = 5 MPa,
// c = 15 MPa, phi = 35 deg, G_I = 30 J/m2, G_II = 300 J/m2, p = 10 E, h = 5 mm) and one 6-node joint driven
// through displacement paths.
//
// The joint: side A corners (0,0,0), (h,0,0), (0,h,0) (counter-clockwise seen from +z, so n = +z points
// into side A, which lies above); side B corners start at the same points. Moving side A by (sx, sy, o)
// gives a uniform jump: opening o, slip |(sx, sy)|. Mid-surface: right triangle with legs h, so h_min = h,
// A = h^2 / 2. Tractions are read back from the forces: sigma = -(sum of side-A forces).n / A.
// TEST_P(BothRules, ...) runs with 3 and 7 points on the scalar reference and on the AVX2 path; the other
// single-joint tests use the AVX2 path (joint_forces).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "kernels/joint_forces.hpp"
#include "kernels/joint_law.hpp"
#include "kernels/joint_rule.hpp"
#include "kernels/softening.hpp"

namespace rift::kernels::joint_test {

constexpr double kE = 40e9, kH = 5e-3, kArea = 0.5 * kH * kH;
constexpr double kP = 10 * kE, kFt = 5e6, kC = 15e6, kGI = 30.0, kGII = 300.0;
inline const double kTanPhi = std::tan(35.0 * std::numbers::pi / 180.0);
constexpr double kZRef = 0.386307;  // femdem.md 1b, 2e5-point numerical integral of z

inline JointMaterial limestone() {
  return {kP, kFt, kC, kTanPhi, kGI, kGII, 0.0};
}

// Reference lengths from femdem.md 1b, computed here independently of the kernel.
constexpr double kOp = 2 * kH * kFt / kP;  // 1.25e-7 m
constexpr double kSp = 2 * kH * kC / kP;   // 3.75e-7 m
inline double exact_length(double f, double peak, double G) {
  return (G - 2.0 / 3.0 * f * peak) / (f * softening_integral());
}

// Which implementation OneJoint::run calls: the AVX2 path unless a BothRules test selects the scalar one.
using Kernel = JointStatus (*)(const JointArgs&, size_t, size_t);
inline Kernel g_kernel = &joint_forces;

// One joint with its state and outputs; side B fixed at the reference, side A moved.
struct OneJoint {
  std::vector<double> X = {0, 0, 0, kH, 0, 0, 0, kH, 0, 0, 0, 0, kH, 0, 0, 0, kH, 0};
  std::vector<double> x = X;
  std::vector<int32_t> nodes{0, 1, 2, 3, 4, 5}, material{0};
  std::vector<JointMaterial> materials;
  const JointRule* rule;
  Softening softening;
  // force: all six corners' forces, x y z each; the kernel writes side B's (row) and side A's are minus them.
  std::vector<double> d_max, row = std::vector<double>(9, 0.0), force = std::vector<double>(18, 0.0);
  std::vector<double> opening{0}, slip{0}, damage{0}, energy{0};
  std::vector<uint8_t> broken{0};
  std::vector<JointBreak> breaks = std::vector<JointBreak>(4);
  std::atomic<size_t> break_count{0};
  std::vector<double> offset;  // initial offset (3), empty = none
  std::vector<double> anchor;  // residual-friction anchors, 3 per point
  JointStatus status;

  explicit OneJoint(int points, Softening s = Softening::energy_exact, JointMaterial m = limestone())
      : materials{m},
        rule(&joint_rule(points)),
        softening(s),
        d_max(static_cast<size_t>(points), 0.0),
        anchor(3 * static_cast<size_t>(points), 0.0) {}

  JointArgs args() {
    JointArgs a{x,   nodes,   material, materials, rule,   softening, d_max,        broken,
                row, opening, slip,     damage,    energy, breaks,    &break_count, offset};
    a.residual_anchor = anchor;
    return a;
  }
  void run() {
    status += g_kernel(args(), 0, 1);
    for (int k = 0; k < 9; ++k) force[k] = -row[k], force[9 + k] = row[k];
  }
  // Side A at reference + (sx, sy, o); side B at reference. Then evaluate.
  void jump(double sx, double sy, double o) {
    for (int i = 0; i < 3; ++i) {
      x[3 * i] = X[3 * i] + sx;
      x[3 * i + 1] = X[3 * i + 1] + sy;
      x[3 * i + 2] = X[3 * i + 2] + o;
    }
    run();
  }
  double side_a_force(int c) const { return force[c] + force[3 + c] + force[6 + c]; }
  double sigma() const { return -side_a_force(2) / kArea; }  // normal traction, tension positive
  double tau_x() const { return -side_a_force(0) / kArea; }  // shear traction along +x
  bool is_broken() const { return broken[0] != 0; }
};

// Work done on the joint, -sum f.dx, by the trapezoid rule between successive evaluations.
struct WorkMeter {
  std::vector<double> x, f;
  double work = 0.0;
  explicit WorkMeter(const OneJoint& j) : x(j.x), f(j.force) {}
  void step(const OneJoint& j) {
    for (size_t c = 0; c < 18; ++c) work -= 0.5 * (f[c] + j.force[c]) * (j.x[c] - x[c]);
    x = j.x;
    f = j.force;
  }
};

// Composite Simpson for the analytic references (independent of the kernel's Gauss-Legendre).
template <class F>
inline double simpson(F f, double a, double b, int n = 2000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

inline void record(const char* key, double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  ::testing::Test::RecordProperty(key, text);
}

// Runs a test with both rules (3 and 7 points) on both paths (scalar reference and AVX2). Each test file
// instantiates it: INSTANTIATE_TEST_SUITE_P(Joint, BothRules, both_rules, rules_name).
enum class Path { scalar, vector };
inline void PrintTo(Path p, std::ostream* os) {
  *os << (p == Path::scalar ? "scalar" : "vector");
}
class BothRules : public ::testing::TestWithParam<std::tuple<int, Path>> {
 protected:
  void SetUp() override { g_kernel = path() == Path::scalar ? &joint_forces_scalar : &joint_forces; }
  void TearDown() override { g_kernel = &joint_forces; }
  static int points() { return std::get<0>(GetParam()); }
  static Path path() { return std::get<1>(GetParam()); }
};
inline const auto both_rules =
    ::testing::Combine(::testing::Values(3, 7), ::testing::Values(Path::scalar, Path::vector));
inline std::string rules_name(const ::testing::TestParamInfo<std::tuple<int, Path>>& info) {
  return std::to_string(std::get<0>(info.param)) + "points_" +
         (std::get<1>(info.param) == Path::scalar ? "scalar" : "vector");
}

// Displacement-controlled opening: 500 steps to op (so o = op is a sample), then 6000 steps over the
// softening length and past it. Returns the work per unit area when the joint broke (or at the end).
struct RampResult {
  double peak = 0, peak_at = 0, work_at_break = 0, broke_at = -1;
};
inline RampResult ramp(OneJoint& j, double peak_len, double soft_len, bool normal, double fixed_o = 0.0) {
  auto set = [&](double u) { normal ? j.jump(0, 0, u) : j.jump(u, 0, fixed_o); };
  set(0.0);
  WorkMeter meter(j);
  RampResult r;
  const int n1 = 500, n2 = 6000;
  for (int k = 1; k <= n1 + n2; ++k) {
    const double u = k <= n1 ? peak_len * k / n1 : peak_len + 1.01 * soft_len * (k - n1) / n2;
    set(u);
    meter.step(j);
    const double t = normal ? j.sigma() : j.tau_x();
    if (t > r.peak) {
      r.peak = t;
      r.peak_at = u;
    }
    if (j.is_broken()) {
      r.broke_at = u;
      r.work_at_break = meter.work / kArea;
      break;
    }
  }
  return r;
}

}  // namespace rift::kernels::joint_test
