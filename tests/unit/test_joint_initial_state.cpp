// The in-situ state of joints: joint_initial_offset inverts the pre-peak law for a given in-situ traction,
// and a joint given that offset (JointArgs::initial_offset) holds the traction with its nodes together and
// keeps its full strength. Limestone numbers of test_joint_support.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kernels/joint_forces.hpp"
#include "kernels/joint_initial_state.hpp"
#include "kernels/joint_law.hpp"
#include "kernels/softening.hpp"
#include "tests/unit/test_joint_support.hpp"

namespace rift::kernels {
namespace {

using namespace joint_test;

INSTANTIATE_TEST_SUITE_P(Joint, BothRules, both_rules, rules_name);

struct Case {
  const char* name;
  double sigma_n, shear[2];  // in-situ normal traction and the shear along two in-plane axes [Pa]
};
// Compression with shear, tension with shear (up to 0.9 f_t), pure shear, pure compression, and shear close
// to the confined strength (f_s = c + 10 MPa tan 35 deg = 22.0 MPa).
const Case kCases[] = {
    {"compression_and_shear", -10e6, {8e6, -5e6}}, {"tension_and_shear", 3e6, {6e6, 2e6}},
    {"near_tensile_peak", 0.9 * kFt, {1e6, 0.0}},  {"pure_shear", 0.0, {0.0, 12e6}},
    {"pure_compression", -40e6, {0.0, 0.0}},       {"near_shear_peak", -10e6, {0.0, 21.9e6}}};

// A skew unit normal and two unit vectors completing it to an orthonormal frame.
struct Frame {
  double n[3], e1[3], e2[3];
};
Frame skew_frame() {
  Frame f;
  const double a[3] = {0.3, -0.5, 0.8}, b[3] = {1.0, 0.2, 0.0};
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  for (int c = 0; c < 3; ++c) f.n[c] = a[c] / la;
  const double bn = b[0] * f.n[0] + b[1] * f.n[1] + b[2] * f.n[2];
  double e1[3];
  for (int c = 0; c < 3; ++c) e1[c] = b[c] - bn * f.n[c];
  const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  for (int c = 0; c < 3; ++c) f.e1[c] = e1[c] / l1;
  f.e2[0] = f.n[1] * f.e1[2] - f.n[2] * f.e1[1];
  f.e2[1] = f.n[2] * f.e1[0] - f.n[0] * f.e1[2];
  f.e2[2] = f.n[0] * f.e1[1] - f.n[1] * f.e1[0];
  return f;
}

// 1. Round trip at one point: the offset, read as opening o = offset.n and sliding vector offset - o n,
// gives back t0 through joint_point_response, intact. The inversion and the law are a few dozen roundings
// each and the law is Lipschitz in the offset (tangent <= p / h), so the traction comes back to ~1e-15 of
// |t0|; 1e-12 is the bound asked for. Both softening rules (they differ only after the peak).
TEST(JointInitialOffset, RoundTripThroughTheLaw) {
  const JointMaterial m = limestone();
  const double Z = softening_integral();
  const Frame f = skew_frame();
  for (Softening rule : {Softening::energy_exact, Softening::y_compatible}) {
    const JointScales k = joint_scales(m, kH, rule, Z);
    for (const Case& c : kCases) {
      double t0[3], offset[3];
      for (int i = 0; i < 3; ++i) t0[i] = c.sigma_n * f.n[i] + c.shear[0] * f.e1[i] + c.shear[1] * f.e2[i];
      ASSERT_TRUE(joint_initial_offset(m, kH, f.n, t0, rule, Z, offset)) << c.name;
      const double o = offset[0] * f.n[0] + offset[1] * f.n[1] + offset[2] * f.n[2];
      double sv[3];
      for (int i = 0; i < 3; ++i) sv[i] = offset[i] - o * f.n[i];
      const double s = std::sqrt(sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]);
      const JointPointResponse r = joint_point_response(m, k, rule, Z, o, s, 0.0);
      EXPECT_EQ(r.d_max, 0.0) << c.name;
      double error = 0.0, size = 0.0;
      for (int i = 0; i < 3; ++i) {
        const double t = r.sigma * f.n[i] + r.tau_per_slip * sv[i];
        error += (t - t0[i]) * (t - t0[i]);
        size += t0[i] * t0[i];
      }
      EXPECT_LE(std::sqrt(error), 1e-12 * std::sqrt(size)) << c.name;
      if (c.sigma_n <= 0.0) {
        EXPECT_NEAR(o, c.sigma_n * kH / kP, 1e-15 * std::hypot(offset[0], offset[1], offset[2])) << c.name;
      }
    }
  }
}

// 2. A traction at or beyond the strength cannot be held: false and a zero offset. Tension at f_t and
// above; shear at the confined f_s; a NaN traction.
TEST(JointInitialOffset, RefusesTractionsAtTheStrength) {
  const JointMaterial m = limestone();
  const double Z = softening_integral(), n[3] = {0, 0, 1};
  const double fs = kC + 10e6 * kTanPhi;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double refused[][3] = {{0, 0, kFt}, {0, 0, 1.5 * kFt}, {fs, 0, -10e6}, {0, 2 * kC, 1e6}, {nan, 0, 0}};
  for (const auto& t : refused) {
    double offset[3] = {1, 1, 1};
    EXPECT_FALSE(joint_initial_offset(m, kH, n, t, Softening::energy_exact, Z, offset));
    for (double o : offset) EXPECT_EQ(o, 0.0);
  }
  double offset[3];
  const double just_below[3] = {fs * (1 - 1e-9), 0, -10e6};
  EXPECT_TRUE(joint_initial_offset(m, kH, n, just_below, Softening::energy_exact, Z, offset));
}

// The test joint (n = +z) given the offset for in-situ traction t0.
void give_in_situ_state(OneJoint& j, const double t0[3]) {
  const double n[3] = {0, 0, 1};
  j.offset.assign(3, 0.0);
  ASSERT_TRUE(
      joint_initial_offset(j.materials[0], kH, n, t0, j.softening, softening_integral(), j.offset.data()));
}

// 3. The element with the offset holds t0 with its nodes together (no jump), on both paths and rules: the
// tractions read back from the forces, to the 1e-12 of the round trip; no damage.
TEST_P(BothRules, OffsetHoldsInSituTractionAtRest) {
  for (const Case& c : kCases) {
    OneJoint j(points());
    const double t0[3] = {c.shear[0], c.shear[1], c.sigma_n};
    give_in_situ_state(j, t0);
    j.run();
    const double size = std::sqrt(t0[0] * t0[0] + t0[1] * t0[1] + t0[2] * t0[2]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(-j.side_a_force(i) / kArea, t0[i], 1e-12 * size) << c.name;
    EXPECT_EQ(j.damage[0], 0.0) << c.name;
  }
}

// 4. A joint in in-situ compression sigma_n0 = -10 MPa, opened from rest: the normal traction starts at
// sigma_n0, peaks at exactly f_t (the full strength, not f_t - |sigma_n0|) when the geometric opening is
// op - o0 = op + |sigma_n0| h / p, and the joint breaks in tension once the law's opening o0 + u reaches
// op + ot. Tolerances as for mode I without the offset (test_joint_law.cpp): 1e-12 on the peak, the break
// within one ramp step.
TEST_P(BothRules, InSituCompressionKeepsTheFullTensileStrength) {
  OneJoint j(points());
  const double sigma_n0 = -10e6, t0[3] = {0, 0, sigma_n0};
  give_in_situ_state(j, t0);
  const double o0 = j.offset[2], ot = exact_length(kFt, kOp, kGI);
  EXPECT_NEAR(o0, sigma_n0 * kH / kP, 1e-15 * std::fabs(o0));
  j.jump(0, 0, 0);
  EXPECT_NEAR(j.sigma(), sigma_n0, 1e-12 * std::fabs(sigma_n0));
  const RampResult r = ramp(j, kOp - o0, ot, true);
  EXPECT_NEAR(r.peak, kFt, 1e-12 * kFt);
  EXPECT_DOUBLE_EQ(r.peak_at, kOp - o0);
  EXPECT_GE(r.broke_at + o0, (kOp + ot) * (1 - 1e-12));
  EXPECT_LT(r.broke_at + o0, kOp + ot + 1.01 * ot / 6000 * 1.0000001);
  EXPECT_EQ(j.broken[0], static_cast<uint8_t>(JointBreakMode::tensile));
  record("peak_sigma", r.peak);
}

// 5. An in-situ shear tau0 = 10 MPa under sigma_n0 = -5 MPa starts pre-peak: slipping further along it, the
// shear traction rises from tau0 to the confined strength f_s = c + 5 MPa tan(phi) exactly at the geometric
// slip sp - s0, the normal traction staying sigma_n0 (1e-12 as above; the slip offset is exact to ~1e-16).
TEST_P(BothRules, InSituShearStartsPrePeak) {
  OneJoint j(points());
  const double sigma_n0 = -5e6, tau0 = 10e6, t0[3] = {tau0, 0, sigma_n0};
  give_in_situ_state(j, t0);
  const double fs = kC - sigma_n0 * kTanPhi, sp = 2 * kH * fs / kP, s0 = j.offset[0];
  EXPECT_NEAR(fs * (2 * s0 / sp - (s0 / sp) * (s0 / sp)), tau0, 1e-12 * tau0);
  j.jump(0, 0, 0);
  EXPECT_NEAR(j.tau_x(), tau0, 1e-12 * tau0);
  const RampResult r = ramp(j, sp - s0, exact_length(fs, sp, kGII), false);
  EXPECT_NEAR(r.peak, fs, 1e-12 * fs);
  EXPECT_NEAR(r.peak_at, sp - s0, 1e-15);
  EXPECT_EQ(j.broken[0], static_cast<uint8_t>(JointBreakMode::shear));
}

}  // namespace
}  // namespace rift::kernels
